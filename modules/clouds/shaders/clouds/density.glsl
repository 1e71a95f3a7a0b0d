#pragma once
// The cloud density field, shared by the march, the light march and the shadow map (and mirrored in
// C++ by src/cloud_field.cpp for the CPU reference). Points are camera-relative metres; lengths in
// the planet-centred frame come from the camera's radius so that float precision does not depend on
// the planet's size (altitude h = h_camera + (r^2 - r_camera^2) / (r + r_camera)).

// Per frame (src/frame_block.cpp mirrors it, std140).
layout(std140, binding = 0) uniform CloudsFrame {
  vec4 cl_planet;          // planet radius m, camera altitude m, camera radius m, layer count
  vec4 cl_up;              // xyz: planet-centred up at the camera; w: max march distance m
  vec4 cl_shell;           // lowest base, highest top (altitudes, m) of the layers; empty-space step m
  vec4 cl_shape_origin;    // camera in shape periods (fraction, drift applied); w: 1 / period
  vec4 cl_detail_origin;   // the same for the detail noise
  vec4 cl_steps;           // max steps, min step m, max step m, light steps
  vec4 cl_light;           // first light step m, octaves, powder, ground albedo
  vec4 cl_medium;          // scattering, absorption (per unit density), phase model, droplet diameter um
  vec4 cl_phase;           // g forward, g backward, forward weight, light marched (0 sun, 1 moon)
  vec4 cl_frame;           // frame index, shape detail on, march width, march height
  vec4 cl_light_model;     // multiple scattering: 0 octaves, 1 diffusion; y: march pixel angle (rad)
  mat4 cl_inverse_view_projection;
};

// One layer (src/frame_block.cpp packs them, std430).
struct CloudLayerGpu {
  vec4 altitude;  // base m, thickness m, base variation m, density per m
  vec4 shape;     // coverage, shape amount, detail amount, coverage filter width
  vec4 profile;   // exp term, exponent, linear term, constant term
  vec4 weather;   // camera in weather periods (fraction, drift applied), xyz; w: 1 / period
  vec4 model;     // dome (0 sheet .. 1 dome), weather channel, casts shadow, -
};
layout(std430, binding = 0) readonly buffer CloudLayers { CloudLayerGpu cl_layers[]; };

layout(binding = 0) uniform sampler3D cl_shape_noise;
layout(binding = 1) uniform sampler3D cl_detail_noise;
layout(binding = 2) uniform sampler3D cl_weather_noise;

// The width a sample stands for (a pixel's footprint at its distance): the noise is read at the
// mip level whose texels match it, so distant clouds average instead of aliasing. Set by the caller.
float clouds_footprint_m = 0.0;
float clouds_lod(float texel_m) { return log2(max(clouds_footprint_m / texel_m, 1.0)); }

float clouds_altitude(vec3 x) {
  float r_c = cl_planet.z;
  float d = 2.0 * r_c * dot(cl_up.xyz, x) + dot(x, x);  // r^2 - r_camera^2
  float r = sqrt(max(r_c * r_c + d, 0.0));
  return cl_planet.y + d / max(r + r_c, 1.0);
}

// What a layer's weather and vertical envelope allow at x, before the noise erodes it (also the
// coarse occupancy that lets the march skip empty space without fetching the shape noise).
float clouds_layer_envelope(CloudLayerGpu L, vec3 x, float h, out float t) {
  t = 0.0;
  // Outside the layer's reach (its base can move by the variation): no texture fetch at all.
  if (h < L.altitude.x - L.altitude.z || h > L.altitude.x + L.altitude.y + L.altitude.z) return 0.0;
  vec4 w4 = textureLod(cl_weather_noise, L.weather.xyz + x * L.weather.w, clouds_lod(1.0 / (L.weather.w * 64.0)));
  int channel = int(L.model.y);
  float w = channel == 0 ? w4.r : channel == 1 ? w4.g : w4.b;
  float base = L.altitude.x + L.altitude.z * (w4.a - 0.5) * 2.0;
  t = (h - base) / max(L.altitude.y, 1e-3);
  if (t <= 0.0 || t >= 1.0) return 0.0;
  // Coverage c covers a fraction c of the sky (the weather channels are equalised to uniform).
  float fw = L.shape.w, c = L.shape.x;
  float lo = (1.0 - c) * (1.0 + fw) - fw;
  float d0 = clamp((w - lo) / fw, 0.0, 1.0);
  if (d0 <= 0.0) return 0.0;
  // Domes: the top rises with the weather's strength; sheets fill the layer. Flat, soft bases.
  float top = mix(1.0, max(d0, 0.05), L.model.x);
  float envelope = smoothstep(0.0, 0.08, t) * (1.0 - smoothstep(top * 0.75, top, t));
  float profile = clamp(L.profile.x * exp(L.profile.y * t) + L.profile.z * t + L.profile.w, 0.0, 1.0);
  return d0 * envelope * profile;
}

// Extinction (1/m) of one layer at x; `detail` adds the detail noise's erosion. `envelope` is what
// the weather allowed before any noise (0: empty space the march may skip).
float clouds_layer_density(CloudLayerGpu L, vec3 x, float h, bool detail, out float envelope) {
  float t;
  envelope = clouds_layer_envelope(L, x, h, t);
  if (envelope <= 0.0) return 0.0;
  float s = textureLod(cl_shape_noise, cl_shape_origin.xyz + x * cl_shape_origin.w, clouds_lod(1.0 / (cl_shape_origin.w * 128.0))).r;
  float erosion = (1.0 - s) * L.shape.y;
  float d = clamp((envelope - erosion) / max(1.0 - erosion, 1e-3), 0.0, 1.0);
  if (detail && d > 0.0 && L.shape.z > 0.0) {
    float n = textureLod(cl_detail_noise, cl_detail_origin.xyz + x * cl_detail_origin.w, clouds_lod(1.0 / (cl_detail_origin.w * 32.0))).r;
    // Wisps at the base, billows at the top (Schneider): the detail erodes thin parts most.
    float e = mix(n, 1.0 - n, clamp(t * 4.0, 0.0, 1.0)) * L.shape.z * 0.35 * (1.0 - d);
    d = clamp((d - e) / max(1.0 - e, 1e-3), 0.0, 1.0);
  }
  return d * L.altitude.w;
}

// Total extinction of the layers at x (shadow_only: only layers that cast shadows); `empty` when no
// layer's weather allows cloud there.
float clouds_density(vec3 x, bool detail, bool shadow_only, out bool empty) {
  empty = true;
  float h = clouds_altitude(x);
  if (h < cl_shell.x || h > cl_shell.y) return 0.0;
  float sum = 0.0, envelope;
  int n = int(cl_planet.w);
  for (int i = 0; i < n; ++i) {
    if (shadow_only && cl_layers[i].model.z < 0.5) continue;
    sum += clouds_layer_density(cl_layers[i], x, h, detail, envelope);
    empty = empty && envelope <= 0.0;
  }
  return sum;
}
float clouds_density(vec3 x, bool detail, bool shadow_only) {
  bool empty;
  return clouds_density(x, detail, shadow_only, empty);
}

// Distances along a ray from a camera-relative origin to the sphere at `altitude` above the
// planet's surface: (near, far), or near > far when missed. Differences of squares are formed first
// (R^2 - r_c^2 = (R - r_c)(R + r_c)) so that precision does not depend on the planet's size.
vec2 clouds_sphere_from(vec3 origin, vec3 dir, float altitude) {
  float R = cl_planet.x + altitude;
  float r_c = cl_planet.z;
  float b = r_c * dot(cl_up.xyz, dir) + dot(origin, dir);
  float c = (altitude - cl_planet.y) * (R + r_c) - (2.0 * r_c * dot(cl_up.xyz, origin) + dot(origin, origin));
  float disc = b * b + c;
  if (disc < 0.0) return vec2(1.0, -1.0);
  float s = sqrt(disc);
  return vec2(-b - s, -b + s);
}
vec2 clouds_sphere(vec3 dir, float altitude) { return clouds_sphere_from(vec3(0.0), dir, altitude); }
