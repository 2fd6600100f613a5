#include "slam/synthetic/sensor/sensor_noise.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(SensorNoise, NormalSamplesHaveUnitVarianceAndNormalTails) {
  SensorNoise noise(7);
  std::vector<float> x(1000003);  // odd count: exercises the tail of FillNormal
  noise.FillNormal(x.data(), x.size());
  double sum = 0, sum2 = 0;
  int beyond_1 = 0, beyond_2 = 0;
  for (float v : x) {
    sum += v;
    sum2 += v * v;
    beyond_1 += std::abs(v) > 1.0f;
    beyond_2 += std::abs(v) > 2.0f;
  }
  const double n = x.size();
  EXPECT_NEAR(sum / n, 0.0, 0.005);
  EXPECT_NEAR(sum2 / n, 1.0, 0.01);
  EXPECT_NEAR(beyond_1 / n, 0.3173, 0.003);  // P(|z| > 1)
  EXPECT_NEAR(beyond_2 / n, 0.0455, 0.001);  // P(|z| > 2)
  EXPECT_NEAR(SensorNoise::NormalQuantile(32768), 1.9e-5, 1e-6);  // quantile at 0.5 + 0.5/65536
  EXPECT_FLOAT_EQ(SensorNoise::NormalQuantile(0), -SensorNoise::NormalQuantile(65535));
  EXPECT_NEAR(SensorNoise::NormalQuantile(65535), 4.33, 0.01);
}

TEST(SensorNoise, UniformSamplesCoverTheUnitIntervalEvenly) {
  SensorNoise noise(3);
  std::vector<float> u(400001);
  noise.FillUniform(u.data(), u.size());
  std::vector<int> bins(10, 0);
  for (float v : u) {
    ASSERT_GE(v, 0.0f);
    ASSERT_LT(v, 1.0f);
    ++bins[static_cast<int>(v * 10)];
  }
  for (int b = 0; b < 10; ++b) EXPECT_NEAR(bins[b] / 400001.0, 0.1, 0.003) << "bin " << b;
}

TEST(SensorNoise, SameSeedSameSequenceDifferentSeedDifferentSequence) {
  std::vector<float> a(1000), b(1000), c(1000);
  SensorNoise(5).FillNormal(a.data(), a.size());
  SensorNoise(5).FillNormal(b.data(), b.size());
  SensorNoise(6).FillNormal(c.data(), c.size());
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

}  // namespace
}  // namespace duskmap
