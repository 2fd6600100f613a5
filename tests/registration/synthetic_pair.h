// Synthetic map-node / query pairs with known relative pose for registration
// tests: random 3D points seen by both cameras, descriptors that match their
// counterpart up to noise, a chosen fraction of geometric outliers (right
// descriptor, wrong query position) and optional "twin" features whose
// descriptors are nearly identical to another feature's far away in the
// image (ambiguous for global NNDR, unique inside a projection window).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "slam/core/camera.h"
#include "slam/core/random.h"
#include "slam/core/rigid3.h"
#include "slam/features/frame_features.h"

namespace duskmap::testing {

struct SyntheticPairOptions {
  int num_points = 300;            // points visible in both views
  double outlier_fraction = 0.5;   // query keypoints moved to random pixels
  double pixel_noise_px = 0.5;     // Gaussian noise on inlier query keypoints
  DescriptorKind kind = DescriptorKind::kFloat;
  double descriptor_noise = 0.02;  // float: Gaussian per dimension before normalising
  int twin_features = 0;           // features turned into twins of another one
  bool query_depth = false;        // give the query 3D points too
  uint64_t seed = 1;
};

struct SyntheticPair {
  PinholeCamera camera;
  FrameFeatures map_node;
  FrameFeatures query;
  Rigid3d node_from_query;
  std::vector<bool> query_is_inlier;  // per query feature
};

inline PinholeCamera TestCamera() {
  PinholeCamera camera;
  camera.width = 640;
  camera.height = 480;
  camera.fx = camera.fy = 525.0;
  camera.cx = 319.5;
  camera.cy = 239.5;
  return camera;
}

inline cv::Mat RandomDescriptor(DescriptorKind kind, Rng* rng) {
  if (kind == DescriptorKind::kBinary) {
    cv::Mat d(1, 32, CV_8U);
    std::uniform_int_distribution<int> byte(0, 255);
    for (int i = 0; i < 32; ++i) d.at<uchar>(i) = static_cast<uchar>(byte(*rng));
    return d;
  }
  cv::Mat d(1, 128, CV_32F);
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (int i = 0; i < 128; ++i) d.at<float>(i) = n(*rng);
  return d / cv::norm(d);
}

inline cv::Mat PerturbDescriptor(const cv::Mat& d, DescriptorKind kind, double noise, Rng* rng) {
  cv::Mat out = d.clone();
  if (kind == DescriptorKind::kBinary) {
    std::uniform_int_distribution<int> bit(0, 255);
    for (int k = 0; k < 6; ++k) {  // flip 6 of 256 bits
      const int b = bit(*rng);
      out.at<uchar>(b / 8) ^= static_cast<uchar>(1u << (b % 8));
    }
    return out;
  }
  std::normal_distribution<float> n(0.0f, static_cast<float>(noise));
  for (int i = 0; i < out.cols; ++i) out.at<float>(i) += n(*rng);
  return out / cv::norm(out);
}

inline SyntheticPair MakeSyntheticPair(const SyntheticPairOptions& options) {
  Rng rng(options.seed);
  SyntheticPair pair;
  pair.camera = TestCamera();
  const PinholeCamera& camera = pair.camera;
  pair.node_from_query =
      Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(0.15, Eigen::Vector3d(0.2, 1.0, 0.1).normalized())),
              Eigen::Vector3d(0.25, -0.05, 0.1));
  const Rigid3d query_from_node = pair.node_from_query.Inverse();
  std::uniform_real_distribution<double> u(0.0, camera.width), v(0.0, camera.height);
  std::uniform_real_distribution<double> depth(1.0, 6.0);
  std::normal_distribution<double> pixel_noise(0.0, options.pixel_noise_px);

  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> node_pixels, query_pixels;
  while (static_cast<int>(points.size()) < options.num_points) {
    const Eigen::Vector2d px(u(rng), v(rng));
    const Eigen::Vector3d p = camera.Unproject(px.x(), px.y(), depth(rng));
    Eigen::Vector2d q;
    if (!camera.Project(query_from_node * p, &q) || !camera.InImage(q.x(), q.y())) continue;
    points.push_back(p);
    node_pixels.push_back(px);
    query_pixels.push_back(q);
  }
  const int n = options.num_points;
  std::vector<cv::Mat> map_descriptors(n);
  for (int i = 0; i < n; ++i) map_descriptors[i] = RandomDescriptor(options.kind, &rng);
  // Twins: feature i + 1 copies feature i's descriptor (up to tiny noise)
  // when the two are far apart in the query image.
  int twins = 0;
  for (int i = 0; i + 1 < n && twins < options.twin_features; i += 2) {
    if ((query_pixels[i] - query_pixels[i + 1]).norm() < 120.0) continue;
    map_descriptors[i + 1] =
        PerturbDescriptor(map_descriptors[i], options.kind, 0.3 * options.descriptor_noise, &rng);
    twins += 2;
  }

  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);  // query feature k shows point order[k]
  const int num_outliers = static_cast<int>(std::lround(options.outlier_fraction * n));
  std::vector<bool> outlier(n, false);
  for (int k = 0; k < num_outliers; ++k) outlier[order[k]] = true;

  FrameFeatures& map = pair.map_node;
  FrameFeatures& query = pair.query;
  map.kind = query.kind = options.kind;
  for (int i = 0; i < n; ++i) {
    map.keypoints.emplace_back(cv::Point2f(node_pixels[i].x(), node_pixels[i].y()), 10.0f);
    map.points_in_camera.push_back(points[i].cast<float>());
    map.descriptors.push_back(map_descriptors[i]);
  }
  for (int k = 0; k < n; ++k) {
    const int i = order[k];
    Eigen::Vector2d px = query_pixels[i] + Eigen::Vector2d(pixel_noise(rng), pixel_noise(rng));
    if (outlier[i]) px = Eigen::Vector2d(u(rng), v(rng));
    query.keypoints.emplace_back(cv::Point2f(px.x(), px.y()), 10.0f);
    query.descriptors.push_back(
        PerturbDescriptor(map_descriptors[i], options.kind, options.descriptor_noise, &rng));
    pair.query_is_inlier.push_back(!outlier[i]);
    if (options.query_depth) {
      query.points_in_camera.push_back((query_from_node * points[i]).cast<float>());
    }
  }
  return pair;
}

}  // namespace duskmap::testing
