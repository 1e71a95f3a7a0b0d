// Independent helpers for the atmosphere reference tests: textbook formulas written apart from
// the library (naive ray-sphere intersection, fixed Gauss-Legendre), so that a test compares two
// separate derivations rather than the library with itself.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <glm/exponential.hpp>
#include <glm/geometric.hpp>

#include "reference/atmosphere_model.h"

namespace welkin::atmosphere::reference::testing {

// Only Rayleigh-type extinction sigma, constant density 1 in the shell.
inline AtmosphereModel constant_shell(glm::dvec3 sigma, double bottom_km, double top_km) {
  AtmosphereModel m;
  m.bottom_radius_km = bottom_km;
  m.top_radius_km = top_km;
  m.rayleigh_scattering = sigma;
  m.rayleigh_density.layers[1] = {.constant_term = 1.0};
  return m;
}

// Only Rayleigh-type extinction sigma, exponential density exp(-h / H).
inline AtmosphereModel exponential_shell(glm::dvec3 sigma, double scale_height_km, double bottom_km,
                                         double top_km) {
  AtmosphereModel m = constant_shell(sigma, bottom_km, top_km);
  m.rayleigh_density.layers[1] = {.exp_term = 1.0, .exp_scale_per_km = -1.0 / scale_height_km};
  return m;
}

// Visible length inside the shell of the ray from (r, 0, 0) with direction (mu, sin, 0), by the
// textbook quadratic t = -b -+ sqrt(b^2 - c) (no cancellation care: the test scales are mild).
inline double naive_visible_length(double r, double mu, double bottom, double top) {
  const double b = r * mu;
  auto roots = [&](double radius, double& t0, double& t1) {
    const double disc = b * b - (r * r - radius * radius);
    if (disc < 0.0) return false;
    t0 = -b - std::sqrt(disc);
    t1 = -b + std::sqrt(disc);
    return true;
  };
  double top0, top1;
  if (!roots(top, top0, top1) || top1 <= 0.0) return 0.0;
  double start = std::max(0.0, top0);
  double end = top1;
  double g0, g1;
  if (roots(bottom, g0, g1) && g1 > 0.0 && g0 < g1) end = std::min(end, std::max(g0, 0.0));
  return std::max(0.0, end - start);
}

// Five-point Gauss-Legendre on `pieces` equal sub-intervals of [a, b].
inline double gauss_legendre_5(const std::function<double(double)>& f, double a, double b,
                               int pieces) {
  const double x1 = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  const double x2 = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  const double w0 = 128.0 / 225.0;
  const double w1 = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
  const double w2 = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
  double sum = 0.0;
  const double h = (b - a) / pieces;
  for (int i = 0; i < pieces; ++i) {
    const double c = a + (i + 0.5) * h;
    const double half = 0.5 * h;
    sum += half * (w0 * f(c) + w1 * (f(c - half * x1) + f(c + half * x1)) +
                   w2 * (f(c - half * x2) + f(c + half * x2)));
  }
  return sum;
}

// Integral over mu in [-1, 1] with pieces graded geometrically towards both ends, where strongly
// anisotropic phase functions (|g| -> 1) put nearly all their mass.
inline double integrate_mu_graded(const std::function<double(double)>& f) {
  double sum = gauss_legendre_5(f, -0.5, 0.5, 8);
  for (int k = 0; k < 40; ++k) {  // [1 - 2^-k, 1 - 2^-(k+1)] towards each end.
    const double lo = 0.5 * std::pow(0.5, k), hi = 0.5 * std::pow(0.5, k + 1);
    sum += gauss_legendre_5(f, 1.0 - lo, 1.0 - hi, 4);
    sum += gauss_legendre_5(f, -1.0 + hi, -1.0 + lo, 4);
  }
  const double last = 0.5 * std::pow(0.5, 40);  // Closing pieces up to the ends themselves.
  return sum + gauss_legendre_5(f, 1.0 - last, 1.0, 1) + gauss_legendre_5(f, -1.0, -1.0 + last, 1);
}

}  // namespace welkin::atmosphere::reference::testing
