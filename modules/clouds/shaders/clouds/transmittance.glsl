#pragma once
// Diffuse light through a cloud: the two-stream transmittance 1 / (1 + 0.75 (1 - g) tau) of a
// conservative slab (g = 0.8) of optical depth tau toward the light.
float clouds_diffuse_transmittance(float tau) { return 1.0 / (1.0 + 0.15 * tau); }
