// The shadow map, one cascade per dispatch: for each texel, a column from above the cloud shell toward
// the ground along the sun's direction, through the layers that cast shadows. Stores where its optical
// depth crosses a few values (clouds/shadow_column.glsl), for the cloud's body and for the direct beam
// through the eroded field, and, apart, the optical depth of the decks over them (layers that cast no
// shadow, above every one that does). The cascades lie side by side in one texture; each texel's four
// quarters (the body's near and far, the beam's near and far) lie one above the other.
#include "clouds/density.glsl"
#include "clouds/shadow_column.glsl"
layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D u_map;
uniform ivec2 u_region;      // this cascade's first column in the texture, and its side in texels
uniform vec3 u_centre;       // the cascade's centre, camera-relative
uniform vec3 u_light;        // toward the sun
uniform vec3 u_axis_u, u_axis_v;  // the map plane's axes through the camera, unit length
uniform float u_extent_m;    // side of the map
uniform float u_start_m;     // columns start this far toward the sun from the plane
uniform int u_steps;
// The altitudes of the layers that cast shadows, lowest base to highest top: the columns span those
// alone. Spanning every layer's (a haze at the ground, cirrus at 8 km) made a column under a sun 10
// degrees up 46 km long instead of 8: stretches of 1.2 km stepped over whole cumulus, and the haze
// under them was lit as if they were not there (a tenth of the path tracer's shadow).
uniform vec2 u_altitudes_m;
// The decks' lowest base and highest top (base above top: none). Thin and smooth (cirrus,
// cirrostratus), they get a fixed number of samples across their slant; their optical depth goes to
// the far half's fourth channel, for the clouds under them (clouds_deck_light), not into the columns
// above.
uniform vec2 u_deck_m;
const int kDeckSteps = 16;

// The column's stretch between two altitudes: from where it enters the top sphere to where it meets
// the base sphere (or leaves the top's); empty (x > y) where it misses.
vec2 clouds_column_between(vec3 start, vec3 dir, vec2 altitudes_m) {
  vec2 outer = clouds_sphere_from(start, dir, altitudes_m.y);
  vec2 inner = clouds_sphere_from(start, dir, altitudes_m.x);
  vec2 seg = outer;
  if (outer.x <= outer.y && inner.x <= inner.y && inner.x > seg.x) seg.y = min(seg.y, inner.x);
  return seg;
}

float clouds_deck_depth(vec3 start, vec3 dir) {
  vec2 seg = u_deck_m.x < u_deck_m.y ? clouds_column_between(start, dir, u_deck_m) : vec2(1.0, -1.0);
  if (seg.x > seg.y) return 0.0;
  clouds_system_g = clouds_weather_system_at(start + dir * (0.5 * (seg.x + seg.y)));
  float step_m = (seg.y - seg.x) / float(kDeckSteps), tau = 0.0;
  for (int i = 0; i < kDeckSteps; ++i)
    tau += clouds_density(start + dir * (seg.x + (float(i) + 0.5) * step_m), false, false) * step_m;
  return tau * (cl.scattering + cl.absorption);
}

// A column's knots as it is marched: where its optical depth crosses each of kCloudsShadowKnots,
// its first cloud's front, its last cloud's back. No cloud: the front at the column's end and no
// optical depth, so that filtering between a cloudy texel and a clear one blends their optical depths
// instead of jumping at the texel's edge.
struct CloudsColumnKnots {
  float tau, front, back;
  vec4 knot;
  bool cloudy;
};
CloudsColumnKnots clouds_knots_start(float end) {
  return CloudsColumnKnots(0.0, end, end, vec4(end), false);
}
// A sub-step `sub` long around t, of extinction d (taken as even across it).
void clouds_knots_add(inout CloudsColumnKnots c, float t, float sub, float d) {
  if (d <= 0.0) return;
  if (!c.cloudy) c.front = t - 0.5 * sub, c.cloudy = true;
  c.back = t + 0.5 * sub;
  for (int q = 0; q < 4; ++q)
    if (c.tau < kCloudsShadowKnots[q] && c.tau + d * sub >= kCloudsShadowKnots[q])
      c.knot[q] = t - 0.5 * sub + (kCloudsShadowKnots[q] - c.tau) / d;
  c.tau += d * sub;
}
CloudsShadowColumn clouds_knots_column(CloudsColumnKnots c) {
  vec4 k = c.cloudy ? min(c.knot, vec4(c.back)) : c.knot;
  return CloudsShadowColumn(vec4(c.front, k.xyz), vec4(k.w, c.back, c.tau, 0.0));
}

void main() {
  clouds_load();
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ivec2(u_region.y);
  if (any(greaterThanEqual(id, size))) return;
  vec2 uv = (vec2(id) + 0.5) / vec2(size);
  vec3 start =
      u_centre + ((uv.x - 0.5) * u_axis_u + (uv.y - 0.5) * u_axis_v) * u_extent_m + u_light * u_start_m;
  vec3 dir = -u_light;
  vec2 column = clouds_column_between(start, dir, u_altitudes_m);
  // The column is the whole line through the texel along the light, its distances measured from
  // the start plane (negative: toward the sun). The plane is tilted with the sun (at 35 degrees up,
  // its far edges lie 25 km above and below the centre's start), so a texel's start may lie inside
  // or under the shell: a column cut at its start missed the cloud above it, and a deck was lit
  // beyond a straight seam across the map.
  // Two curves a column: the cloud's body (the shape alone: the diffuse light goes round the detail's
  // small gaps) and the direct beam's (the detail noise too: toward a low sun the beam grazes the
  // eroded edges, which the shape alone fills in; CloudsShadowGpu's beam half).
  CloudsShadowColumn result = CloudsShadowColumn(vec4(0.0), vec4(0.0)), beam_result = result;
  if (column.x <= column.y) {
    vec2 seg = column;
    // The column is marched in u_steps stretches. Toward a low sun it crosses tens of kilometres of
    // shell (a kilometre a stretch at sunset), and one sample a stretch saw a cumulus with one or two
    // samples: the column's optical depth and front jumped from one texel row to the next as the
    // samples slid through the clouds, which the march showed as bands across the clouds and steps
    // on their edges whatever the map's resolution (godrays-sunset.png). Such a stretch is sampled
    // at its ends: with cloud at either end it is integrated in sub-steps of at most kSubStepM (up
    // to four); where only the weather allows cloud (before the noise erodes it), by its middle as
    // before; not at all where neither end has weather for cloud. Short stretches, as before.
    const float kSubStepM = 250.0;
    float step_m = (seg.y - seg.x) / float(u_steps);
    int subs = clamp(int(ceil(step_m / kSubStepM)), 1, 4);
    CloudsColumnKnots body = clouds_knots_start(seg.y), beam = body;
    // columns are a few km long
    clouds_system_g = clouds_weather_system_at(start + dir * (0.5 * (seg.x + seg.y)));
    bool empty_end = false;
    float d_end = subs > 1 ? clouds_density(start + dir * seg.x, false, true, empty_end) : 0.0;
    for (int i = 0; i < u_steps; ++i) {
      float t0 = seg.x + float(i) * step_m;
      int n = subs;
      if (subs > 1) {
        bool empty_start = empty_end;
        float d_start = d_end;
        d_end = clouds_density(start + dir * (t0 + step_m), false, true, empty_end);
        if (empty_start && empty_end) continue;
        n = d_start > 0.0 || d_end > 0.0 ? subs : 1;
      }
      float sub = step_m / float(n);
      for (int j = 0; j < n; ++j) {
        float t = t0 + (float(j) + 0.5) * sub;
        float d = clouds_density(start + dir * t, false, true) * (cl.scattering + cl.absorption);
        if (d <= 0.0) continue;
        clouds_knots_add(body, t, sub, d);
        // The detail noise only erodes: where the shape alone is empty, so is the eroded field.
        float eroded = clouds_density(start + dir * t, true, true) * (cl.scattering + cl.absorption);
        clouds_knots_add(beam, t, sub, eroded);
      }
    }
    result = clouds_knots_column(body);
    beam_result = clouds_knots_column(beam);
  }
  result.far.w = clouds_deck_depth(start, dir);
  imageStore(u_map, id + ivec2(u_region.x, 0), result.near);
  imageStore(u_map, id + ivec2(u_region.x, size.y), result.far);
  imageStore(u_map, id + ivec2(u_region.x, 2 * size.y), beam_result.near);
  imageStore(u_map, id + ivec2(u_region.x, 3 * size.y), beam_result.far);
}
