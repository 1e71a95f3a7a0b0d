// Independent helpers for the cloud reference tests: textbook formulas written apart from the
// library (Gauss-Legendre nodes by Newton's method, Chandrasekhar's H function by iteration), so
// that a test compares two separate derivations.
#pragma once

#include <cmath>
#include <algorithm>
#include <functional>
#include <glm/vec3.hpp>
#include <utility>
#include <vector>

namespace welkin::clouds::reference::testing {

inline constexpr double kTestPi = 3.14159265358979323846;

// Unit vector from a zenith angle (from +z) and an azimuth, in degrees.
inline glm::dvec3 direction_deg(double zenith_deg, double azimuth_deg) {
  const double z = zenith_deg * kTestPi / 180.0, a = azimuth_deg * kTestPi / 180.0;
  return {std::sin(z) * std::cos(a), std::sin(z) * std::sin(a), std::cos(z)};
}

// n-point Gauss-Legendre nodes and weights on [a, b].
inline std::vector<std::pair<double, double>> gauss_legendre(int n, double a, double b) {
  std::vector<std::pair<double, double>> out;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kTestPi * (i + 0.75) / (n + 0.5)), derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / derivative;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * derivative * derivative);
    out.push_back({0.5 * (a + b) + 0.5 * (b - a) * x, 0.5 * (b - a) * w});
  }
  return out;
}

// Integral of f over mu in [-1, 1] with pieces graded geometrically towards both ends, where phase
// functions with |g| -> 1 put nearly all their mass.
inline double integrate_cosine(const std::function<double(double)>& f) {
  const auto nodes = gauss_legendre(12, -1.0, 1.0);
  auto piece = [&](double a, double b) {
    double sum = 0.0;
    for (const auto& [x, w] : nodes) sum += 0.5 * (b - a) * w * f(0.5 * (a + b) + 0.5 * (b - a) * x);
    return sum;
  };
  double sum = 0.0;
  for (int i = 0; i < 8; ++i) sum += piece(-0.5 + i * 0.125, -0.5 + (i + 1) * 0.125);
  for (int k = 0; k < 50; ++k) {
    const double outer = 0.5 * std::pow(0.5, k), inner = 0.5 * std::pow(0.5, k + 1);
    sum += piece(1.0 - outer, 1.0 - inner) + piece(-1.0 + inner, -1.0 + outer);
  }
  return sum;
}

// Chandrasekhar's H function for isotropic scattering with single-scattering albedo omega,
// from H(mu) = 1 + (omega / 2) mu H(mu) int_0^1 H(mu') / (mu + mu') dmu' (Chandrasekhar 1960,
// "Radiative Transfer", ch. V), solved by iteration on Gauss-Legendre nodes (monotone from H = 1;
// slow, but still converging, for omega = 1).
class ChandrasekharH {
 public:
  explicit ChandrasekharH(double omega, int nodes = 40)
      : omega_(omega), nodes_(gauss_legendre(nodes, 0.0, 1.0)), values_(nodes, 1.0) {
    std::vector<double> kernel(nodes * nodes);  // w_j / (mu_i + mu_j)
    for (int i = 0; i < nodes; ++i) {
      for (int j = 0; j < nodes; ++j) kernel[i * nodes + j] = nodes_[j].second / (nodes_[i].first + nodes_[j].first);
    }
    std::vector<double> next(nodes);
    for (int iteration = 0; iteration < 400000; ++iteration) {
      double change = 0.0;
      for (int i = 0; i < nodes; ++i) {
        double integral = 0.0;
        for (int j = 0; j < nodes; ++j) integral += kernel[i * nodes + j] * values_[j];
        next[i] = 1.0 / (1.0 - 0.5 * omega_ * nodes_[i].first * integral);
        change = std::max(change, std::abs(next[i] - values_[i]));
      }
      values_.swap(next);
      if (change < 1e-15) break;
    }
  }
  // H at any mu from the values at the nodes (Nystrom).
  double operator()(double mu) const {
    double integral = 0.0;
    for (std::size_t j = 0; j < nodes_.size(); ++j) {
      integral += nodes_[j].second * values_[j] / (mu + nodes_[j].first);
    }
    return 1.0 / (1.0 - 0.5 * omega_ * mu * integral);
  }

 private:
  double omega_;
  std::vector<std::pair<double, double>> nodes_;
  std::vector<double> values_;
};

}  // namespace welkin::clouds::reference::testing
