#include "reference/quadrature.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

namespace welkin::clouds::reference {

namespace {

// Beyond this optical depth exp(-depth) underflows to zero in double precision.
constexpr double kOpaqueDepth = 800.0;
constexpr double kMaxPanels = 1 << 20;

// Five-point Gauss-Legendre rule on [a, b] (exact for polynomials of degree 9).
double gauss_legendre_5(const std::function<double(double)>& f, double a, double b) {
  static const double x1 = std::sqrt(5.0 - 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  static const double x2 = std::sqrt(5.0 + 2.0 * std::sqrt(10.0 / 7.0)) / 3.0;
  static const double w0 = 128.0 / 225.0;
  static const double w1 = (322.0 + 13.0 * std::sqrt(70.0)) / 900.0;
  static const double w2 = (322.0 - 13.0 * std::sqrt(70.0)) / 900.0;
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  return h * (w0 * f(c) + w1 * (f(c - h * x1) + f(c + h * x1)) + w2 * (f(c - h * x2) + f(c + h * x2)));
}

double bisect(const std::function<double(double)>& f, double a, double b, double whole, int depth,
              const QuadratureSettings& s) {
  const double mid = 0.5 * (a + b);
  const double left = gauss_legendre_5(f, a, mid), right = gauss_legendre_5(f, mid, b);
  const double halves = left + right;
  if (depth >= s.max_depth ||
      std::abs(halves - whole) <= std::max(s.relative_tolerance * std::abs(halves), s.absolute_tolerance)) {
    return halves;
  }
  return bisect(f, a, mid, left, depth + 1, s) + bisect(f, mid, b, right, depth + 1, s);
}

// Panel count for a stretch of the given length and majorant optical depth.
int panel_count(double length, double max_length, double depth, double max_depth) {
  double n = 1.0;
  if (std::isfinite(max_length) && max_length > 0.0) n = std::max(n, std::ceil(length / max_length));
  if (max_depth > 0.0) n = std::max(n, std::ceil(depth / max_depth));
  return static_cast<int>(std::min(n, kMaxPanels));
}

}  // namespace

double integrate_adaptive(const std::function<double(double)>& f, double a, double b,
                          const QuadratureSettings& settings) {
  if (!(b > a)) return 0.0;
  const int panels = panel_count(b - a, settings.max_panel_length, 0.0, 0.0);
  const double h = (b - a) / panels;
  double sum = 0.0;
  for (int i = 0; i < panels; ++i) {
    const double p0 = a + i * h, p1 = i + 1 == panels ? b : a + (i + 1) * h;
    sum += bisect(f, p0, p1, gauss_legendre_5(f, p0, p1), 0, settings);
  }
  return sum;
}

double optical_depth(const Medium& medium, const Ray& ray, double t0, double t1,
                     const QuadratureSettings& settings) {
  const auto extinction = [&](double t) { return medium.extinction(ray.at(t)); };
  double depth = 0.0;
  for (const MajorantSegment& segment : medium.segments(ray)) {
    const double a = std::max(segment.t0, t0), b = std::min(segment.t1, t1);
    if (!(b > a) || !(segment.majorant > 0.0)) continue;
    if (!std::isfinite(b)) return kInfinity;
    // Panel by panel, so that an opaque medium stops as soon as it is opaque.
    const int panels = panel_count(b - a, settings.max_panel_length, 0.0, 0.0);
    const double h = (b - a) / panels;
    for (int i = 0; i < panels && depth < kOpaqueDepth; ++i) {
      depth += integrate_adaptive(extinction, a + i * h, i + 1 == panels ? b : a + (i + 1) * h, settings);
    }
    if (depth >= kOpaqueDepth) return depth;
  }
  return depth;
}

double transmittance(const Medium& medium, const Ray& ray, const QuadratureSettings& settings) {
  return std::exp(-optical_depth(medium, ray, 0.0, kInfinity, settings));
}

SingleScatteringResult single_scattering(const Medium& medium, const PhaseFunction& phase, const Ray& view,
                                         const Lighting& lighting, const QuadratureSettings& settings) {
  const Ray sun_ray_direction{view.origin, lighting.sun_direction};
  // Everything but the two transmittances and sigma_t is constant along the ray.
  const double source = medium.single_scattering_albedo * lighting.sun_irradiance *
                        phase.evaluate(glm::dot(view.direction, sun_ray_direction.direction));
  const auto extinction = [&](double t) { return medium.extinction(view.at(t)); };

  SingleScatteringResult result;
  double camera_depth = 0.0;  // Optical depth from the camera to the current panel's start.
  for (const MajorantSegment& segment : medium.segments(view)) {
    if (!(segment.majorant > 0.0) || !(segment.t1 > segment.t0)) continue;
    const double length = segment.t1 - segment.t0;
    // An infinite stretch is cut into panels of max_panel_optical_depth until it is opaque.
    const double h =
        std::isfinite(length)
            ? length / panel_count(length, settings.max_panel_length, length * segment.majorant,
                                   settings.max_panel_optical_depth)
            : std::min(settings.max_panel_optical_depth / segment.majorant, settings.max_panel_length);
    int panel = 0;
    for (double a = segment.t0; a < segment.t1 && camera_depth < kOpaqueDepth && panel < kMaxPanels;
         a += h, ++panel) {
      const double b = std::min(a + h, segment.t1);
      const auto integrand = [&](double t) {
        const glm::dvec3 x = view.at(t);
        const double to_camera = camera_depth + integrate_adaptive(extinction, a, t, settings);
        const double to_sun = optical_depth(medium, {x, lighting.sun_direction}, 0.0, kInfinity, settings);
        return medium.extinction(x) * std::exp(-to_camera - to_sun);
      };
      result.radiance += source * integrate_adaptive(integrand, a, b, settings);
      camera_depth += integrate_adaptive(extinction, a, b, settings);
      // What is left is at most source * exp(-camera_depth): stop once it cannot matter.
      if (source * std::exp(-camera_depth) <= 1e-3 * settings.relative_tolerance * result.radiance) {
        camera_depth = kInfinity;
      }
    }
  }
  // The early stop above is for the radiance only: the transmittance gets its own full quadrature.
  result.transmittance = transmittance(medium, view, settings);
  const double behind = lighting.environment(view.origin, glm::normalize(view.direction));
  result.background = result.transmittance * behind;
  return result;
}

}  // namespace welkin::clouds::reference
