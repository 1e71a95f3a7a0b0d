#pragma once
// The light model's weights (light_model.glsl), fitted to the project's path tracer by
// `welkin accuracy clouds --fit` (tools/welkin/cloud_light_fit.cpp), which wrote this file: 20 rays,
// 8192 paths each; the march's relative RMSE after the fit:
//   the built-in cumulus case, 20 rays: low 17.8% (worst 39.3%) high 11.5% (worst 32.9%)
// The fit overrides them with defines while it measures.
#ifndef CLOUDS_MS_DIFFUSION  // k in 1 / (1 + k tau) for the ground's shading: 0.75 (1 - g), g = 0.8
#define CLOUDS_MS_DIFFUSION 0.15
#endif
#ifndef CLOUDS_DIRECT_DEPTH  // the light march's optical depth as the direct beam sees it
#define CLOUDS_DIRECT_DEPTH 1.0
#endif
#ifndef CLOUDS_MS_POWDER  // n in the estimate's fade 1 - exp(-n sigma_t l_1) where the cloud around is thin
#define CLOUDS_MS_POWDER 10.0
#endif
#ifndef CLOUDS_SS_WEIGHT  // single scattering's weight (0 only while the fit measures the other terms)
#define CLOUDS_SS_WEIGHT 1.0
#endif
#ifndef CLOUDS_MS_W0  // D = T_d(tau) - T(tau): the diffuse light beyond the direct beam, toward the light
#define CLOUDS_MS_W0 0.0976356
#endif
#ifndef CLOUDS_MS_W1  // D S(tau_b): ... gathered from the cloud below
#define CLOUDS_MS_W1 0.0328198
#endif
#ifndef CLOUDS_MS_W2  // D p_2(mu): ... forward-peaked
#define CLOUDS_MS_W2 0.0
#endif
#ifndef CLOUDS_MS_W3  // mu_0 T_d(tau_a): the light the top takes in, let down through the cloud above
#define CLOUDS_MS_W3 0.0
#endif
#ifndef CLOUDS_MS_W4  // mu_0 T_d(tau_a) S(tau_b): ... and reflected back up from below
#define CLOUDS_MS_W4 0.0
#endif
#ifndef CLOUDS_MS_W5  // T_d(tau): the diffuse light toward the light, direct beam included
#define CLOUDS_MS_W5 0.0
#endif
#ifndef CLOUDS_MS_W6  // T_d(tau) S(tau_b): ... gathered from the cloud below
#define CLOUDS_MS_W6 0.054638
#endif
#ifndef CLOUDS_MS_W7  // D T_d(tau_a): the diffuse light toward the light that the column above lets by
#define CLOUDS_MS_W7 0.0130539
#endif
#ifndef CLOUDS_MS_W8  // exp(-tau / 4): an octave
#define CLOUDS_MS_W8 0.0
#endif
#ifndef CLOUDS_MS_W9  // exp(-tau / 16): an octave
#define CLOUDS_MS_W9 0.0
#endif
#ifndef CLOUDS_MS_W10  // exp(-tau / 4) p_2(mu): an octave, forward-peaked
#define CLOUDS_MS_W10 0.0
#endif
#ifndef CLOUDS_MS_W11  // D S(tau_B): the diffuse light gathered from the cloud's body below
#define CLOUDS_MS_W11 0.00334799
#endif
#ifndef CLOUDS_MS_W12  // mu_0 T_d(tau_A): the light let down through the body above
#define CLOUDS_MS_W12 0.0
#endif
#ifndef CLOUDS_MS_W13  // T_d(tau) S(tau_B)
#define CLOUDS_MS_W13 0.0
#endif
#ifndef CLOUDS_MS_W14  // mu_0 T_d(tau_A) S(tau_B)
#define CLOUDS_MS_W14 0.0
#endif
#ifndef CLOUDS_MS_W15  // exp(-tau / 16) S(tau_B)
#define CLOUDS_MS_W15 0.0408996
#endif
// Candidates added after this fit (the slab of diffusion theory); the same fit run again with them
// (cumulus case, 2026-11-27) keeps them at 0: only decks in training choose them (clouds-light.md).
#ifndef CLOUDS_MS_W16  // mu_0 (1 + 2k tau_B) / (1 + k (tau_A + tau_B)): the diffuse light in a lit slab
#define CLOUDS_MS_W16 0.0
#endif
#ifndef CLOUDS_MS_W17  // mu_0 (1 + 2k tau_b) / (1 + k (tau_a + tau_b)): the same with the sample's own depths
#define CLOUDS_MS_W17 0.0
#endif
