#pragma once
// The atmosphere's public material include. A material that includes it (the pass binds the
// atmosphere with welkin::atmosphere::bind_for_materials) can, for a camera-relative position in
// metres, get the light between it and the camera and the sun, moon and sky light falling on it.
// Opaque geometry gets aerial perspective from the atmosphere's one deferred pass over the scene
// depth (aerial_perspective_apply.frag/.comp); what writes no depth (the clouds' march, clusters and
// billboards) asks the light environment's welkin_aerial_perspective (light_term.glsl) along its rays.
#include "atmosphere/integrate.glsl"

struct AtmosphereAerialPerspective {
  vec3 inscattering;   // luminance added between the point and the camera
  vec3 transmittance;  // of that path
};

vec3 atmosphere_point_km(vec3 camera_relative_m) { return atm_camera() + camera_relative_m * 1e-3; }
vec3 atmosphere_sun_direction() { return atm.sun_direction; }
vec3 atmosphere_moon_direction() { return atm.moon_direction; }

// Froxels inside the atmosphere; from space (no froxels there: they would cover vacuum) the path is
// marched. The atmosphere's own pass picks one at compile time (ATM_AP_MODE 0 froxels, 1 march);
// materials that leave it undefined choose at run time.
AtmosphereAerialPerspective atm_aerial_perspective_march(vec3 camera_relative_m) {
  float d_km = length(camera_relative_m) * 1e-3;
  vec3 dir = camera_relative_m / max(length(camera_relative_m), 1e-9);
  AtmMarch m = atm_march_to_surface(atm_camera(), dir, d_km, int(atm.raymarch_steps), atm_sun_light(),
                                    atm_moon_light_source());
  return AtmosphereAerialPerspective(m.luminance, m.transmittance);
}

AtmosphereAerialPerspective atm_aerial_perspective_froxels(vec3 camera_relative_m) {
  float d_km = length(camera_relative_m) * 1e-3;
  vec4 clip = atm.aerial_view_projection * vec4(camera_relative_m, 1.0);
  vec2 uv = clip.w > 0.0 ? clip.xy / clip.w * 0.5 + 0.5 : vec2(0.5);
  float w = sqrt(d_km / atm.aerial_distance_km);
  // Slice 0's centre is at w = 0.5 / N; closer than that, fade towards no air at all.
  float fade = clamp(w * float(atm.aerial_slices) * 2.0, 0.0, 1.0);
  // Level 0 named: the volume has no other, and a shader that samples it sparsely (the clouds'
  // march, one pixel in four or sixteen) must read what a dense one reads.
  vec3 s = textureLod(atm_aerial_inscattering, vec3(uv, w), 0.0).rgb;
  vec3 t = textureLod(atm_aerial_transmittance, vec3(uv, w), 0.0).rgb;
  return AtmosphereAerialPerspective(s * fade, mix(vec3(1.0), t, fade));
}

AtmosphereAerialPerspective atmosphere_aerial_perspective(vec3 camera_relative_m) {
#if !defined(ATM_AP_MODE)
  if (atm_camera_in_space()) return atm_aerial_perspective_march(camera_relative_m);
  return atm_aerial_perspective_froxels(camera_relative_m);
#elif ATM_AP_MODE == 1
  return atm_aerial_perspective_march(camera_relative_m);
#else
  return atm_aerial_perspective_froxels(camera_relative_m);
#endif
}

// Illuminance (lux on a plane facing the light) at a point, through the air and the planet's shadow.
vec3 atmosphere_light_irradiance(vec3 camera_relative_m, vec3 direction, vec3 illuminance,
                                 float angular_radius) {
  vec3 p = atmosphere_point_km(camera_relative_m);
  float len = length(p);
  float r = max(len, atm_bottom() + atm.medium.lift_km);
  return illuminance * atm_transmittance_to_light(r, dot(p / max(len, 1e-20), direction), angular_radius);
}
vec3 atmosphere_sun_irradiance(vec3 camera_relative_m) {
  return atmosphere_light_irradiance(camera_relative_m, atm.sun_direction, atm.sun_illuminance,
                                     atm.sun_angular_radius_rad);
}
vec3 atmosphere_moon_irradiance(vec3 camera_relative_m) {
  return atmosphere_light_irradiance(camera_relative_m, atm.moon_direction, atm.moon_illuminance,
                                     atm.moon_angular_radius_rad);
}

// Irradiance from the sky (no sun or moon disc) on a surface with world normal n, from the L1
// spherical harmonics of the sky around the camera (Ramamoorthi & Hanrahan 2001).
vec3 atmosphere_sky_irradiance(vec3 n) {
  vec3 c0 = texelFetch(atm_sky_irradiance_sh, ivec2(0, 0), 0).rgb;
  vec3 c1 = texelFetch(atm_sky_irradiance_sh, ivec2(1, 0), 0).rgb;
  vec3 c2 = texelFetch(atm_sky_irradiance_sh, ivec2(2, 0), 0).rgb;
  vec3 c3 = texelFetch(atm_sky_irradiance_sh, ivec2(3, 0), 0).rgb;
  vec3 e = ATM_PI * 0.282095 * c0 + (2.0 * ATM_PI / 3.0) * 0.488603 * (c1 * n.y + c2 * n.z + c3 * n.x);
  return max(e, vec3(0.0));
}
