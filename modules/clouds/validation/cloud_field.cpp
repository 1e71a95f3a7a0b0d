#include "cloud_field.h"

#include <algorithm>
#include <cmath>

namespace welkin::clouds {

namespace {
double clamp01(double v) { return std::clamp(v, 0.0, 1.0); }
double smoothstep(double a, double b, double x) {
  const double t = clamp01((x - a) / (b - a));
  return t * t * (3.0 - 2.0 * t);
}
}  // namespace

NoiseVolumes read_noise(const CloudsGpu& gpu) {
  NoiseVolumes n;
  n.shape_size = gpu.shape->desc().width, n.detail_size = gpu.detail->desc().width,
  n.weather_size = gpu.weather->desc().width;
  auto read = [](const Texture& t, GLenum format, int channels, std::vector<uint8_t>& out) {
    const int s = t.desc().width;
    out.resize(size_t(s) * s * s * size_t(channels));
    glGetTextureImage(t.id(), 0, format, GL_UNSIGNED_BYTE, GLsizei(out.size()), out.data());
  };
  read(*gpu.shape, GL_RGBA, 4, n.shape);
  read(*gpu.detail, GL_RED, 1, n.detail);
  read(*gpu.weather, GL_RGBA, 4, n.weather);
  n.systems_size = gpu.systems->desc().width;
  read(*gpu.systems, GL_RED, 1, n.systems);
  if (gpu.coverage_map) {
    n.coverage_map_side = gpu.coverage_map->desc().width;
    n.coverage_map.resize(size_t(n.coverage_map_side) * size_t(n.coverage_map_side));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureImage(gpu.coverage_map->id(), 0, GL_RED, GL_UNSIGNED_BYTE, GLsizei(n.coverage_map.size()),
                      n.coverage_map.data());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
  }
  return n;
}

CloudField::CloudField(NoiseVolumes noise, const FrameBlock& frame, std::vector<LayerBlock> layers)
    : noise_(std::move(noise)), frame_(frame), layers_(std::move(layers)) {}

// Trilinear with repeat, texel centres at (i + 0.5) / size: what GL's linear filter does.
double CloudField::sample(const std::vector<uint8_t>& v, int size, int channels, int channel,
                          glm::dvec3 uvw) const {
  const glm::dvec3 p = uvw * double(size) - 0.5;
  const glm::dvec3 f = p - glm::floor(p);
  const glm::ivec3 i = glm::ivec3(glm::floor(p));
  double sum = 0.0;
  for (int k = 0; k < 8; ++k) {
    const glm::ivec3 o(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    glm::ivec3 c = i + o;
    for (int a = 0; a < 3; ++a) c[a] = ((c[a] % size) + size) % size;
    const double w = (o.x ? f.x : 1.0 - f.x) * (o.y ? f.y : 1.0 - f.y) * (o.z ? f.z : 1.0 - f.z);
    sum += w *
           v[(size_t(c.z) * size * size + size_t(c.y) * size + size_t(c.x)) * size_t(channels) +
             size_t(channel)] /
           255.0;
  }
  return sum;
}

double CloudField::altitude(const glm::dvec3& x) const {
  const glm::dvec3 up(frame_.up);
  const double r_c = frame_.camera_radius_m;
  const double d = 2.0 * r_c * glm::dot(up, x) + glm::dot(x, x);
  const double r = std::sqrt(std::max(r_c * r_c + d, 0.0));
  return double(frame_.camera_altitude_m) + d / std::max(r + r_c, 1.0);
}

glm::dvec2 CloudField::sphere(const glm::dvec3& origin, const glm::dvec3& dir, double alt) const {
  const glm::dvec3 up(frame_.up);
  const double R = double(frame_.planet_radius_m) + alt, r_c = frame_.camera_radius_m;
  const double b = r_c * glm::dot(up, dir) + glm::dot(origin, dir);
  const double c = (alt - double(frame_.camera_altitude_m)) * (R + r_c) -
                   (2.0 * r_c * glm::dot(up, origin) + glm::dot(origin, origin));
  const double disc = b * b + c;
  if (disc < 0.0) return {1.0, -1.0};
  const double s = std::sqrt(disc);
  return {-b - s, -b + s};
}

// The painted map at a camera-relative point: projected along the radius onto the map's plane and
// read bilinearly, clamped to its edge; 0 off the map.
double CloudField::painted_coverage(const glm::dvec3& x) const {
  if (frame_.has_map < 0.5f || noise_.coverage_map_side < 1) return 0.0;
  const glm::dvec3 q = glm::dvec3(frame_.map_origin) + glm::dvec3(glm::dot(x, glm::dvec3(frame_.map_east)),
                                                                  glm::dot(x, glm::dvec3(frame_.map_north)),
                                                                  glm::dot(x, glm::dvec3(frame_.map_up)));
  if (q.z <= 0.0) return 0.0;
  const glm::dvec2 uv = glm::dvec2(q.x, -q.y) * (double(frame_.map_scale) / q.z) + 0.5;
  if (uv.x < 0.0 || uv.y < 0.0 || uv.x > 1.0 || uv.y > 1.0) return 0.0;
  const int n = noise_.coverage_map_side;
  const glm::dvec2 p = uv * double(n) - 0.5;
  const glm::dvec2 f = p - glm::floor(p);
  const glm::ivec2 i = glm::ivec2(glm::floor(p));
  double v = 0.0;
  for (int k = 0; k < 4; ++k) {
    const glm::ivec2 c = glm::clamp(i + glm::ivec2(k & 1, k >> 1), glm::ivec2(0), glm::ivec2(n - 1));
    v += ((k & 1) ? f.x : 1.0 - f.x) * ((k >> 1) ? f.y : 1.0 - f.y) *
         noise_.coverage_map[size_t(c.y) * size_t(n) + size_t(c.x)];
  }
  return painted_coverage_offset(v);
}

double CloudField::coverage(const LayerBlock& L, const glm::dvec3& x) const {
  const glm::dvec3 suv = glm::dvec3(frame_.system_origin) + x * double(frame_.system_per_m);
  const double c = system_coverage(L.coverage, sample(noise_.systems, noise_.systems_size, 1, 0, suv),
                                   frame_.system_amount);
  return L.follows_map > 0.5f ? clamp01(c + painted_coverage(x)) : c;
}

namespace {

// The anvil's envelope at height t (density.glsl's clouds_anvil): the towers tall enough to reach it
// spread out under the layer's ceiling, wider with height, flat at the top; a0 the weather's density.
double anvil_envelope(const LayerBlock& L, double w, double lo, double t, double& a0) {
  a0 = 0.0;
  const double s = (t - L.anvil_start) / std::max(1.0 - double(L.anvil_start), 1e-3);
  if (s <= 0.0) return 0.0;
  const double tall =
      std::max(1.0 - lo, double(L.filter_width)) * (1.0 - std::sqrt(1.0 - double(L.anvil_start)));
  const double la = lo + tall * (1.0 - L.anvil_spread * smoothstep(0.0, 0.7, s));
  a0 = clamp01((w - la) / L.filter_width);
  return a0 * smoothstep(0.0, 0.3, s) * (1.0 - smoothstep(0.88, 1.0, s));
}

// A camera-relative offset in the layer's stretched frame (density.glsl's clouds_stretched), and a
// point at height t in its streaked frame (clouds_streaked).
glm::dvec3 stretched(const LayerBlock& L, const glm::dvec3& v) {
  const glm::dvec3 axis(L.streak_axis);
  return v - axis * (glm::dot(v, axis) * (1.0 - 1.0 / double(L.streak)));
}
glm::dvec3 streaked(const LayerBlock& L, const glm::dvec3& x, double t) {
  return stretched(L, x + glm::dvec3(L.streak_axis) * (double(L.hook_m) * (1.0 - t) * (1.0 - t)));
}

}  // namespace

double CloudField::layer_density(const LayerBlock& L, const glm::dvec3& x, double h, bool detail) const {
  const glm::dvec3 wuv = glm::dvec3(L.weather_origin) + stretched(L, x) * double(L.weather_per_m);
  const int channel = int(L.weather_channel);
  const double w = sample(noise_.weather, noise_.weather_size, 4, channel, wuv);
  const double variation = sample(noise_.weather, noise_.weather_size, 4, 3, wuv);
  const double base = L.base_m + L.base_variation_m * (variation - 0.5) * 2.0;
  const double t = (h - base) / std::max(double(L.thickness_m), 1e-3);
  if (t <= 0.0 || t >= 1.0) return 0.0;
  const double fw = L.filter_width;
  const double c = coverage(L, x);
  if (c <= 0.0) return 0.0;
  const double lo = (1.0 - c) * (1.0 + fw) - fw;
  double d0 = clamp01((w - lo) / fw);
  // Domes: the top rises with the weather's strength over the threshold, rounded (density.glsl's
  // clouds_layer_top); the density falls toward it as 1 - u^k.
  double b = 0.0;
  if (d0 > 0.0) {
    const double strength = clamp01((w - lo) / std::max(1.0 - lo, fw));
    const double top = (1.0 - L.dome) + L.dome * std::max(1.0 - (1.0 - strength) * (1.0 - strength), 0.1);
    const double u = t / top;
    if (u < 1.0) b = d0 * smoothstep(0.0, 0.06, t) * (1.0 - std::pow(u, 6.0 + (2.0 - 6.0) * L.dome));
  }
  // The anvil under the ceiling (genera.h), which the noise hardly erodes.
  double anvil_weight = 0.0;
  if (L.anvil_start > 0.0f) {
    double a0 = 0.0;
    const double a = anvil_envelope(L, w, lo, t, a0);
    if (a > b) d0 = std::max(d0, a0);
    b = std::max(b, a);
    anvil_weight = b > 0.0 ? a / b : 0.0;
  }
  if (b <= 0.0) return 0.0;
  // A streaked layer reads the shape and detail noise in its own frame.
  const bool streaks = L.streak > 1.0f || L.hook_m != 0.0f;
  const glm::dvec3 shape_uvw =
      streaks ? glm::dvec3(L.streak_shape_origin) + streaked(L, x, t) * double(frame_.shape_per_m)
              : glm::dvec3(frame_.shape_origin) + x * double(frame_.shape_per_m);
  const double s = sample(noise_.shape, noise_.shape_size, 4, 0, shape_uvw);
  const double erosion =
      (1.0 - s) * L.shape_amount * 0.6 * (1.0 - 0.8 * anvil_weight);  // the shape noise is equalised
  double d = clamp01((b - erosion) / std::max(1.0 - erosion, 1e-3));
  if (detail && d > 0.0 && L.detail_amount > 0.0) {
    // Curl turbulence: the detail noise is read where the curl field (the shape volume's gba) moves
    // the point, in the lowest 30% of the layer, as far as the weather there holds cloud.
    const double k = double(frame_.turbulence_m) * d0 * clamp01(1.0 - t / 0.3);
    glm::dvec3 xd = x;
    if (k > 0.0)
      for (int a = 0; a < 3; ++a)
        xd[a] += k * (2.0 * sample(noise_.shape, noise_.shape_size, 4, 1 + a, shape_uvw) - 1.0);
    const glm::dvec3 detail_uvw =
        streaks ? glm::dvec3(L.streak_detail_origin) + streaked(L, xd, t) * double(frame_.detail_per_m)
                : glm::dvec3(frame_.detail_origin) + xd * double(frame_.detail_per_m);
    const double n = sample(noise_.detail, noise_.detail_size, 1, 0, detail_uvw);
    // Wisps at the base, billows above, as deep as the genus erodes.
    const double m = smoothstep(0.05, 0.35, t);
    const double e =
        (L.wisp * n * (1.0 - m) + L.billow * (1.0 - n) * m) * L.detail_amount * (1.0 - 0.6 * anvil_weight);
    d = clamp01((d - e) / std::max(1.0 - e, 1e-3));
  }
  // The density's rise inside the edge, and the layer's vertical profile.
  const double profile = clamp01(L.profile_exp_term * std::exp(L.profile_exponent * t) +
                                 L.profile_linear_term * t + L.profile_constant_term);
  return std::min(d * L.edge, 1.0) * profile * L.density_per_m;
}

double CloudField::extinction(const glm::dvec3& x, bool detail) const {
  const double h = altitude(x);
  if (h < frame_.lowest_m || h > frame_.highest_m) return 0.0;
  double sum = 0.0;
  for (const LayerBlock& L : layers_) sum += layer_density(L, x, h, detail);
  return sum * (double(frame_.scattering) + double(frame_.absorption));
}

double CloudField::majorant() const {
  double sum = 0.0;
  for (const LayerBlock& L : layers_) sum += L.density_per_m;
  return sum * (double(frame_.scattering) + double(frame_.absorption));
}

}  // namespace welkin::clouds
