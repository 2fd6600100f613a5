#include "slam/features/eval/eval_pairs.h"

#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

#include "slam/core/check.h"
#include "slam/core/input_file.h"

namespace duskmap {
namespace {

std::string Trimmed(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const size_t end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

// Appends the comma-separated items of `text`; false when one is empty.
bool AppendItems(const std::string& text, const std::string& origin, std::vector<PairSelector>* out) {
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    const std::string item = Trimmed(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (item.empty()) return false;
    out->push_back({item, origin});
    if (comma == std::string::npos) return true;
    start = comma + 1;
  }
}

void CheckNoDuplicate(const std::vector<PairSelector>& selectors) {
  std::set<std::string> seen;
  for (const PairSelector& s : selectors) {
    SLAM_THROW_IF_NOT(ConfigError, seen.insert(s.text).second)
        << s.origin << ": pair '" << s.text << "' listed twice";
  }
}

// A positive decimal index (no sign, at most 6 digits); 0 when `text` is not one.
int ParseIndex(const std::string& text) {
  if (text.empty() || text.size() > 6) return 0;
  int value = 0;
  for (const char c : text) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return 0;
    value = value * 10 + (c - '0');
  }
  return value;
}

}  // namespace

std::vector<PairSelector> ParsePairList(const std::string& list) {
  // Checked first: every later message quotes the list or an item of it.
  SLAM_THROW_IF_NOT(ConfigError, list.find('\n') == std::string::npos)
      << "--pairs: the list holds a line break (one line, e.g. 1-5,1-6; a file of pairs goes to --pairs-file)";
  std::vector<PairSelector> selectors;
  SLAM_THROW_IF_NOT(ConfigError, AppendItems(list, "--pairs", &selectors))
      << "--pairs: '" << list << "' has an empty item (expected e.g. 1-5,1-6)";
  CheckNoDuplicate(selectors);
  return selectors;
}

std::vector<PairSelector> ReadPairListFile(const std::string& path) {
  RefuseNonRegularFile(path, "--pairs-file");  // before opening: a FIFO would block
  std::ifstream in(path);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path << ": cannot read the pair list";
  std::string text;  // read by lines: getline marks a read error on `in` (bad())
  for (std::string line; std::getline(in, line);) text += line + '\n';
  SLAM_THROW_IF_NOT(InputError, !in.bad()) << path << ": read failed";
  return ParsePairListText(text, path);
}

std::vector<PairSelector> ParsePairListText(const std::string& text, const std::string& path) {
  std::istringstream in(text);
  std::vector<PairSelector> selectors;
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    const std::string items = Trimmed(line.substr(0, line.find('#')));
    if (items.empty()) continue;
    const std::string origin = path + ":" + std::to_string(line_number);
    SLAM_THROW_IF_NOT(ConfigError, AppendItems(items, origin, &selectors))
        << origin << ": '" << items << "' has an empty item";
  }
  SLAM_THROW_IF_NOT(InputError, !selectors.empty()) << path << ": lists no pair";
  CheckNoDuplicate(selectors);
  return selectors;
}

ImagePairSelector ParseImagePairSelector(const PairSelector& selector) {
  ImagePairSelector pair;
  std::string indices = selector.text;
  const size_t slash = indices.rfind('/');
  if (slash != std::string::npos) {
    pair.sequence = indices.substr(0, slash);
    indices = indices.substr(slash + 1);
  }
  const size_t dash = indices.find('-');
  if (dash != std::string::npos) {
    pair.first_index = ParseIndex(indices.substr(0, dash));
    pair.second_index = ParseIndex(indices.substr(dash + 1));
  }
  SLAM_THROW_IF_NOT(ConfigError, (slash == std::string::npos || !pair.sequence.empty()) &&
                                     pair.first_index > 0 && pair.second_index > 0)
      << selector.origin << ": '" << selector.text
      << "' is not an image pair <i>-<j> or <sequence>/<i>-<j> (imgN's N, from 1)";
  SLAM_THROW_IF_NOT(ConfigError, pair.first_index != pair.second_index)
      << selector.origin << ": '" << selector.text << "' pairs an image with itself";
  return pair;
}

}  // namespace duskmap
