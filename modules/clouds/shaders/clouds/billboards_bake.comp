// The billboards' bake, in stages (BILLBOARDS_BAKE_STAGE), once per layer description and atlas
// settings (src/billboards.cpp keys it):
//   0 choose:  each archetype's place in the layer's noise: of 64 places drawn from the seed, the
//              one whose weather allows the k-th of K equal steps of cloud (one invocation per
//              archetype), so that the archetypes range from a small cloud to a large one and each
//              cell gets the one its own weather matches;
//   1 volume:  the layer's extinction in the archetype's box, from the field's own functions
//              (clouds/density.glsl) with its weather windowed to a disc inside the box, and its fill
//              (the eroded density over the envelope's, which the light model reads);
//   2 atlas:   each view's texel: the optical depth through the volume, the point that hides half of
//              the opacity, the diffuse transmittance toward 16 directions from four points along
//              the view, projected on spherical harmonics, and the fill averaged over what each
//              sample adds to the view (clouds/billboards.glsl).
// The bake reads the noise in a frame of its own (the noise's origin at zero, the world's axes), so
// it depends on the settings alone, not on where the camera is or when: scrubbing equals playing.
#include "clouds/density.glsl"
#include "clouds/placement.glsl"
#include "clouds/billboards.glsl"
#include "clouds/transmittance.glsl"

layout(local_size_x = 64) in;
// place (m in the noise's frame), score
layout(std430, binding = 7) buffer BillboardArchetypes { BillboardArchetype bb_archetypes[]; };
#if BILLBOARDS_BAKE_STAGE == 1
layout(r32f, binding = 0) uniform writeonly image3D o_volume;
layout(r8, binding = 2) uniform writeonly image3D o_fill_volume;
#elif BILLBOARDS_BAKE_STAGE == 2
layout(rgba16f, binding = 1) uniform writeonly image2DArray o_atlas;
layout(r8, binding = 3) uniform writeonly image2DArray o_fill_atlas;
#endif
uniform int u_layer;
uniform float u_coverage;  // the coverage the archetypes are baked at

CloudLayerGpu bake_layer() {
  CloudLayerGpu L = cl_layers[u_layer];
  L.coverage = u_coverage;
  L.weather_origin = vec3(0.0);
  L.streak_shape_origin = vec3(0.0), L.streak_detail_origin = vec3(0.0);  // the noise's frame, as below
  L.follows_map = 0.0;  // no painted map
  L.handover_near_m = 0.0, L.handover_crossfade_m = 0.0, L.handover_far_m = 0.0;
  return L;
}

// The layer's extinction (1/m) at x (the noise's frame) and height h above the planet's surface, and
// its fill there (0 outside the envelope).
vec2 archetype_field(CloudLayerGpu L, vec3 x, float h) {
  clouds_detail_sample = -1.0, clouds_painted_sample = 2.0, clouds_detail_displacement = 0.0;
  clouds_system_g = 0.5;
  clouds_shape_sample =
      textureLod(cl_shape_noise, x * cl.shape_per_m, clouds_lod(1.0 / (cl.shape_per_m * 128.0)));
  float envelope;
  clouds_fill = 0.0, clouds_envelope_sigma = 0.0;
  float sigma = clouds_layer_density(L, clouds_weather_fetch(L, x), false, true, x, h, envelope) *
                (cl.scattering + cl.absorption);
  return vec2(sigma, clouds_envelope_sigma > 0.0 ? min(clouds_fill / clouds_envelope_sigma, 1.0) : 0.0);
}

void main() {
  clouds_load();
  cl.shape_origin = vec3(0.0), cl.detail_origin = vec3(0.0);
  CloudLayerGpu L = bake_layer();
  int id = int(gl_GlobalInvocationID.x);
  float hw = u_box.x, hh = u_box.y;
  float centre_h = L.base_m + u_volume.y;  // the box's centre above the surface
#if BILLBOARDS_BAKE_STAGE == 0
  if (id >= u_atlas.z) return;
  // Scores are sums of five envelopes (at most 5): archetype k aims at 5 (k + 1/2) / K.
  float period = 1.0 / L.weather_per_m, target = 5.0 * (float(id) + 0.5) / float(u_atlas.z), best = 3.4e38,
        best_score = 0.0;
  vec2 place = vec2(0.0);
  const vec2 columns[5] =
      vec2[5](vec2(0.0), vec2(0.5, 0.0), vec2(-0.5, 0.0), vec2(0.0, 0.5), vec2(0.0, -0.5));
  for (int j = 0; j < 64; ++j) {
    vec2 p = random4(ivec2(id, 0), j, 2u).xy * period;
    float score = 0.0, t, d0;
    for (int c = 0; c < 5; ++c) {
      float h = L.base_m + 0.33 * L.thickness_m;
      vec3 x = vec3(p + columns[c] * 0.84 * hw, h);
      score += clouds_layer_envelope(L, clouds_weather_fetch(L, x), false, x, h, t, d0);
    }
    if (score > 0.0 && abs(score - target) < best) best = abs(score - target), best_score = score, place = p;
  }
  bb_archetypes[id] = BillboardArchetype(place, best_score, 0.0);
#elif BILLBOARDS_BAKE_STAGE == 1
  int n = int(u_volume.x), slices = int(u_box.w);
  if (id >= n * n * slices * u_atlas.z) return;
  int i = id % n, j = (id / n) % n, l = id / (n * n);
  int archetype = l / slices;
  vec3 p =
      vec3((vec2(i, j) + 0.5) / float(n) * 2.0 - 1.0, (float(l % slices) + 0.5) / float(slices) * 2.0 - 1.0) *
      vec3(hw, hw, hh);
  // The weather faded out toward the box's sides: a cloud inside it, not a cut block of the layer.
  // From 0.8 of the half width (was 0.55): the disc kept 44% of the cell, and the billboards covered
  // less of the horizon than the field (docs/clouds-far.md, "The billboards' fill and cover").
  clouds_weather_scale = 1.0 - smoothstep(0.8, 0.95, length(p.xy) / hw);
  clouds_footprint_m = 2.0 * hw / float(n);  // the noise averaged over a voxel
  vec3 x = vec3(bb_archetypes[archetype].place + p.xy, centre_h + p.z);
  vec2 sigma_fill = clouds_weather_scale > 0.0 ? archetype_field(L, x, centre_h + p.z) : vec2(0.0);
  imageStore(o_volume, ivec3(i, j, l), vec4(sigma_fill.x));
  imageStore(o_fill_volume, ivec3(i, j, l), vec4(sigma_fill.y));
#elif BILLBOARDS_BAKE_STAGE == 2
  int r = u_atlas.w, views = u_atlas.x * u_atlas.y;
  if (id >= r * r * views * u_atlas.z) return;
  int i = id % r, j = (id / r) % r, v = (id / (r * r)) % views, archetype = id / (r * r * views);
  vec3 d = billboard_view_direction(v / u_atlas.x, v % u_atlas.x), f = -d, right, up;
  billboard_view_axes(d, right, up);
  vec2 uv = (vec2(i, j) + 0.5) / float(r) * 2.0 - 1.0;
  vec3 q = (uv.x * right + uv.y * up) * u_box.z;  // on the plane through the centre
  vec2 span = billboard_box_span(q, f);
  int steps = 2 * int(u_volume.x);
  float dt = max(span.y - span.x, 0.0) / float(steps);
  // The optical depth, and the fill weighted by what each step adds to the view (its opacity times
  // the transmittance in front of it).
  float tau = 0.0, fill_sum = 0.0, fill_weight = 0.0;
  for (int s = 0; s < steps; ++s) {
    vec2 sigma_fill = billboard_extinction_fill(q + f * (span.x + (float(s) + 0.5) * dt), archetype);
    float added = exp(-tau) * (1.0 - exp(-sigma_fill.x * dt));
    fill_sum += added * sigma_fill.y, fill_weight += added;
    tau += sigma_fill.x * dt;
  }
  // Empty: no depth, the transmittance 1 toward every direction.
  vec4 a = vec4(0.0), sh_diffuse = vec4(1.0 / 0.282095, 0.0, 0.0, 0.0);
  if (tau > 1e-5) {
    // The points that hide the k-th quarter of the opacity (k = 0..3), and the one that hides half:
    // where the depth reaches -ln(1 - share (1 - e^-tau)).
    float shares[5] = float[5](0.125, 0.375, 0.5, 0.625, 0.875);
    float t_at[5];
    int next = 0;
    float sum = 0.0, opacity = 1.0 - exp(-tau);
    for (int s = 0; s < steps && next < 5; ++s) {
      float step_tau = billboard_extinction(q + f * (span.x + (float(s) + 0.5) * dt), archetype) * dt;
      while (next < 5 && sum + step_tau >= -log(1.0 - shares[next] * opacity)) {
        t_at[next] =
            span.x + (float(s) + (-log(1.0 - shares[next] * opacity) - sum) / max(step_tau, 1e-30)) * dt;
        ++next;
      }
      sum += step_tau;
    }
    for (; next < 5; ++next) t_at[next] = span.y;
    vec3 p = q + f * t_at[2];
    a = vec4(tau, t_at[2] / u_box.z, p.z + u_volume.y, billboard_extinction(p, archetype));
    // The transmittance toward 16 directions of a Fibonacci sphere from the four points, projected.
    sh_diffuse = vec4(0.0);
    for (int k = 0; k < 16; ++k) {
      float z = 1.0 - (float(k) + 0.5) / 8.0, ring = sqrt(1.0 - z * z), phi = 2.3999632 * float(k);
      vec3 w = vec3(ring * cos(phi), ring * sin(phi), z);
      float diffuse = 0.0;
      for (int m = 0; m < 5; ++m) {
        if (m == 2) continue;
        float depth = billboard_march_depth(q + f * t_at[m], w, archetype, 10);
        diffuse += 0.25 * clouds_diffuse_transmittance(depth);
      }
      sh_diffuse += billboard_sh(w) * (diffuse * 4.0 * 3.14159265 / 16.0);
    }
  }
  int layer = 2 * (archetype * views + v);
  imageStore(o_atlas, ivec3(i, j, layer), a);
  imageStore(o_atlas, ivec3(i, j, layer + 1), sh_diffuse);
  imageStore(o_fill_atlas, ivec3(i, j, archetype * views + v),
             vec4(fill_weight > 0.0 ? fill_sum / fill_weight : 1.0));
#endif
}
