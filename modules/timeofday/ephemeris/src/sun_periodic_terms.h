// Internal: the Earth series of SPA Table A4.2, kept apart from the code that sums them.
#pragma once

#include <span>

namespace welkin::timeofday::detail {

// One term A cos(B + C * JME).
struct PeriodicTerm {
  double a;
  double b;
  double c;
};

using PeriodicSeries = std::span<const PeriodicTerm>;

// L0..L5, B0..B1 and R0..R4: the series multiplied by JME^0, JME^1, ...
extern const PeriodicSeries kEarthLongitude[6];
extern const PeriodicSeries kEarthLatitude[2];
extern const PeriodicSeries kEarthRadius[5];

}  // namespace welkin::timeofday::detail
