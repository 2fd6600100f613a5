#include "slam/synthetic/assets/zip_archive.h"

#include <zip.h>

#include <filesystem>
#include <mutex>
#include <optional>

#include "slam/core/check.h"
#include "slam/synthetic/assets/archive_path.h"

namespace duskmap {
namespace {

std::string ZipErrorText(int code) {
  zip_error_t error;
  zip_error_init_with_code(&error, code);
  std::string text = zip_error_strerror(&error);
  zip_error_fini(&error);
  return text;
}

std::string OpenProblem(int code) {
  switch (code) {
    case ZIP_ER_NOZIP:
      return "not a ZIP archive";
    case ZIP_ER_INCONS:
      return "corrupt ZIP archive (" + ZipErrorText(code) + ")";
    default:
      return "cannot open the ZIP archive (" + ZipErrorText(code) + ")";
  }
}

struct FileCloser {
  void operator()(zip_file_t* file) const { zip_fclose(file); }
};

}  // namespace

struct ZipArchive::Impl {
  std::string path;
  zip_t* archive = nullptr;
  std::mutex mutex;  // libzip archives are not thread-safe

  ~Impl() {
    if (archive != nullptr) zip_discard(archive);
  }
  std::string Describe(const std::string& file) const { return path + "!/" + file; }
  // The index of a file entry, or nullopt.
  std::optional<zip_uint64_t> Locate(const std::string& archive_path) const {
    const zip_int64_t index = zip_name_locate(archive, archive_path.c_str(), 0);
    if (index < 0) return std::nullopt;
    return static_cast<zip_uint64_t>(index);
  }
};

ZipArchive::ZipArchive(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ZipArchive::ZipArchive(ZipArchive&&) noexcept = default;
ZipArchive& ZipArchive::operator=(ZipArchive&&) noexcept = default;
ZipArchive::~ZipArchive() = default;

ZipArchive ZipArchive::Open(const std::string& path) {
  SLAM_THROW_IF_NOT(InputError, std::filesystem::is_regular_file(path)) << path << ": no such file";
  int code = ZIP_ER_OK;
  zip_t* archive = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &code);
  SLAM_THROW_IF_NOT(InputError, archive != nullptr) << path << ": " << OpenProblem(code);
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->archive = archive;
  return ZipArchive(std::move(impl));
}

const std::string& ZipArchive::path() const { return impl_->path; }

std::vector<std::string> ZipArchive::FilePaths() const {
  std::lock_guard<std::mutex> lock(impl_->mutex);
  std::vector<std::string> paths;
  const zip_int64_t count = zip_get_num_entries(impl_->archive, 0);
  for (zip_int64_t i = 0; i < count; ++i) {
    const char* name = zip_get_name(impl_->archive, static_cast<zip_uint64_t>(i), 0);
    if (name == nullptr) continue;
    const std::string entry = name;
    if (entry.empty() || entry.back() == '/') continue;  // a folder
    if (NormalizeArchivePath(entry) == entry) paths.push_back(entry);
  }
  return paths;
}

bool ZipArchive::Contains(const std::string& archive_path) const {
  if (NormalizeArchivePath(archive_path) != archive_path) return false;
  std::lock_guard<std::mutex> lock(impl_->mutex);
  return impl_->Locate(archive_path).has_value();
}

std::string ZipArchive::Read(const std::string& archive_path, int64_t max_bytes) const {
  const std::optional<std::string> normalized = NormalizeArchivePath(archive_path);
  SLAM_THROW_IF_NOT(InputError, normalized.has_value())
      << impl_->Describe(archive_path) << ": path leaves the archive (absolute or '..')";
  std::lock_guard<std::mutex> lock(impl_->mutex);
  const std::optional<zip_uint64_t> index = impl_->Locate(*normalized);
  SLAM_THROW_IF_NOT(InputError, index.has_value()) << impl_->Describe(*normalized) << ": no such file in the archive";
  zip_stat_t stat;
  zip_stat_init(&stat);
  SLAM_THROW_IF_NOT(InputError, zip_stat_index(impl_->archive, *index, 0, &stat) == 0 && (stat.valid & ZIP_STAT_SIZE))
      << impl_->Describe(*normalized) << ": cannot read its size (" << zip_strerror(impl_->archive) << ")";
  SLAM_THROW_IF_NOT(InputError, stat.size <= static_cast<zip_uint64_t>(max_bytes))
      << impl_->Describe(*normalized) << ": " << stat.size << " bytes uncompressed, over the limit of " << max_bytes;
  std::unique_ptr<zip_file_t, FileCloser> file(zip_fopen_index(impl_->archive, *index, 0));
  SLAM_THROW_IF_NOT(InputError, file != nullptr)
      << impl_->Describe(*normalized) << ": cannot open (" << zip_strerror(impl_->archive) << ")";
  std::string bytes(stat.size, '\0');
  zip_uint64_t done = 0;
  while (done < stat.size) {
    const zip_int64_t got = zip_fread(file.get(), bytes.data() + done, stat.size - done);
    SLAM_THROW_IF_NOT(InputError, got >= 0)
        << impl_->Describe(*normalized) << ": corrupt data (" << zip_file_strerror(file.get()) << ")";
    SLAM_THROW_IF_NOT(InputError, got > 0)
        << impl_->Describe(*normalized) << ": data end after " << done << " of " << stat.size << " bytes";
    done += static_cast<zip_uint64_t>(got);
  }
  // The checksum is verified when the end of the data is read: read past it.
  char extra = 0;
  const zip_int64_t tail = zip_fread(file.get(), &extra, 1);
  SLAM_THROW_IF_NOT(InputError, tail == 0)
      << impl_->Describe(*normalized) << ": corrupt data ("
      << (tail < 0 ? zip_file_strerror(file.get()) : "longer than its recorded size") << ")";
  return bytes;
}

}  // namespace duskmap
