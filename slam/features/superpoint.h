// SuperPoint (DeTone, Malisiewicz, Rabinovich, CVPRW 2018) as one
// configuration of the generic ONNX extractor (onnx_extractor.h). The network
// takes a 1x1xHxW gray image in [0, 1] (H, W multiples of 8; the input is
// padded) and returns the 65-channel detector logits ("semi", 1x65xH/8xW/8)
// and the 256-channel descriptor map (1x256xH/8xW/8), found by their shapes.
// Decoding follows the reference (spec §1.2, ../shared/spec outside this
// repository): channel softmax, drop the dustbin, depth-to-space to full
// resolution, max-pool NMS of radius nms_radius_px with two suppression
// passes, score > threshold, border removal; descriptors are bilinearly
// sampled from the coarse map and L2-normalised.
#pragma once

#include <memory>

#include "slam/features/feature_extractor.h"

namespace duskmap {

// The dense contract of a SuperPoint model with these options.
OnnxFeatureOptions SuperPointContract(const SuperPointOptions& options);

// The extractor of type "superpoint"; throws InputError when the model is
// missing or is not SuperPoint-shaped ("not a SuperPoint model").
std::unique_ptr<FeatureExtractor> CreateSuperPointExtractor(const SuperPointOptions& options,
                                                            int max_features,
                                                            double max_depth_m = 0.0);

}  // namespace duskmap
