#include "welkin/timeofday/delta_t.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace welkin::timeofday {
namespace {

// Evaluates c[0] + c[1] t + c[2] t^2 + ... by Horner's rule.
template <std::size_t N>
double polynomial(const double (&c)[N], double t) {
  double sum = 0.0;
  for (std::size_t i = N; i-- > 0;) sum = sum * t + c[i];
  return sum;
}

// The long-term parabola of Morrison & Stephenson (2004) that the canon uses outside -500..2150.
double long_term_parabola(double y) {
  const double u = (y - 1820.0) / 100.0;
  return -20.0 + 32.0 * u * u;
}

}  // namespace

double delta_t_espenak_meeus(double y) {
  if (!std::isfinite(y) || y < kDeltaTFirstYear || y >= kDeltaTLastYear + 1.0) {
    throw std::invalid_argument("Delta-T: year " + std::to_string(y) +
                                " is outside the Espenak-Meeus range -1999..3000; pass an "
                                "explicit Delta-T instead");
  }
  // Coefficients from "Polynomial Expressions for Delta T", Five Millennium Canon of Solar
  // Eclipses (Espenak & Meeus 2006), one piece per historical era.
  if (y < -500.0) return long_term_parabola(y);
  if (y < 500.0) {
    static constexpr double c[] = {10583.6,    -1014.41,    33.78311,    -5.952053,
                                   -0.1798452, 0.022174192, 0.0090316521};
    return polynomial(c, y / 100.0);
  }
  if (y < 1600.0) {
    static constexpr double c[] = {1574.2,     -556.01,      71.23472,    0.319781,
                                   -0.8503463, -0.005050998, 0.0083572073};
    return polynomial(c, (y - 1000.0) / 100.0);
  }
  if (y < 1700.0) {
    static constexpr double c[] = {120.0, -0.9808, -0.01532, 1.0 / 7129.0};
    return polynomial(c, y - 1600.0);
  }
  if (y < 1800.0) {
    static constexpr double c[] = {8.83, 0.1603, -0.0059285, 0.00013336, -1.0 / 1174000.0};
    return polynomial(c, y - 1700.0);
  }
  if (y < 1860.0) {
    static constexpr double c[] = {13.72,       -0.332447,    0.0068612,     0.0041116,
                                   -0.00037436, 0.0000121272, -0.0000001699, 0.000000000875};
    return polynomial(c, y - 1800.0);
  }
  if (y < 1900.0) {
    static constexpr double c[] = {7.62,       0.5737,        -0.251754,
                                   0.01680668, -0.0004473624, 1.0 / 233174.0};
    return polynomial(c, y - 1860.0);
  }
  if (y < 1920.0) {
    static constexpr double c[] = {-2.79, 1.494119, -0.0598939, 0.0061966, -0.000197};
    return polynomial(c, y - 1900.0);
  }
  if (y < 1941.0) {
    static constexpr double c[] = {21.20, 0.84493, -0.076100, 0.0020936};
    return polynomial(c, y - 1920.0);
  }
  if (y < 1961.0) {
    static constexpr double c[] = {29.07, 0.407, -1.0 / 233.0, 1.0 / 2547.0};
    return polynomial(c, y - 1950.0);
  }
  if (y < 1986.0) {
    static constexpr double c[] = {45.45, 1.067, -1.0 / 260.0, -1.0 / 718.0};
    return polynomial(c, y - 1975.0);
  }
  if (y < 2005.0) {
    static constexpr double c[] = {63.86, 0.3345, -0.060374, 0.0017275, 0.000651814, 0.00002373599};
    return polynomial(c, y - 2000.0);
  }
  if (y < 2050.0) {
    static constexpr double c[] = {62.92, 0.32217, 0.005589};
    return polynomial(c, y - 2000.0);
  }
  if (y < 2150.0) return long_term_parabola(y) - 0.5628 * (2150.0 - y);
  return long_term_parabola(y);
}

}  // namespace welkin::timeofday
