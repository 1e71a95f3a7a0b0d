#pragma once
// The light model's weights (light_model.glsl), fitted to the project's path tracer by
// `welkin accuracy clouds --fit` (tools/welkin/cloud_light_fit.cpp), which wrote this file: 62 rays,
// 8192 paths each; the march's relative RMSE after the fit:
//   the built-in cumulus case, 20 rays:
//     low 29% (worst 69.5%) high 28.1% (worst 72.8%)
//   modules/clouds/validation/training/stratus-deck.json with
//   modules/clouds/validation/training/stratus-deck-rays.json, 12 rays:
//     low 8.3% (worst 17.9%) high 12.6% (worst 32.8%)
//   modules/clouds/validation/training/stratus-deck-low-sun.json with
//   modules/clouds/validation/training/stratus-deck-rays.json, 12 rays:
//     low 16.5% (worst 34.3%) high 14.9% (worst 34.5%)
//   modules/clouds/validation/training/cumulus-low-sun.json with
//   modules/clouds/validation/training/cumulus-low-sun-rays.json, 18 rays:
//     low 28.8% (worst 52.5%) high 19.4% (worst 37.4%)
//   kept back: modules/clouds/validation/holdout/stratocumulus-low-sun.json with
//   modules/clouds/validation/holdout/stratocumulus-rays.json, 17 rays:
//     low 55.5% (worst 159.4%) high 23.7% (worst 49.6%)
// The fit overrides them with defines while it measures.
// CLOUDS_MS_DIFFUSION: k in 1 / (1 + k tau) for the ground's shading: 0.75 (1 - g), g = 0.8
#ifndef CLOUDS_MS_DIFFUSION
#define CLOUDS_MS_DIFFUSION 0.15
#endif
// CLOUDS_DIRECT_DEPTH: the light march's optical depth as the direct beam sees it
#ifndef CLOUDS_DIRECT_DEPTH
#define CLOUDS_DIRECT_DEPTH 1.0
#endif
// CLOUDS_MS_POWDER: n in the estimate's fade 1 - exp(-n sigma_t l_1) where the cloud around is thin
#ifndef CLOUDS_MS_POWDER
#define CLOUDS_MS_POWDER 10.0
#endif
// CLOUDS_SS_WEIGHT: single scattering's weight (0 only while the fit measures the other terms)
#ifndef CLOUDS_SS_WEIGHT
#define CLOUDS_SS_WEIGHT 1.0
#endif
#ifndef CLOUDS_SHAPE_DETAIL  // the march reads the detail noise (light_model_defines; not low)
#define CLOUDS_SHAPE_DETAIL 1
#endif
#if CLOUDS_SHAPE_DETAIL
// CLOUDS_MS_W0: D = T_d(tau) - T(tau): the diffuse light beyond the direct beam, toward the light
#ifndef CLOUDS_MS_W0
#define CLOUDS_MS_W0 0.0
#endif
// CLOUDS_MS_W1: D S(tau_b): ... gathered from the cloud below
#ifndef CLOUDS_MS_W1
#define CLOUDS_MS_W1 0.0
#endif
// CLOUDS_MS_W2: D p_2(mu): ... forward-peaked
#ifndef CLOUDS_MS_W2
#define CLOUDS_MS_W2 0.0
#endif
// CLOUDS_MS_W3: mu_0 T_d(tau_a): the light the top takes in, let down through the cloud above
#ifndef CLOUDS_MS_W3
#define CLOUDS_MS_W3 0.0
#endif
// CLOUDS_MS_W4: mu_0 T_d(tau_a) S(tau_b): ... and reflected back up from below
#ifndef CLOUDS_MS_W4
#define CLOUDS_MS_W4 0.0
#endif
// CLOUDS_MS_W5: T_d(tau): the diffuse light toward the light, direct beam included
#ifndef CLOUDS_MS_W5
#define CLOUDS_MS_W5 0.0
#endif
// CLOUDS_MS_W6: T_d(tau) S(tau_b): ... gathered from the cloud below
#ifndef CLOUDS_MS_W6
#define CLOUDS_MS_W6 0.0
#endif
// CLOUDS_MS_W7: D T_d(tau_a): the diffuse light toward the light that the column above lets by
#ifndef CLOUDS_MS_W7
#define CLOUDS_MS_W7 0.0
#endif
// CLOUDS_MS_W8: exp(-tau / 4): an octave
#ifndef CLOUDS_MS_W8
#define CLOUDS_MS_W8 0.0
#endif
// CLOUDS_MS_W9: exp(-tau / 16): an octave
#ifndef CLOUDS_MS_W9
#define CLOUDS_MS_W9 0.0
#endif
// CLOUDS_MS_W10: exp(-tau / 4) p_2(mu): an octave, forward-peaked
#ifndef CLOUDS_MS_W10
#define CLOUDS_MS_W10 0.0
#endif
// CLOUDS_MS_W11: D S(tau_B): the diffuse light gathered from the cloud's body below
#ifndef CLOUDS_MS_W11
#define CLOUDS_MS_W11 0.0
#endif
// CLOUDS_MS_W12: mu_0 T_d(tau_A): the light let down through the body above
#ifndef CLOUDS_MS_W12
#define CLOUDS_MS_W12 0.0
#endif
// CLOUDS_MS_W13: T_d(tau) S(tau_B)
#ifndef CLOUDS_MS_W13
#define CLOUDS_MS_W13 0.0
#endif
// CLOUDS_MS_W14: mu_0 T_d(tau_A) S(tau_B)
#ifndef CLOUDS_MS_W14
#define CLOUDS_MS_W14 0.0
#endif
// CLOUDS_MS_W15: exp(-tau / 16) S(tau_B)
#ifndef CLOUDS_MS_W15
#define CLOUDS_MS_W15 0.0
#endif
// CLOUDS_MS_W16: mu_0 (1 + 2k tau_B) / (1 + k (tau_A + tau_B)): the diffuse light in a lit slab
#ifndef CLOUDS_MS_W16
#define CLOUDS_MS_W16 0.0203602
#endif
// CLOUDS_MS_W17: mu_0 (1 + 2k tau_b) / (1 + k (tau_a + tau_b)): the same with the sample's own depths
#ifndef CLOUDS_MS_W17
#define CLOUDS_MS_W17 0.0
#endif
// CLOUDS_MS_W18: mu_0 D: the diffuse light beyond the direct beam, per unit area of a deck's lit top
#ifndef CLOUDS_MS_W18
#define CLOUDS_MS_W18 0.0
#endif
// CLOUDS_MS_W19: mu_0 D S(tau_b)
#ifndef CLOUDS_MS_W19
#define CLOUDS_MS_W19 0.0
#endif
// CLOUDS_MS_W20: mu_0 T_d(tau) S(tau_b)
#ifndef CLOUDS_MS_W20
#define CLOUDS_MS_W20 0.0
#endif
// CLOUDS_MS_W21: mu_0 D T_d(tau_a)
#ifndef CLOUDS_MS_W21
#define CLOUDS_MS_W21 0.0
#endif
// CLOUDS_MS_W22: mu_0 exp(-tau / 16)
#ifndef CLOUDS_MS_W22
#define CLOUDS_MS_W22 0.0263169
#endif
// CLOUDS_MS_W23: c D, c = clamp(tau_A / tau, mu_0, 1): the cosine at which the light entered the lit surface
#ifndef CLOUDS_MS_W23
#define CLOUDS_MS_W23 0.0485005
#endif
// CLOUDS_MS_W24: c D S(tau_b)
#ifndef CLOUDS_MS_W24
#define CLOUDS_MS_W24 0.0625032
#endif
// CLOUDS_MS_W25: f D, f the clear fraction of the light march: light let in through gaps and the soft edge
#ifndef CLOUDS_MS_W25
#define CLOUDS_MS_W25 0.0
#endif
// CLOUDS_MS_W26: f D S(tau_b)
#ifndef CLOUDS_MS_W26
#define CLOUDS_MS_W26 0.0
#endif
// CLOUDS_MS_W27: mu_0 exp(-tau / 4)
#ifndef CLOUDS_MS_W27
#define CLOUDS_MS_W27 0.00568455
#endif
// CLOUDS_MS_W28: T_d(tau) (1 - mu) / 2: the diffuse light seen from the light's side (a lit surface's
// reflection)
#ifndef CLOUDS_MS_W28
#define CLOUDS_MS_W28 0.0244033
#endif
// CLOUDS_MS_W29: D (1 - mu) / 2
#ifndef CLOUDS_MS_W29
#define CLOUDS_MS_W29 0.0248784
#endif
// CLOUDS_MS_W30: F mu_0 D S(tau_b), F the sample's density over its un-eroded envelope's: light leaks
// between billows
#ifndef CLOUDS_MS_W30
#define CLOUDS_MS_W30 0.252482
#endif
// CLOUDS_MS_W31: F c D S(tau_b)
#ifndef CLOUDS_MS_W31
#define CLOUDS_MS_W31 0.0516174
#endif
// CLOUDS_MS_W32: E F mu_0 D S(tau_b), E = k tau_e / (1 + k tau_e), tau_e the optical depth to the cloud's
// side: the diffuse light falls toward the side where it escapes
#ifndef CLOUDS_MS_W32
#define CLOUDS_MS_W32 0.0
#endif
// CLOUDS_MS_W33: E F c D S(tau_b)
#ifndef CLOUDS_MS_W33
#define CLOUDS_MS_W33 0.0
#endif
// CLOUDS_MS_W34: E c D
#ifndef CLOUDS_MS_W34
#define CLOUDS_MS_W34 0.0
#endif
// CLOUDS_MS_W35: E mu_0 (1 + 2k tau_B) / (1 + k (tau_A + tau_B))
#ifndef CLOUDS_MS_W35
#define CLOUDS_MS_W35 0.0
#endif
// CLOUDS_MS_W36: E T_d(tau) (1 - mu) / 2
#ifndef CLOUDS_MS_W36
#define CLOUDS_MS_W36 0.0
#endif
// CLOUDS_MS_W37: E mu_0 exp(-tau / 16)
#ifndef CLOUDS_MS_W37
#define CLOUDS_MS_W37 0.0
#endif
// CLOUDS_MS_W38: max(n.l, 0) D, n the outward normal of the un-eroded envelope (the cloud's body) at the
// sample: a face lit by the light
#ifndef CLOUDS_MS_W38
#define CLOUDS_MS_W38 0.0
#endif
// CLOUDS_MS_W39: max(-n.l, 0) D: a face in the cloud's own shadow
#ifndef CLOUDS_MS_W39
#define CLOUDS_MS_W39 0.0
#endif
// CLOUDS_MS_W40: max(n.l, 0) T_d(tau) S(tau_b)
#ifndef CLOUDS_MS_W40
#define CLOUDS_MS_W40 0.0
#endif
// CLOUDS_MS_W41: (1 + n.l) / 2 T_d(tau)
#ifndef CLOUDS_MS_W41
#define CLOUDS_MS_W41 0.0
#endif
// CLOUDS_MS_W42: (1 + n.l) / 2 (1 + n.(-v)) / 2 D, v the view ray: the lit face turned toward the camera
#ifndef CLOUDS_MS_W42
#define CLOUDS_MS_W42 0.0
#endif
// CLOUDS_MS_W43: F max(n.l, 0) D S(tau_b)
#ifndef CLOUDS_MS_W43
#define CLOUDS_MS_W43 0.0
#endif
// CLOUDS_MS_W44: (1 + n.(-v)) / 2 D: the face turned toward the camera
#ifndef CLOUDS_MS_W44
#define CLOUDS_MS_W44 0.0
#endif
// CLOUDS_MS_W45: A = max(N - T, 0), N the direct beam's mean transmittance over the columns 300 m across the
// light from the sample's: sunlight let into the cloud around the sample that its own column does not get
#ifndef CLOUDS_MS_W45
#define CLOUDS_MS_W45 0.0
#endif
// CLOUDS_MS_W46: A S(tau_b)
#ifndef CLOUDS_MS_W46
#define CLOUDS_MS_W46 0.0
#endif
// CLOUDS_MS_W47: A (1 - mu) / 2: seen from the light's side
#ifndef CLOUDS_MS_W47
#define CLOUDS_MS_W47 0.0
#endif
// CLOUDS_MS_W48: A with the columns 1.2 km away
#ifndef CLOUDS_MS_W48
#define CLOUDS_MS_W48 0.0
#endif
// CLOUDS_MS_W49: A S(tau_b), the columns 1.2 km away
#ifndef CLOUDS_MS_W49
#define CLOUDS_MS_W49 0.0
#endif
// CLOUDS_MS_W50: A (1 - mu) / 2, the columns 1.2 km away
#ifndef CLOUDS_MS_W50
#define CLOUDS_MS_W50 0.0
#endif
// CLOUDS_MS_W51: A T_d(tau), the columns 1.2 km away: their light diffused through the sample's own column
#ifndef CLOUDS_MS_W51
#define CLOUDS_MS_W51 0.0
#endif
#else  // without the detail noise (low): a smoother field than the path tracer's
// CLOUDS_MS_W0: D = T_d(tau) - T(tau): the diffuse light beyond the direct beam, toward the light
#ifndef CLOUDS_MS_W0
#define CLOUDS_MS_W0 0.0
#endif
// CLOUDS_MS_W1: D S(tau_b): ... gathered from the cloud below
#ifndef CLOUDS_MS_W1
#define CLOUDS_MS_W1 0.0
#endif
// CLOUDS_MS_W2: D p_2(mu): ... forward-peaked
#ifndef CLOUDS_MS_W2
#define CLOUDS_MS_W2 0.0
#endif
// CLOUDS_MS_W3: mu_0 T_d(tau_a): the light the top takes in, let down through the cloud above
#ifndef CLOUDS_MS_W3
#define CLOUDS_MS_W3 0.0
#endif
// CLOUDS_MS_W4: mu_0 T_d(tau_a) S(tau_b): ... and reflected back up from below
#ifndef CLOUDS_MS_W4
#define CLOUDS_MS_W4 0.0
#endif
// CLOUDS_MS_W5: T_d(tau): the diffuse light toward the light, direct beam included
#ifndef CLOUDS_MS_W5
#define CLOUDS_MS_W5 0.0
#endif
// CLOUDS_MS_W6: T_d(tau) S(tau_b): ... gathered from the cloud below
#ifndef CLOUDS_MS_W6
#define CLOUDS_MS_W6 0.0
#endif
// CLOUDS_MS_W7: D T_d(tau_a): the diffuse light toward the light that the column above lets by
#ifndef CLOUDS_MS_W7
#define CLOUDS_MS_W7 0.0
#endif
// CLOUDS_MS_W8: exp(-tau / 4): an octave
#ifndef CLOUDS_MS_W8
#define CLOUDS_MS_W8 0.0
#endif
// CLOUDS_MS_W9: exp(-tau / 16): an octave
#ifndef CLOUDS_MS_W9
#define CLOUDS_MS_W9 0.000285684
#endif
// CLOUDS_MS_W10: exp(-tau / 4) p_2(mu): an octave, forward-peaked
#ifndef CLOUDS_MS_W10
#define CLOUDS_MS_W10 0.0
#endif
// CLOUDS_MS_W11: D S(tau_B): the diffuse light gathered from the cloud's body below
#ifndef CLOUDS_MS_W11
#define CLOUDS_MS_W11 0.0
#endif
// CLOUDS_MS_W12: mu_0 T_d(tau_A): the light let down through the body above
#ifndef CLOUDS_MS_W12
#define CLOUDS_MS_W12 0.0
#endif
// CLOUDS_MS_W13: T_d(tau) S(tau_B)
#ifndef CLOUDS_MS_W13
#define CLOUDS_MS_W13 0.0
#endif
// CLOUDS_MS_W14: mu_0 T_d(tau_A) S(tau_B)
#ifndef CLOUDS_MS_W14
#define CLOUDS_MS_W14 0.0
#endif
// CLOUDS_MS_W15: exp(-tau / 16) S(tau_B)
#ifndef CLOUDS_MS_W15
#define CLOUDS_MS_W15 0.0
#endif
// CLOUDS_MS_W16: mu_0 (1 + 2k tau_B) / (1 + k (tau_A + tau_B)): the diffuse light in a lit slab
#ifndef CLOUDS_MS_W16
#define CLOUDS_MS_W16 0.0
#endif
// CLOUDS_MS_W17: mu_0 (1 + 2k tau_b) / (1 + k (tau_a + tau_b)): the same with the sample's own depths
#ifndef CLOUDS_MS_W17
#define CLOUDS_MS_W17 0.0200639
#endif
// CLOUDS_MS_W18: mu_0 D: the diffuse light beyond the direct beam, per unit area of a deck's lit top
#ifndef CLOUDS_MS_W18
#define CLOUDS_MS_W18 0.0
#endif
// CLOUDS_MS_W19: mu_0 D S(tau_b)
#ifndef CLOUDS_MS_W19
#define CLOUDS_MS_W19 0.0
#endif
// CLOUDS_MS_W20: mu_0 T_d(tau) S(tau_b)
#ifndef CLOUDS_MS_W20
#define CLOUDS_MS_W20 0.0
#endif
// CLOUDS_MS_W21: mu_0 D T_d(tau_a)
#ifndef CLOUDS_MS_W21
#define CLOUDS_MS_W21 0.0
#endif
// CLOUDS_MS_W22: mu_0 exp(-tau / 16)
#ifndef CLOUDS_MS_W22
#define CLOUDS_MS_W22 0.0101433
#endif
// CLOUDS_MS_W23: c D, c = clamp(tau_A / tau, mu_0, 1): the cosine at which the light entered the lit surface
#ifndef CLOUDS_MS_W23
#define CLOUDS_MS_W23 0.0
#endif
// CLOUDS_MS_W24: c D S(tau_b)
#ifndef CLOUDS_MS_W24
#define CLOUDS_MS_W24 0.0
#endif
// CLOUDS_MS_W25: f D, f the clear fraction of the light march: light let in through gaps and the soft edge
#ifndef CLOUDS_MS_W25
#define CLOUDS_MS_W25 0.0
#endif
// CLOUDS_MS_W26: f D S(tau_b)
#ifndef CLOUDS_MS_W26
#define CLOUDS_MS_W26 0.0
#endif
// CLOUDS_MS_W27: mu_0 exp(-tau / 4)
#ifndef CLOUDS_MS_W27
#define CLOUDS_MS_W27 0.0
#endif
// CLOUDS_MS_W28: T_d(tau) (1 - mu) / 2: the diffuse light seen from the light's side (a lit surface's
// reflection)
#ifndef CLOUDS_MS_W28
#define CLOUDS_MS_W28 0.0505514
#endif
// CLOUDS_MS_W29: D (1 - mu) / 2
#ifndef CLOUDS_MS_W29
#define CLOUDS_MS_W29 0.00387491
#endif
// CLOUDS_MS_W30: F mu_0 D S(tau_b), F the sample's density over its un-eroded envelope's: light leaks
// between billows
#ifndef CLOUDS_MS_W30
#define CLOUDS_MS_W30 0.213233
#endif
// CLOUDS_MS_W31: F c D S(tau_b)
#ifndef CLOUDS_MS_W31
#define CLOUDS_MS_W31 0.180782
#endif
// CLOUDS_MS_W32: E F mu_0 D S(tau_b), E = k tau_e / (1 + k tau_e), tau_e the optical depth to the cloud's
// side: the diffuse light falls toward the side where it escapes
#ifndef CLOUDS_MS_W32
#define CLOUDS_MS_W32 0.0
#endif
// CLOUDS_MS_W33: E F c D S(tau_b)
#ifndef CLOUDS_MS_W33
#define CLOUDS_MS_W33 0.0
#endif
// CLOUDS_MS_W34: E c D
#ifndef CLOUDS_MS_W34
#define CLOUDS_MS_W34 0.0
#endif
// CLOUDS_MS_W35: E mu_0 (1 + 2k tau_B) / (1 + k (tau_A + tau_B))
#ifndef CLOUDS_MS_W35
#define CLOUDS_MS_W35 0.0
#endif
// CLOUDS_MS_W36: E T_d(tau) (1 - mu) / 2
#ifndef CLOUDS_MS_W36
#define CLOUDS_MS_W36 0.0
#endif
// CLOUDS_MS_W37: E mu_0 exp(-tau / 16)
#ifndef CLOUDS_MS_W37
#define CLOUDS_MS_W37 0.0
#endif
// CLOUDS_MS_W38: max(n.l, 0) D, n the outward normal of the un-eroded envelope (the cloud's body) at the
// sample: a face lit by the light
#ifndef CLOUDS_MS_W38
#define CLOUDS_MS_W38 0.0
#endif
// CLOUDS_MS_W39: max(-n.l, 0) D: a face in the cloud's own shadow
#ifndef CLOUDS_MS_W39
#define CLOUDS_MS_W39 0.0
#endif
// CLOUDS_MS_W40: max(n.l, 0) T_d(tau) S(tau_b)
#ifndef CLOUDS_MS_W40
#define CLOUDS_MS_W40 0.0
#endif
// CLOUDS_MS_W41: (1 + n.l) / 2 T_d(tau)
#ifndef CLOUDS_MS_W41
#define CLOUDS_MS_W41 0.0
#endif
// CLOUDS_MS_W42: (1 + n.l) / 2 (1 + n.(-v)) / 2 D, v the view ray: the lit face turned toward the camera
#ifndef CLOUDS_MS_W42
#define CLOUDS_MS_W42 0.0
#endif
// CLOUDS_MS_W43: F max(n.l, 0) D S(tau_b)
#ifndef CLOUDS_MS_W43
#define CLOUDS_MS_W43 0.0
#endif
// CLOUDS_MS_W44: (1 + n.(-v)) / 2 D: the face turned toward the camera
#ifndef CLOUDS_MS_W44
#define CLOUDS_MS_W44 0.0
#endif
// CLOUDS_MS_W45: A = max(N - T, 0), N the direct beam's mean transmittance over the columns 300 m across the
// light from the sample's: sunlight let into the cloud around the sample that its own column does not get
#ifndef CLOUDS_MS_W45
#define CLOUDS_MS_W45 0.0
#endif
// CLOUDS_MS_W46: A S(tau_b)
#ifndef CLOUDS_MS_W46
#define CLOUDS_MS_W46 0.0
#endif
// CLOUDS_MS_W47: A (1 - mu) / 2: seen from the light's side
#ifndef CLOUDS_MS_W47
#define CLOUDS_MS_W47 0.0
#endif
// CLOUDS_MS_W48: A with the columns 1.2 km away
#ifndef CLOUDS_MS_W48
#define CLOUDS_MS_W48 0.0
#endif
// CLOUDS_MS_W49: A S(tau_b), the columns 1.2 km away
#ifndef CLOUDS_MS_W49
#define CLOUDS_MS_W49 0.0
#endif
// CLOUDS_MS_W50: A (1 - mu) / 2, the columns 1.2 km away
#ifndef CLOUDS_MS_W50
#define CLOUDS_MS_W50 0.0
#endif
// CLOUDS_MS_W51: A T_d(tau), the columns 1.2 km away: their light diffused through the sample's own column
#ifndef CLOUDS_MS_W51
#define CLOUDS_MS_W51 0.0
#endif
#endif
