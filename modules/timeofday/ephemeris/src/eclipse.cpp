#include "welkin/timeofday/eclipse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "welkin/timeofday/coordinates.h"

namespace welkin::timeofday {
namespace {

void check_discs(const char* who, double rs, double rm, double d) {
  if (!std::isfinite(rs) || !std::isfinite(rm) || !std::isfinite(d) || rs <= 0.0 || rm < 0.0 ||
      d < 0.0) {
    throw std::invalid_argument(std::string(who) +
                                ": need a finite sun radius > 0 and finite moon radius and "
                                "separation >= 0 (got " +
                                std::to_string(rs) + ", " + std::to_string(rm) + ", " +
                                std::to_string(d) + ")");
  }
}

// Area shared by two discs of radii r1, r2 whose centres are d apart.
double overlap_area(double r1, double r2, double d) {
  if (d >= r1 + r2) return 0.0;
  if (d <= std::fabs(r1 - r2)) {
    const double r = std::min(r1, r2);
    return kPi * r * r;
  }
  // Two circular segments, one cut from each disc by the common chord.
  const double c1 = std::clamp((d * d + r1 * r1 - r2 * r2) / (2.0 * d * r1), -1.0, 1.0);
  const double c2 = std::clamp((d * d + r2 * r2 - r1 * r1) / (2.0 * d * r2), -1.0, 1.0);
  const double kite = (-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2);
  return r1 * r1 * std::acos(c1) + r2 * r2 * std::acos(c2) - 0.5 * std::sqrt(std::max(0.0, kite));
}

// Half the angle of the ring of radius rho (sun centre at the origin) that lies inside the moon's
// disc of radius rm centred delta away; all lengths in solar radii.
double covered_half_angle(double rho, double rm, double delta) {
  if (rho <= rm - delta) return kPi;
  if (rho >= rm + delta || rho <= delta - rm) return 0.0;
  const double c = (rho * rho + delta * delta - rm * rm) / (2.0 * rho * delta);
  return std::acos(std::clamp(c, -1.0, 1.0));
}

constexpr int kGaussPoints = 48;

struct GaussRule {
  std::array<double, kGaussPoints> x;
  std::array<double, kGaussPoints> w;
};

// Gauss-Legendre nodes and weights on [-1, 1] by Newton's method on P_n.
GaussRule make_gauss_rule() {
  GaussRule rule{};
  const int n = kGaussPoints;
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::fabs(dx) < 1e-15) break;
    }
    rule.x[i] = x;
    rule.w[i] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return rule;
}

// Integrates over rho in [a, b] with rho = a + (b - a)(1 - cos phi) / 2: the square-root edges
// of the integrand (ring tangencies, the solar limb) become smooth in phi.
template <typename F>
double integrate_with_sqrt_edges(F&& f, double a, double b) {
  static const GaussRule rule = make_gauss_rule();
  double sum = 0.0;
  for (int i = 0; i < kGaussPoints; ++i) {
    const double phi = kPi * 0.5 * (rule.x[i] + 1.0);
    const double rho = a + (b - a) * 0.5 * (1.0 - std::cos(phi));
    const double jacobian = (b - a) * 0.5 * std::sin(phi) * kPi * 0.5;
    sum += rule.w[i] * f(rho) * jacobian;
  }
  return sum;
}

}  // namespace

double sun_visible_fraction(double sun_angular_radius, double moon_angular_radius,
                            double separation) {
  check_discs("sun_visible_fraction", sun_angular_radius, moon_angular_radius, separation);
  const double covered = overlap_area(sun_angular_radius, moon_angular_radius, separation) /
                         (kPi * sun_angular_radius * sun_angular_radius);
  return std::clamp(1.0 - covered, 0.0, 1.0);
}

double sun_visible_flux_fraction(double sun_angular_radius, double moon_angular_radius,
                                 double separation, double limb_darkening_u) {
  check_discs("sun_visible_flux_fraction", sun_angular_radius, moon_angular_radius, separation);
  if (!std::isfinite(limb_darkening_u) || limb_darkening_u < 0.0 || limb_darkening_u > 1.0) {
    throw std::invalid_argument("sun_visible_flux_fraction: limb-darkening coefficient " +
                                std::to_string(limb_darkening_u) + " is outside [0, 1]");
  }
  const double rm = moon_angular_radius / sun_angular_radius;
  const double delta = separation / sun_angular_radius;
  if (delta >= 1.0 + rm || rm == 0.0) return 1.0;
  if (rm >= 1.0 + delta) return 0.0;
  const double u = limb_darkening_u;
  auto covered_flux = [&](double rho) {
    const double mu = std::sqrt(std::max(0.0, 1.0 - rho * rho));
    return (1.0 - u * (1.0 - mu)) * 2.0 * rho * covered_half_angle(rho, rm, delta);
  };
  // Split where the covered arc has kinks so each piece is smooth inside.
  std::array<double, 4> edges = {0.0, std::fabs(delta - rm), delta + rm, 1.0};
  std::sort(edges.begin(), edges.end());
  double covered = 0.0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const double a = std::clamp(edges[i], 0.0, 1.0);
    const double b = std::clamp(edges[i + 1], 0.0, 1.0);
    if (b > a) covered += integrate_with_sqrt_edges(covered_flux, a, b);
  }
  const double total = kPi * (1.0 - u / 3.0);
  return std::clamp(1.0 - covered / total, 0.0, 1.0);
}

}  // namespace welkin::timeofday
