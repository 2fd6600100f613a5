#include "slam/io/calibration.h"

#include <fstream>

#include <nlohmann/json.hpp>

#include "slam/core/check.h"
#include "slam/core/system_error.h"
#include "slam/core/json_fields.h"
#include "slam/io/calibration_json.h"

namespace duskmap {

TumCalibration ReadCalibration(const std::string& path) {
  nlohmann::json json;
  try {
    json = ReadJsonFile(path);
  } catch (const ConfigError& e) {
    throw InputError(e.what());
  }
  TumCalibration c;
  try {
    c = ReadJsonOptions<TumCalibration>(json, path);
  } catch (const ConfigError& e) {
    throw InputError(e.what());
  }
  SLAM_THROW_IF_NOT(InputError, c.camera.IsValid()) << path << ": invalid intrinsics";
  // Raw 16-bit depth units per metre: 1000 (millimetres) and 5000 (TUM) are
  // usual; below 1 a unit is over a metre, above 1e5 the range is under 0.66 m.
  SLAM_THROW_IF_NOT(InputError, c.depth_scale >= kMinDepthScale && c.depth_scale <= kMaxDepthScale)
      << path << ": depth_scale must be in [1, 100000] raw units per metre (1000 = millimetres), got "
      << c.depth_scale;
  return c;
}

void WriteCalibration(const std::string& path, const TumCalibration& c) {
  const nlohmann::json json = ToJsonObject(c);
  std::ofstream out(path);
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": cannot write calibration";
  out << json.dump(2) << "\n";
  SLAM_THROW_IF_NOT(InputError, out.good()) << path << ": write failed: " << LastSystemError();
}

TumCalibration DefaultTumCalibration(const std::string& folder_name) {
  TumCalibration c;
  c.depth_scale = 5000.0;
  c.camera.width = 640;
  c.camera.height = 480;
  auto set = [&c](double fx, double fy, double cx, double cy) {
    c.camera.fx = fx;
    c.camera.fy = fy;
    c.camera.cx = cx;
    c.camera.cy = cy;
  };
  if (folder_name.find("freiburg1") != std::string::npos) {
    set(517.3, 516.5, 318.6, 255.3);
  } else if (folder_name.find("freiburg2") != std::string::npos) {
    set(520.9, 521.0, 325.1, 249.7);
  } else if (folder_name.find("freiburg3") != std::string::npos) {
    set(535.4, 539.2, 320.1, 247.6);
  } else {
    set(525.0, 525.0, 319.5, 239.5);
  }
  return c;
}

}  // namespace duskmap
