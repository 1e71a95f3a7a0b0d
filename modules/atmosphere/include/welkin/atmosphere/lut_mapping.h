#pragma once
// CPU mirror (double precision) of the shaders' transmittance-LUT parameterisation, so tests and
// `welkin probe` can say which (r, mu) a texel holds and where a (r, mu) is looked up.
#include <algorithm>
#include <cmath>

namespace welkin::atmosphere {

struct RadiusMu {
  double r_km;
  double mu;
};

// Texel centres at the ends of [0, 1] (the LUT holds its domain's boundary values exactly): texel
// i's centre (i + 0.5) / size holds the parameter i / (size - 1), and the two are exact inverses.
inline double unit_to_sub_uv(double u, double size) {
  return (0.5 + u * (size - 1.0)) / size;
}
inline double sub_uv_to_unit(double u, double size) {
  return (u - 0.5 / size) * (size / (size - 1.0));
}

// (r, mu) of the texel centre (x, y) of a width x height transmittance LUT.
inline RadiusMu transmittance_texel_r_mu(int x, int y, int width, int height, double bottom_km,
                                         double top_km) {
  double x_mu = sub_uv_to_unit((x + 0.5) / width, width), x_r = sub_uv_to_unit((y + 0.5) / height, height);
  double H = std::sqrt(top_km * top_km - bottom_km * bottom_km);
  double rho = H * x_r;
  double r = std::sqrt(rho * rho + bottom_km * bottom_km);
  double d_min = top_km - r, d_max = rho + H;
  double d = d_min + x_mu * (d_max - d_min);
  double mu = d <= 0.0 ? 1.0 : (H * H - rho * rho - d * d) / (2.0 * r * d);
  return {r, std::clamp(mu, -1.0, 1.0)};
}

// Where the shaders look (r, mu) up (common.glsl, atm_transmittance_uv): the inverse of
// transmittance_texel_r_mu, as texture coordinates in [0, 1].
struct TextureUv {
  double u, v;
};
inline TextureUv transmittance_uv(double r_km, double mu, int width, int height, double bottom_km,
                                  double top_km) {
  const double H = std::sqrt(top_km * top_km - bottom_km * bottom_km);
  const double rho = std::sqrt(std::max(0.0, (r_km - bottom_km) * (r_km + bottom_km)));
  const double disc = r_km * r_km * (mu * mu - 1.0) + top_km * top_km;
  const double d = std::max(0.0, -r_km * mu + std::sqrt(std::max(0.0, disc)));
  const double d_min = top_km - r_km, d_max = rho + H;
  const double x_mu = d_max > d_min ? (d - d_min) / (d_max - d_min) : 0.0;
  return {unit_to_sub_uv(std::clamp(x_mu, 0.0, 1.0), width),
          unit_to_sub_uv(std::clamp(rho / H, 0.0, 1.0), height)};
}

// The sky-view LUT's horizon seen from radius r: beta is its angle from the nadir, zenith_horizon
// (pi - beta) its zenith angle.
struct SkyViewMapping {
  double beta;
  double zenith_horizon;
};

inline SkyViewMapping sky_view_mapping(double r_km, double bottom_km) {
  const double pi = 3.14159265358979323846;
  double cos_beta = std::sqrt(std::max(0.0, (r_km - bottom_km) * (r_km + bottom_km))) / r_km;
  double beta = std::acos(std::clamp(cos_beta, -1.0, 1.0));
  return {beta, pi - beta};
}

struct ZenithAzimuth {
  double cos_zenith;
  double azimuth;  // radians from the sun's azimuth, in [-pi, pi]
};

// View direction of the texel centre (x, y) of a width x height sky-view LUT seen from radius r
// (the inverse of common.glsl's atm_sky_view_uv_local: v through tan of half the angle from the
// horizon, u through the pseudo-angle 1 - x / (|x| + |y|)).
inline ZenithAzimuth sky_view_texel_direction(int x, int y, int width, int height, double r_km,
                                              double bottom_km) {
  const SkyViewMapping m = sky_view_mapping(r_km, bottom_km);
  double c = 1.0 - 2.0 * sub_uv_to_unit((y + 0.5) / height, height);
  double e = 2.0 * std::atan(c * std::abs(c) * std::tan(0.5 * (c >= 0.0 ? m.zenith_horizon : m.beta)));
  double s = 2.0 * (x + 0.5) / width - 1.0;
  double px = 1.0 - 2.0 * s * s;
  return {std::cos(m.zenith_horizon - e), (s < 0 ? -1.0 : 1.0) * std::atan2(1.0 - std::abs(px), px)};
}

}  // namespace welkin::atmosphere
