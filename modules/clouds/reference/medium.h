// Participating media for the cloud reference: extinction in 1/m at a point, and along any ray
// the stretches where it may be non-zero, each with a majorant (an upper bound on extinction
// there) for delta and ratio tracking. Lengths are in metres; directions are unit vectors.
#pragma once

#include <functional>
#include <glm/vec3.hpp>
#include <limits>
#include <vector>

namespace welkin::clouds::reference {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The half-line origin + t direction, t >= 0.
struct Ray {
  glm::dvec3 origin{0.0};
  glm::dvec3 direction{0.0, 0.0, 1.0};
  glm::dvec3 at(double t) const { return origin + t * direction; }
};

// A stretch [t0, t1] of a ray on which extinction never exceeds `majorant` (1/m). t1 may be
// infinite (a horizontal ray inside an infinite slab).
struct MajorantSegment {
  double t0 = 0.0;
  double t1 = 0.0;
  double majorant = 0.0;
};

// Sorted by t, disjoint, all within t >= 0; outside them extinction is zero.
using MajorantSegments = std::vector<MajorantSegment>;

class Medium {
 public:
  virtual ~Medium() = default;
  // Extinction coefficient sigma_t at p, 1/m.
  virtual double extinction(const glm::dvec3& p) const = 0;
  // Where along the ray extinction may be non-zero, with a bound on it over each stretch.
  virtual MajorantSegments segments(const Ray& ray) const = 0;
  // sigma_s / sigma_t, the same everywhere (clouds: very close to 1).
  double single_scattering_albedo = 1.0;
};

// Constant extinction between the horizontal planes z = z_bottom and z = z_top, infinite in x, y.
class HomogeneousSlab final : public Medium {
 public:
  HomogeneousSlab(double z_bottom, double z_top, double extinction, double albedo = 1.0);
  double extinction(const glm::dvec3& p) const override;
  MajorantSegments segments(const Ray& ray) const override;
  double z_bottom() const { return z_bottom_; }
  double z_top() const { return z_top_; }

 private:
  double z_bottom_, z_top_, extinction_;
};

// Constant extinction inside a ball.
class HomogeneousSphere final : public Medium {
 public:
  HomogeneousSphere(const glm::dvec3& center, double radius, double extinction, double albedo = 1.0);
  double extinction(const glm::dvec3& p) const override;
  MajorantSegments segments(const Ray& ray) const override;

 private:
  glm::dvec3 center_;
  double radius_, extinction_;
};

// Any extinction field given as functions: the real cloud field (spherical shells about the
// planet's centre, density mirroring the GLSL) plugs in here. The segments function must bound
// the field: a point found above its majorant is counted as a violation by the trackers.
class FunctionMedium final : public Medium {
 public:
  using ExtinctionFunction = std::function<double(const glm::dvec3&)>;
  using SegmentsFunction = std::function<MajorantSegments(const Ray&)>;
  FunctionMedium(ExtinctionFunction extinction, SegmentsFunction segments, double albedo = 1.0);
  double extinction(const glm::dvec3& p) const override { return extinction_(p); }
  MajorantSegments segments(const Ray& ray) const override { return segments_(ray); }

 private:
  ExtinctionFunction extinction_;
  SegmentsFunction segments_;
};

// The stretches of the ray inside the shell inner_radius <= |x - center| <= outer_radius (zero,
// one or two of them), each with the given majorant. inner_radius 0 makes it a ball.
MajorantSegments spherical_shell_segments(const Ray& ray, const glm::dvec3& center, double inner_radius,
                                          double outer_radius, double majorant);

// Entry and exit distances of a ray through a sphere; false when it misses (or only grazes it).
bool intersect_sphere(const Ray& ray, const glm::dvec3& center, double radius, double& t_near,
                      double& t_far);

}  // namespace welkin::clouds::reference
