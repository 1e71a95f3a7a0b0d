#include "reference/phase.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <string>

#include "reference/medium.h"

namespace welkin::clouds::reference {

glm::dvec3 rotate_from_axis(const glm::dvec3& axis, double cos_theta, double phi) {
  // Any unit vector perpendicular to the axis, from the world axis least aligned with it.
  const glm::dvec3 a = std::abs(axis.x) < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(axis, a));
  const glm::dvec3 v = glm::cross(axis, u);
  const double sin_theta = std::sqrt(std::max(0.0, (1.0 - cos_theta) * (1.0 + cos_theta)));
  return glm::normalize(cos_theta * axis + sin_theta * (std::cos(phi) * u + std::sin(phi) * v));
}

glm::dvec3 PhaseFunction::sample_direction(const glm::dvec3& forward, RandomStream& rng) const {
  const double cos_theta = sample_cos_theta(rng);
  return rotate_from_axis(forward, cos_theta, 2.0 * kPi * rng.uniform());
}

double HenyeyGreenstein::evaluate(double cos_theta) const {
  const double denominator = 1.0 + g_ * g_ - 2.0 * g_ * cos_theta;
  return (1.0 - g_ * g_) / (4.0 * kPi * denominator * std::sqrt(denominator));
}

double HenyeyGreenstein::sample_cos_theta(RandomStream& rng) const {
  const double xi = rng.uniform();
  // Near g = 0 the inversion below divides by g: HG is isotropic there to within 1e-6 anyway.
  if (std::abs(g_) < 1e-6) return 1.0 - 2.0 * xi;
  const double s = (1.0 - g_ * g_) / (1.0 - g_ + 2.0 * g_ * xi);
  return std::clamp((1.0 + g_ * g_ - s * s) / (2.0 * g_), -1.0, 1.0);
}

DualLobeHenyeyGreenstein::DualLobeHenyeyGreenstein(double g_forward, double g_backward,
                                                   double backward_weight)
    : forward_(g_forward), backward_(g_backward), backward_weight_(backward_weight) {}

double DualLobeHenyeyGreenstein::evaluate(double cos_theta) const {
  return (1.0 - backward_weight_) * forward_.evaluate(cos_theta) +
         backward_weight_ * backward_.evaluate(cos_theta);
}

double DualLobeHenyeyGreenstein::sample_cos_theta(RandomStream& rng) const {
  return rng.uniform() < backward_weight_ ? backward_.sample_cos_theta(rng) : forward_.sample_cos_theta(rng);
}

double DualLobeHenyeyGreenstein::mean_cosine() const {
  return (1.0 - backward_weight_) * forward_.g() + backward_weight_ * backward_.g();
}

Draine::Draine(double g, double alpha) : hg_(g), g_(g), alpha_(alpha) {
  if (!(alpha >= -1.0)) throw std::invalid_argument("Draine phase: alpha must be >= -1");
}

double Draine::evaluate(double cos_theta) const {
  const double normalisation = 1.0 + alpha_ * (1.0 + 2.0 * g_ * g_) / 3.0;
  return hg_.evaluate(cos_theta) * (1.0 + alpha_ * cos_theta * cos_theta) / normalisation;
}

double Draine::sample_cos_theta(RandomStream& rng) const {
  // Draine / HG is proportional to 1 + alpha mu^2, at most max(1, 1 + alpha): accept a HG draw
  // with probability (1 + alpha mu^2) / max(1, 1 + alpha). Acceptance is at least 1 / (1 + alpha)
  // on average (about one half for the cloud fits), so the loop ends; the cap only guards against a
  // broken generator.
  const double bound = std::max(1.0, 1.0 + alpha_);
  double mu = 0.0;
  for (int attempt = 0; attempt < 100000; ++attempt) {
    mu = hg_.sample_cos_theta(rng);
    if (rng.uniform() * bound < 1.0 + alpha_ * mu * mu) return mu;
  }
  return mu;
}

double Draine::mean_cosine() const {
  // Draine 2003, eq. 6 (and Jendersie & d'Eon 2023): <cos> = g (1 + alpha (3 + 2 g^2) / 5) /
  // (1 + alpha (1 + 2 g^2) / 3).
  const double g2 = g_ * g_;
  return g_ * (1.0 + alpha_ * (3.0 + 2.0 * g2) / 5.0) / (1.0 + alpha_ * (1.0 + 2.0 * g2) / 3.0);
}

ApproximateMieParameters approximate_mie_parameters(double diameter_um) {
  const double d = diameter_um;
  if (!(d >= 5.0 && d <= 50.0)) {
    throw std::invalid_argument("approximate Mie phase: droplet diameter " + std::to_string(d) +
                                " um is outside the fit's range [5, 50] um");
  }
  // Jendersie & d'Eon 2023, the fit for 5 um <= d <= 50 um (constants as published; the same
  // figures appear in public ports such as Herzberger's webgpu-sky-atmosphere).
  return {.g_hg = std::exp(-0.0990567 / (d - 1.67154)),
          .g_draine = std::exp(-2.20679 / (d + 3.91029) - 0.428934),
          .alpha = std::exp(3.62489 - 8.29288 / (d + 5.52825)),
          .w_draine = std::exp(-0.599085 / (d - 0.641583) - 0.665888)};
}

ApproximateMie::ApproximateMie(const ApproximateMieParameters& parameters)
    : parameters_(parameters), hg_(parameters.g_hg), draine_(parameters.g_draine, parameters.alpha) {}

double ApproximateMie::evaluate(double cos_theta) const {
  return (1.0 - parameters_.w_draine) * hg_.evaluate(cos_theta) +
         parameters_.w_draine * draine_.evaluate(cos_theta);
}

double ApproximateMie::sample_cos_theta(RandomStream& rng) const {
  return rng.uniform() < parameters_.w_draine ? draine_.sample_cos_theta(rng) : hg_.sample_cos_theta(rng);
}

double ApproximateMie::mean_cosine() const {
  return (1.0 - parameters_.w_draine) * hg_.g() + parameters_.w_draine * draine_.mean_cosine();
}

}  // namespace welkin::clouds::reference
