#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "welkin/atmosphere/gpu.h"
#include "welkin/atmosphere/lut_mapping.h"
#include "welkin/gfx/debug_content.h"

namespace welkin::atmosphere {

namespace {

// Bruneton's two-layer form on the GPU always: one layer goes in the second slot with a zero-width
// first slot, none leaves both at zero density.
void pack_profile(const DensityProfile& p, glm::vec4* out) {
  DensityLayer l0{}, l1{};
  if (p.size() == 1) l1 = p[0];
  if (p.size() >= 2) l0 = p[0], l1 = p[1];
  out[0] = {l0.width_km, l0.exp_term, l0.exp_scale_per_km, l0.linear_term_per_km};
  out[1] = {l0.constant_term, 0, 0, 0};
  out[2] = {l1.width_km, l1.exp_term, l1.exp_scale_per_km, l1.linear_term_per_km};
  out[3] = {l1.constant_term, 0, 0, 0};
}

glm::dvec3 any_perpendicular(const glm::dvec3& v) {
  glm::dvec3 a = std::abs(v.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(v, a));
}

// Where sunlight comes from on the moon's visible face, from its illuminated fraction k: the phase
// angle is acos(2k - 1), and the lit limb faces the sun across the sky.
glm::dvec3 moon_light_direction(const glm::dvec3& moon, const glm::dvec3& sun, double fraction) {
  double phase = std::acos(std::clamp(2.0 * fraction - 1.0, -1.0, 1.0));
  glm::dvec3 towards_sun = sun - moon * glm::dot(sun, moon);
  towards_sun = glm::length(towards_sun) > 1e-9 ? glm::normalize(towards_sun) : any_perpendicular(moon);
  return -moon * std::cos(phase) + towards_sun * std::sin(phase);
}

}  // namespace

GpuUniforms make_uniforms(const Atmosphere& a, const Sun* sun_in, const Moon* moon, const FrameView& view) {
  GpuUniforms u;
  const ResolvedQuality q = resolve_quality(a);
  const double bottom = a.bottom_radius_km, top = a.top_radius_km;
  // Samples and the camera stay this far above the ground: a few float ulps at the planet's radius
  // (3 m on Earth), so a point on the ground never rounds below it, yet far below any scale height.
  const double lift = std::max(1e-5 * (top - bottom), 5e-7 * bottom);
  u.rayleigh_scattering = glm::vec4(a.rayleigh_scattering, 0.0f);
  u.mie_scattering = glm::vec4(a.mie_scattering, a.mie_g);
  u.mie_extinction = glm::vec4(a.mie_extinction, float(int(a.mie_phase)));
  u.absorption_extinction = glm::vec4(a.absorption_extinction, a.multiple_scattering_factor);
  u.ground_albedo = glm::vec4(a.ground_albedo, float(lift));
  u.radii = glm::vec4(float(bottom), float(top), float(std::sqrt((top - bottom) * (top + bottom))),
                      float(top - bottom));
  pack_profile(a.rayleigh_density, &u.density[0]);
  pack_profile(a.mie_density, &u.density[4]);
  pack_profile(a.absorption_density, &u.density[8]);
  const glm::dvec2 moments = mie_legendre_moments(a.mie_phase, a.mie_g);
  u.mie_moments = glm::vec4(float(moments.x), float(moments.y), 0.0f, 0.0f);

  // Camera relative to the planet in double, rounded to float only once: stable at any distance.
  glm::dvec3 cam = (view.camera_position_m - planet_center_m(a)) * 1e-3;
  double r = glm::length(cam);
  if (r < bottom + lift) {
    cam = (r > 0.0 ? cam / r : glm::dvec3(0, 0, 1)) * (bottom + lift);
    r = bottom + lift;
  }
  u.camera_km = glm::vec4(glm::vec3(cam), float(r));

  const Sun sun = sun_in ? *sun_in : Sun{};
  const glm::dvec3 sun_dir = direction_from_azimuth_elevation(sun.azimuth_deg, sun.elevation_deg);
  const double sun_radius = glm::radians(double(sun.angular_radius_deg));
  u.sun_direction = glm::vec4(glm::vec3(sun_dir), float(std::cos(sun_radius)));
  u.sun_illuminance = glm::vec4(sun.color * sun.illuminance_lux * sun.visible_fraction, float(sun_radius));
  u.flags = glm::vec4(sun.disc ? 1.0f : 0.0f, sun.limb_darkening ? 1.0f : 0.0f, 0.0f, 0.0f);
  if (moon) {
    const glm::dvec3 moon_dir = direction_from_azimuth_elevation(moon->azimuth_deg, moon->elevation_deg);
    const double moon_radius = glm::radians(double(moon->angular_radius_deg));
    u.moon_direction = glm::vec4(glm::vec3(moon_dir), float(std::cos(moon_radius)));
    u.moon_illuminance = glm::vec4(moon->color * moon->illuminance_lux, float(moon_radius));
    u.moon_light = glm::vec4(glm::vec3(moon_light_direction(moon_dir, sun_dir, moon->illuminated_fraction)),
                             moon->illuminated_fraction);
    u.flags.z = moon->disc ? 1.0f : 0.0f;
    u.flags.w = moon->lights_sky ? 1.0f : 0.0f;
  } else {
    u.moon_direction = glm::vec4(0, 0, -1, 1);
  }

  u.inverse_view_projection = view.inverse_view_projection;
  u.view_projection = view.view_projection;
  u.aerial_inverse_view_projection = view.inverse_view_projection;
  u.aerial_view_projection = view.view_projection;
  // Sky-view frame at the camera: z up, x towards the sun's azimuth (any horizontal axis when the
  // sun is at the zenith or nadir).
  const glm::dvec3 up = cam / r;
  // Moonlight scatters in the air only where it can show. With the sun above the horizon of a camera
  // inside the atmosphere the sky it lights is thousands of times brighter than anything a moon of at
  // most 1/1000 of the sun's illuminance adds, and the second light doubles the cost of every march
  // (a shader permutation without it, passes.cpp), so it is left out.
  if (moon && u.flags.w > 0.5f && r < top && glm::dot(sun_dir, up) > 0.0) {
    const glm::vec3 sc = sun.color, mc = moon->color;
    const double sun_lux = double(sun.illuminance_lux) * sun.visible_fraction * std::min({sc.r, sc.g, sc.b});
    const double moon_lux = double(moon->illuminance_lux) * std::max({mc.r, mc.g, mc.b});
    if (moon_lux <= 1e-3 * sun_lux) u.flags.w = 0.0f;
  }
  glm::dvec3 x = sun_dir - up * glm::dot(sun_dir, up);
  x = glm::length(x) > 1e-9 ? glm::normalize(x) : any_perpendicular(up);
  const glm::dvec3 y = glm::cross(up, x);
  u.sky_frame = glm::mat4(glm::vec4(glm::vec3(x), 0), glm::vec4(glm::vec3(y), 0), glm::vec4(glm::vec3(up), 0),
                          glm::vec4(0, 0, 0, 1));

  u.transmittance_size = {q.transmittance_width, q.transmittance_height, q.transmittance_steps, 0};
  u.multiscattering_size = {q.multiscattering_size, q.multiscattering_steps, q.multiscattering_iterations, 0};
  u.sky_view_size = {q.sky_view_width, q.sky_view_height, q.sky_view_steps, 0};
  u.aerial_size = {q.aerial_perspective_width, q.aerial_perspective_height, q.aerial_perspective_slices,
                   q.aerial_perspective_steps_per_slice};
  u.aerial_params = {a.aerial_perspective_distance_km, float(q.raymarch_steps), r >= top ? 1.0f : 0.0f,
                     float(q.raymarch_light_steps)};
  // The sky-view LUT's horizon for this camera (common.glsl, atm_sky_view_uv_local), once per frame in
  // double rather than per pixel.
  const SkyViewMapping sv = sky_view_mapping(r, bottom);
  const double n = q.sky_view_height;
  u.sky_view_params = {float(std::sin(sv.beta)), float(std::cos(sv.beta)),
                       float(1.0 / std::tan(0.5 * sv.zenith_horizon)), float(1.0 / std::tan(0.5 * sv.beta))};
  // v's texel mapping, unit_to_sub_uv(v, n) = v (n - 1) / n + 0.5 / n, as a scale and an offset.
  u.sky_view_params_v = {float((n - 1.0) / n), float(0.5 / n), float(sv.zenith_horizon),
                         float(sv.beta)};
  return u;
}

bool luts_differ(const GpuUniforms& a, const GpuUniforms& b) {
  // Everything up to the camera is the medium: exactly what the persistent LUTs depend on.
  const size_t medium_bytes = offsetof(GpuUniforms, camera_km);
  return std::memcmp(&a, &b, medium_bytes) != 0 || a.transmittance_size != b.transmittance_size ||
         a.multiscattering_size != b.multiscattering_size;
}

namespace {

// b with a's view: what remains differs only where the frames differ in anything else.
GpuUniforms with_view_of(const GpuUniforms& a, GpuUniforms b) {
  b.inverse_view_projection = a.inverse_view_projection;
  b.view_projection = a.view_projection;
  return b;
}

// Every corner ray of the view whose inverse is `inverse_view_projection` projects inside the frustum
// of `view_projection` (the frusta share their apex, the camera, so the corners bound the view).
bool frustum_inside(const glm::mat4& view_projection, const glm::mat4& inverse_view_projection) {
  for (const float x : {-1.0f, 1.0f})
    for (const float y : {-1.0f, 1.0f}) {
      const glm::vec4 far_point = inverse_view_projection * glm::vec4(x, y, 0.5f, 1.0f);
      const glm::vec3 dir = glm::normalize(glm::vec3(far_point) / far_point.w);
      const glm::vec4 clip = view_projection * glm::vec4(dir * 1000.0f, 1.0f);
      if (clip.w <= 0.0f || std::abs(clip.x) > clip.w || std::abs(clip.y) > clip.w) return false;
    }
  return true;
}

}  // namespace

bool sky_view_differs(const GpuUniforms& a, const GpuUniforms& b) {
  GpuUniforms view_free = with_view_of(a, b);
  view_free.aerial_inverse_view_projection = a.aerial_inverse_view_projection;
  view_free.aerial_view_projection = a.aerial_view_projection;
  view_free.aerial_size = a.aerial_size;
  view_free.aerial_params = a.aerial_params;
  return std::memcmp(&a, &view_free, sizeof(GpuUniforms)) != 0;
}

bool aerial_perspective_differs(const GpuUniforms& a, const GpuUniforms& b) {
  const GpuUniforms view_free = with_view_of(a, b);
  return std::memcmp(&a, &view_free, sizeof(GpuUniforms)) != 0;
}

void choose_aerial_frustum(GpuUniforms& u, const GpuUniforms& kept, bool kept_valid,
                           const glm::mat4& previous_view_projection, bool turned_before) {
  u.aerial_view_projection = u.view_projection;
  u.aerial_inverse_view_projection = u.inverse_view_projection;
  const bool turning = u.view_projection != previous_view_projection;
  if (!kept_valid || !turning) return;  // a still view: fitted to it (remade once a turn stops)
  GpuUniforms same_frustum = u;
  same_frustum.aerial_view_projection = kept.aerial_view_projection;
  same_frustum.aerial_inverse_view_projection = kept.aerial_inverse_view_projection;
  if (aerial_perspective_differs(same_frustum, kept)) return;  // the camera or anything else moved
  if (frustum_inside(kept.aerial_view_projection, u.inverse_view_projection)) {
    u = same_frustum;
    return;
  }
  if (!turned_before) return;  // the first frame of a turn: perhaps the only one
  // Turning on, out of it: a new volume around this view, wider on the image plane.
  const glm::mat4 widen =
      glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / kAerialTurningMargin, 1.0f / kAerialTurningMargin, 1.0f));
  u.aerial_view_projection = widen * u.view_projection;
  u.aerial_inverse_view_projection = u.inverse_view_projection * glm::inverse(widen);
}

}  // namespace welkin::atmosphere
