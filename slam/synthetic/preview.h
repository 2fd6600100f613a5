// Previews a person can judge at a glance (`duskmap generate --preview`):
//  - sessions.png: the same living-room viewpoint in every session, side by
//    side, labelled with session name and clock time;
//  - exposure.png: the first session's camera turning from the room towards
//    the west windows, showing auto-exposure darkening the interior (with the
//    same turn in the last session below);
//  - top_view.png: the floor plan seen from above with every session's
//    ground-truth route.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "slam/synthetic/generator_config.h"
#include "slam/synthetic/scene/scene.h"

namespace duskmap {

class SessionSimulator;

struct SessionPreview {
  std::string name;
  std::string clock_time;
  cv::Mat view_bgr;                  // the common viewpoint
  std::vector<cv::Mat> turn_bgr;     // the turn towards the windows
  std::vector<Eigen::Vector2d> route_xy;
};

// The common preview viewpoint (living room, looking north-west).
Rigid3d PreviewWorldFromCamera();

// Renders the preview images of one session with a fresh camera (the
// simulator's lighting and renderer are reused; its camera is not touched).
SessionPreview RenderSessionPreview(const GeneratorConfig& config, const SessionSimulator& simulator,
                                    const std::string& name, const std::string& clock_time,
                                    const std::vector<Eigen::Vector2d>& route_xy, uint64_t seed);

// Writes sessions.png, exposure.png and top_view.png into `folder`.
void WritePreviews(const Scene& scene, const std::vector<SessionPreview>& previews, const std::string& folder);

}  // namespace duskmap
