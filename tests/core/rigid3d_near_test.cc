// The shared Rigid3dNear matcher (tests/testing/rigid3d_near.h).
#include "tests/testing/rigid3d_near.h"

#include <cmath>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

namespace duskmap {
namespace {

using testing::Rigid3dNear;

const Rigid3d kExpected(Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ())),
                        Eigen::Vector3d(1.0, 2.0, 3.0));

// kExpected moved by `offset_m` along x and turned by `angle_deg` about y.
Rigid3d Moved(double offset_m, double angle_deg) {
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(angle_deg * M_PI / 180.0, Eigen::Vector3d::UnitY()));
  return Rigid3d(kExpected.rotation * turn, kExpected.translation + Eigen::Vector3d(offset_m, 0, 0));
}

TEST(Rigid3dNear, MatchesPosesWithinBothTolerances) {
  EXPECT_THAT(kExpected, Rigid3dNear(kExpected, 0.0, 0.0));
  EXPECT_THAT(Moved(0.009, 0.4), Rigid3dNear(kExpected, 0.01, 0.5));
  EXPECT_THAT(Moved(-0.009, -0.4), Rigid3dNear(kExpected, 0.01, 0.5));
}

TEST(Rigid3dNear, RefusesPosesOutsideEitherTolerance) {
  EXPECT_THAT(Moved(0.011, 0.0), ::testing::Not(Rigid3dNear(kExpected, 0.01, 0.5)));
  EXPECT_THAT(Moved(0.0, 0.6), ::testing::Not(Rigid3dNear(kExpected, 0.01, 0.5)));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(Rigid3d(kExpected.rotation, Eigen::Vector3d(nan, 0, 0)),
              ::testing::Not(Rigid3dNear(kExpected, 1.0, 180.0)));
}

TEST(Rigid3dNear, AFailureSaysHowFarThePoseIs) {
  EXPECT_NONFATAL_FAILURE(EXPECT_THAT(Moved(0.25, 0.0), Rigid3dNear(kExpected, 0.01, 0.5)),
                          "which is 0.25 m and ");
  EXPECT_NONFATAL_FAILURE(EXPECT_THAT(Moved(0.0, 2.0), Rigid3dNear(kExpected, 0.01, 0.5)),
                          "is within 0.01 m and 0.5 deg of Rigid3d(");
  const std::string explained = ::testing::DescribeMatcher<Rigid3d>(Rigid3dNear(kExpected, 0.01, 0.5));
  EXPECT_EQ(explained.rfind("is within 0.01 m and 0.5 deg of Rigid3d(t=[1 2 3], q(xyzw)=[", 0), 0u)
      << explained;
}

}  // namespace
}  // namespace duskmap
