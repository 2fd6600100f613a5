#include "slam/synthetic/light/solar.h"

#include <gtest/gtest.h>

namespace duskmap {
namespace {

TEST(ComputeSunsetTime, SherbrookeLateMarchWithDstIsNear1910) {
  const double sunset_h = ComputeSunsetTime(SolarSite());
  EXPECT_GT(sunset_h, 19.0);
  EXPECT_LT(sunset_h, 19.3);
}

TEST(ComputeSunPosition, AfternoonSunSinksInTheWest) {
  const SolarSite site;
  const SunPosition at_1646 = ComputeSunPosition(site, 16.0 + 46.0 / 60);
  const SunPosition at_1827 = ComputeSunPosition(site, 18.0 + 27.0 / 60);
  const SunPosition at_1942 = ComputeSunPosition(site, 19.0 + 42.0 / 60);
  EXPECT_GT(at_1646.elevation_deg, 15.0);
  EXPECT_LT(at_1646.elevation_deg, 35.0);
  EXPECT_GT(at_1646.elevation_deg, at_1827.elevation_deg);
  EXPECT_LT(at_1942.elevation_deg, -3.0);  // in civil twilight
  EXPECT_GT(at_1942.elevation_deg, -9.0);
  EXPECT_GT(at_1646.azimuth_deg, 210.0);  // south-west to west
  EXPECT_LT(at_1827.azimuth_deg, 290.0);
  EXPECT_GT(at_1827.azimuth_deg, at_1646.azimuth_deg);
}

TEST(ComputeSunPosition, NoonSunIsDueSouth) {
  const SolarSite site;
  double best_h = 0, best_el = -90;
  for (double h = 11.0; h < 15.0; h += 0.01) {
    const double el = ComputeSunPosition(site, h).elevation_deg;
    if (el > best_el) {
      best_el = el;
      best_h = h;
    }
  }
  EXPECT_NEAR(ComputeSunPosition(site, best_h).azimuth_deg, 180.0, 2.0);
  EXPECT_NEAR(best_el, 90.0 - 45.40 + 2.9, 1.5);  // declination about +3 deg on 28 March
  const Eigen::Vector3d d = SunDirectionInWorld(ComputeSunPosition(site, best_h));
  EXPECT_LT(d.y(), 0.0);  // towards the south
  EXPECT_NEAR(d.norm(), 1.0, 1e-12);
}

}  // namespace
}  // namespace duskmap
