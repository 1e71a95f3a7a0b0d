#pragma once
// Cloud phase functions (1/sr), mirrored by reference/phase.cpp.
const float CLOUDS_PI = 3.14159265358979;

float clouds_hg(float mu, float g) {
  float d = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) / (4.0 * CLOUDS_PI * d * sqrt(d));
}

// Draine 2003: Henyey-Greenstein times (1 + a mu^2), normalised.
float clouds_draine(float mu, float g, float a) {
  float d = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) * (1.0 + a * mu * mu) /
         (4.0 * CLOUDS_PI * d * sqrt(d) * (1.0 + a * (1.0 + 2.0 * g * g) / 3.0));
}

// Jendersie & d'Eon 2023: Mie scattering by droplets of diameter d (5-50 um) as HG + Draine.
float clouds_droplet_mie(float mu, float d) {
  float g_hg = exp(-0.0990567 / (d - 1.67154));
  float g_d = exp(-2.20679 / (d + 3.91029) - 0.428934);
  float alpha = exp(3.62489 - 8.29288 / (d + 5.52825));
  float w_d = exp(-0.599085 / (d - 0.641583) - 0.665888);
  return (1.0 - w_d) * clouds_hg(mu, g_hg) + w_d * clouds_draine(mu, g_d, alpha);
}

// The phase of octave k of the multiple-scattering approximation: anisotropy scaled by c^k
// (Wrenninge 2015, c = 0.5), so higher orders scatter more evenly.
// CLOUDS_PHASE_MODEL (src/density_field.cpp, light_model_defines) compiles the model in; undefined, it is
// read from the block.
float clouds_phase(float mu, float octave_scale) {
#ifdef CLOUDS_PHASE_MODEL
  const bool droplets = CLOUDS_PHASE_MODEL == 1;
#else
  bool droplets = cl.phase_model > 0.5;
#endif
  if (droplets) {
    // The droplet fit has no g to scale: blend it toward isotropic instead.
    return mix(1.0 / (4.0 * CLOUDS_PI), clouds_droplet_mie(mu, cl.droplet_diameter_um), octave_scale);
  }
  return mix(clouds_hg(mu, cl.g_backward * octave_scale), clouds_hg(mu, cl.g_forward * octave_scale),
             cl.forward_weight);
}
