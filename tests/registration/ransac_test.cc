#include "slam/registration/ransac.h"

#include <cmath>

#include <Eigen/Core>
#include <Eigen/QR>

#include <gtest/gtest.h>

namespace duskmap {
namespace {

// Estimates a 2D line y = a x + b from two points: a minimal mock estimator.
class LineEstimator {
 public:
  using Model = Eigen::Vector2d;  // (a, b)
  static constexpr int kMinSampleSize = 2;
  explicit LineEstimator(std::vector<Eigen::Vector2d> points) : points_(std::move(points)) {}

  void Estimate(const std::vector<int>& sample, std::vector<Model>* models) const {
    ++estimate_calls;
    const Eigen::Vector2d& p = points_[sample[0]];
    const Eigen::Vector2d& q = points_[sample[1]];
    if (std::abs(q.x() - p.x()) < 1e-12) return;
    const double a = (q.y() - p.y()) / (q.x() - p.x());
    models->push_back(Model(a, p.y() - a * p.x()));
  }
  void Residuals(const Model& m, std::vector<double>* residuals) const {
    residuals->resize(points_.size());
    for (size_t i = 0; i < points_.size(); ++i) {
      (*residuals)[i] = std::abs(points_[i].y() - (m[0] * points_[i].x() + m[1]));
    }
  }
  bool Refine(const std::vector<int>& inliers, Model* m) const {
    Eigen::MatrixXd A(inliers.size(), 2);
    Eigen::VectorXd y(inliers.size());
    for (size_t k = 0; k < inliers.size(); ++k) {
      A(k, 0) = points_[inliers[k]].x();
      A(k, 1) = 1.0;
      y[k] = points_[inliers[k]].y();
    }
    *m = A.colPivHouseholderQr().solve(y);
    return true;
  }
  mutable int estimate_calls = 0;

 private:
  std::vector<Eigen::Vector2d> points_;
};

std::vector<Eigen::Vector2d> LineWithOutliers(int inliers, int outliers, uint64_t seed) {
  Rng rng(seed);
  std::uniform_real_distribution<double> x(-10, 10), y(-50, 50);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < inliers; ++i) {
    const double xi = x(rng);
    points.emplace_back(xi, 2.0 * xi - 1.0 + noise(rng));
  }
  for (int i = 0; i < outliers; ++i) points.emplace_back(x(rng), y(rng));
  return points;
}

TEST(RunRansac, FindsLineAmongOutliers) {
  const LineEstimator estimator(LineWithOutliers(60, 40, 1));
  RansacOptions options;
  options.max_residual = 0.3;
  const RansacReport<Eigen::Vector2d> report = RunRansac(options, estimator, 100);
  ASSERT_TRUE(report.success);
  EXPECT_NEAR(report.model[0], 2.0, 0.02);
  EXPECT_NEAR(report.model[1], -1.0, 0.05);
  EXPECT_GE(report.inliers.size(), 58u);
  EXPECT_LE(report.inliers.size(), 62u);
  // Adaptive stopping: with 60 % inliers and s = 2, ~11 trials reach 0.99.
  EXPECT_LT(report.num_trials, 40);
}

TEST(RunRansac, SameSeedSameResultDifferentSeedStillCorrect) {
  const LineEstimator estimator(LineWithOutliers(30, 70, 2));
  RansacOptions options;
  options.max_residual = 0.3;
  const auto a = RunRansac(options, estimator, 100);
  const auto b = RunRansac(options, estimator, 100);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.num_trials, b.num_trials);
  options.random_seed = 99;
  const auto c = RunRansac(options, estimator, 100);
  ASSERT_TRUE(c.success);
  EXPECT_NEAR(c.model[0], 2.0, 0.05);
}

TEST(RunRansac, CapsTrialsAndHandlesTooLittleData) {
  const LineEstimator estimator(LineWithOutliers(0, 100, 3));
  RansacOptions options;
  options.max_residual = 1e-9;
  options.max_trials = 25;
  const auto report = RunRansac(options, estimator, 100);
  EXPECT_EQ(report.num_trials, 25);
  const LineEstimator tiny(LineWithOutliers(1, 0, 4));
  EXPECT_FALSE(RunRansac(options, tiny, 1).success);
  options.confidence = 1.0;
  EXPECT_THROW(RunRansac(options, estimator, 100), ConfigError);
}

}  // namespace
}  // namespace duskmap
