#include "slam/synthetic/depth_sensor.h"

#include <cmath>

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
                      cv::RNG& rng) {
  const cv::Mat& z = view.depth_m;
  cv::Mat out(z.size(), CV_32FC1, cv::Scalar(0.0f));
  cv::Mat noise(z.size(), CV_32FC1), uniform(z.size(), CV_32FC1);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, 1.0);
  rng.fill(uniform, cv::RNG::UNIFORM, 0.0, 1.0);
  for (int r = 0; r < z.rows; ++r) {
    const float* zr = z.ptr<float>(r);
    const int* id = view.surface_id.ptr<int>(r);
    const float* cos_r = view.cos_incidence.ptr<float>(r);
    const float* nz = noise.ptr<float>(r);
    const float* un = uniform.ptr<float>(r);
    float* o = out.ptr<float>(r);
    for (int c = 0; c < z.cols; ++c) {
      const double d = zr[c];
      if (id[c] < 0 || scene.quads[id[c]].emission == Emission::kSky) continue;  // glass
      if (d < options.min_range_m || d > options.max_range_m) continue;
      if (cos_r[c] < options.min_cos_incidence) continue;
      if (un[c] < options.dropout_probability) continue;
      bool edge = false;
      for (int dr = -1; dr <= 1 && !edge; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          const int rr = r + dr, cc = c + dc;
          if (rr < 0 || cc < 0 || rr >= z.rows || cc >= z.cols) continue;
          if (std::abs(z.at<float>(rr, cc) - d) > options.edge_jump_m) {
            edge = true;
            break;
          }
        }
      }
      // Reuse the uniform sample, rescaled, for the edge decision.
      if (edge && un[c] < options.dropout_probability + options.edge_dropout_probability * (1.0 - options.dropout_probability)) continue;
      const double sigma = options.noise_base_m + options.noise_quadratic * (d - 0.4) * (d - 0.4);
      o[c] = static_cast<float>(d + sigma * nz[c]);
    }
  }
  return out;
}

}  // namespace duskmap
