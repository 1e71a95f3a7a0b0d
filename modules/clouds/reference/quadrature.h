// Deterministic quadrature for smooth media: optical depth (so transmittance) along a ray and
// single scattering of the sun towards a camera. The ground truth the Monte Carlo estimators and
// the GPU march are checked against where the medium is smooth.
#pragma once

#include <functional>

#include "reference/lighting.h"
#include "reference/medium.h"
#include "reference/phase.h"

namespace welkin::clouds::reference {

struct QuadratureSettings {
  double relative_tolerance = 1e-10;  // Per panel: |one 5-point rule - two halves| <= tol * |value|.
  double absolute_tolerance = 1e-300;
  // Panels are at most this long: adaptivity cannot see a feature that falls between the nodes of
  // a coarse panel, so set it below the smallest feature of a FunctionMedium (e.g. 20 m).
  double max_panel_length = kInfinity;
  // Single scattering only: panels hold at most this majorant optical depth, so that the camera's
  // transmittance is resolved however dense the medium.
  double max_panel_optical_depth = 0.5;
  int max_depth = 30;  // Bisections per panel.
};

// Integral of f over [a, b] (finite) by recursive bisection of a 5-point Gauss-Legendre rule.
double integrate_adaptive(const std::function<double(double)>& f, double a, double b,
                          const QuadratureSettings& settings = {});

// Optical depth of the medium along the ray between t0 and t1 (t1 may be infinite: a stretch of
// infinite length with a positive majorant counts as infinitely deep). Stops early once past 800,
// where exp(-depth) is 0 in double precision.
double optical_depth(const Medium& medium, const Ray& ray, double t0, double t1,
                     const QuadratureSettings& settings = {});

// Transmittance along the whole ray, exp(-optical depth).
double transmittance(const Medium& medium, const Ray& ray, const QuadratureSettings& settings = {});

struct SingleScatteringResult {
  double radiance = 0.0;       // Sun light scattered once towards the camera (sky excluded).
  double transmittance = 0.0;  // Along the whole camera ray.
  double background = 0.0;     // transmittance * sky radiance: what is seen behind the medium.
};

// Integral along the camera ray of T_cam sigma_s p(view . sun) E T_sun, with both transmittances
// by quadrature. `view.direction` points away from the camera.
SingleScatteringResult single_scattering(const Medium& medium, const PhaseFunction& phase, const Ray& view,
                                         const Lighting& lighting, const QuadratureSettings& settings = {});

}  // namespace welkin::clouds::reference
