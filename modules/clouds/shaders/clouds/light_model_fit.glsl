#pragma once
// The multiple-scattering estimate's coefficients (light_model.glsl), fitted to the project's path
// tracer by `welkin accuracy clouds --fit`, which writes this file; the fit overrides them with
// defines while it searches. These are the hand-set values the fit starts from.
#ifndef CLOUDS_MS_DIFFUSION
#define CLOUDS_MS_DIFFUSION 0.15
#endif
#ifndef CLOUDS_MS_BASE
#define CLOUDS_MS_BASE 0.159155
#endif
#ifndef CLOUDS_MS_BELOW
#define CLOUDS_MS_BELOW 0.0358099
#endif
#ifndef CLOUDS_MS_BELOW_SATURATION
#define CLOUDS_MS_BELOW_SATURATION 0.15
#endif
#ifndef CLOUDS_MS_DIRECT
#define CLOUDS_MS_DIRECT 0.25
#endif
#ifndef CLOUDS_MS_POWDER
#define CLOUDS_MS_POWDER 1000.0
#endif
#ifndef CLOUDS_DIRECT_DEPTH
#define CLOUDS_DIRECT_DEPTH 1.0
#endif
