#include "reference/phase_sampling.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace welkin::atmosphere::reference {

glm::dvec3 direction_about(const glm::dvec3& axis, double cos_theta, double phi) {
  // Branchless orthonormal basis (Duff et al. 2017).
  const double sign = std::copysign(1.0, axis.z);
  const double a = -1.0 / (sign + axis.z);
  const double b = axis.x * axis.y * a;
  const glm::dvec3 t(1.0 + sign * axis.x * axis.x * a, sign * b, -sign * axis.x);
  const glm::dvec3 u(b, sign + axis.y * axis.y * a, -axis.y);
  const double sin_theta = std::sqrt(std::max(0.0, (1.0 - cos_theta) * (1.0 + cos_theta)));
  return glm::normalize(sin_theta * std::cos(phi) * t + sin_theta * std::sin(phi) * u +
                        cos_theta * axis);
}

PhaseSample sample_rayleigh(const glm::dvec3& forward, double xi_cos, double xi_phi) {
  const double q = 4.0 * xi_cos - 2.0;
  const double u = std::cbrt(q + std::sqrt(q * q + 1.0));
  const double cos_theta = std::clamp(u - 1.0 / u, -1.0, 1.0);
  return {direction_about(forward, cos_theta, 2.0 * kPi * xi_phi), 1.0};
}

PhaseSample sample_mie(const AtmosphereModel& model, const glm::dvec3& forward, double xi_cos,
                       double xi_phi) {
  const double g = model.mie_g;
  double cos_theta = 2.0 * xi_cos - 1.0;
  if (std::abs(g) >= 1e-6) {  // Below, the inversion cancels badly and HG is isotropic anyway.
    const double f = (1.0 - g * g) / (1.0 - g + 2.0 * g * xi_cos);
    cos_theta = std::clamp((1.0 + g * g - f * f) / (2.0 * g), -1.0, 1.0);
  }
  PhaseSample out{direction_about(forward, cos_theta, 2.0 * kPi * xi_phi), 1.0};
  if (model.mie_phase == MiePhase::cornette_shanks) {
    out.weight = 3.0 * (1.0 + cos_theta * cos_theta) / (2.0 * (2.0 + g * g));
  }
  return out;
}

glm::dvec3 sample_cosine_hemisphere(const glm::dvec3& normal, double xi_cos, double xi_phi) {
  return direction_about(normal, std::sqrt(1.0 - xi_cos), 2.0 * kPi * xi_phi);
}

}  // namespace welkin::atmosphere::reference
