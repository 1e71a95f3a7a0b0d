#include "reference/medium.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <utility>

namespace welkin::clouds::reference {

HomogeneousSlab::HomogeneousSlab(double z_bottom, double z_top, double extinction, double albedo)
    : z_bottom_(z_bottom), z_top_(z_top), extinction_(extinction) {
  single_scattering_albedo = albedo;
}

double HomogeneousSlab::extinction(const glm::dvec3& p) const {
  return p.z >= z_bottom_ && p.z <= z_top_ ? extinction_ : 0.0;
}

MajorantSegments HomogeneousSlab::segments(const Ray& ray) const {
  const double oz = ray.origin.z, dz = ray.direction.z;
  double t0 = 0.0, t1 = kInfinity;
  if (dz == 0.0) {
    if (oz < z_bottom_ || oz > z_top_) return {};
  } else {
    const double a = (z_bottom_ - oz) / dz, b = (z_top_ - oz) / dz;
    t0 = std::max(0.0, std::min(a, b));
    t1 = std::max(a, b);
  }
  if (!(t1 > t0) || !(z_top_ > z_bottom_)) return {};
  return {{t0, t1, extinction_}};
}

HomogeneousSphere::HomogeneousSphere(const glm::dvec3& center, double radius, double extinction,
                                     double albedo)
    : center_(center), radius_(radius), extinction_(extinction) {
  single_scattering_albedo = albedo;
}

double HomogeneousSphere::extinction(const glm::dvec3& p) const {
  const glm::dvec3 d = p - center_;
  return glm::dot(d, d) <= radius_ * radius_ ? extinction_ : 0.0;
}

MajorantSegments HomogeneousSphere::segments(const Ray& ray) const {
  return spherical_shell_segments(ray, center_, 0.0, radius_, extinction_);
}

FunctionMedium::FunctionMedium(ExtinctionFunction extinction, SegmentsFunction segments, double albedo)
    : extinction_(std::move(extinction)), segments_(std::move(segments)) {
  single_scattering_albedo = albedo;
}

bool intersect_sphere(const Ray& ray, const glm::dvec3& center, double radius, double& t_near,
                      double& t_far) {
  // t^2 + 2 b t + c = 0 with the closest approach computed directly, which keeps the
  // discriminant accurate for a small sphere seen from far away (or a planet from its surface).
  const glm::dvec3 oc = ray.origin - center;
  const double b = glm::dot(oc, ray.direction);
  const glm::dvec3 closest = oc - b * ray.direction;
  const double discriminant = radius * radius - glm::dot(closest, closest);
  if (!(discriminant > 0.0)) return false;
  const double root = std::sqrt(discriminant);
  const double c = glm::dot(oc, oc) - radius * radius;
  // Citardauq form for the root that would otherwise cancel.
  const double q = -b - std::copysign(root, b);
  const double ta = q, tb = q != 0.0 ? c / q : -b;
  t_near = std::min(ta, tb);
  t_far = std::max(ta, tb);
  return true;
}

MajorantSegments spherical_shell_segments(const Ray& ray, const glm::dvec3& center, double inner_radius,
                                          double outer_radius, double majorant) {
  double outer_near, outer_far;
  if (!intersect_sphere(ray, center, outer_radius, outer_near, outer_far) || outer_far <= 0.0) return {};
  const double start = std::max(0.0, outer_near);
  double inner_near, inner_far;
  if (inner_radius <= 0.0 || !intersect_sphere(ray, center, inner_radius, inner_near, inner_far) ||
      inner_far <= start || inner_near >= outer_far) {
    return {{start, outer_far, majorant}};
  }
  // The ray crosses the hollow: the part before it (if any) and the part after it (if any).
  MajorantSegments out;
  if (inner_near > start) out.push_back({start, inner_near, majorant});
  if (outer_far > inner_far) out.push_back({std::max(start, inner_far), outer_far, majorant});
  return out;
}

}  // namespace welkin::clouds::reference
