#include "slam/synthetic/light/solar.h"

#include <algorithm>
#include <cmath>

namespace duskmap {
namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
}  // namespace

int DayOfYearAfter(int day_of_year, int days) {
  int year_length = std::max(365, day_of_year);
  int day = day_of_year + std::max(0, days);
  while (day > year_length) {
    day -= year_length;
    year_length = 365;
  }
  return day;
}

SunPosition ComputeSunPosition(const SolarSite& site, double local_time_h) {
  const double utc_h = local_time_h - site.utc_offset_h;
  // Fractional year (radians).
  const double gamma = 2.0 * kPi / 365.0 * (site.day_of_year - 1 + (utc_h - 12.0) / 24.0);
  const double eqtime_min =
      229.18 * (0.000075 + 0.001868 * std::cos(gamma) - 0.032077 * std::sin(gamma) -
                0.014615 * std::cos(2 * gamma) - 0.040849 * std::sin(2 * gamma));
  const double decl = 0.006918 - 0.399912 * std::cos(gamma) + 0.070257 * std::sin(gamma) -
                      0.006758 * std::cos(2 * gamma) + 0.000907 * std::sin(2 * gamma) -
                      0.002697 * std::cos(3 * gamma) + 0.00148 * std::sin(3 * gamma);
  const double true_solar_min = utc_h * 60.0 + eqtime_min + 4.0 * site.longitude_deg;
  const double hour_angle = (true_solar_min / 4.0 - 180.0) * kDeg;
  const double lat = site.latitude_deg * kDeg;
  const double cos_zenith = std::sin(lat) * std::sin(decl) +
                            std::cos(lat) * std::cos(decl) * std::cos(hour_angle);
  const double zenith = std::acos(std::max(-1.0, std::min(1.0, cos_zenith)));
  // Azimuth clockwise from north.
  const double azimuth = std::atan2(std::sin(hour_angle),
                                    std::cos(hour_angle) * std::sin(lat) -
                                        std::tan(decl) * std::cos(lat)) +
                         kPi;
  SunPosition sun;
  sun.elevation_deg = 90.0 - zenith / kDeg;
  sun.azimuth_deg = std::fmod(azimuth / kDeg + 360.0, 360.0);
  return sun;
}

Eigen::Vector3d SunDirectionInWorld(const SunPosition& sun) {
  const double el = sun.elevation_deg * kDeg;
  const double az = sun.azimuth_deg * kDeg;
  return Eigen::Vector3d(std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el));
}

double ComputeSunsetTime(const SolarSite& site) {
  double lo = 12.0, hi = 23.99;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (ComputeSunPosition(site, mid).elevation_deg > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace duskmap
