#pragma once
// Diffuse light through a cloud: the two-stream transmittance 1 / (1 + k tau) of a conservative slab
// of optical depth tau toward the light (k = 0.75 (1 - g) in two-stream theory; fitted, see
// light_model_fit.glsl).
#include "clouds/light_model_fit.glsl"
float clouds_diffuse_transmittance(float tau) { return 1.0 / (1.0 + CLOUDS_MS_DIFFUSION * tau); }
// The direct beam toward the light through the optical depth the light march measured: the march
// and the shadow map leave the detail noise out (it erodes edges the light crosses at most once), so
// they overestimate the depth; the factor is fitted with the rest.
float clouds_direct_transmittance(float tau) { return exp(-CLOUDS_DIRECT_DEPTH * tau); }
