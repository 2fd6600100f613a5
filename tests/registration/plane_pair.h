// A real-image registration pair with exact ground truth, shared by the
// registration tests and bench/registration_bench.cc: the oxford-leuven
// reference image (resized to 640x480) is a tilted plane at ~2 m seen by the
// map camera (exact depth); the query is leuven image `query_index` (2..6,
// darker and darker) warped by the plane homography of a known camera motion
// composed with the dataset's homography, without depth. Without ../shared
// (`real` == false) a deterministic texture and a darkened copy are used.
#pragma once

#include <cmath>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/camera.h"
#include "slam/core/rigid3.h"

namespace duskmap::testing {

struct PlanePair {
  bool real = false;  // built from the leuven images
  PinholeCamera camera;
  cv::Mat map_image, map_depth_m, query_image;
  Rigid3d node_from_query;
};

inline cv::Mat TexturedImage(int width, int height) {
  cv::RNG rng(1);
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(128, 128, 128));
  for (int i = 0; i < 500; ++i) {
    const cv::Point c(rng.uniform(0, width), rng.uniform(0, height));
    cv::circle(image, c, rng.uniform(3, 28), cv::Scalar::all(rng.uniform(0, 256)), cv::FILLED,
               cv::LINE_AA);
  }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.0);
  return image;
}

// Reads a 3x3 homography written as 9 whitespace-separated numbers.
inline bool ReadHomography(const std::string& path, cv::Matx33d* h) {
  std::ifstream in(path);
  for (int i = 0; i < 9; ++i) in >> h->val[i];
  return static_cast<bool>(in);
}

inline PlanePair MakePlanePair(const std::string& shared_dir, int query_index) {
  constexpr int kWidth = 640, kHeight = 480;
  PlanePair pair;
  PinholeCamera& c = pair.camera;
  c.width = kWidth;
  c.height = kHeight;
  c.fx = c.fy = 525.0;
  c.cx = 319.5;
  c.cy = 239.5;
  const std::string dir = shared_dir + "/data/illumination/oxford-leuven/";
  const cv::Mat img1 = cv::imread(dir + "img1.ppm");
  const cv::Mat imgn = cv::imread(dir + "img" + std::to_string(query_index) + ".ppm");
  cv::Matx33d h1n;
  pair.real = !img1.empty() && !imgn.empty() &&
              ReadHomography(dir + "H1to" + std::to_string(query_index) + "p", &h1n);
  cv::Mat source;
  if (pair.real) {
    cv::resize(img1, pair.map_image, cv::Size(kWidth, kHeight), 0, 0, cv::INTER_AREA);
    cv::resize(imgn, source, cv::Size(kWidth, kHeight), 0, 0, cv::INTER_AREA);
    const cv::Matx33d scale(double(kWidth) / img1.cols, 0, 0, 0, double(kHeight) / img1.rows, 0,
                            0, 0, 1);
    h1n = scale * h1n * scale.inv();
  } else {
    pair.map_image = TexturedImage(kWidth, kHeight);
    source = pair.map_image * 0.6;
    h1n = cv::Matx33d::eye();
  }
  // Plane n . X = d in the map camera; depth of pixel (u, v) is d / (n . ray).
  const cv::Vec3d normal = cv::normalize(cv::Vec3d(0.2, -0.1, 1.0));
  const double plane_d = 2.0;
  pair.map_depth_m.create(kHeight, kWidth, CV_32F);
  for (int v = 0; v < kHeight; ++v) {
    for (int u = 0; u < kWidth; ++u) {
      const cv::Vec3d ray((u - c.cx) / c.fx, (v - c.cy) / c.fy, 1.0);
      pair.map_depth_m.at<float>(v, u) = static_cast<float>(plane_d / normal.dot(ray));
    }
  }
  pair.node_from_query = Rigid3d(
      Eigen::Quaterniond(
          Eigen::AngleAxisd(5.0 * M_PI / 180.0, Eigen::Vector3d(0.3, 1, 0).normalized())),
      Eigen::Vector3d(0.15, 0.03, 0.05));
  const Rigid3d query_from_node = pair.node_from_query.Inverse();
  const Eigen::Matrix3d r = query_from_node.rotation.toRotationMatrix();
  cv::Matx33d rotation;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) rotation(i, j) = r(i, j);
  const cv::Vec3d t(query_from_node.translation.x(), query_from_node.translation.y(),
                    query_from_node.translation.z());
  const cv::Matx33d k(c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  // x_query = K (R + t n^T / d) K^-1 x_map for points on the plane.
  const cv::Matx33d motion = k * (rotation + t * normal.t() * (1.0 / plane_d)) * k.inv();
  // dst(x) = src(M^-1 x) with M^-1 = H1n * motion^-1: the query pixel's scene
  // point in image 1 coordinates, mapped into image n.
  cv::warpPerspective(source, pair.query_image, motion * h1n.inv(), cv::Size(kWidth, kHeight));
  return pair;
}

}  // namespace duskmap::testing
