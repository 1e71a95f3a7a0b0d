#include "reference/ray_geometry.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace welkin::atmosphere::reference {

namespace {

// Discriminant of |origin + s dir| = radius: radius^2 - r^2 (1 - mu^2), factored for precision.
double discriminant(double radius, double r, double mu) {
  return (radius - r) * (radius + r) + r * r * mu * mu;
}

// a / b with 0 / 0 = 0: the tangent-at-the-boundary cases.
double safe_ratio(double a, double b) {
  return b == 0.0 ? 0.0 : a / b;
}

}  // namespace

double clamp_to_ground(const AtmosphereModel& model, double r_km) {
  return std::max(r_km, model.bottom_radius_km);
}

bool ray_hits_sphere_below(double bottom_radius_km, double r_km, double mu) {
  return mu < 0.0 && discriminant(bottom_radius_km, r_km, mu) >
                         kTangentTolerance * bottom_radius_km * bottom_radius_km;
}

RayInterval atmosphere_interval(const AtmosphereModel& model, double r_km, double mu) {
  const double r = clamp_to_ground(model, r_km);
  const double top = model.top_radius_km;
  const double d_top = discriminant(top, r, mu);
  RayInterval out;
  if (r > top) {
    if (mu >= 0.0 || d_top < 0.0) return out;  // Leaving, or passing beside the atmosphere.
    out.start_km = safe_ratio((r - top) * (r + top), -r * mu + std::sqrt(d_top));
  }
  out.intersects = true;
  const double bottom = model.bottom_radius_km;
  if (ray_hits_sphere_below(bottom, r, mu)) {
    out.hits_ground = true;
    out.end_km =
        safe_ratio((r - bottom) * (r + bottom), -r * mu + std::sqrt(discriminant(bottom, r, mu)));
  } else if (mu >= 0.0 && r <= top) {
    out.end_km = safe_ratio((top - r) * (top + r), r * mu + std::sqrt(std::max(d_top, 0.0)));
  } else {
    out.end_km = -r * mu + std::sqrt(std::max(d_top, 0.0));
  }
  out.end_km = std::max(out.end_km, out.start_km);
  return out;
}

double radius_along_ray(double r_km, double mu, double s_km) {
  const double along = s_km + r_km * mu;
  const double perp_sq = r_km * r_km * (1.0 - mu) * (1.0 + mu);
  return std::sqrt(along * along + std::max(perp_sq, 0.0));
}

double altitude_along_ray(double bottom_radius_km, double r_km, double mu, double s_km) {
  // rho^2 - R^2 = (r - R)(r + R) + s (2 r mu + s): exact to rounding even where rho ~ R.
  const double rho_sq_minus_bottom_sq =
      (r_km - bottom_radius_km) * (r_km + bottom_radius_km) + s_km * (2.0 * r_km * mu + s_km);
  const double rho =
      std::sqrt(std::max(bottom_radius_km * bottom_radius_km + rho_sq_minus_bottom_sq, 0.0));
  return rho_sq_minus_bottom_sq / (rho + bottom_radius_km);
}

std::vector<double> ray_breakpoints(const AtmosphereModel& model, double r_km, double mu,
                                    double s0_km, double s1_km) {
  std::vector<double> points{s0_km, s1_km};
  auto add = [&](double s) {
    if (s > s0_km && s < s1_km) points.push_back(s);
  };
  add(-r_km * mu);  // Lowest point of the ray.
  for (double h : model.kink_altitudes_km()) {
    const double rho = model.bottom_radius_km + h;
    const double d = discriminant(rho, r_km, mu);
    if (d < 0.0) continue;
    add(-r_km * mu - std::sqrt(d));
    add(-r_km * mu + std::sqrt(d));
  }
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

RadiusMu radius_mu(const glm::dvec3& position_km, const glm::dvec3& direction) {
  const double r = glm::length(position_km);
  const double mu = r > 0.0 ? glm::dot(position_km, direction) / r : 1.0;
  return {r, std::clamp(mu, -1.0, 1.0)};
}

}  // namespace welkin::atmosphere::reference
