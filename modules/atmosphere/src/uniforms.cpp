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

DensityLayerBlock pack_layer(const DensityLayer& l) {
  DensityLayerBlock out{};
  out.width_km = l.width_km;
  out.exp_term = l.exp_term;
  out.exp_scale_per_km = l.exp_scale_per_km;
  out.linear_term_per_km = l.linear_term_per_km;
  out.constant_term = l.constant_term;
  return out;
}

// Bruneton's two-layer form on the GPU always: one layer goes in the upper slot with a zero-width
// lower slot, none leaves both at zero density.
void pack_profile(const DensityProfile& p, DensityLayerBlock (&out)[2]) {
  DensityLayer lower{}, upper{};
  if (p.size() == 1) upper = p[0];
  if (p.size() >= 2) lower = p[0], upper = p[1];
  out[0] = pack_layer(lower);
  out[1] = pack_layer(upper);
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

FrameBlock make_uniforms(const Atmosphere& a, const Sun* sun_in, const Moon* moon, const FrameView& view) {
  FrameBlock u{};
  const ResolvedQuality q = resolve_quality(a);
  const double bottom = a.bottom_radius_km, top = a.top_radius_km;
  // Samples and the camera stay this far above the ground: a few float ulps at the planet's radius
  // (3 m on Earth), so a point on the ground never rounds below it, yet far below any scale height.
  const double lift = std::max(1e-5 * (top - bottom), 5e-7 * bottom);
  auto& m = u.medium;
  m.rayleigh_scattering = a.rayleigh_scattering;
  m.mie_scattering = a.mie_scattering;
  m.mie_g = a.mie_g;
  m.mie_extinction = a.mie_extinction;
  m.mie_phase = float(int(a.mie_phase));
  m.absorption_extinction = a.absorption_extinction;
  m.multiple_scattering_factor = a.multiple_scattering_factor;
  m.ground_albedo = a.ground_albedo;
  m.lift_km = float(lift);
  m.bottom_radius_km = float(bottom);
  m.top_radius_km = float(top);
  m.horizon_distance_km = float(std::sqrt((top - bottom) * (top + bottom)));
  m.thickness_km = float(top - bottom);
  pack_profile(a.rayleigh_density, m.rayleigh_density);
  pack_profile(a.mie_density, m.mie_density);
  pack_profile(a.absorption_density, m.absorption_density);
  const glm::dvec2 moments = mie_legendre_moments(a.mie_phase, a.mie_g);
  m.mie_moment_1 = float(moments.x);
  m.mie_moment_2 = float(moments.y);

  // Camera relative to the planet in double, rounded to float only once: stable at any distance.
  glm::dvec3 cam = (view.camera_position_m - planet_center_m(a)) * 1e-3;
  double r = glm::length(cam);
  if (r < bottom + lift) {
    cam = (r > 0.0 ? cam / r : glm::dvec3(0, 0, 1)) * (bottom + lift);
    r = bottom + lift;
  }
  u.camera_km = glm::vec3(cam);
  u.camera_radius_km = float(r);

  const Sun sun = sun_in ? *sun_in : Sun{};
  const glm::dvec3 sun_dir = direction_from_azimuth_elevation(sun.azimuth_deg, sun.elevation_deg);
  const double sun_radius = glm::radians(double(sun.angular_radius_deg));
  u.sun_direction = glm::vec3(sun_dir);
  u.sun_cos_angular_radius = float(std::cos(sun_radius));
  u.sun_illuminance = sun.color * sun.illuminance_lux * sun.visible_fraction;
  u.sun_angular_radius_rad = float(sun_radius);
  u.sun_disc = sun.disc ? 1.0f : 0.0f;
  u.sun_limb_darkening = sun.limb_darkening ? 1.0f : 0.0f;
  if (moon) {
    const glm::dvec3 moon_dir = direction_from_azimuth_elevation(moon->azimuth_deg, moon->elevation_deg);
    const double moon_radius = glm::radians(double(moon->angular_radius_deg));
    u.moon_direction = glm::vec3(moon_dir);
    u.moon_cos_angular_radius = float(std::cos(moon_radius));
    u.moon_illuminance = moon->color * moon->illuminance_lux;
    u.moon_angular_radius_rad = float(moon_radius);
    u.moon_sunlit_direction = glm::vec3(moon_light_direction(moon_dir, sun_dir, moon->illuminated_fraction));
    u.moon_illuminated_fraction = moon->illuminated_fraction;
    u.moon_disc = moon->disc ? 1.0f : 0.0f;
    u.moon_lights_sky = moon->lights_sky ? 1.0f : 0.0f;
  } else {
    u.moon_direction = glm::vec3(0, 0, -1);
    u.moon_cos_angular_radius = 1.0f;
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
  if (moon && u.moon_lights_sky > 0.5f && r < top && glm::dot(sun_dir, up) > 0.0) {
    const glm::vec3 sc = sun.color, mc = moon->color;
    const double sun_lux = double(sun.illuminance_lux) * sun.visible_fraction * std::min({sc.r, sc.g, sc.b});
    const double moon_lux = double(moon->illuminance_lux) * std::max({mc.r, mc.g, mc.b});
    if (moon_lux <= 1e-3 * sun_lux) u.moon_lights_sky = 0.0f;
  }
  glm::dvec3 x = sun_dir - up * glm::dot(sun_dir, up);
  x = glm::length(x) > 1e-9 ? glm::normalize(x) : any_perpendicular(up);
  const glm::dvec3 y = glm::cross(up, x);
  u.sky_frame = glm::mat4(glm::vec4(glm::vec3(x), 0), glm::vec4(glm::vec3(y), 0), glm::vec4(glm::vec3(up), 0),
                          glm::vec4(0, 0, 0, 1));

  u.transmittance_width = q.transmittance_width;
  u.transmittance_height = q.transmittance_height;
  u.transmittance_steps = q.transmittance_steps;
  u.multiscattering_size = q.multiscattering_size;
  u.multiscattering_steps = q.multiscattering_steps;
  u.multiscattering_iterations = q.multiscattering_iterations;
  u.sky_view_width = q.sky_view_width;
  u.sky_view_height = q.sky_view_height;
  u.sky_view_steps = q.sky_view_steps;
  u.aerial_width = q.aerial_perspective_width;
  u.aerial_height = q.aerial_perspective_height;
  u.aerial_slices = q.aerial_perspective_slices;
  u.aerial_steps_per_slice = q.aerial_perspective_steps_per_slice;
  u.aerial_distance_km = a.aerial_perspective_distance_km;
  u.raymarch_steps = float(q.raymarch_steps);
  u.camera_in_space = r >= top ? 1.0f : 0.0f;
  u.raymarch_light_steps = float(q.raymarch_light_steps);
  // The sky-view LUT's horizon for this camera (common.glsl, atm_sky_view_uv_local), once per frame in
  // double rather than per pixel.
  const SkyViewMapping sv = sky_view_mapping(r, bottom);
  const double n = q.sky_view_height;
  u.sky_view_sin_beta = float(std::sin(sv.beta));
  u.sky_view_cos_beta = float(std::cos(sv.beta));
  u.sky_view_inv_tan_half_zenith_horizon = float(1.0 / std::tan(0.5 * sv.zenith_horizon));
  u.sky_view_inv_tan_half_beta = float(1.0 / std::tan(0.5 * sv.beta));
  // v's texel mapping, unit_to_sub_uv(v, n) = v (n - 1) / n + 0.5 / n, as a scale and an offset.
  u.sky_view_v_scale = float((n - 1.0) / n);
  u.sky_view_v_offset = float(0.5 / n);
  u.sky_view_zenith_horizon = float(sv.zenith_horizon);
  u.sky_view_beta = float(sv.beta);
  return u;
}

bool luts_differ(const FrameBlock& a, const FrameBlock& b) {
  return std::memcmp(&a.medium, &b.medium, sizeof a.medium) != 0 ||
         persistent_lut_sizes(a) != persistent_lut_sizes(b);
}

namespace {

// b with a's view: what remains differs only where the frames differ in anything else.
FrameBlock with_view_of(const FrameBlock& a, FrameBlock b) {
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

bool sky_view_differs(const FrameBlock& a, const FrameBlock& b) {
  FrameBlock view_free = with_view_of(a, b);
  view_free.aerial_inverse_view_projection = a.aerial_inverse_view_projection;
  view_free.aerial_view_projection = a.aerial_view_projection;
  view_free.aerial_width = a.aerial_width;
  view_free.aerial_height = a.aerial_height;
  view_free.aerial_slices = a.aerial_slices;
  view_free.aerial_steps_per_slice = a.aerial_steps_per_slice;
  view_free.aerial_distance_km = a.aerial_distance_km;
  // the sky's per-pixel march does not read the LUT (camera_in_space follows the camera, compared)
  view_free.raymarch_steps = a.raymarch_steps;
  view_free.camera_in_space = a.camera_in_space;
  view_free.raymarch_light_steps = a.raymarch_light_steps;
  return std::memcmp(&a, &view_free, sizeof(FrameBlock)) != 0;
}

bool aerial_perspective_differs(const FrameBlock& a, const FrameBlock& b) {
  const FrameBlock view_free = with_view_of(a, b);
  return std::memcmp(&a, &view_free, sizeof(FrameBlock)) != 0;
}

void choose_aerial_frustum(FrameBlock& u, const FrameBlock& kept, bool kept_valid,
                           const glm::mat4& previous_view_projection, bool turned_before) {
  u.aerial_view_projection = u.view_projection;
  u.aerial_inverse_view_projection = u.inverse_view_projection;
  const bool turning = u.view_projection != previous_view_projection;
  if (!kept_valid || !turning) return;  // a still view: fitted to it (remade once a turn stops)
  FrameBlock same_frustum = u;
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
