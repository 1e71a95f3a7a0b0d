// Globally adaptive Gauss-Kronrod (7/15 point) quadrature of RGB-valued integrands, in the manner
// of QUADPACK's QAG: the interval with the largest error is bisected until every channel meets
// its tolerance. The error estimate is |K15 - G7| per channel, which for smooth integrands is far
// larger than the true error of K15, so the stated tolerances are conservative.
#pragma once

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

namespace welkin::atmosphere::reference {

// Convergence request: per channel, error <= max(absolute_tolerance, relative_tolerance * |I|).
struct QuadratureSettings {
  double relative_tolerance = 1e-9;
  double absolute_tolerance = 1e-13;
  int max_intervals = 4000;  // Safety stop; `converged` tells whether it was hit.
};

// Integral per channel, with the evidence of how far to trust it.
struct QuadratureResult {
  glm::dvec3 value{0.0};
  glm::dvec3 error{0.0};  // Estimated absolute error per channel.
  int evaluations = 0;    // Integrand calls.
  bool converged = true;
};

namespace detail {

// QUADPACK qk15 abscissae (Kronrod; odd indices are the Gauss points) and weights.
inline constexpr double kXgk[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
inline constexpr double kWgk[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr double kWg[4] = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct GkInterval {
  double a, b;
  glm::dvec3 value, error;
  bool splittable;
};

template <class F>
GkInterval gauss_kronrod_15(F& f, double a, double b) {
  const double centre = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  const glm::dvec3 fc = f(centre);
  glm::dvec3 kronrod = fc * kWgk[7];
  glm::dvec3 gauss = fc * kWg[3];
  for (int j = 0; j < 7; ++j) {
    const double dx = half * kXgk[j];
    const glm::dvec3 sum = f(centre - dx) + f(centre + dx);
    kronrod += sum * kWgk[j];
    if (j % 2 == 1) gauss += sum * kWg[j / 2];
  }
  GkInterval out{a, b, kronrod * half, glm::abs((kronrod - gauss) * half), true};
  // Stop bisecting once the midpoint no longer separates the ends in floating point.
  const double scale = std::max(std::abs(a), std::abs(b));
  out.splittable = (b - a) > 64.0 * 2.220446049250313e-16 * scale && (b - a) > 1e-300;
  return out;
}

}  // namespace detail

// Integrates f (double -> glm::dvec3) over [breakpoints.front(), breakpoints.back()], starting
// from the pieces between consecutive sorted breakpoints: put kinks and jumps there.
template <class F>
QuadratureResult integrate_gauss_kronrod(F&& f, std::span<const double> breakpoints,
                                         const QuadratureSettings& settings = {}) {
  QuadratureResult result;
  std::vector<detail::GkInterval> intervals;
  for (size_t i = 0; i + 1 < breakpoints.size(); ++i) {
    if (!(breakpoints[i + 1] > breakpoints[i])) continue;
    intervals.push_back(detail::gauss_kronrod_15(f, breakpoints[i], breakpoints[i + 1]));
    result.evaluations += 15;
  }
  const double rel = std::max(settings.relative_tolerance, 1e-15);
  while (true) {
    glm::dvec3 value(0.0), error(0.0);
    for (const auto& iv : intervals) {
      value += iv.value;
      error += iv.error;
    }
    result.value = value;
    result.error = error;
    glm::dvec3 tolerance;
    bool done = true;
    for (int c = 0; c < 3; ++c) {
      tolerance[c] = std::max(settings.absolute_tolerance, rel * std::abs(value[c]));
      if (!(error[c] <= tolerance[c])) done = false;
    }
    if (done) break;
    // Bisect the interval that contributes most to the worst-normalised channel error.
    int worst = -1;
    double worst_key = 0.0;
    for (size_t i = 0; i < intervals.size(); ++i) {
      if (!intervals[i].splittable) continue;
      double key = 0.0;
      for (int c = 0; c < 3; ++c) key = std::max(key, intervals[i].error[c] / tolerance[c]);
      if (key > worst_key) {
        worst_key = key;
        worst = static_cast<int>(i);
      }
    }
    if (worst < 0 || static_cast<int>(intervals.size()) >= settings.max_intervals) {
      result.converged = false;
      break;
    }
    const detail::GkInterval parent = intervals[worst];
    const double mid = 0.5 * (parent.a + parent.b);
    intervals[worst] = detail::gauss_kronrod_15(f, parent.a, mid);
    intervals.push_back(detail::gauss_kronrod_15(f, mid, parent.b));
    result.evaluations += 30;
  }
  return result;
}

}  // namespace welkin::atmosphere::reference
