#include "slam/datasets/poses_file.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "slam/core/check.h"
#include "slam/core/input_file.h"

namespace duskmap {
namespace {

constexpr double kMaxQuaternionNormError = 1e-3;

bool ParseDouble(const std::string& token, double* value) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && errno != ERANGE;
}

bool ParseInt64(const std::string& token, int64_t* value) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  *value = std::strtoll(token.c_str(), &end, 10);
  return end == token.c_str() + token.size() && errno != ERANGE;
}

// Parses one non-comment line; returns an empty string or the problem.
std::string ParseLine(const std::string& text, PoseLine* pose) {
  std::istringstream stream(text);
  std::vector<std::string> tokens;
  for (std::string token; stream >> token;) tokens.push_back(token);
  if (tokens.size() != 8 && tokens.size() != 9) {
    return "expected 'stamp x y z qx qy qz qw [id]', got " + std::to_string(tokens.size()) +
           " fields";
  }
  double values[8];
  for (int i = 0; i < 8; ++i) {
    if (!ParseDouble(tokens[i], &values[i])) return "field " + std::to_string(i + 1) + " '" +
                                                     tokens[i] + "' is not a number";
    if (!std::isfinite(values[i])) return "non-finite value '" + tokens[i] + "'";
  }
  if (tokens.size() == 9 && !ParseInt64(tokens[8], &pose->id)) {
    return "id '" + tokens[8] + "' is not an integer";
  }
  const Eigen::Quaterniond q(values[7], values[4], values[5], values[6]);
  if (std::abs(q.norm() - 1.0) > kMaxQuaternionNormError) {
    return "quaternion is not unit length (norm " + std::to_string(q.norm()) + ")";
  }
  pose->stamp_s = values[0];
  pose->stamp_text = tokens[0];
  pose->map_from_frame = Rigid3d(q, Eigen::Vector3d(values[1], values[2], values[3]));
  return "";
}

}  // namespace

PosesFile ParsePosesText(const std::string& text) {
  PosesFile file;
  std::istringstream stream(text);
  std::string line;
  for (int number = 1; std::getline(stream, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    PoseLine pose;
    pose.line = number;
    std::string problem = ParseLine(line, &pose);
    if (problem.empty() && !file.poses.empty() && !(pose.stamp_s > file.poses.back().stamp_s)) {
      problem = "timestamp " + pose.stamp_text + " is not after the previous one (" +
                file.poses.back().stamp_text + ")";
    }
    if (problem.empty()) {
      file.poses.push_back(std::move(pose));
    } else {
      file.bad_lines.push_back({number, problem});
    }
  }
  return file;
}

PosesFile ReadPosesFile(const std::string& path) {
  RefuseNonRegularFile(path);  // before opening: a FIFO would block
  std::ifstream in(path, std::ios::binary);
  SLAM_THROW_IF_NOT(InputError, in.good()) << path << ": cannot open pose file";
  std::ostringstream contents;
  contents << in.rdbuf();
  return ParsePosesText(contents.str());
}

}  // namespace duskmap
