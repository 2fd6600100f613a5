#include "slam/datasets/calibration_yaml.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "slam/core/check.h"
#include "slam/core/input_file.h"

namespace duskmap {
namespace {

struct YamlEntry {
  int line = 0;
  std::string scalar;                        // the value of `key: value`
  std::map<std::string, std::string> items;  // the children of `key:` (one level)
};
using YamlDocument = std::map<std::string, YamlEntry>;

std::string Trim(const std::string& s) {
  const size_t first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

std::string Unquote(const std::string& s) {
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) {
    return s.substr(1, s.size() - 2);
  }
  return s;
}

// Splits "key: value" at the first ':' followed by a space or the line end.
bool SplitKey(const std::string& text, std::string* key, std::string* value) {
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == ':' && (i + 1 == text.size() || text[i + 1] == ' ')) {
      *key = Trim(text.substr(0, i));
      *value = Trim(text.substr(i + 1));
      return !key->empty();
    }
  }
  return false;
}

// Parses the lines into top-level entries with one level of children; a flow
// list `[ ... ]` may span several lines.
YamlDocument ParseDocument(const std::string& text, const std::string& where) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) lines.push_back(line);
  YamlDocument document;
  YamlEntry* parent = nullptr;
  for (size_t i = 0; i < lines.size(); ++i) {
    const int number = static_cast<int>(i) + 1;
    const std::string trimmed = Trim(lines[i]);
    if (trimmed.empty() || trimmed[0] == '#' || trimmed[0] == '%' || trimmed == "---" ||
        trimmed == "...") {
      continue;
    }
    const bool is_child = lines[i].find_first_not_of(" \t") > 0;
    std::string key, value;
    SLAM_THROW_IF_NOT(InputError, SplitKey(trimmed, &key, &value))
        << where << ":" << number << ": expected 'key: value'";
    if (!value.empty() && value[0] == '[') {
      while (value.find(']') == std::string::npos && i + 1 < lines.size()) {
        value += " " + Trim(lines[++i]);
      }
      SLAM_THROW_IF_NOT(InputError, value.back() == ']')
          << where << ":" << number << ": unterminated list for '" << key << "'";
    }
    if (is_child) {
      SLAM_THROW_IF_NOT(InputError, parent != nullptr)
          << where << ":" << number << ": indented key '" << key << "' without a parent";
      parent->items[key] = value;
      continue;
    }
    SLAM_THROW_IF_NOT(InputError, document.count(key) == 0)
        << where << ":" << number << ": duplicate key '" << key << "'";
    YamlEntry& entry = document[key];
    entry.line = number;
    const bool tag_only = value.rfind("!!", 0) == 0;
    entry.scalar = tag_only ? "" : value;
    parent = entry.scalar.empty() ? &entry : nullptr;
  }
  return document;
}

bool ToDouble(const std::string& token, double* value) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && errno != ERANGE;
}

int ReadInt(const YamlEntry& entry, const std::string& key, const std::string& where) {
  double value = 0.0;
  SLAM_THROW_IF_NOT(InputError, ToDouble(entry.scalar, &value) && value == std::floor(value) &&
                                    value >= 0.0 && value < 1e6)
      << where << ":" << entry.line << ": " << key << " '" << entry.scalar
      << "' is not an image size";
  return static_cast<int>(value);
}

// A {rows, cols, data} matrix with the expected shape (cols = 0: any).
std::vector<double> ReadMatrix(const YamlDocument& document, const std::string& key,
                               int rows, int cols, const std::string& where) {
  const YamlEntry& entry = document.at(key);
  const std::string at = where + ":" + std::to_string(entry.line) + ": " + key;
  double r = 0.0, c = 0.0;
  SLAM_THROW_IF_NOT(InputError, entry.items.count("rows") && entry.items.count("cols") &&
                                    entry.items.count("data"))
      << at << ": expected a {rows, cols, data} matrix";
  SLAM_THROW_IF_NOT(InputError, ToDouble(entry.items.at("rows"), &r) &&
                                    ToDouble(entry.items.at("cols"), &c))
      << at << ": rows/cols are not numbers";
  SLAM_THROW_IF_NOT(InputError, r == rows && (cols == 0 ? c >= 1 && c <= 16 : c == cols))
      << at << ": expected a " << rows << "x" << (cols == 0 ? std::string("N")
                                                          : std::to_string(cols))
      << " matrix, got " << r << "x" << c;
  std::string data = entry.items.at("data");
  SLAM_THROW_IF_NOT(InputError, data.size() >= 2 && data.front() == '[' && data.back() == ']')
      << at << ": data is not a [ ... ] list";
  data = data.substr(1, data.size() - 2);
  std::vector<double> values;
  std::istringstream stream(data);
  for (std::string token; std::getline(stream, token, ',');) {
    double value = 0.0;
    SLAM_THROW_IF_NOT(InputError, ToDouble(Trim(token), &value))
        << at << ": '" << Trim(token) << "' is not a number";
    values.push_back(value);
  }
  SLAM_THROW_IF_NOT(InputError, values.size() == static_cast<size_t>(r * c))
      << at << ": " << values.size() << " values for a " << r << "x" << c << " matrix";
  return values;
}

void ReadDistortion(const YamlDocument& document, const std::string& where,
                    CameraCalibration* calibration) {
  if (!document.count("distortion_coefficients")) return;
  calibration->distortion = ReadMatrix(document, "distortion_coefficients", 1, 0, where);
  const auto model = document.find("distortion_model");
  calibration->fisheye =
      model != document.end() && Unquote(model->second.scalar) == "equidistant";
  const size_t n = calibration->distortion.size();
  SLAM_THROW_IF_NOT(InputError, calibration->fisheye ? n == 4 : (n == 4 || n == 5 || n == 8 ||
                                                                 n == 12 || n == 14))
      << where << ":" << document.at("distortion_coefficients").line
      << ": unsupported number of distortion coefficients " << n;
}

}  // namespace

CameraCalibration ParseCalibrationYaml(const std::string& text, const std::string& where) {
  const YamlDocument document = ParseDocument(text, where);
  for (const char* key : {"image_width", "image_height", "camera_matrix", "local_transform"}) {
    SLAM_THROW_IF_NOT(InputError, document.count(key))
        << where << ": missing required key '" << key << "'";
  }
  CameraCalibration calibration;
  if (document.count("camera_name")) calibration.name = Unquote(document.at("camera_name").scalar);
  calibration.image_width = ReadInt(document.at("image_width"), "image_width", where);
  calibration.image_height = ReadInt(document.at("image_height"), "image_height", where);
  const std::vector<double> k = ReadMatrix(document, "camera_matrix", 3, 3, where);
  calibration.camera_matrix = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(k.data());
  ReadDistortion(document, where, &calibration);
  if (document.count("rectification_matrix")) {
    const std::vector<double> r = ReadMatrix(document, "rectification_matrix", 3, 3, where);
    calibration.rectification =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(r.data());
  }
  if (document.count("projection_matrix")) {
    const std::vector<double> p = ReadMatrix(document, "projection_matrix", 3, 4, where);
    calibration.projection =
        Eigen::Map<const Eigen::Matrix<double, 3, 4, Eigen::RowMajor>>(p.data());
  }
  const std::vector<double> t = ReadMatrix(document, "local_transform", 3, 4, where);
  calibration.body_from_camera = RigidFromRowMajor3x4(
      t.data(), where + ":" + std::to_string(document.at("local_transform").line));
  CheckCalibration(calibration, where);
  return calibration;
}

CameraCalibration ReadCalibrationYaml(const std::string& path) {
  RefuseNonRegularFile(path);  // before opening: a FIFO would block
  std::ifstream in(path, std::ios::binary);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path << ": cannot open calibration file";
  std::ostringstream contents;
  contents << in.rdbuf();
  return ParseCalibrationYaml(contents.str(), path);
}

}  // namespace duskmap
