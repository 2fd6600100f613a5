// Procedural surface relief: the small height variations of real materials
// (plaster and paint, wood grain and plank joints, tile grout, fabric weave
// and wrinkles, book spines, radiator fins, curtain folds, door and cabinet
// panels, leaves) that an albedo map alone does not carry. Lit from one side
// the relief shows as shading, lit from another it shows differently: the
// same wall looks different under the window's daylight and under a lamp at
// night. lighting.cc tilts each texel's shading normal by the slopes of the
// height. Printed surfaces (pictures, posters, packaging, clock faces,
// switches, screens), lamp shades and windows are flat.
#pragma once

#include <opencv2/core.hpp>

namespace duskmap {

// A height map in metres (CV_32F) drawn beside an albedo of the same size.
class ReliefCanvas {
 public:
  ReliefCanvas() = default;  // disabled: every call does nothing
  ReliefCanvas(cv::Size size, double texel_m);

  bool enabled() const { return !height_m_.empty(); }
  cv::Mat& height_m() { return height_m_; }

  // Adds value noise of this amplitude (metres) and cell size (metres).
  void AddNoise(double amplitude_m, double cell_m, cv::RNG& rng);
  // Adds a constant to a rectangle of texels (clipped to the map).
  void AddRect(const cv::Rect& texels, double height_m);
  // A V-groove of this depth whose centre line is one texel column (or row).
  void GrooveColumn(int column, double depth_m);
  void GrooveRow(int row, double depth_m);

 private:
  cv::Mat height_m_;
  double texel_m_ = 0.0;
};

// Slopes (dh/dx along columns, dh/dy along rows) of a height map whose
// texels measure texel_x_m x texel_y_m, by central differences (one-sided at
// the borders): CV_32FC2, metres per metre.
cv::Mat ReliefSlopes(const cv::Mat& height_m, double texel_x_m, double texel_y_m);

}  // namespace duskmap
