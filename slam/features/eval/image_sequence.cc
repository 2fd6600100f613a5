#include "slam/features/eval/image_sequence.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include "slam/core/check.h"

namespace duskmap {
namespace fs = std::filesystem;
namespace {

constexpr const char* kImageExtensions[] = {".ppm", ".png", ".jpg", ".jpeg", ".pgm", ".bmp"};
constexpr const char* kImagePattern = "{ppm,png,jpg,jpeg,pgm,bmp}";

std::string Lowercase(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

bool IsImageFile(const fs::path& path) {
  const std::string extension = Lowercase(path.extension().string());
  for (const char* e : kImageExtensions) {
    if (extension == e) return true;
  }
  return false;
}

// The entries of `folder` (sorted); InputError when it cannot be listed.
std::vector<fs::directory_entry> Entries(const fs::path& folder) {
  std::error_code error;
  std::vector<fs::directory_entry> entries;
  fs::directory_iterator it(folder, error);
  for (; !error && it != fs::directory_iterator(); it.increment(error)) entries.push_back(*it);
  SLAM_THROW_IF_NOT(InputError, !error) << folder.string() << ": " << error.message();
  std::sort(entries.begin(), entries.end(),
            [](const fs::directory_entry& a, const fs::directory_entry& b) { return a.path() < b.path(); });
  return entries;
}

bool IsRegularFile(const fs::directory_entry& entry) {
  std::error_code error;
  return entry.is_regular_file(error);
}

bool IsFolder(const fs::directory_entry& entry) {
  std::error_code error;
  return entry.is_directory(error);
}

std::vector<fs::path> ImageFiles(const fs::path& folder) {
  std::vector<fs::path> images;
  for (const fs::directory_entry& entry : Entries(folder)) {
    if (IsRegularFile(entry) && IsImageFile(entry.path())) images.push_back(entry.path());
  }
  return images;
}

// The imgN images by N; InputError when two files claim one N.
std::map<int, fs::path> NumberedImages(const fs::path& folder, const std::vector<fs::path>& images) {
  static const std::regex kNumbered("img([0-9]{1,6})");
  std::map<int, fs::path> numbered;
  for (const fs::path& image : images) {
    std::smatch match;
    const std::string stem = image.stem().string();
    if (!std::regex_match(stem, match, kNumbered)) continue;
    const int index = std::stoi(match[1].str());
    const auto [it, inserted] = numbered.emplace(index, image);
    SLAM_THROW_IF_NOT(InputError, inserted)
        << folder.string() << ": " << it->second.filename().string() << " and " << image.filename().string()
        << " are both image " << index;
  }
  return numbered;
}

// The (i, j) of every H<i>to<j>p file in `folder`.
std::set<std::pair<int, int>> HomographyFiles(const fs::path& folder) {
  static const std::regex kHomography("H([0-9]{1,6})to([0-9]{1,6})p");
  std::set<std::pair<int, int>> files;
  for (const fs::directory_entry& entry : Entries(folder)) {
    std::smatch match;
    const std::string name = entry.path().filename().string();
    if (IsRegularFile(entry) && std::regex_match(name, match, kHomography)) {
      files.emplace(std::stoi(match[1].str()), std::stoi(match[2].str()));
    }
  }
  return files;
}

cv::Matx33d ReadHomography(const fs::path& path) {
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path.string() << ": cannot open homography";
  std::ostringstream text;
  text << in.rdbuf();
  return ParseHomography(text.str(), path.string());
}

bool IsFinite(const cv::Matx33d& m) {
  for (const double v : m.val) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

fs::path HomographyPath(const std::string& directory, int from, int to) {
  return fs::path(directory) / ("H" + std::to_string(from) + "to" + std::to_string(to) + "p");
}

std::string FolderName(const fs::path& dir) {
  return dir.filename().empty() ? dir.parent_path().filename().string() : dir.filename().string();
}

bool HoldsImages(const fs::path& folder) { return !ImageFiles(folder).empty(); }

std::string IndexList(const ImageSequence& sequence) {
  std::string list;
  for (const SequenceImage& image : sequence.images) {
    list += (list.empty() ? "" : ", ") + std::to_string(image.index);
  }
  return list;
}

void ReadHomographyLayout(const fs::path& dir, const std::map<int, fs::path>& numbered, ImageSequence* seq) {
  SLAM_THROW_IF_NOT(InputError, numbered.count(1) == 1)
      << dir.string() << ": no reference image img1." << kImagePattern;
  const std::set<std::pair<int, int>> files = HomographyFiles(dir);
  for (const auto& [from, to] : files) {
    SLAM_THROW_IF_NOT(InputError, from != 1 || to == 1 || numbered.count(to) == 1)
        << (dir / ("img" + std::to_string(to))).string() << "." << kImagePattern << ": missing (H1to"
        << to << "p names it)";
  }
  for (const auto& [index, path] : numbered) {
    seq->images.push_back({index, path.string()});
    if (index == 1) continue;
    SLAM_THROW_IF_NOT(InputError, files.count({1, index}) == 1)
        << HomographyPath(seq->directory, 1, index).string() << ": missing (" << path.filename().string()
        << " has no homography; a sequence with H files needs H1toNp for each imgN, or --layout static for a "
           "fixed camera)";
    seq->pairs.push_back({1, index, ReadHomography(HomographyPath(seq->directory, 1, index))});
  }
  SLAM_THROW_IF_NOT(InputError, !seq->pairs.empty())
      << dir.string() << ": no target image with a homography (img2 + H1to2p)";
}

void ReadStaticLayout(const fs::path& dir, const std::vector<fs::path>& files,
                      const std::map<int, fs::path>& numbered, ImageSequence* seq) {
  if (!numbered.empty()) {
    for (const auto& [index, path] : numbered) seq->images.push_back({index, path.string()});
  } else {
    for (size_t i = 0; i < files.size(); ++i) seq->images.push_back({static_cast<int>(i) + 1, files[i].string()});
  }
  SLAM_THROW_IF_NOT(InputError, seq->images.size() >= 2)
      << dir.string() << ": " << seq->images.size()
      << " image(s); a fixed camera's sequence needs two or more (img1, img2, ... or any names)";
  for (size_t i = 1; i < seq->images.size(); ++i) {
    seq->pairs.push_back({seq->images[0].index, seq->images[i].index, cv::Matx33d::eye()});
  }
}

}  // namespace

cv::Matx33d ParseHomography(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  cv::Matx33d h;
  for (int i = 0; i < 9; ++i) {
    SLAM_THROW_IF_NOT(InputError, static_cast<bool>(in >> h.val[i]) && std::isfinite(h.val[i]))
        << path << ": expected 9 finite numbers";
  }
  const double determinant = cv::determinant(h);
  SLAM_THROW_IF_NOT(InputError, std::abs(determinant) > 1e-12) << path << ": singular homography";
  // Entries near the double range pass the checks above with an infinite
  // determinant, and pairs composed through the reference need the inverse.
  SLAM_THROW_IF_NOT(InputError, std::isfinite(determinant) && IsFinite(h.inv()))
      << path << ": homography out of range (its determinant or inverse is not finite)";
  return h;
}

const char* SequenceLayoutName(SequenceLayout layout) {
  return layout == SequenceLayout::kStatic ? "static" : "homography";
}

const SequenceImage* ImageSequence::Image(int index) const {
  for (const SequenceImage& image : images) {
    if (image.index == index) return &image;
  }
  return nullptr;
}

bool HasHomographyFiles(const std::string& directory) { return !HomographyFiles(directory).empty(); }

ImageSequence ReadImageSequence(const std::string& directory, SequenceLayout layout) {
  const fs::path dir(directory);
  std::error_code error;
  SLAM_THROW_IF_NOT(InputError, fs::is_directory(dir, error)) << directory << ": not a directory";
  ImageSequence seq;
  seq.name = FolderName(dir);
  seq.directory = directory;
  seq.layout = layout;
  const std::vector<fs::path> files = ImageFiles(dir);
  const std::map<int, fs::path> numbered = NumberedImages(dir, files);
  if (layout == SequenceLayout::kHomography) {
    ReadHomographyLayout(dir, numbered, &seq);
  } else {
    ReadStaticLayout(dir, files, numbered, &seq);
  }
  return seq;
}

SequenceSet FindImageSequences(const std::string& root, std::optional<SequenceLayout> layout) {
  std::error_code error;
  SLAM_THROW_IF_NOT(InputError, fs::is_directory(root, error)) << root << ": not a directory";
  std::vector<std::string> dirs;
  for (const fs::directory_entry& entry : Entries(root)) {
    if (IsFolder(entry) && HoldsImages(entry.path())) dirs.push_back(entry.path().string());
  }
  const std::vector<fs::path> root_images = ImageFiles(root);
  if (!root_images.empty() && (NumberedImages(root, root_images).count(1) == 1 || dirs.empty())) {
    dirs = {root};
  }
  SLAM_THROW_IF_NOT(InputError, !dirs.empty())
      << root << ": no image sequence here or in its sub-folders (imgN images, with H1toNp homographies "
         "or from a fixed camera)";
  SequenceSet set;
  set.detected = !layout.has_value();
  if (layout.has_value()) {
    set.layout = *layout;
  } else {
    std::string with_h, without_h;
    for (const std::string& d : dirs) (HasHomographyFiles(d) ? with_h : without_h) = d;
    SLAM_THROW_IF_NOT(InputError, with_h.empty() || without_h.empty())
        << without_h << ": no H1toNp file, while " << with_h
        << " has them (a homography sequence needs H1toNp for each imgN; --layout static evaluates every "
           "sequence as a fixed camera)";
    set.layout = with_h.empty() ? SequenceLayout::kStatic : SequenceLayout::kHomography;
  }
  for (const std::string& d : dirs) set.sequences.push_back(ReadImageSequence(d, set.layout));
  return set;
}

void SelectSequencePairs(const std::vector<PairSelector>& selectors, std::vector<ImageSequence>* sequences) {
  std::vector<ImagePairSelector> parsed;
  for (const PairSelector& s : selectors) {
    parsed.push_back(ParseImagePairSelector(s));
    if (parsed.back().sequence.empty()) continue;
    const bool known = std::any_of(sequences->begin(), sequences->end(),
                                   [&](const ImageSequence& q) { return q.name == parsed.back().sequence; });
    std::string names;
    for (const ImageSequence& q : *sequences) names += (names.empty() ? "" : ", ") + q.name;
    SLAM_THROW_IF_NOT(ConfigError, known)
        << s.origin << ": pair '" << s.text << "': no sequence '" << parsed.back().sequence
        << "' (sequences: " << names << ")";
  }
  std::vector<ImageSequence> kept;  // *sequences is left as it was when a selector fails
  for (ImageSequence seq : *sequences) {
    std::vector<SequencePair> pairs;
    for (size_t k = 0; k < parsed.size(); ++k) {
      const ImagePairSelector& p = parsed[k];
      if (!p.sequence.empty() && p.sequence != seq.name) continue;
      for (const int index : {p.first_index, p.second_index}) {
        SLAM_THROW_IF_NOT(ConfigError, seq.Image(index) != nullptr)
            << selectors[k].origin << ": pair '" << selectors[k].text << "' does not exist in sequence "
            << seq.name << " (no image " << index << "; images " << IndexList(seq) << ")";
      }
      SequencePair pair{p.first_index, p.second_index, cv::Matx33d::eye()};
      if (seq.layout == SequenceLayout::kHomography) {
        const fs::path direct = HomographyPath(seq.directory, p.first_index, p.second_index);
        std::error_code error;
        if (fs::is_regular_file(direct, error)) {
          pair.second_from_first = ReadHomography(direct);
        } else {
          // Every image has H1toNp (checked when read): compose through the reference.
          const auto from_reference = [&](int index) {
            return index == 1 ? cv::Matx33d::eye() : ReadHomography(HomographyPath(seq.directory, 1, index));
          };
          pair.second_from_first = from_reference(p.second_index) * from_reference(p.first_index).inv();
          SLAM_THROW_IF_NOT(InputError, IsFinite(pair.second_from_first))
              << seq.directory << ": pair '" << selectors[k].text << "' composed as H1to" << p.second_index
              << "p * H1to" << p.first_index << "p^-1 is not finite (entries out of range)";
        }
      }
      pairs.push_back(pair);
    }
    if (pairs.empty()) continue;
    seq.pairs = std::move(pairs);
    kept.push_back(std::move(seq));
  }
  *sequences = std::move(kept);
}

}  // namespace duskmap
