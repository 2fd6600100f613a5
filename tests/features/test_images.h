// Deterministic test images and warps shared by the feature tests.
#pragma once

#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/random.h"

namespace duskmap::testing {

// A corner- and blob-rich 8-bit gray image: random filled shapes of random
// grey levels, lightly blurred.
inline cv::Mat TexturedImage(int width = 640, int height = 480, uint64_t seed = 1) {
  cv::RNG rng(seed);
  cv::Mat image(height, width, CV_8UC1, cv::Scalar(128));
  const int shapes = width * height / 700;
  for (int i = 0; i < shapes; ++i) {
    const cv::Point c(rng.uniform(0, width), rng.uniform(0, height));
    const int r = rng.uniform(3, 28);
    const cv::Scalar g(rng.uniform(0, 256));
    if (i % 3 == 0) {
      cv::circle(image, c, r, g, cv::FILLED, cv::LINE_AA);
    } else if (i % 3 == 1) {
      cv::rectangle(image, c, c + cv::Point(r, rng.uniform(3, 28)), g, cv::FILLED);
    } else {
      const cv::Point pts[3] = {c, c + cv::Point(r, rng.uniform(-20, 20)),
                                c + cv::Point(rng.uniform(-20, 20), r)};
      cv::fillConvexPoly(image, pts, 3, g, cv::LINE_AA);
    }
  }
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.0);
  return image;
}

// Rotation by angle_deg and scaling about the image centre; *h receives
// the 3x3 target_from_reference homography.
inline cv::Mat WarpRotateScale(const cv::Mat& image, double angle_deg, double scale,
                               cv::Matx33d* h) {
  const cv::Point2f center(image.cols / 2.0f - 0.5f, image.rows / 2.0f - 0.5f);
  const cv::Mat a = cv::getRotationMatrix2D(center, angle_deg, scale);
  *h = cv::Matx33d(a.at<double>(0, 0), a.at<double>(0, 1), a.at<double>(0, 2),
                   a.at<double>(1, 0), a.at<double>(1, 1), a.at<double>(1, 2), 0, 0, 1);
  cv::Mat out;
  cv::warpAffine(image, out, a, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT_101);
  return out;
}

inline cv::Mat AddNoise(const cv::Mat& image, double sigma, uint64_t seed) {
  cv::RNG rng(seed);
  cv::Mat noise(image.size(), CV_16SC1);
  rng.fill(noise, cv::RNG::NORMAL, 0, sigma);
  cv::Mat out16;
  image.convertTo(out16, CV_16S);
  out16 += noise;
  cv::Mat out;
  out16.convertTo(out, CV_8U);
  return out;
}

inline std::string SharedDir() { return DUSKMAP_SHARED_DIR; }
inline std::string LeuvenDir() { return SharedDir() + "/data/illumination/oxford-leuven"; }

}  // namespace duskmap::testing
