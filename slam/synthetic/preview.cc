#include "slam/synthetic/preview.h"

#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "slam/core/check.h"
#include "slam/io/folder_commit.h"
#include "slam/io/image_file.h"
#include "slam/synthetic/session_simulator.h"

namespace duskmap {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kThumbWidth = 160;

cv::Mat Thumbnail(const cv::Mat& image, const std::string& label) {
  cv::Mat thumb;
  const int height = kThumbWidth * image.rows / image.cols;
  cv::resize(image, thumb, cv::Size(kThumbWidth, height), 0, 0, cv::INTER_AREA);
  cv::rectangle(thumb, cv::Rect(0, 0, 96, 16), cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(thumb, label, cv::Point(3, 12), cv::FONT_HERSHEY_SIMPLEX, 0.38, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  return thumb;
}

cv::Mat Grid(const std::vector<cv::Mat>& tiles, int columns) {
  SLAM_CHECK(!tiles.empty());
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  cv::Mat grid(rows * tiles[0].rows, columns * tiles[0].cols, CV_8UC3, cv::Scalar(40, 40, 40));
  for (size_t i = 0; i < tiles.size(); ++i) {
    const int r = static_cast<int>(i) / columns, c = static_cast<int>(i) % columns;
    tiles[i].copyTo(grid(cv::Rect(c * tiles[0].cols, r * tiles[0].rows, tiles[i].cols, tiles[i].rows)));
  }
  return grid;
}

void Write(const std::string& path, const cv::Mat& image) {
  WriteImageFile(path, image, {cv::IMWRITE_PNG_COMPRESSION, 9});
}

cv::Mat TopView(const Scene& scene, const std::vector<SessionPreview>& previews) {
  const double px_per_m = 60.0, margin = 20.0;
  const Eigen::Vector2d extent = scene.max_corner_xy - scene.min_corner_xy;
  cv::Mat image(static_cast<int>(extent.y() * px_per_m + 2 * margin + 20),
                static_cast<int>(extent.x() * px_per_m + 2 * margin), CV_8UC3, cv::Scalar(255, 255, 255));
  auto to_px = [&](const Eigen::Vector3d& p) {
    return cv::Point(static_cast<int>(margin + (p.x() - scene.min_corner_xy.x()) * px_per_m),
                     static_cast<int>(margin + (scene.max_corner_xy.y() - p.y()) * px_per_m));
  };
  for (const Quad& q : scene.quads) {
    const Eigen::Vector3d c[4] = {q.origin_in_world, q.PointAt(q.size_u_m, 0), q.PointAt(q.size_u_m, q.size_v_m), q.PointAt(0, q.size_v_m)};
    const bool horizontal = std::abs(q.normal().z()) > 0.9;
    if (horizontal && q.origin_in_world.z() > 2.2) continue;  // ceilings
    if (horizontal && q.origin_in_world.z() < 0.01 && q.room >= 0) {
      if (q.size_u_m * q.size_v_m > 3.0) continue;  // floors
    }
    std::vector<cv::Point> poly;
    for (const auto& p : c) poly.push_back(to_px(p));
    const cv::Scalar color = q.emission == Emission::kSky ? cv::Scalar(255, 160, 60)
                             : horizontal ? cv::Scalar(200, 200, 200) : cv::Scalar(60, 60, 60);
    cv::polylines(image, poly, true, color, q.emission == Emission::kSky ? 3 : 1, cv::LINE_AA);
  }
  for (size_t i = 0; i < previews.size(); ++i) {
    cv::Mat hue(1, 1, CV_8UC3, cv::Scalar(static_cast<int>(170.0 * i / previews.size()), 230, 210));
    cv::cvtColor(hue, hue, cv::COLOR_HSV2BGR);
    const cv::Vec3b c = hue.at<cv::Vec3b>(0, 0);
    const cv::Scalar color(c[0], c[1], c[2]);
    const auto& route = previews[i].route_xy;
    for (size_t k = 1; k < route.size(); ++k) {
      cv::line(image, to_px({route[k - 1].x(), route[k - 1].y(), 0}), to_px({route[k].x(), route[k].y(), 0}), color, 1, cv::LINE_AA);
    }
    cv::putText(image, previews[i].name, cv::Point(static_cast<int>(margin + 22 * i), image.rows - 8),
                cv::FONT_HERSHEY_SIMPLEX, 0.5, color, 2, cv::LINE_AA);
  }
  const Eigen::Vector3d dock = scene.docking_world_from_camera.translation;
  cv::circle(image, to_px(dock), 5, cv::Scalar(0, 0, 255), 2, cv::LINE_AA);
  return image;
}

}  // namespace

Rigid3d PreviewWorldFromCamera() {
  return Rigid3d(CameraRotationFromYawPitchRoll(150.0 * kPi / 180.0, -8.0 * kPi / 180.0, 0.0),
                 Eigen::Vector3d(5.2, 1.0, 1.4));
}

SessionPreview RenderSessionPreview(const GeneratorConfig& config, const SessionSimulator& simulator,
                                    const std::string& name, const std::string& clock_time,
                                    const std::vector<Eigen::Vector2d>& route_xy, uint64_t seed) {
  SessionPreview preview;
  preview.name = name;
  preview.clock_time = clock_time;
  preview.route_xy = route_xy;
  RenderedView view;
  CameraModel camera(config.camera, seed);
  simulator.renderer().Render(simulator.radiance(), PreviewWorldFromCamera(), &view);
  camera.Settle(view.radiance, 15);
  preview.view_bgr = camera.Capture(view.radiance);
  // Turn from the room (north) towards the west windows, one frame per step.
  const Eigen::Vector3d position(3.0, 2.2, 1.3);
  for (int step = 0; step <= 6; ++step) {
    const double yaw = (80.0 + 100.0 * step / 6.0) * kPi / 180.0;
    simulator.renderer().Render(simulator.radiance(),
                                Rigid3d(CameraRotationFromYawPitchRoll(yaw, 0.0, 0.0), position), &view);
    if (step == 0) camera.Settle(view.radiance, 15);
    preview.turn_bgr.push_back(camera.Capture(view.radiance));
  }
  return preview;
}

void WritePreviews(const Scene& scene, const std::vector<SessionPreview>& previews, const std::string& folder) {
  SLAM_CHECK(!previews.empty());
  CreateFolder(folder);
  std::vector<cv::Mat> tiles;
  for (const SessionPreview& p : previews) tiles.push_back(Thumbnail(p.view_bgr, p.name + "  " + p.clock_time));
  Write(folder + "/sessions.png", Grid(tiles, previews.size() > 6 ? 6 : static_cast<int>(previews.size())));
  std::vector<cv::Mat> turn;
  for (const SessionPreview* p : {&previews.front(), &previews.back()}) {
    for (size_t k = 0; k < p->turn_bgr.size(); ++k) {
      turn.push_back(Thumbnail(p->turn_bgr[k], p->name + " " + p->clock_time + " t" + std::to_string(k)));
    }
  }
  Write(folder + "/exposure.png", Grid(turn, static_cast<int>(previews.front().turn_bgr.size())));
  Write(folder + "/top_view.png", TopView(scene, previews));
}

}  // namespace duskmap
