#pragma once
// The light a cloud sample scatters toward the camera, per unit extinction (the albedo included):
// shared by the march, the mesh clusters' puffs and the billboards, so that the paths light one cloud
// alike (docs/clouds-light.md).
//   mu: cosine between the view ray and the direction toward the light; phase_single: the phase at mu;
//   CloudsLightInputs: what each path measures about the sample (below); l: toward the light; up: the
//   local vertical; e_light, e_sky: the light's and the sky's irradiance there.
// Needs clouds/density.glsl (the block) and clouds/phase.glsl.
// CLOUDS_MULTIPLE_SCATTERING and CLOUDS_POWDER (src/density_field.cpp, light_model_defines) compile the
// model's choices in; undefined, they are read from the block. CLOUDS_SHAPE_DETAIL (the march reads the
// detail noise: every quality but low) chooses between the two sets of fitted weights.
#include "clouds/transmittance.glsl"
#ifdef CLOUDS_MULTIPLE_SCATTERING
const bool clouds_diffusion_model = CLOUDS_MULTIPLE_SCATTERING == 1;
#else
#define clouds_diffusion_model (cl.multiple_scattering > 0.5)
#endif

// What the diffusion model reads about a sample. The transmittances toward the light enter linearly,
// so an average of sources over many samples is the source of their averages (the billboards' atlas
// keeps those averages toward every direction).
struct CloudsLightInputs {
  float direct;                      // the direct beam's transmittance toward the light, through the
                                     // cloud's body beyond the light steps (the diffusion terms')
  float beam;                        // the same through the eroded field (the single scattering's;
                                     // clouds_light_optical_depth)
  float diffuse;                     // the two-stream (diffuse) transmittance toward the light
  float sigma_t;                     // extinction at the sample (1/m)
  float depth_below_m;               // the cloud's depth under the sample (the light it reflects back up)
  float depth_above_m;               // and over it, up to the top of its column (the light it lets down)
  float octave4, octave16;           // exp(-tau / 4), exp(-tau / 16)
  float column_below, column_above;  // the optical depths of the cloud's body under and over the sample
  float tau;                         // the optical depth toward the light
  float clear;                       // the fraction of the light march's way that was clear (0: unknown)
  float fill;                        // the sample's density over its un-eroded envelope's (1: unknown)
  float escape;                      // the optical depth to the cloud's side nearest known (1e4: unknown)
  float facing_light, facing_view;   // n.l and n.(-v), n the un-eroded envelope's outward normal (< -1:
                                     // unknown, read as a deck's top: mu_0 and 0)
  float around_near, around_far;     // the direct beam's mean transmittance at the sample's depth over
                                     // columns 300 m and 1.2 km from its own, beyond its own column's
                                     // (clouds_shadow_around; 0: unknown)
};

// Schneider's beer-powder darkening of thin edges (cl.powder = 0: off).
float clouds_powder(float sigma_t) {
#ifdef CLOUDS_POWDER
  if (CLOUDS_POWDER == 0) return 1.0;
#endif
  return 1.0 - cl.powder * exp(-2.0 * sigma_t * cl.light_step_m);
}

// The multiple-scattering estimate: a sum of terms, each a physical shape with a weight fitted to the
// path tracer (light_model_fit.glsl; `welkin accuracy clouds --fit` solves for the weights as a
// non-negative least-squares problem, the march being linear in them). With tau the optical depth
// toward the light, tau_b and tau_a the optical depths below and above (local extinction times the
// depths), T_d the two-stream transmittance, T the direct beam's, S(x) = x / (1 + k x) the slab's
// saturating reflection, D = T_d(tau) - T(tau) >= 0 the diffuse light beyond the direct beam:
//   0  D                        the diffuse light a conservative slab lets through toward the light
//   1  D S(tau_b)               ... gathered from the cloud below (a top sees all of it, a base none)
//   2  D p_2(mu)                ... forward-peaked: second-order scattering keeps half the anisotropy
//   3  mu_0 T_d(tau_a)          the light the cloud's top takes in (mu_0 of the sun's), let down
//                               through the cloud above: a base under a thick column is dark
//   4  mu_0 T_d(tau_a) S(tau_b) ... and reflected back up by the cloud below
//   5  T_d(tau)                 the diffuse light toward the light, direct beam included
//   6  T_d(tau) S(tau_b)        ... gathered from below
//   7  D T_d(tau_a)             the diffuse light toward the light that the column above also lets by
//   8  exp(-tau / 4)            octaves (Wrenninge): light scattered a few times sees a fraction of
//   9  exp(-tau / 16)           the optical depth
//  10  exp(-tau / 4) p_2(mu)    ... with half the anisotropy
//  11-15                        terms 1, 3, 6, 4 and 9 with the cloud's body (tau_B, tau_A) for tau_b, tau_a
//  16  mu_0 (1 + 2k tau_B) / (1 + k (tau_A + tau_B))
//                               the diffuse light inside a conservative plane-parallel slab lit from
//                               above (diffusion theory: it falls linearly with depth, from about
//                               2 mu_0 at a thick slab's top to mu_0 T_d(tau_A + tau_B) at its
//                               base): a deck's dark base, whatever the slant path toward a low sun
//  17  the same with the sample's own tau_a, tau_b
//  18-22  terms 0, 1, 6, 7 and 9 times mu_0: the light a lit surface takes in per unit area, when the
//         surface is a deck's top (the diffusion slab's mu_0 F_0)
//  23  c D, c = clamp(tau_A / tau, mu_0, 1): the cosine at which the light entered the surface between
//      the sample and the light; a deck's top gives tau_A = mu_0 tau (c = mu_0), a cumulus's sunlit
//      side a slant depth shorter than the column above (c = 1)
//  24  c D S(tau_b)
//  25  f D, f the fraction of the light march's way that is clear: light let in through gaps and
//      the soft edge toward the light rather than diffused through the column
//  26  f D S(tau_b)
//  27  mu_0 exp(-tau / 4)
//  28  T_d(tau) (1 - mu) / 2    the diffuse light seen from the light's side: a lit surface reflects
//  29  D (1 - mu) / 2           more than the cloud lets through (the cloud's brighter face)
//  30  F mu_0 D S(tau_b)      terms 19 and 24 times F, the fraction of the un-eroded envelope's
//  31  F c D S(tau_b)         density the noise left at the sample: between billows (small F)
//                               light diffused in the cloud leaks out through the gaps and sides
//  32-37  terms 30, 31, 23, 16, 28 and 22 times E = k tau_e / (1 + k tau_e), tau_e the optical
//         depth to the cloud's side (the march: two level probes, clouds_side_optical_depth): the diffuse
//         light falls toward a free surface, where it escapes (diffusion theory's boundary: the
//         fluence near the side grows with the depth behind it); a shadowed side is lit by the
//         diffuse light alone and is the darker for it
//  38  max(n.l, 0) D          n the outward normal of the un-eroded envelope at the sample (the
//  39  max(-n.l, 0) D           cloud's body, clouds_envelope_normal): a face lit by the light or one
//  40  max(n.l, 0) T_d S(tau_b)  in the cloud's own shadow, which the depth toward the light alone
//  41  (1 + n.l) / 2 T_d         cannot tell apart; v the view ray, (1 + n.(-v)) / 2 the face turned
//  42  (1 + n.l) / 2 (1 + n.(-v)) / 2 D   toward the camera (diffused light leaves a face toward its
//  43  F max(n.l, 0) D S(tau_b)           normal); 43 is 30-31 with the face's own cosine
//  44  (1 + n.(-v)) / 2 D
//  45  A = max(N - M, 0), N the direct beam's mean transmittance over the columns 300 m across the
//      light from the sample's, M its own column's (the shadow map at the sample's depth): sunlight
//      let into the cloud around the sample that its own column does not get; under a low sun a column
//      through a broken field crosses several clouds while its neighbours toward the layer's top pass
//      through gaps
//  46  A S(tau_b)             ... gathered from the cloud below
//  47  A (1 - mu) / 2         ... seen from the light's side
//  48-50  terms 45-47 with the columns 1.2 km away
//  51  A_far T_d(tau): the light of the far columns diffused through the sample's own
// All fade where the cloud around the sample is thin (its outskirts, wisps: little light has been
// scattered toward it by neighbours, the physical side of Schneider's "powder"), by
// 1 - exp(-n sigma_t l_1), l_1 the first light step.
// Two-stream theory's k = 0.75 (1 - g) for the clouds' phase function, g its mean cosine (the dual
// lobes' weighted g; the droplet fit's lobes likewise): the default lobes (g = 0.7 and -0.2, half
// each) have g = 0.25, k = 0.56, a cloud three to four times as diffusive as the g = 0.8 of
// CLOUDS_MS_DIFFUSION (which the ground's shading through the clouds keeps).
bool clouds_droplet_phase() {
#ifdef CLOUDS_PHASE_MODEL
  return CLOUDS_PHASE_MODEL == 1;
#else
  return cl.phase_model > 0.5;
#endif
}
float clouds_two_stream_k() {
  bool droplets = clouds_droplet_phase();
  float d = cl.droplet_diameter_um;
  float w_d = exp(-0.599085 / (d - 0.641583) - 0.665888);
  float g = droplets ? (1.0 - w_d) * exp(-0.0990567 / (d - 1.67154)) +
                           w_d * exp(-2.20679 / (d + 3.91029) - 0.428934)
                     : mix(cl.g_backward, cl.g_forward, cl.forward_weight);
  return 0.75 * (1.0 - g);
}
// The share of the scattered light that stays in the phase function's forward peak (delta-Eddington:
// g^2 of each Henyey-Greenstein lobe; the droplets' fit by its mean cosine): light a thin deck
// scatters by a few degrees still arrives as from the sun.
float clouds_forward_fraction() {
  float g = 1.0 - clouds_two_stream_k() / 0.75;
  return clouds_droplet_phase() ? g * g
                  : mix(cl.g_backward * cl.g_backward, cl.g_forward * cl.g_forward, cl.forward_weight);
}
float clouds_slab_diffuse(float tau) {
  return 1.0 / (1.0 + clouds_two_stream_k() * tau);
}
float clouds_slab_reflection(float tau) {
  return tau / (1.0 + clouds_two_stream_k() * tau);
}
float clouds_multiple_scattering(float mu, CloudsLightInputs s, vec3 l, vec3 up) {
  float tau_below = s.sigma_t * s.depth_below_m, tau_above = s.sigma_t * s.depth_above_m;
  float reflection = clouds_slab_reflection(tau_below);
  float through_above = clouds_slab_diffuse(tau_above);
  float above = max(dot(l, up), 0.0) * through_above;
  float beyond = max(s.diffuse - s.direct, 0.0);
  float forward = clouds_phase(mu, 0.5) * 4.0 * CLOUDS_PI;
  float sum = beyond * (CLOUDS_MS_W0 + CLOUDS_MS_W1 * reflection + CLOUDS_MS_W2 * forward +
                        CLOUDS_MS_W7 * through_above) +
              above * (CLOUDS_MS_W3 + CLOUDS_MS_W4 * reflection) +
              s.diffuse * (CLOUDS_MS_W5 + CLOUDS_MS_W6 * reflection) +
              s.octave4 * (CLOUDS_MS_W8 + CLOUDS_MS_W10 * forward) + CLOUDS_MS_W9 * s.octave16;
  float body_reflection = clouds_slab_reflection(s.column_below);
  float body_above = max(dot(l, up), 0.0) * clouds_slab_diffuse(s.column_above);
  sum += body_reflection * (CLOUDS_MS_W11 * beyond + CLOUDS_MS_W13 * s.diffuse + CLOUDS_MS_W15 * s.octave16) +
         body_above * (CLOUDS_MS_W12 + CLOUDS_MS_W14 * body_reflection);
  float k = clouds_two_stream_k(), mu_0 = max(dot(l, up), 0.0);
  float slab_body = (1.0 + 2.0 * k * s.column_below) / (1.0 + k * (s.column_above + s.column_below));
  float slab = (1.0 + 2.0 * k * tau_below) / (1.0 + k * (tau_above + tau_below));
  sum += mu_0 * (CLOUDS_MS_W16 * slab_body + CLOUDS_MS_W17 * slab);
  sum += mu_0 * (beyond * (CLOUDS_MS_W18 + CLOUDS_MS_W19 * reflection + CLOUDS_MS_W21 * through_above) +
                 CLOUDS_MS_W20 * s.diffuse * reflection + CLOUDS_MS_W22 * s.octave16 +
                 CLOUDS_MS_W27 * s.octave4);
  float entered = clamp(s.column_above / max(s.tau, 1e-6), mu_0, 1.0);
  sum += beyond * (entered * (CLOUDS_MS_W23 + CLOUDS_MS_W24 * reflection) +
                   s.clear * (CLOUDS_MS_W25 + CLOUDS_MS_W26 * reflection));
  sum += 0.5 * (1.0 - mu) * (CLOUDS_MS_W28 * s.diffuse + CLOUDS_MS_W29 * beyond);
  sum += s.fill * beyond * reflection * (CLOUDS_MS_W30 * mu_0 + CLOUDS_MS_W31 * entered);
  float escape = k * s.escape / (1.0 + k * s.escape);
  sum += escape * (s.fill * beyond * reflection * (CLOUDS_MS_W32 * mu_0 + CLOUDS_MS_W33 * entered) +
                   CLOUDS_MS_W34 * entered * beyond + CLOUDS_MS_W35 * mu_0 * slab_body +
                   CLOUDS_MS_W36 * 0.5 * (1.0 - mu) * s.diffuse + CLOUDS_MS_W37 * mu_0 * s.octave16);
  float n_l = s.facing_light < -1.5 ? mu_0 : s.facing_light;
  float n_v = s.facing_view < -1.5 ? 0.0 : s.facing_view;
  float lit = max(n_l, 0.0), lit_half = 0.5 * (1.0 + n_l), toward_view = 0.5 * (1.0 + n_v);
  sum += beyond * (CLOUDS_MS_W38 * lit + CLOUDS_MS_W39 * max(-n_l, 0.0) +
                   CLOUDS_MS_W42 * lit_half * toward_view + CLOUDS_MS_W44 * toward_view) +
         s.diffuse * (CLOUDS_MS_W40 * lit * reflection + CLOUDS_MS_W41 * lit_half) +
         CLOUDS_MS_W43 * s.fill * lit * beyond * reflection;
  float around_near = s.around_near, around_far = s.around_far;
  float light_side = 0.5 * (1.0 - mu);
  sum += around_near * (CLOUDS_MS_W45 + CLOUDS_MS_W46 * reflection + CLOUDS_MS_W47 * light_side) +
         around_far * (CLOUDS_MS_W48 + CLOUDS_MS_W49 * reflection + CLOUDS_MS_W50 * light_side +
                       CLOUDS_MS_W51 * s.diffuse);
  return sum * (1.0 - exp(-CLOUDS_MS_POWDER * s.sigma_t * cl.light_step_m));
}

// The sky's light from above and the lit ground's from below at a sample tau_below and tau_above
// deep in its cloud (the local extinction times the cloud's depth under and over it): the mean
// intensity a conservative two-stream slab holds there when lit diffusely from one side, from the top
// T (1 + 2 k tau_below) with T = 1 / (1 + k (tau_above + tau_below)), from the bottom the same turned
// over. Under a sky and a ground of one radiance the two sum to it at every depth (the white
// furnace); a sample in thin cloud sees half of each. The ground under the column is lit by the
// light and the sky through that same column (its transmitted flux, T again): under a deck it gets
// a deck's light, not the clear sky's. No extra density samples: on software rasterisers each is
// most of a step's cost. The sky alone against the path tracer, the cumulus case's 20 rays: 35%
// relative RMSE at `high`, 30% at `low`; through the diffuse transmittance toward the sun, as
// before, 69% and 79% (docs/clouds-light.md).
vec3 clouds_ambient(vec3 e_sky, vec3 e_light_on_ground, float tau_below, float tau_above) {
  float k = clouds_two_stream_k(), t = 1.0 / (1.0 + k * (tau_above + tau_below));
  vec3 e_ground = cl.ground_albedo * (e_light_on_ground + e_sky) * t;
  vec3 mean_intensity = e_sky * (1.0 + 2.0 * k * tau_below) + e_ground * (1.0 + 2.0 * k * tau_above);
  return mean_intensity * t / (2.0 * CLOUDS_PI);
}

vec3 clouds_light_source(float mu, float phase_single, CloudsLightInputs s, vec3 l, vec3 up, vec3 e_light,
                         vec3 e_sky) {
  float scattered = CLOUDS_SS_WEIGHT * phase_single * s.beam + clouds_multiple_scattering(mu, s, l, up);
  scattered *= clouds_powder(s.sigma_t);
  vec3 ambient = clouds_ambient(e_sky, e_light * max(dot(l, up), 0.0), s.sigma_t * s.depth_below_m,
                                s.sigma_t * s.depth_above_m);
  float albedo = cl.scattering / max(cl.scattering + cl.absorption, 1e-9);
  return albedo * (e_light * scattered + ambient);
}

// The inputs from the optical depth toward the light.
CloudsLightInputs clouds_light_inputs(float tau, float sigma_t, float depth_below_m, float depth_above_m) {
  float direct = clouds_direct_transmittance(tau);
  return CloudsLightInputs(direct, direct, clouds_slab_diffuse(tau), sigma_t, depth_below_m,
                           depth_above_m, exp(-0.25 * tau), exp(-0.0625 * tau), sigma_t * depth_below_m,
                           sigma_t * depth_above_m, tau, 0.0, 1.0, 1e4, -2.0, -2.0, 0.0, 0.0);
}

vec3 clouds_sample_source(float mu, float phase_single, float tau, float sigma_t, float depth_below_m,
                          float depth_above_m, vec3 l, vec3 up, vec3 e_light, vec3 e_sky) {
  if (clouds_diffusion_model)
    return clouds_light_source(mu, phase_single,
                               clouds_light_inputs(tau, sigma_t, depth_below_m, depth_above_m), l, up,
                               e_light, e_sky);
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
  vec3 ambient = clouds_ambient(e_sky, e_light * max(dot(l, up), 0.0), sigma_t * depth_below_m,
                                sigma_t * depth_above_m);
  float albedo = cl.scattering / max(cl.scattering + cl.absorption, 1e-9);
  return albedo * (e_light * scattered + ambient);
}
