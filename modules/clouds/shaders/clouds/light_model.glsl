#pragma once
// The light a cloud sample scatters toward the camera, per unit extinction (the albedo included):
// shared by the march and the mesh clusters' puffs, so that both paths light one cloud alike.
//   mu: cosine between the view ray and the direction toward the light; phase_single: the phase at mu;
//   tau: optical depth toward the light; sigma_t: extinction at the sample (1/m);
//   depth_below_m: the cloud's depth under the sample (its light reflected back up); l: toward the
//   light; up: the local vertical; e_light, e_sky: the light's and the sky's irradiance there.
// Needs clouds/density.glsl (the block) and clouds/phase.glsl.
// The two ways the optical depth toward the light enters the diffusion model: the direct beam's
// transmittance exp(-tau), and the two-stream (diffuse) transmittance 1 / (1 + 0.15 tau). The source
// is linear in both, so an average of sources over many samples is the source of their averages
// (the billboards' atlas keeps those averages toward every direction).
// CLOUDS_MULTIPLE_SCATTERING and CLOUDS_POWDER (src/density_field.cpp, light_model_defines) compile the
// model's choices in; undefined, they are read from the block.
#include "clouds/transmittance.glsl"
#ifdef CLOUDS_MULTIPLE_SCATTERING
const bool clouds_diffusion_model = CLOUDS_MULTIPLE_SCATTERING == 1;
#else
#define clouds_diffusion_model (cl.multiple_scattering > 0.5)
#endif

// Schneider's beer-powder darkening of thin edges (cl.powder = 0: off).
float clouds_powder(float sigma_t) {
#ifdef CLOUDS_POWDER
  if (CLOUDS_POWDER == 0) return 1.0;
#endif
  return 1.0 - cl.powder * exp(-2.0 * sigma_t * cl.light_step_m);
}

// The diffusion model's source from the two transmittances (see clouds_sample_source).
vec3 clouds_diffusion_source(float mu, float phase_single, float direct, float diffuse, float sigma_t,
                             float depth_below_m, vec3 l, vec3 up, vec3 e_light, vec3 e_sky) {
  // Single scattering, and the multiple-scattering estimate: the diffuse light a conservative slab
  // lets through beyond the direct beam (its two-stream transmittance toward the light), times what
  // the cloud below sends back up: in a slab the diffuse light falls linearly from the lit top to the
  // base, so a point with little cloud under it (a base) keeps little of it and one deep above the
  // base (a top) gathers the reflection of all the cloud beneath. The form is (base + below tau_b) /
  // (1 + saturation tau_b), tau_b the optical depth below; its coefficients are fitted to the path
  // tracer (light_model_fit.glsl).
  float tau_below = sigma_t * depth_below_m;
  float below =
      (CLOUDS_MS_BASE + CLOUDS_MS_BELOW * tau_below) / (1.0 + CLOUDS_MS_BELOW_SATURATION * tau_below);
  // Where the cloud is thin around the point (its outskirts, wisps) little light has been scattered
  // toward it from its neighbours: the multiple-scattering estimate fades with the optical depth of
  // the first light step at the local density (the physical side of Schneider's "powder").
  float neighbours = 1.0 - exp(-CLOUDS_MS_POWDER * sigma_t * cl.light_step_m);
  float scattered =
      phase_single * direct + max(diffuse - CLOUDS_MS_DIRECT * direct, 0.0) * below * neighbours;
  scattered *= clouds_powder(sigma_t);
  // Sky from above and the lit ground from below, diffused through the cloud: the two-stream
  // transmittance 1 / (1 + 0.75 (1 - g) tau) with g = 0.8, tau the optical depth toward the light
  // (no extra samples: on software rasterisers each density sample is most of a step's cost).
  vec3 e_ground = cl.ground_albedo * (e_light * max(dot(l, up), 0.0) * direct + e_sky);
  vec3 ambient = (e_sky + e_ground) * diffuse / (2.0 * CLOUDS_PI);
  float albedo = cl.scattering / max(cl.scattering + cl.absorption, 1e-9);
  return albedo * (e_light * scattered + ambient);
}

vec3 clouds_sample_source(float mu, float phase_single, float tau, float sigma_t, float depth_below_m, vec3 l,
                          vec3 up, vec3 e_light, vec3 e_sky) {
  if (clouds_diffusion_model)
    return clouds_diffusion_source(mu, phase_single, clouds_direct_transmittance(tau),
                                   clouds_diffuse_transmittance(tau), sigma_t, depth_below_m, l, up, e_light,
                                   e_sky);
  // Wrenninge 2015: octave k scatters b^k of the light, sees a^k of the optical depth, and a
  // phase whose anisotropy is scaled by c^k (a = b = c = 1/2).
  float scattered = 0.0;
  int octaves = int(cl.octaves);
  float weight = 1.0;
  for (int k = 0; k < octaves; ++k) {
    scattered += weight * clouds_phase(mu, weight) * exp(-weight * tau);
    weight *= 0.5;
  }
  scattered *= clouds_powder(sigma_t);
  float direct = exp(-tau);
  vec3 e_ground = cl.ground_albedo * (e_light * max(dot(l, up), 0.0) * direct + e_sky);
  vec3 ambient = (e_sky + e_ground) * clouds_diffuse_transmittance(tau) / (2.0 * CLOUDS_PI);
  float albedo = cl.scattering / max(cl.scattering + cl.absorption, 1e-9);
  return albedo * (e_light * scattered + ambient);
}
