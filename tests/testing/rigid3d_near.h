// Test support shared by the suites (tests/testing/): a gmock matcher for
// Rigid3d poses.
//
//   EXPECT_THAT(result.node_from_query, Rigid3dNear(truth, 0.01, 0.5));
//
// matches a pose whose translation is at most max_translation_m from the
// expected one's and whose rotation is at most max_rotation_deg from it (the
// angle of the relative rotation); a failure prints both poses and both errors.
#pragma once

#include <cmath>
#include <ostream>

#include <gmock/gmock.h>

#include "slam/core/rigid3.h"

namespace duskmap::testing {

class Rigid3dNearMatcher {
 public:
  using is_gtest_matcher = void;

  Rigid3dNearMatcher(const Rigid3d& expected, double max_translation_m, double max_rotation_deg)
      : expected_(expected),
        max_translation_m_(max_translation_m),
        max_rotation_deg_(max_rotation_deg) {}

  bool MatchAndExplain(const Rigid3d& actual, std::ostream* os) const {
    const double translation_m = (actual.translation - expected_.translation).norm();
    const double rotation_deg = RotationAngleRad(actual.rotation, expected_.rotation) * 180.0 / M_PI;
    if (os) {
      *os << "which is " << translation_m << " m and " << rotation_deg << " deg from " << expected_;
    }
    return translation_m <= max_translation_m_ && rotation_deg <= max_rotation_deg_;
  }

  void DescribeTo(std::ostream* os) const {
    *os << "is within " << max_translation_m_ << " m and " << max_rotation_deg_ << " deg of "
        << expected_;
  }

  void DescribeNegationTo(std::ostream* os) const {
    *os << "is not within " << max_translation_m_ << " m and " << max_rotation_deg_ << " deg of "
        << expected_;
  }

 private:
  Rigid3d expected_;
  double max_translation_m_;
  double max_rotation_deg_;
};

inline Rigid3dNearMatcher Rigid3dNear(const Rigid3d& expected, double max_translation_m,
                                      double max_rotation_deg) {
  return Rigid3dNearMatcher(expected, max_translation_m, max_rotation_deg);
}

}  // namespace duskmap::testing
