// Stars as points at infinity, drawn over the sky before the geometry covers it. Each star's light
// is spread over the 2x2 pixels around its projection with bilinear weights (stars.frag), so a star
// keeps its flux wherever it falls between pixel centres. Radiance = illuminance x transmittance /
// the pixel's solid angle, which for a pinhole camera is cos^3 theta / f^2 (f in pixels).
#include "atmosphere/common.glsl"

layout(std430, binding = 0) readonly buffer AtmStars { AtmosphereStarGpu atm_stars[]; };
uniform mat3 u_celestial_to_world;
uniform vec2 u_viewport;   // pixels
uniform float u_focal_px;  // focal length in pixels
flat out vec3 v_radiance;
flat out vec2 v_center;

void main() {
  AtmosphereStarGpu s = atm_stars[gl_VertexID];
  vec3 d = normalize(u_celestial_to_world * s.direction);
  vec4 clip = atm.view_projection * vec4(d, 0.0);
  vec3 t = atm_transmittance_to_space(atm.camera_km, d);
  if (clip.w <= 0.0 || all(equal(t, vec3(0.0)))) {
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // behind the camera or below the horizon: clipped away
    gl_PointSize = 1.0;
    return;
  }
  vec2 ndc = clip.xy / clip.w;
  v_center = (ndc * 0.5 + 0.5) * u_viewport;
  // clip.w = d . forward = cos theta for a unit direction.
  float pixel_solid_angle = clip.w * clip.w * clip.w / (u_focal_px * u_focal_px);
  v_radiance = s.illuminance_lux * s.color * t / pixel_solid_angle;
  gl_Position = vec4(ndc, 0.0, 1.0);
  gl_PointSize = 2.0;
}
