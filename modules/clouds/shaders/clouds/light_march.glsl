#pragma once
// The light march: what the march measures toward the light at each cloud sample, for the light
// model (clouds/light_model.glsl). Needs clouds/density.glsl and the clouds' light term (its shadow map).

// The cloud around a sample, from the density evaluation that found it: read before the light march
// evaluates other points.
struct CloudsSampleGeometry {
  float depth_below_m, depth_above_m, column_below, column_above, fill;
};
CloudsSampleGeometry clouds_sample_geometry() {
  return CloudsSampleGeometry(clouds_depth_below_m, clouds_depth_above_m, clouds_column_below,
                              clouds_column_above, clouds_fill);
}

// Optical depth toward the light from x: steps that double from the first light step, then, toward
// the sun, the rest of the way from the clouds' shadow map (its optical depth between the sun and
// where the steps end; layers that cast shadows only). The first CLOUDS_LIGHT_DETAIL steps see the
// detail noise (where the layers use it): it erodes the edges and opens the gaps the light crosses,
// which decide the direct beam. Against the path tracer's single scattering on a broken deck under a
// low sun at `high` (docs/clouds-light.md): the first step alone 11.1% too dark (worst ray 32.5%),
// the first two 4.4% (13.8%), all three 1.6% (2.9%). The multiple-scattering weights were fitted on
// the first step alone and make up for its darker beam; refitted with every step reading it (branch
// light3) the training sets improve but the accuracy test's cumulus seen from above toward the sun
// doubles (the estimate there 2.2 times the path tracer's), so it stays 1.
// 0: no step reads it (the term budget measures both).
#ifndef CLOUDS_LIGHT_DETAIL
#define CLOUDS_LIGHT_DETAIL 1
#endif
// The decks over the casters (cirrus over cumulus: layers that cast no shadow on materials, wholly above
// those that do): the share of their optical depth along the shadow map's column (its fourth
// channel) that lies above x, where a light march ended (inside a deck, its own steps took the rest).
float clouds_deck_share(vec3 x) {
  return clamp((cs.deck_top_m - clouds_altitude(x)) / max(cs.deck_top_m - cs.deck_base_m, 1.0), 0.0, 1.0);
}

// The light under the decks, their optical depth toward the sun tau: the direct beam they let through,
// the phase function's forward peak kept in it (delta-Eddington), and a conservative slab's diffuse
// light (Eddington's transmission of a slab lit at mu_0, less that beam), which comes down spread like
// an overcast's and is added to the sky's irradiance, itself let through as a slab lets diffuse light.
// Beer's law alone kept a twentieth of the light under a deck of slant depth 3; the path tracer keeps
// a third and more (docs/clouds-light.md).
void clouds_deck_light(float tau, inout vec3 e_light, inout vec3 e_sky) {
  if (tau <= 0.0) return;
  float mu_0 = cs.column_vertical, tau_vertical = tau * mu_0;
  float direct = exp(-(1.0 - clouds_forward_fraction()) * tau);
  float total =
      (0.5 + 0.75 * mu_0 + (0.5 - 0.75 * mu_0) * direct) / (1.0 + clouds_two_stream_k() * tau_vertical);
  e_sky = e_sky * clouds_slab_diffuse(tau_vertical) + e_light * (mu_0 * max(total - direct, 0.0));
  e_light *= direct;
}

// `clear`: the fraction of the steps' way where the field is empty (the light model weighs light let
// in through gaps and soft edges against light diffused through the column by it); `deck`: the decks'
// optical depth beyond the steps, from the same texel of the shadow map (clouds_deck_light); `beam`:
// the direct beam's optical depth, the map's beyond the steps read through the eroded field (the
// single scattering's; the returned depth, the diffuse light's, reads the cloud's body there).
// `layers`: the compiled layers the steps read (density.glsl; those the march's band can reach).
float clouds_light_optical_depth(int layers, vec3 x, vec3 l, float extinction_per_density, out float clear,
                                 out float deck, out float beam) {
  float tau = 0.0, s = 0.0, step_m = cl.light_step_m, clear_m = 0.0;
  int n = int(cl.light_steps);
  if (n > 0) {
    float d = clouds_density(layers, x + l * (0.5 * step_m), int(CLOUDS_LIGHT_DETAIL) > 0, false);
    tau = d * step_m, clear_m = d > 0.0 ? 0.0 : step_m;
    s = step_m, step_m *= 2.0;
  }
  for (int k = 1; k < n; ++k) {
    float d = clouds_density(layers, x + l * (s + 0.5 * step_m), k < int(CLOUDS_LIGHT_DETAIL), false);
    tau += d * step_m, clear_m += d > 0.0 ? 0.0 : step_m;
    s += step_m;
    step_m *= 2.0;
  }
  clear = clear_m / max(s, 1e-6);
  tau *= extinction_per_density;
  deck = 0.0, beam = tau;
  if (cl.moon_marched < 0.5) {
    float depth;
    CloudsShadowPlace at = clouds_shadow_place(x + l * s, depth);
    CloudsShadowColumn column = clouds_shadow_read(at, false);
    tau += clouds_column_optical_depth(column, depth);
    beam += clouds_column_optical_depth(clouds_shadow_read(at, true), depth);
    deck = column.far.w * clouds_deck_share(x + l * s);
  }
  return tau;
}
float clouds_light_optical_depth(vec3 x, vec3 l, float extinction_per_density, out float clear,
                                 out float deck) {
  float beam;
  return clouds_light_optical_depth(CLOUDS_ALL_LAYERS, x, l, extinction_per_density, clear, deck, beam);
}

// The optical depth from x to the cloud's side (CloudsLightInputs.escape): two samples of the shape
// noise alone (no detail: the light diffused in the cloud goes round its small gaps) one first light
// step away, level, toward the light's azimuth and away from it, where a cumulus's lit and shadowed
// sides face. A probe in clear air puts the side half way to it; one in cloud, beyond it.
float clouds_side_optical_depth(int layers, vec3 x, vec3 l, vec3 up, float sigma_t,
                                float extinction_per_density) {
  vec3 level = l - up * dot(l, up);
  level = dot(level, level) > 1e-6 ? normalize(level) : normalize(cross(up, vec3(1.0, 0.0, 0.0)));
  float r = cl.light_step_m, side = 1e4;
  for (int i = 0; i < 2; ++i) {
    float d = clouds_density(layers, x + level * (i == 0 ? r : -r), false, false) * extinction_per_density;
    side = min(side, d > 0.0 ? r * (sigma_t + d) : 0.25 * r * sigma_t);
  }
  return side;
}

// The layers' extinction at x as the weather shapes it, before the profile and any noise: the cloud's
// body, whose surface the light model reads a normal from (clouds_envelope_normal; with the profile,
// which rises with height, the normal turned down inside every body). Every layer, read from the
// buffer with run-time checks.
float clouds_envelope_density(vec3 x) {
  float h = clouds_altitude(x), sum = 0.0;
  if (h < cl.lowest_m || h > cl.highest_m) return 0.0;
  clouds_painted_sample = 2.0;
  for (int i = 0; i < cl_layer_count; ++i) {
    CloudLayerGpu L = i < CLOUDS_LOCAL_LAYERS ? cl_local_layers[i] : cl_layers[i];
    float t, d0;
    vec4 w4 = clouds_weather_fetch(L, x);
    sum += clouds_layer_envelope(L, w4, L.follows_map > 0.5, x, h, t, d0) * L.density_per_m;
  }
  return sum;
}

// The outward normal of the un-eroded envelope at x (-grad / |grad| of clouds_envelope_density, central
// differences one first light step across, six weather fetches a layer): which face of the cloud's body
// the sample lies under, a side lit by the light or one in the cloud's own shadow, whatever the noise
// carved there. Where the envelope is flat, the local vertical (a deck's top).
vec3 clouds_envelope_normal(vec3 x, vec3 up) {
  vec3 e = normalize(cross(up, abs(up.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
  vec3 n = cross(up, e);
  float r = cl.light_step_m;
  vec3 grad = e * (clouds_envelope_density(x + e * r) - clouds_envelope_density(x - e * r)) +
              n * (clouds_envelope_density(x + n * r) - clouds_envelope_density(x - n * r)) +
              up * (clouds_envelope_density(x + up * r) - clouds_envelope_density(x - up * r));
  float len = length(grad);
  return len > 1e-12 ? -grad / len : up;
}

// The light the sample at x scatters toward the camera, per unit extinction (clouds_sample_source).
vec3 clouds_marched_source(int layers, vec3 x, vec3 l, float mu, float phase_single, float sigma_t,
                           float extinction_per_density, CloudsSampleGeometry g, vec3 up, vec3 e_light,
                           vec3 e_sky) {
  float clear, deck, beam;
  float tau = clouds_light_optical_depth(layers, x, l, extinction_per_density, clear, deck, beam);
  clouds_deck_light(deck, e_light, e_sky);
  if (!clouds_diffusion_model)
    return clouds_sample_source(mu, phase_single, tau, sigma_t, g.depth_below_m, g.depth_above_m, l, up,
                                e_light, e_sky);
  CloudsLightInputs s = clouds_light_inputs(tau, sigma_t, g.depth_below_m, g.depth_above_m);
  s.column_below = g.column_below, s.column_above = g.column_above, s.clear = clear, s.fill = g.fill;
  s.beam = clouds_direct_transmittance(beam);
  // Two density samples more per cloud sample: only where the weights read the side's depth (the
  // sum of the constants folds at compile time).
  if (CLOUDS_MS_W32 + CLOUDS_MS_W33 + CLOUDS_MS_W34 + CLOUDS_MS_W35 + CLOUDS_MS_W36 + CLOUDS_MS_W37 > 0.0)
    s.escape = clouds_side_optical_depth(layers, x, l, up, sigma_t, extinction_per_density);
  // Six weather fetches a layer more: only where the weights read the envelope's normal. x is
  // camera-relative, so the view ray runs along it.
  if (CLOUDS_MS_W38 + CLOUDS_MS_W39 + CLOUDS_MS_W40 + CLOUDS_MS_W41 + CLOUDS_MS_W42 + CLOUDS_MS_W43 +
          CLOUDS_MS_W44 > 0.0) {
    vec3 n = clouds_envelope_normal(x, up);
    s.facing_light = dot(n, l), s.facing_view = -dot(n, normalize(x));
  }
  // Ten shadow map fetches more a radius: only where the weights read the columns around the sample's.
  if (CLOUDS_MS_W45 + CLOUDS_MS_W46 + CLOUDS_MS_W47 > 0.0 && cl.moon_marched < 0.5)
    s.around_near = clouds_shadow_around(x, 300.0);
  if (CLOUDS_MS_W48 + CLOUDS_MS_W49 + CLOUDS_MS_W50 + CLOUDS_MS_W51 > 0.0 && cl.moon_marched < 0.5)
    s.around_far = clouds_shadow_around(x, 1200.0);
  return clouds_light_source(mu, phase_single, s, l, up, e_light, e_sky);
}
