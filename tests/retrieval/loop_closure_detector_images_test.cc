// Loop closure detection on real images under illumination change (shared
// data: Oxford "leuven" light sequence and the Edge Foci scenes), with
// OpenCV's SIFT (float) and ORB (binary) descriptors.
#include <filesystem>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "slam/retrieval/loop_closure_detector.h"

namespace duskmap {
namespace {

namespace fs = std::filesystem;

const fs::path kIllumination = fs::path(DUSKMAP_SHARED_DIR) / "data" / "illumination";

FrameFeatures Extract(const fs::path& image, bool binary) {
  const cv::Mat gray = cv::imread(image.string(), cv::IMREAD_GRAYSCALE);
  EXPECT_FALSE(gray.empty()) << image;
  cv::Ptr<cv::Feature2D> detector =
      binary ? cv::Ptr<cv::Feature2D>(cv::ORB::create(400)) : cv::Ptr<cv::Feature2D>(cv::SIFT::create(400));
  FrameFeatures f;
  detector->detectAndCompute(gray, cv::noArray(), f.keypoints, f.descriptors);
  // Strongest first, as the FrameFeatures contract says.
  std::vector<int> order(f.keypoints.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return f.keypoints[a].response > f.keypoints[b].response;
  });
  FrameFeatures sorted;
  sorted.kind = binary ? DescriptorKind::kBinary : DescriptorKind::kFloat;
  for (int i : order) {
    sorted.keypoints.push_back(f.keypoints[i]);
    sorted.descriptors.push_back(f.descriptors.row(i));
  }
  sorted.points_in_camera.assign(sorted.keypoints.size(), Eigen::Vector3f::Zero());
  return sorted;
}

class LcdImagesTest : public ::testing::TestWithParam<bool> {};

// Map: the bright leuven image plus the first image of each Edge Foci scene.
// The darker leuven images must score the leuven node highest.
TEST_P(LcdImagesTest, DarkerViewsScoreTheirPlaceHighest) {
  if (!fs::exists(kIllumination / "oxford-leuven" / "img1.ppm")) {
    GTEST_SKIP() << "shared data not found at " << kIllumination << " (../shared is absent)";
  }
  const bool binary = GetParam();
  LoopClosureDetector lcd{LoopClosureOptions()};
  lcd.AddMapNode(1, 0, Extract(kIllumination / "oxford-leuven" / "img1.ppm", binary));
  NodeId id = 2;
  for (const char* scene : {"notredame", "obama", "paintedladies", "rushmore", "yosemite"}) {
    for (const char* image : {"img1.png", "img2.png"}) {
      lcd.AddMapNode(id++, 0, Extract(kIllumination / "ef-dataset" / scene / image, binary));
    }
  }
  for (const char* dark : {"img2.ppm", "img3.ppm", "img4.ppm"}) {
    SCOPED_TRACE(dark);
    const LcdResult r = lcd.Localize(Extract(kIllumination / "oxford-leuven" / dark, binary));
    ASSERT_NE(r.status, LcdStatus::kBadSignature);
    const Likelihood& l = lcd.last_likelihood();
    for (NodeId other = 2; other < id; ++other) EXPECT_GT(l.Raw(1), l.Raw(other)) << "node " << other;
    EXPECT_GT(l.Adjusted(1), 1.0f);
    EXPECT_EQ(r.hypothesis, 1);
  }
}

INSTANTIATE_TEST_SUITE_P(Descriptors, LcdImagesTest, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "Orb" : "Sift"; });

}  // namespace
}  // namespace duskmap
