// Covariance and information of a registration link (spec 6.6, reference
// util3d::estimateMotion3DTo2D). For each inlier k, p_k is the map point (node
// frame) and q_k the query's 3D point brought into the node frame; when the
// query has no depth there, q_k is the query ray scaled to 1.1 x the depth of
// p_k in the query frame (the reference's "10 % error"). With e_k = |p_k - q_k|^2
// and a_k = angle(p_k, q_k) in rad, each sorted ascending and r the median
// ratio:
//   var_lin = 2.1981 * e[n / r],  var_ang = 2.1981 * a[n / r]
// (index n/r: the 25th percentile for r = 4). Covariance =
// diag(var_lin x3, var_ang x3), floored at 1e-8 / 3e-8; information = inverse.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "slam/core/camera.h"
#include "slam/core/graph_types.h"
#include "slam/core/rigid3.h"

namespace duskmap {

struct LinkInformationOptions {
  int variance_median_ratio = 4;          // Vis/PnPVarianceMedianRatio (index n / ratio)
  double missing_depth_scale = 1.1;       // depth factor for query points without depth
  double min_linear_variance_m2 = 1e-8;   // floor on var_lin, m^2
  double min_angular_variance_rad2 = 3e-8;  // floor on var_ang (rad, as the reference)
  double max_linear_variance_m2 = 0.0;    // reject above this (Vis/PnPMaxVariance); 0 = off

  void Check() const;
};

struct LinkCovariance {
  double linear_variance_m2 = 0.0;
  double angular_variance = 0.0;  // variance of the angle, rad^2 (reference: not squared angles)
  Information6d information = Information6d::Identity();  // (x, y, z, roll, pitch, yaw)
};

struct InlierCorrespondence {
  Eigen::Vector3d point_in_node;       // finite, metres
  Eigen::Vector2d pixel_in_query;      // query keypoint, px
  Eigen::Vector3d point_in_query;      // query 3D point, metres; NaN when missing
};

// Needs at least one correspondence (SLAM_CHECK) and a finite node_from_query.
LinkCovariance ComputeLinkInformation(const LinkInformationOptions& options,
                                      const std::vector<InlierCorrespondence>& inliers,
                                      const PinholeCamera& query_camera,
                                      const Rigid3d& node_from_query);

}  // namespace duskmap
