#pragma once
// The billboard clouds (src/billboards.cpp): a few archetype clouds baked from the layer's own field
// into small extinction volumes, and from those into an atlas of views that holds what relighting
// needs, not a colour. Each archetype lives in its own frame: x along the wind, y across it, z up;
// its box is [-hw, hw]^2 x [-hh, hh] about its centre, seen from the views of a grid of azimuths and
// elevations (toward the viewer: (cos e cos a, cos e sin a, sin e)), each an orthographic square of
// the sphere that holds the cloud. Per texel and view, two layers:
//   2v:     the optical depth through the cloud; the depth (along the view, from the sphere's centre
//           plane, in radii) and height above the layer's base (m) of the point that hides half of
//           its opacity; the extinction there (1/m);
//   2v + 1: the first four spherical-harmonic coefficients of the diffuse transmittance
//           1 / (1 + 0.15 tau(w)) toward every direction w, averaged over four points along the view
//           that each hide a quarter of the opacity. The light model is linear in it
//           (clouds/light_model.glsl), so the average over the view of that part of what the samples
//           scatter is found from it toward the light, at any time of day; the direct beam is taken
//           from the optical depth it stands for.
// And a third texture (r8, one layer per view and archetype): the fill the light model's terms 30-31
// read (the eroded density over the envelope's, clouds/density.glsl), averaged along the view with
// each sample's share of the opacity (what it adds to the pixel), as the march's samples add it.

#include "clouds/billboard_block.glsl.h"

// An archetype cloud the bake chose (clouds/billboards_bake.comp) and the placement reads: where it
// lies in the layer's noise (metres) and its score, the sum of the five envelopes it was chosen by.
struct BillboardArchetype {
  vec2 place;
  float score;
  float unused;  // std430 packs the array by 16 bytes, as it did the vec4s before
};

uniform ivec4 u_atlas;  // view azimuths, view elevations, archetypes, texels per side
uniform vec4 u_box;     // half width m, half height m, bounding radius m, volume slices per archetype
uniform vec4 u_volume;  // texels per side of an archetype's volume, height of the box's centre above the
                        // layer's base m

// The elevations' sines span [-kBillboardSinRange, kBillboardSinRange] (one row: the horizon).
const float kBillboardSinRange = 0.6;

// Toward the viewer of view (row, column), in the archetype's frame.
vec3 billboard_view_direction(int row, int column) {
  float s = u_atlas.y > 1 ? -kBillboardSinRange + 2.0 * kBillboardSinRange * float(row) / float(u_atlas.y - 1)
                          : 0.0;
  float a = 6.2831853 * float(column) / float(u_atlas.x);
  float c = sqrt(1.0 - s * s);
  return vec3(c * cos(a), c * sin(a), s);
}
// The orthographic view's image axes (right, up) for a view direction d (toward the viewer).
void billboard_view_axes(vec3 d, out vec3 right, out vec3 up) {
  right = normalize(cross(-d, vec3(0.0, 0.0, 1.0)));
  up = cross(right, -d);
}
// The three views around a direction toward the viewer (the archetype's frame): the corners of the
// triangle it falls in when each cell of the (azimuth, elevation) grid is split along its diagonal,
// packed as row * azimuths + column, and their barycentric weights (three reads, not a quad's four).
void billboard_views(vec3 d, out ivec3 views, out vec3 weights) {
  float a = atan(d.y, d.x) / 6.2831853;
  float fa = fract(a) * float(u_atlas.x);
  int c0 = int(floor(fa)) % u_atlas.x, c1 = (c0 + 1) % u_atlas.x;
  float wa = fract(fa);
  float fr = u_atlas.y > 1 ? clamp((d.z + kBillboardSinRange) / (2.0 * kBillboardSinRange), 0.0, 1.0) *
                                 float(u_atlas.y - 1)
                           : 0.0;
  int r0 = min(int(floor(fr)), max(u_atlas.y - 2, 0)), r1 = min(r0 + 1, u_atlas.y - 1);
  float wr = u_atlas.y > 1 ? fr - float(r0) : 0.0;
  int v00 = r0 * u_atlas.x + c0, v01 = r0 * u_atlas.x + c1, v10 = r1 * u_atlas.x + c0,
      v11 = r1 * u_atlas.x + c1;
  if (wa >= wr) {
    views = ivec3(v00, v01, v11);
    weights = vec3(1.0 - wa, wa - wr, wr);
  } else {
    views = ivec3(v00, v10, v11);
    weights = vec3(1.0 - wr, wr - wa, wa);
  }
}

// Spherical harmonics to first order (real, orthonormal): Y00, Y1-1, Y10, Y11.
vec4 billboard_sh(vec3 w) { return vec4(0.282095, 0.488603 * w.y, 0.488603 * w.z, 0.488603 * w.x); }
// A transmittance toward w from its coefficients (kept within its range: a first-order fit of a
// sharp function may overshoot).
float billboard_transmittance(vec4 sh, vec3 w, float lowest) {
  return clamp(dot(sh, billboard_sh(w)), lowest, 1.0);
}

// Where a segment p + t d (the archetype's frame, m) lies in the box: (t near, t far), near > far when
// missed.
vec2 billboard_box_span(vec3 p, vec3 d) {
  vec3 half_size = vec3(u_box.x, u_box.x, u_box.y);
  vec3 inv = 1.0 / (abs(d) + 1e-12) * sign(d + 1e-30);
  vec3 ta = (-half_size - p) * inv, tb = (half_size - p) * inv;
  vec3 lo = min(ta, tb), hi = max(ta, tb);
  return vec2(max(max(lo.x, lo.y), lo.z), min(min(hi.x, hi.y), hi.z));
}

#ifdef BILLBOARDS_VOLUME
// Archetypes' extinction volumes (1/m), stacked along z: archetype k holds slices [k n, (k + 1) n);
// and beside them (BILLBOARDS_FILL_VOLUME) the fill the march's light model reads (clouds_fill: the
// eroded density over the un-eroded envelope's; 0 outside the envelope, so that the filtered fill
// falls toward a cloud's edge as the field's does).
layout(binding = BILLBOARDS_VOLUME) uniform sampler3D u_billboard_volume;
layout(binding = BILLBOARDS_FILL_VOLUME) uniform sampler3D u_billboard_fill_volume;
// Where p (the archetype's frame, m) lies in the volumes' texture coordinates; x < 0: outside the box.
vec3 billboard_volume_coordinates(vec3 p, int archetype) {
  vec3 f = p / vec3(u_box.x, u_box.x, u_box.y) * 0.5 + 0.5;
  if (any(lessThan(f, vec3(0.0))) || any(greaterThan(f, vec3(1.0)))) return vec3(-1.0);
  float slices = u_box.w;
  // Kept half a slice inside its own stack: no archetype reads its neighbour's.
  float z =
      (clamp(f.z * slices, 0.5, slices - 0.5) + float(archetype) * slices) / (slices * float(u_atlas.z));
  return vec3(f.xy, z);
}
float billboard_extinction(vec3 p, int archetype) {
  vec3 c = billboard_volume_coordinates(p, archetype);
  return c.x < 0.0 ? 0.0 : textureLod(u_billboard_volume, c, 0.0).r;
}
// The extinction (1/m) and the fill at p.
vec2 billboard_extinction_fill(vec3 p, int archetype) {
  vec3 c = billboard_volume_coordinates(p, archetype);
  if (c.x < 0.0) return vec2(0.0);
  return vec2(textureLod(u_billboard_volume, c, 0.0).r, textureLod(u_billboard_fill_volume, c, 0.0).r);
}
// The optical depth from p toward w, to where the ray leaves the box, in `steps` midpoint steps.
float billboard_march_depth(vec3 p, vec3 w, int archetype, int steps) {
  float length_m = max(billboard_box_span(p, w).y, 0.0);
  float dt = length_m / float(steps), tau = 0.0;
  for (int i = 0; i < steps; ++i)
    tau += billboard_extinction(p + w * ((float(i) + 0.5) * dt), archetype) * dt;
  return tau;
}
#endif
