#include "slam/vocabulary/synthetic_descriptors.h"

#include <algorithm>
#include <limits>
#include <random>

#include "slam/core/check.h"
#include "slam/core/random.h"

namespace duskmap {

void SyntheticDescriptorOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError, cols > 0) << "SyntheticDescriptorOptions.cols must be > 0, got " << cols;
  SLAM_THROW_IF_NOT(ConfigError, float_noise_sigma >= 0.0)
      << "SyntheticDescriptorOptions.float_noise_sigma must be >= 0, got " << float_noise_sigma;
  SLAM_THROW_IF_NOT(ConfigError, bit_flip_probability >= 0.0 && bit_flip_probability <= 1.0)
      << "SyntheticDescriptorOptions.bit_flip_probability must be in [0, 1], got "
      << bit_flip_probability;
}

SyntheticDescriptors::SyntheticDescriptors(const SyntheticDescriptorOptions& options)
    : options_(options) {
  options_.Check();
}

void SyntheticDescriptors::Prototype(uint64_t stream, uint8_t* row) const {
  Rng rng(DeriveSeed(options_.seed, stream));
  if (options_.kind == DescriptorKind::kFloat) {
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    float* f = reinterpret_cast<float*>(row);
    for (int i = 0; i < options_.cols; ++i) f[i] = uniform(rng);
  } else {
    for (int i = 0; i < options_.cols; i += 8) {
      const uint64_t bits = rng();
      for (int k = 0; k < 8 && i + k < options_.cols; ++k) row[i + k] = (bits >> (8 * k)) & 0xFF;
    }
  }
}

cv::Mat SyntheticDescriptors::Observe(const std::vector<int64_t>& landmarks, int appearance,
                                      double keep_probability, uint64_t observation_seed) const {
  const int type = options_.kind == DescriptorKind::kFloat ? CV_32F : CV_8U;
  cv::Mat rows(static_cast<int>(landmarks.size()), options_.cols, type);
  Rng noise(DeriveSeed(options_.seed ^ 0x5EEDull, observation_seed));
  std::normal_distribution<float> gauss(0.0f, static_cast<float>(options_.float_noise_sigma));
  std::bernoulli_distribution flip(options_.bit_flip_probability);
  for (size_t r = 0; r < landmarks.size(); ++r) {
    const uint64_t base = static_cast<uint64_t>(landmarks[r]) * 1024;
    uint64_t stream = base;
    if (appearance != 0) {
      Rng pair(DeriveSeed(options_.seed + 7, base + static_cast<uint64_t>(appearance)));
      if (std::uniform_real_distribution<double>(0.0, 1.0)(pair) >= keep_probability) {
        stream = base + static_cast<uint64_t>(appearance);
      }
    }
    uint8_t* row = rows.ptr<uint8_t>(static_cast<int>(r));
    Prototype(stream, row);
    if (options_.kind == DescriptorKind::kFloat) {
      float* f = reinterpret_cast<float*>(row);
      for (int i = 0; i < options_.cols; ++i) f[i] += gauss(noise);
    } else if (options_.bit_flip_probability > 0.0) {
      for (int i = 0; i < options_.cols; ++i) {
        for (int b = 0; b < 8; ++b) {
          if (flip(noise)) row[i] ^= static_cast<uint8_t>(1u << b);
        }
      }
    }
  }
  return rows;
}

cv::Mat SyntheticDescriptors::Random(int rows, uint64_t seed) const {
  std::vector<int64_t> ids(rows);
  for (int i = 0; i < rows; ++i) ids[i] = -1 - static_cast<int64_t>(DeriveSeed(seed, i) >> 24);
  return Observe(ids, 0, 1.0, seed);
}

FrameFeatures SyntheticDescriptors::ToFeatures(const cv::Mat& descriptors) const {
  FrameFeatures f;
  f.kind = options_.kind;
  f.descriptors = descriptors;
  f.keypoints.resize(descriptors.rows);
  f.points_in_camera.assign(descriptors.rows,
                            Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN()));
  for (int i = 0; i < descriptors.rows; ++i) {
    f.keypoints[i] = cv::KeyPoint(static_cast<float>(i % 640), static_cast<float>(i / 640), 7.0f,
                                  -1.0f, static_cast<float>(descriptors.rows - i));
  }
  return f;
}

}  // namespace duskmap
