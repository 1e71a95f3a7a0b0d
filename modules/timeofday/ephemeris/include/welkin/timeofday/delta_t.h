// Delta-T = TT - UT, the drift of Earth's rotation against uniform time, in seconds.
#pragma once

namespace welkin::timeofday {

// First and last years the Espenak-Meeus polynomials are published for.
inline constexpr double kDeltaTFirstYear = -1999.0;
inline constexpr double kDeltaTLastYear = 3000.0;

// Delta-T in seconds from the Espenak & Meeus polynomials (Five Millennium Canon of Solar
// Eclipses, NASA/TP-2006-214141) at a decimal year such as 2017.64. Throws std::invalid_argument
// outside [kDeltaTFirstYear, kDeltaTLastYear + 1) or for a non-finite year.
double delta_t_espenak_meeus(double decimal_year);

}  // namespace welkin::timeofday
