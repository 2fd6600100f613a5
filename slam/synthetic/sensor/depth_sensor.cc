#include "slam/synthetic/sensor/depth_sensor.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "slam/core/check.h"

namespace duskmap {

void DepthSensorOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, min_range_m >= 0 && max_range_m > min_range_m)
      << "depth.min_range_m/max_range_m must satisfy 0 <= min < max";
  SLAM_THROW_IF_NOT(ConfigError, noise_base_m >= 0 && noise_quadratic >= 0) << "depth noise coefficients must be >= 0";
  SLAM_THROW_IF_NOT(ConfigError, min_cos_incidence >= 0 && min_cos_incidence < 1)
      << "depth.min_cos_incidence must be in [0, 1), got " << min_cos_incidence;
  SLAM_THROW_IF_NOT(ConfigError, dropout_probability >= 0 && dropout_probability <= 1)
      << "depth.dropout_probability must be in [0, 1]";
  SLAM_THROW_IF_NOT(ConfigError, edge_dropout_probability >= 0 && edge_dropout_probability <= 1)
      << "depth.edge_dropout_probability must be in [0, 1]";
  SLAM_THROW_IF_NOT(ConfigError, edge_jump_m > 0) << "depth.edge_jump_m must be > 0";
}

cv::Mat SimulateDepth(const DepthSensorOptions& options, const Scene& scene, const RenderedView& view,
                      SensorNoise& noise) {
  const cv::Mat& z = view.depth_m;
  cv::Mat out(z.size(), CV_32FC1, cv::Scalar(0.0f));
  std::vector<float> normal(z.cols), uniform(z.cols);
  std::vector<uint8_t> glass(scene.quads.size());
  for (size_t i = 0; i < scene.quads.size(); ++i) glass[i] = scene.quads[i].emission == Emission::kSky;
  const int num_quads = static_cast<int>(scene.quads.size());
  const float min_range = static_cast<float>(options.min_range_m);
  const float max_range = static_cast<float>(options.max_range_m);
  const float min_cos = static_cast<float>(options.min_cos_incidence);
  const float edge_jump = static_cast<float>(options.edge_jump_m);
  const float dropout = static_cast<float>(options.dropout_probability);
  // The uniform sample decides both dropouts: below `dropout` always, below
  // `edge_dropout` when the pixel is at a depth discontinuity.
  const float edge_dropout = static_cast<float>(options.dropout_probability +
                                                options.edge_dropout_probability * (1.0 - options.dropout_probability));
  for (int r = 0; r < z.rows; ++r) {
    noise.FillNormal(normal.data(), z.cols);
    noise.FillUniform(uniform.data(), z.cols);
    const float* rows[3] = {z.ptr<float>(std::max(r - 1, 0)), z.ptr<float>(r), z.ptr<float>(std::min(r + 1, z.rows - 1))};
    const float* zr = rows[1];
    const int* id = view.surface_id.ptr<int>(r);
    const float* cos_r = view.cos_incidence.ptr<float>(r);
    float* o = out.ptr<float>(r);
    for (int c = 0; c < z.cols; ++c) {
      const float d = zr[c];
      if (id[c] < 0 || (id[c] < num_quads && glass[id[c]])) continue;  // meshes: >= num_quads
      if (d < min_range || d > max_range) continue;
      if (cos_r[c] < min_cos) continue;
      const float u = uniform[c];
      if (u < dropout) continue;
      if (u < edge_dropout) {
        // Edge test over the 3x3 neighbourhood (clamped at the border, where
        // the pixel itself stands in for the missing neighbour).
        const int c0 = std::max(c - 1, 0), c1 = std::min(c + 1, z.cols - 1);
        bool edge = false;
        for (int k = 0; k < 3 && !edge; ++k) {
          edge = std::abs(rows[k][c0] - d) > edge_jump || std::abs(rows[k][c] - d) > edge_jump ||
                 std::abs(rows[k][c1] - d) > edge_jump;
        }
        if (edge) continue;
      }
      const float e = d - 0.4f;
      const double sigma = options.noise_base_m + options.noise_quadratic * e * e;
      o[c] = static_cast<float>(d + sigma * normal[c]);
    }
  }
  return out;
}

}  // namespace duskmap
