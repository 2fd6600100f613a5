// A WxBS-style pair folder with exact ground truth, for the epipolar
// feature benchmark's tests (features and CLI).
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/features/test_images.h"

namespace duskmap::testing {

// Two fronto-parallel textured planes (depth 4 m left of column 320 in the
// first image, 2.5 m right of it) seen by two cameras: the second is turned
// 5 degrees about y and moved 0.3 m right, 0.05 m down, 0.1 m forward. Each
// plane maps the first image into the second by its homography, so the
// ground truth and F are exact.
struct TwoPlanePair {
  cv::Matx33d k{500, 0, 319.5, 0, 500, 239.5, 0, 0, 1};
  cv::Matx33d r;
  cv::Vec3d t{-0.3, -0.05, -0.1};  // x2 = R x1 + t
  cv::Matx33d h_far, h_near, f;

  TwoPlanePair() {
    const double a = 5.0 * CV_PI / 180.0;
    r = cv::Matx33d(std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a));
    const cv::Vec3d n(0, 0, 1);
    h_far = k * (r + t * n.t() * (1.0 / 4.0)) * k.inv();
    h_near = k * (r + t * n.t() * (1.0 / 2.5)) * k.inv();
    const cv::Matx33d tx(0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0);
    f = k.inv().t() * tx * r * k.inv();
  }

  static cv::Point2d Apply(const cv::Matx33d& h, const cv::Point2d& p) {
    const cv::Vec3d q = h * cv::Vec3d(p.x, p.y, 1.0);
    return {q[0] / q[2], q[1] / q[2]};
  }
  cv::Point2d Map(const cv::Point2d& p1) const { return Apply(p1.x < 320 ? h_far : h_near, p1); }

  // Writes 01.png, 02.png and corrs.txt into `folder`; `shift_px` moves every
  // second point of the ground truth (a wrong ground truth).
  void Write(const std::filesystem::path& folder, double shift_px = 0.0) const {
    std::filesystem::create_directories(folder);
    cv::Mat first = TexturedImage(640, 480, 7);
    cv::Mat map_x(480, 640, CV_32F), map_y(480, 640, CV_32F);
    const cv::Matx33d far_inv = h_far.inv(), near_inv = h_near.inv();
    for (int y = 0; y < 480; ++y) {
      for (int x = 0; x < 640; ++x) {
        const cv::Point2d near = Apply(near_inv, {double(x), double(y)});
        const cv::Point2d far = Apply(far_inv, {double(x), double(y)});
        cv::Point2d source(-100, -100);
        if (near.x >= 320 && near.x < 640 && near.y >= 0 && near.y < 480) {
          source = near;  // the nearer plane hides the farther one
        } else if (far.x >= 0 && far.x < 320 && far.y >= 0 && far.y < 480) {
          source = far;
        }
        map_x.at<float>(y, x) = static_cast<float>(source.x);
        map_y.at<float>(y, x) = static_cast<float>(source.y);
      }
    }
    cv::Mat second;
    cv::remap(first, second, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(90));
    cv::imwrite((folder / "01.png").string(), first);
    cv::imwrite((folder / "02.png").string(), second);
    std::ofstream corrs(folder / "corrs.txt");
    int n = 0;
    for (int y = 60; y < 440; y += 40) {
      for (int x = 40; x < 620; x += 45) {
        const cv::Point2d p2 = Map({double(x), double(y)});
        if (p2.x < 0 || p2.y < 0 || p2.x > 639 || p2.y > 479) continue;
        const double shift = (n++ % 2 == 1) ? shift_px : 0.0;
        corrs << x << " " << y << " " << p2.x << " " << p2.y + shift << "\n";
      }
    }
  }
};

}  // namespace duskmap::testing
