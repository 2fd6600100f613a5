// libFuzzer target: the calibration YAML parser must either return a checked
// calibration or throw duskmap::Error, for any input.
#include <cstddef>
#include <cstdint>
#include <string>

#include "slam/core/check.h"
#include "slam/datasets/calibration_yaml.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const duskmap::CameraCalibration calibration = duskmap::ParseCalibrationYaml(
        std::string(reinterpret_cast<const char*>(data), size), "fuzz.yaml");
    duskmap::CameraForImage(calibration, calibration.image_width, calibration.image_height,
                            "fuzz.yaml");
  } catch (const duskmap::Error&) {
  }
  return 0;
}
