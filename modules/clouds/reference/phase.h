// Cloud phase functions of the scattering angle's cosine (between the direction light travels
// before and after scattering), normalised to 1 over the sphere (isotropic: 1 / (4 pi) per sr),
// each with an exact sampler, so the path tracer's phase weight is 1.
#pragma once

#include <glm/vec3.hpp>

#include "reference/random_stream.h"

namespace welkin::clouds::reference {

class PhaseFunction {
 public:
  virtual ~PhaseFunction() = default;
  // Phase function value, 1/sr.
  virtual double evaluate(double cos_theta) const = 0;
  // A cosine drawn with density 2 pi evaluate(cos_theta) on [-1, 1].
  virtual double sample_cos_theta(RandomStream& rng) const = 0;
  // Mean cosine (asymmetry parameter), closed form.
  virtual double mean_cosine() const = 0;
  // A direction drawn about `forward` (unit) with this phase function, uniform azimuth.
  glm::dvec3 sample_direction(const glm::dvec3& forward, RandomStream& rng) const;
};

// Henyey-Greenstein with asymmetry g in (-1, 1); g = 0 is isotropic.
class HenyeyGreenstein final : public PhaseFunction {
 public:
  explicit HenyeyGreenstein(double g) : g_(g) {}
  double evaluate(double cos_theta) const override;
  double sample_cos_theta(RandomStream& rng) const override;
  double mean_cosine() const override { return g_; }
  double g() const { return g_; }

 private:
  double g_;
};

// (1 - backward_weight) HG(g_forward) + backward_weight HG(g_backward). The defaults are
// takram three-clouds' (scatterAnisotropy1 = 0.7, scatterAnisotropy2 = -0.2,
// scatterAnisotropyMix = 0.5, which weights the second lobe).
class DualLobeHenyeyGreenstein final : public PhaseFunction {
 public:
  DualLobeHenyeyGreenstein(double g_forward = 0.7, double g_backward = -0.2, double backward_weight = 0.5);
  double evaluate(double cos_theta) const override;
  double sample_cos_theta(RandomStream& rng) const override;
  double mean_cosine() const override;

 private:
  HenyeyGreenstein forward_, backward_;
  double backward_weight_;
};

// Draine (2003): HG times (1 + alpha cos^2) renormalised; alpha = 1 with g = 0 is Rayleigh.
// Needs alpha >= -1 (non-negative everywhere). Sampled by rejection against HG(g).
class Draine final : public PhaseFunction {
 public:
  Draine(double g, double alpha);
  double evaluate(double cos_theta) const override;
  double sample_cos_theta(RandomStream& rng) const override;
  double mean_cosine() const override;

 private:
  HenyeyGreenstein hg_;
  double g_, alpha_;
};

// Parameters of the Jendersie & d'Eon blend (1 - w_draine) HG(g_hg) + w_draine Draine(g_draine, alpha).
struct ApproximateMieParameters {
  double g_hg = 0.0;
  double g_draine = 0.0;
  double alpha = 0.0;
  double w_draine = 0.0;
};

// The fit of Jendersie & d'Eon 2023 for water droplets of diameter 5 um <= d <= 50 um (outside
// this range: std::invalid_argument).
ApproximateMieParameters approximate_mie_parameters(double diameter_um);

// Jendersie & d'Eon 2023, "An Approximate Mie Scattering Function for Fog and Cloud Rendering"
// (SIGGRAPH 2023 Talks): Mie scattering by cloud droplets fitted as an HG + Draine blend.
class ApproximateMie final : public PhaseFunction {
 public:
  explicit ApproximateMie(const ApproximateMieParameters& parameters);
  explicit ApproximateMie(double diameter_um) : ApproximateMie(approximate_mie_parameters(diameter_um)) {}
  double evaluate(double cos_theta) const override;
  double sample_cos_theta(RandomStream& rng) const override;
  double mean_cosine() const override;
  const ApproximateMieParameters& parameters() const { return parameters_; }

 private:
  ApproximateMieParameters parameters_;
  HenyeyGreenstein hg_;
  Draine draine_;
};

// Unit vector at angle acos(cos_theta) from `axis` (unit) and azimuth phi about it.
glm::dvec3 rotate_from_axis(const glm::dvec3& axis, double cos_theta, double phi);

}  // namespace welkin::clouds::reference
