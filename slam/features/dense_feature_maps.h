// Decoding of a dense local-feature network's outputs (onnx_extractor.h):
// per-cell score logits to a full-resolution heat map (SuperPoint's
// depth-to-space), a one-channel score map, max-pool non-maximum suppression,
// and bilinear sampling of a descriptor map at keypoints.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace duskmap {

// The full-resolution heat map (CV_32F, (Hc * cell) x (Wc * cell)) of
// 1xCxHcxWc logits, C = cell² (+1 when `dustbin`): softmax over the C
// channels, the dustbin dropped, channel k = row k / cell, column k % cell of
// its cell.
cv::Mat DecodeCellScores(const cv::Mat& logits, int cell_size_px, bool dustbin);

// The HxW plane of a 1x1xHxW score map (CV_32F), through a sigmoid when asked.
cv::Mat ScoreMapPlane(const cv::Mat& map, bool sigmoid);

// Max-pool non-maximum suppression of `scores` with two suppression passes
// (SuperPoint's): suppressed pixels are 0. Radius 0 keeps every score.
cv::Mat MaxPoolNms(const cv::Mat& scores, int radius_px);

// Bilinear samples of the 1xDxHdxWd descriptor map at keypoints given in
// full-resolution pixels, map pixel j centred on pixel stride * (j + 0.5) -
// 0.5 (clamped to the map); one CV_32F row of D each, L2-normalised when
// asked (rows of norm 0 stay 0).
cv::Mat SampleDescriptorMap(const cv::Mat& map, const std::vector<cv::KeyPoint>& keypoints,
                            int stride_px, bool normalize);

// L2-normalises every row of a CV_32F matrix in place (rows of norm 0 stay 0).
void NormalizeRows(cv::Mat* rows);

}  // namespace duskmap
