#include "slam/synthetic/assets/furniture_catalog.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include <Eigen/Dense>

#include "slam/core/check.h"
#include "slam/synthetic/assets/archive_path.h"
#include "slam/synthetic/assets/java_properties.h"
#include "slam/synthetic/assets/zip_archive.h"

namespace duskmap {
namespace {

constexpr char kPropertiesPath[] = "PluginFurnitureCatalog.properties";
// How far a modelRotation may be from a rotation (R^T R - I, det - 1): the
// catalogs write them with float precision.
constexpr double kRotationTolerance = 1e-3;

using Properties = std::map<std::string, std::string>;

std::string Trim(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t\r\n\f");
  if (begin == std::string::npos) return "";
  const size_t end = text.find_last_not_of(" \t\r\n\f");
  return text.substr(begin, end - begin + 1);
}

std::optional<double> ParseNumber(const std::string& text) {
  const std::string trimmed = Trim(text);
  const char* begin = trimmed.data() + (!trimmed.empty() && trimmed[0] == '+' ? 1 : 0);
  const char* end = trimmed.data() + trimmed.size();
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end || begin == end || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string Get(const Properties& properties, const std::string& key) {
  const auto it = properties.find(key);
  return it == properties.end() ? std::string() : it->second;
}

// The N of every key#N.
std::set<int> EntryIndices(const Properties& properties) {
  std::set<int> indices;
  for (const auto& [key, value] : properties) {
    const size_t hash = key.rfind('#');
    if (hash == std::string::npos || hash + 1 == key.size()) continue;
    int index = 0;
    const char* begin = key.data() + hash + 1;
    const char* end = key.data() + key.size();
    const auto [ptr, ec] = std::from_chars(begin, end, index);
    if (ec == std::errc() && ptr == end) indices.insert(index);
  }
  return indices;
}

// Reads entries while naming the properties file and the entry in errors.
class EntryReader {
 public:
  EntryReader(const Properties& properties, std::string source, const ZipArchive& archive)
      : properties_(properties), source_(std::move(source)), archive_(archive) {}

  FurnitureEntry Read(int index, const std::string& catalog_license) const {
    FurnitureEntry entry;
    entry.index = index;
    entry.id = Value("id", index);
    entry.name = Value("name", index);
    const std::string suffix = "#" + std::to_string(index);
    SLAM_THROW_IF_NOT(InputError, properties_.count("name" + suffix))
        << source_ << ": entry #" << index << " has no name" << suffix;
    entry.category = Value("category", index);
    entry.creator = Value("creator", index);
    entry.license = properties_.count("license" + suffix) ? Value("license", index) : catalog_license;
    entry.multi_part_model = Trim(Value("multiPartModel", index)) == "true";
    entry.model_path = ModelPath(index, entry.name);
    entry.size_cm = Eigen::Vector3d(Size("width", index, entry.name), Size("depth", index, entry.name),
                                    Size("height", index, entry.name));
    entry.model_rotation = Rotation(index, entry.name);
    return entry;
  }

 private:
  std::string Value(const std::string& key, int index) const {
    return Get(properties_, key + "#" + std::to_string(index));
  }
  std::string Name(int index, const std::string& name) const {
    return "entry #" + std::to_string(index) + " '" + name + "'";
  }

  std::string ModelPath(int index, const std::string& name) const {
    const std::string key = "model#" + std::to_string(index);
    const std::string model = Trim(Get(properties_, key));
    SLAM_THROW_IF_NOT(InputError, !model.empty()) << source_ << ": " << Name(index, name) << " has no " << key;
    // The catalogs give archive paths from the root, with a leading '/'.
    const std::string relative = model[0] == '/' ? model.substr(1) : model;
    const std::optional<std::string> path =
        relative.empty() || relative[0] == '/' ? std::nullopt : NormalizeArchivePath(relative);
    SLAM_THROW_IF_NOT(InputError, path.has_value())
        << source_ << ": " << Name(index, name) << ": " << key << " '" << model
        << "' leaves the archive (absolute or '..')";
    SLAM_THROW_IF_NOT(InputError, archive_.Contains(*path))
        << source_ << ": " << Name(index, name) << ": " << key << " '" << model << "' is not in the archive";
    return *path;
  }

  double Size(const std::string& what, int index, const std::string& name) const {
    const std::string key = what + "#" + std::to_string(index);
    const auto it = properties_.find(key);
    SLAM_THROW_IF_NOT(InputError, it != properties_.end()) << source_ << ": " << Name(index, name) << " has no " << key;
    const std::optional<double> value = ParseNumber(it->second);
    SLAM_THROW_IF_NOT(InputError, value.has_value() && *value > 0)
        << source_ << ": " << Name(index, name) << ": " << key << " must be a positive number (centimetres), got '"
        << it->second << "'";
    return *value;
  }

  std::optional<Eigen::Matrix3d> Rotation(int index, const std::string& name) const {
    const std::string key = "modelRotation#" + std::to_string(index);
    const auto it = properties_.find(key);
    if (it == properties_.end()) return std::nullopt;
    std::vector<double> numbers;
    size_t begin = 0;
    const std::string& text = it->second;
    while ((begin = text.find_first_not_of(" \t", begin)) != std::string::npos) {
      const size_t end = std::min(text.find_first_of(" \t", begin), text.size());
      const std::optional<double> number = ParseNumber(text.substr(begin, end - begin));
      SLAM_THROW_IF_NOT(InputError, number.has_value())
          << source_ << ": " << Name(index, name) << ": " << key << " has a malformed number in '" << text << "'";
      numbers.push_back(*number);
      begin = end;
    }
    SLAM_THROW_IF_NOT(InputError, numbers.size() == 9)
        << source_ << ": " << Name(index, name) << ": " << key << " must have 9 numbers, got " << numbers.size();
    Eigen::Matrix3d rotation;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) rotation(r, c) = numbers[3 * r + c];
    }
    const double error = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    const bool is_rotation = error < kRotationTolerance && std::abs(rotation.determinant() - 1) < kRotationTolerance;
    SLAM_THROW_IF_NOT(InputError, is_rotation)
        << source_ << ": " << Name(index, name) << ": " << key << " is not a rotation: '" << text << "'";
    return rotation;
  }

  const Properties& properties_;
  std::string source_;
  const ZipArchive& archive_;
};

}  // namespace

std::string DefaultFurnitureCatalogPath() { return "/usr/share/sweethome3d/furniture/BlendSwap-CC-0.sh3f"; }

std::string FurnitureEntry::Key() const {
  const size_t hash = id.rfind('#');
  return hash == std::string::npos ? id : id.substr(hash + 1);
}

void FurnitureCatalogOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, max_file_bytes > 0)
      << "furniture_catalog.max_file_bytes must be > 0, got " << max_file_bytes;
}

FurnitureCatalog::FurnitureCatalog(std::unique_ptr<ZipArchive> archive, FurnitureCatalogInfo info,
                                   std::vector<FurnitureEntry> entries, FurnitureCatalogOptions options)
    : archive_(std::move(archive)), info_(std::move(info)), entries_(std::move(entries)), options_(options) {}
FurnitureCatalog::FurnitureCatalog(FurnitureCatalog&&) noexcept = default;
FurnitureCatalog& FurnitureCatalog::operator=(FurnitureCatalog&&) noexcept = default;
FurnitureCatalog::~FurnitureCatalog() = default;

FurnitureCatalog FurnitureCatalog::Open(const std::string& path, const FurnitureCatalogOptions& options) {
  options.Check();
  SLAM_THROW_IF_NOT(InputError, std::filesystem::exists(path))
      << path << ": furniture catalog not found (install the Debian package sweethome3d-furniture: run "
      << "scripts/setup.sh)";
  auto archive = std::make_unique<ZipArchive>(ZipArchive::Open(path));
  SLAM_THROW_IF_NOT(InputError, archive->Contains(kPropertiesPath))
      << path << ": no " << kPropertiesPath << " in the archive (not a SweetHome3D furniture catalog)";
  const std::string source = path + "!/" + kPropertiesPath;
  const Properties properties = ParseJavaProperties(archive->Read(kPropertiesPath, options.max_file_bytes), source);

  FurnitureCatalogInfo info;
  info.id = Get(properties, "id");
  info.name = Get(properties, "name");
  info.description = Get(properties, "description");
  info.version = Get(properties, "version");
  info.license = Get(properties, "license");
  info.provider = Get(properties, "provider");

  const EntryReader reader(properties, source, *archive);
  std::vector<FurnitureEntry> entries;
  for (const int index : EntryIndices(properties)) entries.push_back(reader.Read(index, info.license));
  SLAM_THROW_IF_NOT(InputError, !entries.empty()) << source << ": lists no furniture (no name#N/model#N keys)";
  return FurnitureCatalog(std::move(archive), std::move(info), std::move(entries), options);
}

const std::string& FurnitureCatalog::path() const { return archive_->path(); }

const FurnitureEntry& FurnitureCatalog::Find(const std::string& name_or_id) const {
  for (const FurnitureEntry& entry : entries_) {
    if (!entry.id.empty() && entry.id == name_or_id) return entry;
  }
  std::vector<const FurnitureEntry*> matches;
  for (const FurnitureEntry& entry : entries_) {
    if (!entry.id.empty() && entry.Key() == name_or_id) matches.push_back(&entry);
  }
  if (matches.empty()) {
    for (const FurnitureEntry& entry : entries_) {
      if (entry.name == name_or_id) matches.push_back(&entry);
    }
  }
  SLAM_THROW_IF_NOT(InputError, !matches.empty()) << path() << ": no model '" << name_or_id << "' in the catalog";
  if (matches.size() > 1) {
    std::string ids;
    for (const FurnitureEntry* entry : matches) ids += (ids.empty() ? "" : ", ") + entry->Key();
    SLAM_THROW(InputError) << path() << ": model name '" << name_or_id << "' is ambiguous (" << matches.size()
                           << " pieces: " << ids << "); give an id";
  }
  return *matches.front();
}

bool FurnitureCatalog::Contains(const std::string& path_in_zip) const { return archive_->Contains(path_in_zip); }

std::string FurnitureCatalog::ReadFile(const std::string& path_in_zip) const {
  return archive_->Read(path_in_zip, options_.max_file_bytes);
}

MeshFiles FurnitureCatalog::Files() const {
  const ZipArchive* archive = archive_.get();
  const int64_t max_bytes = options_.max_file_bytes;
  MeshFiles files;
  files.container = archive->path();
  files.read = [archive, max_bytes](const std::string& path) -> std::optional<std::string> {
    if (!archive->Contains(path)) return std::nullopt;
    return archive->Read(path, max_bytes);
  };
  return files;
}

}  // namespace duskmap
