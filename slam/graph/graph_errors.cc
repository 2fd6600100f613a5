#include "slam/graph/graph_errors.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace duskmap {
namespace {

constexpr double kMinInformation = 1e-4;

// sqrt(1 / min(diag entries > 1e-4)); 0 when no entry is usable.
double Sigma(const Eigen::Vector3d& diagonal) {
  double min_information = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    if (diagonal[i] > kMinInformation) min_information = std::min(min_information, diagonal[i]);
  }
  return std::isfinite(min_information) ? std::sqrt(1.0 / min_information) : 0.0;
}

void Offer(const LinkKey& key, double error, double sigma, LinkErrorRatio* best) {
  if (!(sigma > 0.0)) return;
  const double ratio = error / sigma;
  if (!best->found || ratio > best->ratio) {
    *best = LinkErrorRatio{key, true, error, ratio};
  }
}

}  // namespace

MaxGraphErrors ComputeMaxGraphErrors(const PoseGraph& graph) {
  MaxGraphErrors errors;
  for (const auto& [key, link] : graph.links()) {
    const Rigid3d& world_from_a = graph.node(link.from).world_from_node;
    const Rigid3d& world_from_b = graph.node(link.to).world_from_node;
    const Rigid3d a_from_b_optimized = world_from_a.Inverse() * world_from_b;
    const Eigen::Vector3d delta = a_from_b_optimized.translation - link.from_from_to.translation;
    const double linear_error = delta.cwiseAbs().maxCoeff();
    const double angular_error =
        RotationAngleRad(a_from_b_optimized.rotation, link.from_from_to.rotation);
    const Eigen::Matrix<double, 6, 1> diagonal = link.information.diagonal();
    Offer(key, linear_error, Sigma(diagonal.head<3>()), &errors.linear);
    Offer(key, angular_error, Sigma(diagonal.tail<3>()), &errors.angular);
  }
  return errors;
}

}  // namespace duskmap
