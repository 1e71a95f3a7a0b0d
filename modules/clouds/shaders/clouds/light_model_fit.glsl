#pragma once
// The multiple-scattering estimate's coefficients (light_model.glsl), fitted to the project's path
// tracer by `welkin accuracy clouds --fit` (tools/welkin/cmd_accuracy_clouds.cpp), which wrote this file:
// 20 rays, 8192 paths each; relative RMSE at high 17.9% (from the hand-set values) -> high 11.9%, low 21%.
// The fit overrides them with defines while it searches.
#ifndef CLOUDS_MS_DIFFUSION  // k in the diffuse transmittance 1 / (1 + k tau) toward the light
#define CLOUDS_MS_DIFFUSION 0.165022
#endif
#ifndef CLOUDS_MS_BASE  // the diffuse light's weight with no cloud below
#define CLOUDS_MS_BASE 0.149046
#endif
#ifndef CLOUDS_MS_BELOW  // its growth with the optical depth below
#define CLOUDS_MS_BELOW 0.035808
#endif
#ifndef CLOUDS_MS_BELOW_SATURATION  // the saturation of that growth
#define CLOUDS_MS_BELOW_SATURATION 0.144207
#endif
#ifndef CLOUDS_MS_DIRECT  // the share of the direct beam taken out of the diffuse light
#define CLOUDS_MS_DIRECT 0.261118
#endif
#ifndef CLOUDS_MS_POWDER  // the estimate's fade where the cloud around is thin
#define CLOUDS_MS_POWDER 10.0976
#endif
#ifndef CLOUDS_DIRECT_DEPTH  // the light march's optical depth as the direct beam sees it
#define CLOUDS_DIRECT_DEPTH 0.715277
#endif
