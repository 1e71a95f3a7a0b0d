// The full-screen triangle of the god rays' application, and what the haze's light needs that is the
// same for every pixel (the sun's irradiance and the sky's at the camera), found once per vertex
// instead of once per pixel.
out vec2 v_ndc;
#if GODRAYS_HAZE
#include "godrays/haze.glsl"
#include "welkin/lighting.glsl"
flat out vec3 v_sun_irradiance;
flat out vec3 v_sky_radiance;  // mean over the sphere of directions: (up + down irradiance) / 4 pi
#endif
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
  v_ndc = p;
#if GODRAYS_HAZE
  v_sun_irradiance = welkin_sun_irradiance(vec3(0.0));
  v_sky_radiance = (welkin_sky_irradiance(u_up) + welkin_sky_irradiance(-u_up)) / 12.5663706143592;
#endif
  gl_Position = vec4(p, 0.0, 1.0);
}
