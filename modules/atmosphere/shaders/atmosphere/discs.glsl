#pragma once
// Sun and moon discs: luminance seen along a view direction, before the atmosphere's transmittance.
// Each disc's luminance is normalised so that integrating it over the disc gives the illuminance.
#include "atmosphere/common.glsl"

// Fraction of a pixel-wide edge inside a disc of angular radius `radius` at angle `angle` from its
// centre: anti-aliases the limb without blurring the disc.
float atm_disc_coverage(float angle, float radius, float pixel_angle) {
  return clamp((radius - angle) / max(pixel_angle, 1e-7) + 0.5, 0.0, 1.0);
}

// Solid angle of a cone of half-angle `radius`, without cancellation for tiny discs.
float atm_cone_solid_angle(float radius) {
  float s = sin(0.5 * radius);
  return 4.0 * ATM_PI * s * s;
}

vec3 atm_sun_disc(vec3 v, float pixel_angle) {
  if (atm.sun_disc < 0.5) return vec3(0.0);
  float radius = atm.sun_angular_radius_rad;
  float c = dot(v, atm.sun_direction);
  if (c < cos(min(radius + pixel_angle, ATM_PI))) return vec3(0.0);  // cheap rejection, most pixels
  float angle = acos(clamp(c, -1.0, 1.0));
  float cover = atm_disc_coverage(angle, radius, pixel_angle);
  if (cover <= 0.0) return vec3(0.0);
  vec3 l = atm.sun_illuminance / atm_cone_solid_angle(radius);
  if (atm.sun_limb_darkening > 0.5) {
    // Limb darkening I(mu)/I(1) = mu^a with a per channel (Neckel & Labs 1994 fit used by Hillaire),
    // times (a + 2) / 2, its inverse disc average, so the illuminance is unchanged.
    const vec3 a = vec3(0.397, 0.503, 0.652);
    float x = clamp(angle / radius, 0.0, 1.0);
    float mu = sqrt(max(0.0, 1.0 - x * x));
    l *= pow(vec3(max(mu, 1e-4)), a) * (a + 2.0) * 0.5;
  }
  return l * cover;
}

// The moon as a sphere lit from atm.moon_sunlit_direction (its phase); the lit part of the disc
// carries all of the phase-dependent illuminance.
vec3 atm_moon_disc(vec3 v, float pixel_angle) {
  if (atm.moon_disc < 0.5) return vec3(0.0);
  float radius = atm.moon_angular_radius_rad;
  vec3 m = atm.moon_direction;
  float c = dot(v, m);
  if (c < cos(min(radius + pixel_angle, ATM_PI))) return vec3(0.0);
  float angle = acos(clamp(c, -1.0, 1.0));
  float cover = atm_disc_coverage(angle, radius, pixel_angle);
  if (cover <= 0.0) return vec3(0.0);
  // Point on the sphere's visible face behind this pixel, in world axes.
  vec3 off = v - m * dot(v, m);
  float x = clamp(length(off) / max(sin(radius), 1e-7), 0.0, 1.0);
  vec3 side = length(off) > 0.0 ? normalize(off) : vec3(0.0);
  vec3 n = side * x - m * sqrt(max(0.0, 1.0 - x * x));
  float lit = smoothstep(-0.03, 0.03, dot(n, atm.moon_sunlit_direction));
  float fraction = max(atm.moon_illuminated_fraction, 1e-3);
  return atm.moon_illuminance / (atm_cone_solid_angle(radius) * fraction) * lit * cover;
}
