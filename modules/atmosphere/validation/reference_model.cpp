#include "validation/reference_model.h"

namespace welkin::atmosphere {

reference::DensityProfile to_reference(const DensityProfile& p) {
  reference::DensityProfile out;
  auto conv = [](const DensityLayer& l) {
    return reference::DensityLayer{l.width_km, l.exp_term, l.exp_scale_per_km, l.linear_term_per_km,
                                   l.constant_term};
  };
  if (p.size() == 1) out.layers[1] = conv(p[0]);
  if (p.size() >= 2) out.layers[0] = conv(p[0]), out.layers[1] = conv(p[1]);
  return out;
}

reference::AtmosphereModel to_reference(const Atmosphere& a) {
  reference::AtmosphereModel m;
  m.bottom_radius_km = a.bottom_radius_km;
  m.top_radius_km = a.top_radius_km;
  m.rayleigh_scattering = glm::dvec3(a.rayleigh_scattering);
  m.rayleigh_density = to_reference(a.rayleigh_density);
  m.mie_scattering = glm::dvec3(a.mie_scattering);
  m.mie_extinction = glm::dvec3(a.mie_extinction);
  m.mie_density = to_reference(a.mie_density);
  m.mie_phase = a.mie_phase == MiePhase::cornette_shanks ? reference::MiePhase::cornette_shanks
                                                         : reference::MiePhase::henyey_greenstein;
  m.mie_g = a.mie_g;
  m.absorption_extinction = glm::dvec3(a.absorption_extinction);
  m.absorption_density = to_reference(a.absorption_density);
  m.ground_albedo = glm::dvec3(a.ground_albedo);
  return m;
}

}  // namespace welkin::atmosphere
