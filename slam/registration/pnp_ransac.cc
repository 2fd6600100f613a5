#include "slam/registration/pnp_ransac.h"

#include <cmath>
#include <limits>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "slam/core/check.h"
#include "slam/registration/ransac.h"

namespace duskmap {
namespace {

cv::Matx33d CameraMatrix(const PinholeCamera& camera) {
  return cv::Matx33d(camera.fx, 0.0, camera.cx, 0.0, camera.fy, camera.cy, 0.0, 0.0, 1.0);
}

Rigid3d FromRvecTvec(const cv::Mat& rvec, const cv::Mat& tvec) {
  cv::Mat rotation_cv;
  cv::Rodrigues(rvec, rotation_cv);
  Eigen::Matrix3d rotation;
  cv::cv2eigen(rotation_cv, rotation);
  Eigen::Vector3d translation(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  return Rigid3d(rotation, translation);
}

void ToRvecTvec(const Rigid3d& pose, cv::Mat* rvec, cv::Mat* tvec) {
  cv::Mat rotation_cv;
  cv::eigen2cv(Eigen::Matrix3d(pose.rotation.toRotationMatrix()), rotation_cv);
  cv::Rodrigues(rotation_cv, *rvec);
  *tvec = (cv::Mat_<double>(3, 1) << pose.translation.x(), pose.translation.y(),
           pose.translation.z());
}

// The estimator concept of ransac.h for 3D-2D correspondences.
class PnpEstimator {
 public:
  using Model = Rigid3d;
  static constexpr int kMinSampleSize = 3;

  PnpEstimator(const std::vector<Eigen::Vector3d>& points,
               const std::vector<Eigen::Vector2d>& pixels, const PinholeCamera& camera,
               PnpMinimalSolver solver)
      : points_(points), pixels_(pixels), camera_(camera), camera_matrix_(CameraMatrix(camera)),
        flags_(solver == PnpMinimalSolver::kP3P ? cv::SOLVEPNP_P3P : cv::SOLVEPNP_AP3P) {}

  void Estimate(const std::vector<int>& sample, std::vector<Model>* models) const {
    std::vector<cv::Point3d> object(3);
    std::vector<cv::Point2d> image(3);
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d& p = points_[sample[i]];
      object[i] = cv::Point3d(p.x(), p.y(), p.z());
      image[i] = cv::Point2d(pixels_[sample[i]].x(), pixels_[sample[i]].y());
    }
    if (IsDegenerate(object)) return;
    std::vector<cv::Mat> rvecs, tvecs;
    try {
      cv::solveP3P(object, image, camera_matrix_, cv::noArray(), rvecs, tvecs, flags_);
    } catch (const cv::Exception&) {
      return;  // numerically degenerate sample
    }
    for (size_t i = 0; i < rvecs.size(); ++i) {
      const Rigid3d model = FromRvecTvec(rvecs[i], tvecs[i]);
      if (model.IsFinite()) models->push_back(model);
    }
  }

  void Residuals(const Model& model, std::vector<double>* residuals) const {
    residuals->resize(points_.size());
    for (size_t i = 0; i < points_.size(); ++i) {
      (*residuals)[i] = ReprojectionErrorPx(camera_, model, points_[i], pixels_[i]);
    }
  }

  bool Refine(const std::vector<int>& inliers, Model* model) const {
    if (inliers.size() < 4) return false;
    std::vector<cv::Point3d> object;
    std::vector<cv::Point2d> image;
    object.reserve(inliers.size());
    image.reserve(inliers.size());
    for (int i : inliers) {
      object.emplace_back(points_[i].x(), points_[i].y(), points_[i].z());
      image.emplace_back(pixels_[i].x(), pixels_[i].y());
    }
    cv::Mat rvec, tvec;
    ToRvecTvec(*model, &rvec, &tvec);
    try {
      cv::solvePnPRefineLM(object, image, camera_matrix_, cv::noArray(), rvec, tvec);
    } catch (const cv::Exception&) {
      return false;
    }
    const Rigid3d refined = FromRvecTvec(rvec, tvec);
    if (!refined.IsFinite()) return false;
    *model = refined;
    return true;
  }

 private:
  // Collinear (or coincident) sample points admit no unique pose.
  static bool IsDegenerate(const std::vector<cv::Point3d>& object) {
    const cv::Point3d a = object[1] - object[0];
    const cv::Point3d b = object[2] - object[0];
    const double cross = cv::norm(a.cross(b));
    const double scale = cv::norm(a) * cv::norm(b);
    return !(cross > 1e-6 * scale) || scale <= 0.0;
  }

  const std::vector<Eigen::Vector3d>& points_;
  const std::vector<Eigen::Vector2d>& pixels_;
  const PinholeCamera& camera_;
  cv::Matx33d camera_matrix_;
  int flags_;
};

}  // namespace

void PnpRansacOptions::Check() const {
  SLAM_THROW_IF_NOT(ConfigError,
                    max_reprojection_error_px > 0.0 && std::isfinite(max_reprojection_error_px))
      << "PnpRansacOptions.max_reprojection_error_px: must be finite and > 0, got "
      << max_reprojection_error_px;
  SLAM_THROW_IF_NOT(ConfigError, confidence > 0.0 && confidence < 1.0)
      << "PnpRansacOptions.confidence: must be in (0, 1), got " << confidence;
  SLAM_THROW_IF_NOT(ConfigError, max_trials >= 1)
      << "PnpRansacOptions.max_trials: must be >= 1, got " << max_trials;
  SLAM_THROW_IF_NOT(ConfigError, refine_rounds >= 0)
      << "PnpRansacOptions.refine_rounds: must be >= 0, got " << refine_rounds;
}

double ReprojectionErrorPx(const PinholeCamera& camera, const Rigid3d& camera_from_points,
                           const Eigen::Vector3d& point, const Eigen::Vector2d& pixel) {
  Eigen::Vector2d projected;
  if (!camera.Project(camera_from_points * point, &projected)) {
    return std::numeric_limits<double>::infinity();
  }
  const double error = (projected - pixel).norm();
  return std::isfinite(error) ? error : std::numeric_limits<double>::infinity();
}

PnpResult EstimatePnpRansac(const PnpRansacOptions& options,
                            const std::vector<Eigen::Vector3d>& points,
                            const std::vector<Eigen::Vector2d>& pixels,
                            const PinholeCamera& camera) {
  options.Check();
  SLAM_CHECK(points.size() == pixels.size());
  SLAM_CHECK(camera.IsValid());
  PnpResult result;
  if (points.size() < 4) return result;

  RansacOptions ransac;
  ransac.max_residual = options.max_reprojection_error_px;
  ransac.confidence = options.confidence;
  ransac.max_trials = options.max_trials;
  ransac.refine_rounds = options.refine_rounds;
  ransac.random_seed = options.random_seed;
  const PnpEstimator estimator(points, pixels, camera, options.solver);
  const RansacReport<Rigid3d> report =
      RunRansac(ransac, estimator, static_cast<int>(points.size()));
  result.num_trials = report.num_trials;
  if (!report.success || report.inliers.size() < 4 || !report.model.IsFinite()) return result;
  result.success = true;
  result.camera_from_points = report.model;
  result.inliers = report.inliers;
  return result;
}

}  // namespace duskmap
