// Illuminance from the sun and moon on a surface facing them, outside the atmosphere.
#pragma once

namespace welkin::timeofday {

// Solar illuminance at 1 AU outside the atmosphere, lux (the usual figure for photopic vision).
inline constexpr double kSolarIlluminanceLux = 128000.0;
// Full moon at mean distance and 1 AU from the sun, outside the atmosphere, lux (Allen,
// Astrophysical Quantities: 0.267 lx).
inline constexpr double kFullMoonIlluminanceLux = 0.267;

// Sun's illuminance at `distance_au`, inverse-square. Throws std::invalid_argument unless the
// distance is finite and positive.
double sun_illuminance_lux(double distance_au);

// The moon's brightness relative to full moon at the same distances: the phase law of Krisciunas
// & Schaefer (1991, PASP 103, 1033), 10^(-0.4 (0.026 |a| + 4e-9 a^4)) with a in degrees, which
// keeps the opposition surge; waxing and waning are taken as equal. Throws outside [0, 180].
double moon_phase_law(double phase_angle_deg);

// Moon's illuminance: kFullMoonIlluminanceLux times the phase law, inverse-square in both the
// Earth-moon distance (against kMoonMeanDistanceKm) and the sun-moon distance (against 1 AU,
// approximated by the Earth-sun distance). Ignores lunar eclipses and earthshine.
double moon_illuminance_lux(double phase_angle_deg, double moon_distance_km,
                            double sun_distance_au);

}  // namespace welkin::timeofday
