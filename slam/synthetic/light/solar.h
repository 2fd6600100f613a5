// Solar position from the NOAA general solar position equations (Spencer's
// Fourier series for the equation of time and declination), accurate to a
// fraction of a degree, which is all the lighting needs.
#pragma once

#include <Eigen/Core>

namespace duskmap {

struct SolarSite {
  double latitude_deg = 45.40;    // north positive (Sherbrooke, Quebec)
  double longitude_deg = -71.89;  // east positive
  double utc_offset_h = -4.0;     // local clock minus UTC (EDT, daylight saving time)
  int day_of_year = 87;           // 1..366 (87 = 28 March: sunset near 19:10 local)
};

struct SunPosition {
  double elevation_deg = 0.0;  // above the horizon (no refraction)
  double azimuth_deg = 0.0;    // clockwise from north
};

// The day of the year `days` (>= 0) days after `day_of_year` (1..366):
// past the year's end it wraps into the next year, taken to have 365 days
// (day_of_year 366 is the last day of a leap year). `days` 0 returns
// `day_of_year` itself.
int DayOfYearAfter(int day_of_year, int days);

// Sun position at a local clock time given in hours since midnight.
SunPosition ComputeSunPosition(const SolarSite& site, double local_time_h);

// Unit vector towards the sun in the world frame (x east, y north, z up).
Eigen::Vector3d SunDirectionInWorld(const SunPosition& sun);

// Local clock time (hours) of sunset (centre of the disc at the horizon),
// found by bisection between solar noon and midnight.
double ComputeSunsetTime(const SolarSite& site);

}  // namespace duskmap
