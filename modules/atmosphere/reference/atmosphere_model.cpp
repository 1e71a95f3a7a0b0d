#include "reference/atmosphere_model.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace welkin::atmosphere::reference {

namespace {

double layer_value(const DensityLayer& layer, double h) {
  // Skip exp() when the term is absent: cheaper, and avoids 0 * inf for steep scales.
  double value = layer.linear_term_per_km * h + layer.constant_term;
  if (layer.exp_term != 0.0) value += layer.exp_term * std::exp(layer.exp_scale_per_km * h);
  return value;
}

// 1 + g^2 - 2 g mu written as a sum of non-negative terms, so that it keeps full relative
// precision in the forward (g > 0, mu -> 1) and backward (g < 0, mu -> -1) peaks.
double hg_denominator_base(double g, double mu) {
  return g >= 0.0 ? (1.0 - g) * (1.0 - g) + 2.0 * g * (1.0 - mu)
                  : (1.0 + g) * (1.0 + g) - 2.0 * g * (1.0 + mu);
}

std::string fmt(double v) {
  std::ostringstream out;
  out.precision(9);
  out << v;
  return out.str();
}

void check_rgb(std::vector<std::string>& problems, const char* name, const glm::dvec3& v) {
  static const char* kChannel[3] = {"r", "g", "b"};
  for (int c = 0; c < 3; ++c) {
    if (std::isnan(v[c]) || std::isinf(v[c])) {
      problems.push_back(std::string(name) + "." + kChannel[c] + " is not finite (" + fmt(v[c]) +
                         ")");
    } else if (v[c] < 0.0) {
      problems.push_back(std::string(name) + "." + kChannel[c] + " is negative (" + fmt(v[c]) +
                         "), expected >= 0");
    }
  }
}

void check_profile(std::vector<std::string>& problems, const char* name,
                   const DensityProfile& profile) {
  for (int i = 0; i < 2; ++i) {
    const DensityLayer& l = profile.layers[i];
    const double fields[5] = {l.width_km, l.exp_term, l.exp_scale_per_km, l.linear_term_per_km,
                              l.constant_term};
    static const char* kField[5] = {"width_km", "exp_term", "exp_scale_per_km",
                                    "linear_term_per_km", "constant_term"};
    for (int f = 0; f < 5; ++f) {
      if (!std::isfinite(fields[f])) {
        problems.push_back(std::string(name) + ".layers[" + std::to_string(i) + "]." + kField[f] +
                           " is not finite (" + fmt(fields[f]) + ")");
      }
    }
    if (l.width_km < 0.0) {
      problems.push_back(std::string(name) + ".layers[" + std::to_string(i) +
                         "].width_km is negative (" + fmt(l.width_km) + ")");
    }
  }
}

}  // namespace

double DensityProfile::density(double altitude_km) const {
  const DensityLayer& layer = altitude_km < layers[0].width_km ? layers[0] : layers[1];
  return std::clamp(layer_value(layer, altitude_km), 0.0, 1.0);
}

std::vector<double> DensityProfile::kink_altitudes_km() const {
  std::vector<double> out;
  const double boundary = layers[0].width_km;
  if (boundary > 0.0) out.push_back(boundary);
  for (int i = 0; i < 2; ++i) {
    const DensityLayer& l = layers[i];
    auto keep = [&](double h) {
      const bool in_layer = i == 0 ? h < boundary : h >= boundary;
      if (std::isfinite(h) && in_layer) out.push_back(h);
    };
    for (double target : {0.0, 1.0}) {
      if (l.exp_term == 0.0 && l.linear_term_per_km != 0.0) {
        keep((target - l.constant_term) / l.linear_term_per_km);
      } else if (l.linear_term_per_km == 0.0 && l.exp_term != 0.0 && l.exp_scale_per_km != 0.0) {
        const double ratio = (target - l.constant_term) / l.exp_term;
        if (ratio > 0.0) keep(std::log(ratio) / l.exp_scale_per_km);
      }
    }
  }
  return out;
}

AtmosphereModel AtmosphereModel::earth() {
  AtmosphereModel m;
  m.bottom_radius_km = 6360.0;
  m.top_radius_km = 6460.0;
  m.rayleigh_scattering = {5.802e-3, 13.558e-3, 33.1e-3};
  m.rayleigh_density.layers[1] = {.exp_term = 1.0, .exp_scale_per_km = -1.0 / 8.0};
  m.mie_scattering = glm::dvec3(3.996e-3);
  m.mie_extinction = glm::dvec3(4.440e-3);
  m.mie_density.layers[1] = {.exp_term = 1.0, .exp_scale_per_km = -1.0 / 1.2};
  m.mie_phase = MiePhase::cornette_shanks;
  m.mie_g = 0.8;
  m.absorption_extinction = {0.650e-3, 1.881e-3, 0.085e-3};
  // Tent: 0 at 10 km, 1 at 25 km, 0 at 40 km.
  m.absorption_density.layers[0] = {
      .width_km = 25.0, .linear_term_per_km = 1.0 / 15.0, .constant_term = -2.0 / 3.0};
  m.absorption_density.layers[1] = {.linear_term_per_km = -1.0 / 15.0, .constant_term = 8.0 / 3.0};
  m.ground_albedo = glm::dvec3(0.3);
  return m;
}

std::vector<std::string> AtmosphereModel::validate() const {
  std::vector<std::string> problems;
  if (!std::isfinite(bottom_radius_km) || bottom_radius_km <= 0.0) {
    problems.push_back("bottom_radius_km must be finite and > 0 (found " + fmt(bottom_radius_km) +
                       ")");
  }
  if (!std::isfinite(top_radius_km)) {
    problems.push_back("top_radius_km is not finite (" + fmt(top_radius_km) + ")");
  } else if (!(top_radius_km > bottom_radius_km)) {
    problems.push_back("top_radius_km (" + fmt(top_radius_km) +
                       ") must be greater than bottom_radius_km (" + fmt(bottom_radius_km) + ")");
  }
  check_rgb(problems, "rayleigh_scattering", rayleigh_scattering);
  check_rgb(problems, "mie_scattering", mie_scattering);
  check_rgb(problems, "mie_extinction", mie_extinction);
  check_rgb(problems, "absorption_extinction", absorption_extinction);
  check_rgb(problems, "ground_albedo", ground_albedo);
  {
    static const char* kChannel[3] = {"r", "g", "b"};
    for (int c = 0; c < 3; ++c) {
      // NaN compares false, so only finite pairs can report this.
      if (mie_extinction[c] < mie_scattering[c]) {
        problems.push_back(std::string("mie_extinction.") + kChannel[c] + " (" +
                           fmt(mie_extinction[c]) + ") is below mie_scattering." + kChannel[c] +
                           " (" + fmt(mie_scattering[c]) + "): negative absorption");
      }
    }
  }
  for (int c = 0; c < 3; ++c) {
    if (ground_albedo[c] > 1.0) {
      problems.push_back("ground_albedo." + std::string(1, "rgb"[c]) + " (" +
                         fmt(ground_albedo[c]) + ") exceeds 1: the ground would create energy");
    }
  }
  if (!(mie_g > -1.0 && mie_g < 1.0)) {
    problems.push_back("mie_g (" + fmt(mie_g) + ") must lie in the open interval (-1, 1)");
  }
  if (mie_phase != MiePhase::cornette_shanks && mie_phase != MiePhase::henyey_greenstein) {
    problems.push_back("mie_phase is not a known phase function");
  }
  check_profile(problems, "rayleigh_density", rayleigh_density);
  check_profile(problems, "mie_density", mie_density);
  check_profile(problems, "absorption_density", absorption_density);
  return problems;
}

AtmosphereModel AtmosphereModel::scaled(double k) const {
  AtmosphereModel m = *this;
  m.bottom_radius_km *= k;
  m.top_radius_km *= k;
  m.rayleigh_scattering /= k;
  m.mie_scattering /= k;
  m.mie_extinction /= k;
  m.absorption_extinction /= k;
  for (DensityProfile* p : {&m.rayleigh_density, &m.mie_density, &m.absorption_density}) {
    for (DensityLayer& l : p->layers) {
      l.width_km *= k;
      l.exp_scale_per_km /= k;
      l.linear_term_per_km /= k;
    }
  }
  return m;
}

AtmosphereModel AtmosphereModel::with_density_scale(double factor) const {
  AtmosphereModel m = *this;
  m.rayleigh_scattering *= factor;
  m.mie_scattering *= factor;
  m.mie_extinction *= factor;
  m.absorption_extinction *= factor;
  return m;
}

LocalCoefficients AtmosphereModel::coefficients(double altitude_km) const {
  if (!(altitude_km >= 0.0 && altitude_km <= thickness_km())) return {};
  const double rho_r = rayleigh_density.density(altitude_km);
  const double rho_m = mie_density.density(altitude_km);
  const double rho_a = absorption_density.density(altitude_km);
  LocalCoefficients out;
  out.rayleigh_scattering = rayleigh_scattering * rho_r;
  out.mie_scattering = mie_scattering * rho_m;
  out.extinction = out.rayleigh_scattering + mie_extinction * rho_m + absorption_extinction * rho_a;
  return out;
}

glm::dvec3 AtmosphereModel::extinction(double altitude_km) const {
  if (!(altitude_km >= 0.0 && altitude_km <= thickness_km())) return glm::dvec3(0.0);
  return rayleigh_scattering * rayleigh_density.density(altitude_km) +
         mie_extinction * mie_density.density(altitude_km) +
         absorption_extinction * absorption_density.density(altitude_km);
}

double AtmosphereModel::max_extinction() const {
  const glm::dvec3 sum = rayleigh_scattering + mie_extinction + absorption_extinction;
  return std::max({sum.x, sum.y, sum.z, 0.0});
}

double AtmosphereModel::mie_phase_value(double cos_theta) const {
  return mie_phase == MiePhase::henyey_greenstein ? henyey_greenstein_phase(mie_g, cos_theta)
                                                  : cornette_shanks_phase(mie_g, cos_theta);
}

std::vector<double> AtmosphereModel::kink_altitudes_km() const {
  std::vector<double> out;
  for (const DensityProfile* p : {&rayleigh_density, &mie_density, &absorption_density}) {
    for (double h : p->kink_altitudes_km()) {
      if (h > 0.0 && h < thickness_km()) out.push_back(h);
    }
  }
  std::sort(out.begin(), out.end());
  // Merge kinks that differ by rounding only (24.999999999999996 and 25).
  const double merge = 1e-12 * thickness_km();
  out.erase(
      std::unique(out.begin(), out.end(), [merge](double a, double b) { return b - a <= merge; }),
      out.end());
  return out;
}

double rayleigh_phase(double cos_theta) {
  return 3.0 / (16.0 * kPi) * (1.0 + cos_theta * cos_theta);
}

double cornette_shanks_phase(double g, double cos_theta) {
  const double base = hg_denominator_base(g, cos_theta);
  return 3.0 * (1.0 - g * g) * (1.0 + cos_theta * cos_theta) /
         (8.0 * kPi * (2.0 + g * g) * base * std::sqrt(base));
}

double henyey_greenstein_phase(double g, double cos_theta) {
  const double base = hg_denominator_base(g, cos_theta);
  return (1.0 - g * g) / (4.0 * kPi * base * std::sqrt(base));
}

}  // namespace welkin::atmosphere::reference
