#include "welkin/timeofday/illuminance.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "welkin/timeofday/moon.h"

namespace welkin::timeofday {

double sun_illuminance_lux(double distance_au) {
  if (!std::isfinite(distance_au) || distance_au <= 0.0) {
    throw std::invalid_argument("sun_illuminance_lux: distance " + std::to_string(distance_au) +
                                " AU must be finite and positive");
  }
  return kSolarIlluminanceLux / (distance_au * distance_au);
}

double moon_phase_law(double phase_angle_deg) {
  if (!std::isfinite(phase_angle_deg) || phase_angle_deg < 0.0 || phase_angle_deg > 180.0) {
    throw std::invalid_argument("moon_phase_law: phase angle " + std::to_string(phase_angle_deg) +
                                " deg is outside [0, 180]");
  }
  const double a = phase_angle_deg;
  const double a2 = a * a;
  return std::pow(10.0, -0.4 * (0.026 * a + 4.0e-9 * a2 * a2));
}

double moon_illuminance_lux(double phase_angle_deg, double moon_distance_km,
                            double sun_distance_au) {
  if (!std::isfinite(moon_distance_km) || moon_distance_km <= 0.0 ||
      !std::isfinite(sun_distance_au) || sun_distance_au <= 0.0) {
    throw std::invalid_argument("moon_illuminance_lux: distances must be finite and positive");
  }
  const double earth_moon = kMoonMeanDistanceKm / moon_distance_km;
  return kFullMoonIlluminanceLux * moon_phase_law(phase_angle_deg) * earth_moon * earth_moon /
         (sun_distance_au * sun_distance_au);
}

}  // namespace welkin::timeofday
