// Normalised link errors of an optimised graph (spec 7.4, reference
// graph::computeMaxGraphErrors). For a link a->b with measurement T_link and
// optimised poses P_a, P_b, T_opt = P_a^-1 P_b:
//   linear error  = max(|dx|, |dy|, |dz|) between the translations, m;
//   linear sigma  = sqrt(1 / min(information diagonal x, y, z)), ignoring
//                   entries <= 1e-4 (so the largest of the three std devs);
//   angular error = angular distance between the rotations, rad;
//   angular sigma = sqrt(1 / min(information diagonal roll, pitch, yaw)), likewise.
// Ratios are error / sigma; the largest of each kind is reported with its link.
#pragma once

#include "slam/graph/pose_graph.h"

namespace duskmap {

struct LinkErrorRatio {
  LinkKey link;        // valid only when `found`
  bool found = false;  // false when the graph has no link with a usable sigma
  double error = 0.0;  // m or rad
  double ratio = 0.0;  // error / sigma
};

struct MaxGraphErrors {
  LinkErrorRatio linear;
  LinkErrorRatio angular;
};

// Uses the poses stored in `graph`.
MaxGraphErrors ComputeMaxGraphErrors(const PoseGraph& graph);

}  // namespace duskmap
