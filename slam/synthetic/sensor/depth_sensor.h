// The registered depth of a structured-light RGB-D sensor: axial noise
// growing with the square of the distance (Nguyen et al. 2012 Kinect model),
// no return through glass, beyond the maximum range, at grazing angles or at
// random/edge dropouts. Seeded.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "slam/synthetic/render/renderer.h"
#include "slam/synthetic/scene/scene.h"
#include "slam/synthetic/sensor/sensor_noise.h"

namespace duskmap {

struct DepthSensorOptions {
  double min_range_m = 0.4;        // closer surfaces give no depth
  double max_range_m = 4.0;        // farther surfaces give no depth
  double noise_base_m = 0.0012;    // sigma(z) = base + quadratic * (z - 0.4)^2
  double noise_quadratic = 0.0019; // 1/m
  double min_cos_incidence = 0.2;  // grazing angles below acos(0.2) = 78 deg give no depth
  double dropout_probability = 0.01;       // random missing pixels
  double edge_dropout_probability = 0.5;   // at depth discontinuities
  double edge_jump_m = 0.1;                // depth step that counts as a discontinuity

  void Check() const;
};

// Depth image (metres, 0 = none) of a rendered view.
cv::Mat SimulateDepth(const DepthSensorOptions& options, const Scene& scene, const RenderedView& view,
                      SensorNoise& noise);

}  // namespace duskmap
