// welkin-terrain-gen: the sample valley terrain, generated procedurally and written as Draco .glb.
//
//   welkin-terrain-gen --seed 1 --out assets/terrain/valley.glb [--report valley.json] [--preview top.png]
//
// Frames. The engine's world frame is x east, y north, z up, metres, origin at the runway centre.
// glTF is y-up, so the file stores glTF (X, Y, Z) = (east, up, south) = (x, z, -y); a loader maps back
// with x = X, y = -Z, z = Y (a +90 degree rotation about the x axis, no scale). Texture v grows
// southward, so the top row of each image is the north edge.
//
// Content: a 40 x 40 km tile (|x|, |y| <= 20 km) on a grid that is densest at the runway (~12 m) and
// coarsest at the edges (~94 m), with a skirt along its border; a coarse ring from 20 to 60 km for the
// distant mountains; a flat 3 km x 60 m runway strip along x (heading 090) with an apron to its north;
// a few box buildings. Heights: ridged multifractal noise under a mountain envelope that rises with
// distance from the valley axis (2-3 km peaks in the ring), domain-warped, then droplet hydraulic
// erosion and a thermal (talus) pass on a raster of the tile. Same seed and same binary: same bytes
// (single-threaded, integer hashing for randomness, no clocks).
#include <stb_image_write.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "welkin/assets/glb_writer.h"
#include "welkin/core/error.h"
#include "welkin/gfx/image.h"
#include "welkin/scene/scene_file.h"

namespace {

using welkin::assets::DracoSettings;
using welkin::assets::GlbWriter;
using welkin::assets::MeshData;

constexpr double kTileHalf = 20000.0;  // m
constexpr double kRingHalf = 60000.0;
constexpr double kRunwayHalfLength = 1500.0, kRunwayHalfWidth = 30.0;
// Flat zone: the runway with margins and an apron to the north for the buildings.
constexpr double kFlatX = 1700.0, kFlatSouth = -90.0, kFlatNorth = 450.0, kFlatBlend = 500.0;

// --- Deterministic noise -------------------------------------------------------------------------

uint32_t hash3(int32_t x, int32_t y, uint32_t seed) {
  uint32_t h = seed * 0x9E3779B9u ^ uint32_t(x) * 0x85EBCA6Bu ^ uint32_t(y) * 0xC2B2AE35u;
  h ^= h >> 16;
  h *= 0x7FEB352Du;
  h ^= h >> 15;
  h *= 0x846CA68Bu;
  h ^= h >> 16;
  return h;
}

double smooth(double t) {
  return t * t * t * (t * (t * 6 - 15) + 10);
}

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// 256 unit gradient directions; a table keeps the noise cheap (it is evaluated ~10^8 times).
struct Gradients {
  double g[256][2];
  Gradients() {
    for (int k = 0; k < 256; ++k)
      g[k][0] = std::cos(k * 6.283185307179586 / 256), g[k][1] = std::sin(k * 6.283185307179586 / 256);
  }
};
const Gradients kGradients;

// 2D gradient noise in about [-1, 1].
double gradient_noise(double x, double y, uint32_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const int32_t ix = int32_t(fx), iy = int32_t(fy);
  const double tx = x - fx, ty = y - fy;
  auto corner = [&](int dx, int dy) {
    const double* g = kGradients.g[hash3(ix + dx, iy + dy, seed) & 255];
    return g[0] * (tx - dx) + g[1] * (ty - dy);
  };
  const double u = smooth(tx), v = smooth(ty);
  const double a = corner(0, 0) + u * (corner(1, 0) - corner(0, 0));
  const double b = corner(0, 1) + u * (corner(1, 1) - corner(0, 1));
  return 1.4 * (a + v * (b - a));
}

double fbm(double x, double y, uint32_t seed, int octaves) {
  double sum = 0, amp = 0.5;
  for (int i = 0; i < octaves; ++i, x *= 2.03, y *= 2.03, amp *= 0.5)
    sum += amp * gradient_noise(x, y, seed + i);
  return sum;
}

// Musgrave's ridged multifractal: sharp crests, smooth valleys; about [0, 1]. Each octave is rotated
// so that no lattice line (where gradient noise can cross zero along a straight segment) lines up
// across octaves or with the axes.
double ridged(double x, double y, uint32_t seed, int octaves) {
  constexpr double c = 0.8090169943749475, s = 0.5877852522924731;  // 36 degrees
  double px = x * c - y * s + 0.37, py = x * s + y * c + 0.71;
  double signal = 1.0 - std::abs(gradient_noise(px, py, seed));
  signal *= signal;
  double result = signal, weight = 1.0, amp = 1.0;
  for (int i = 1; i < octaves; ++i) {
    const double nx = (px * c - py * s) * 2.0 + 0.13 * i, ny = (px * s + py * c) * 2.0 + 0.29 * i;
    px = nx, py = ny;
    amp *= 0.5;
    weight = std::clamp(signal * 2.0, 0.0, 1.0);
    signal = 1.0 - std::abs(gradient_noise(px, py, seed + 17 * i));
    signal *= signal * weight;
    result += signal * amp;
  }
  return result / 1.6;
}

// --- Terrain ----------------------------------------------------------------------------------------

class Terrain {
 public:
  explicit Terrain(uint32_t seed) : seed_(seed) { runway_height_ = std::round(natural(0.0, 0.0)); }

  double runway_height() const { return runway_height_; }

  // Valley axis: straight along the runway, meandering farther out.
  double axis(double x) const {
    return 900.0 * std::sin(x / 7300.0 + 0.3 * seed_) * smoothstep(2500, 9000, std::abs(x));
  }

  double natural(double x, double y) const {
    const double wx = x + 1800.0 * fbm(x / 11000.0, y / 11000.0, seed_ + 101, 4);
    const double wy = y + 1800.0 * fbm(x / 11000.0 + 5.2, y / 11000.0 + 1.3, seed_ + 202, 4);
    const double dv = std::abs(y - axis(x));
    const double re = std::sqrt((x / 2.2) * (x / 2.2) + dv * dv);
    const double envelope = 2200.0 * smoothstep(2000.0, 24000.0, re);
    const double floor =
        160.0 + 0.006 * std::min(std::abs(x), 20000.0) + 35.0 * fbm(x / 5000.0, y / 5000.0, seed_ + 303, 3);
    const double hills =
        110.0 * (0.5 + 0.5 * fbm(x / 2600.0, y / 2600.0, seed_ + 404, 5)) * smoothstep(2500.0, 7000.0, re);
    return floor + hills + envelope * (0.25 + 0.8 * ridged(wx / 15000.0, wy / 15000.0, seed_ + 505, 8));
  }

  // 1 inside the flat zone, falling to 0 over kFlatBlend outside it.
  static double flat_weight(double x, double y) {
    const double dx = std::max(std::abs(x) - kFlatX, 0.0);
    const double dy = std::max({kFlatSouth - y, y - kFlatNorth, 0.0});
    return 1.0 - smoothstep(0.0, kFlatBlend, std::sqrt(dx * dx + dy * dy));
  }

  double flattened(double x, double y) const {
    const double w = flat_weight(x, y);
    return w >= 1.0 ? runway_height_ : natural(x, y) * (1 - w) + runway_height_ * w;
  }

 private:
  uint32_t seed_;
  double runway_height_ = 0;
};

// A square raster over the tile: heights after erosion, sampled bilinearly.
struct Raster {
  int n = 0;        // samples per side
  double cell = 0;  // metres between samples
  std::vector<float> h;
  float& at(int i, int j) { return h[size_t(j) * n + i]; }
  float at(int i, int j) const { return h[size_t(j) * n + i]; }
  double world_x(int i) const { return -kTileHalf + i * cell; }
  double world_y(int j) const { return -kTileHalf + j * cell; }
  double sample(double x, double y) const {
    const double fx = std::clamp((x + kTileHalf) / cell, 0.0, n - 1.0001);
    const double fy = std::clamp((y + kTileHalf) / cell, 0.0, n - 1.0001);
    const int i = int(fx), j = int(fy);
    const double tx = fx - i, ty = fy - j;
    return (at(i, j) * (1 - tx) + at(i + 1, j) * tx) * (1 - ty) +
           (at(i, j + 1) * (1 - tx) + at(i + 1, j + 1) * tx) * ty;
  }
};

// Droplet erosion (after H. Beyer, 2015) on heights measured in cells, so slopes are unitless.
void hydraulic_erosion(Raster& r, uint32_t seed, int droplets) {
  const int n = r.n;
  std::vector<float> hc(r.h.size());
  for (size_t k = 0; k < hc.size(); ++k) hc[k] = float(r.h[k] / r.cell);
  auto H = [&](int i, int j) -> float& { return hc[size_t(j) * n + i]; };
  constexpr int kRadius = 2;
  std::vector<std::pair<int, float>> brush;  // offsets and weights of the erosion brush
  float wsum = 0;
  for (int dj = -kRadius; dj <= kRadius; ++dj)
    for (int di = -kRadius; di <= kRadius; ++di) {
      const float d = std::sqrt(float(di * di + dj * dj));
      if (d <= kRadius) {
        brush.emplace_back(dj * n + di, kRadius - d + 0.5f);
        wsum += kRadius - d + 0.5f;
      }
    }
  for (auto& b : brush) b.second /= wsum;
  const float inertia = 0.05f, capacity_factor = 4.0f, min_capacity = 0.01f, deposit_rate = 0.3f,
              erode_rate = 0.5f, evaporate = 0.015f, gravity = 4.0f;
  for (int d = 0; d < droplets; ++d) {
    const uint32_t h1 = hash3(d, 1, seed), h2 = hash3(d, 2, seed);
    float px = 2.0f + (h1 % 100000u) / 100000.0f * (n - 5), py = 2.0f + (h2 % 100000u) / 100000.0f * (n - 5);
    float dx = 0, dy = 0, speed = 1, water = 1, sediment = 0;
    for (int step = 0; step < 96; ++step) {
      const int i = int(px), j = int(py);
      const float tx = px - i, ty = py - j;
      const float h00 = H(i, j), h10 = H(i + 1, j), h01 = H(i, j + 1), h11 = H(i + 1, j + 1);
      const float gx = (h10 - h00) * (1 - ty) + (h11 - h01) * ty;
      const float gy = (h01 - h00) * (1 - tx) + (h11 - h10) * tx;
      const float height =
          h00 * (1 - tx) * (1 - ty) + h10 * tx * (1 - ty) + h01 * (1 - tx) * ty + h11 * tx * ty;
      dx = dx * inertia - gx * (1 - inertia);
      dy = dy * inertia - gy * (1 - inertia);
      const float len = std::sqrt(dx * dx + dy * dy);
      if (len < 1e-9f) break;
      dx /= len, dy /= len;
      px += dx, py += dy;
      if (px < kRadius + 1 || py < kRadius + 1 || px >= n - kRadius - 2 || py >= n - kRadius - 2) break;
      const int ni = int(px), nj = int(py);
      const float ntx = px - ni, nty = py - nj;
      const float nh = H(ni, nj) * (1 - ntx) * (1 - nty) + H(ni + 1, nj) * ntx * (1 - nty) +
                       H(ni, nj + 1) * (1 - ntx) * nty + H(ni + 1, nj + 1) * ntx * nty;
      const float dh = nh - height;
      const float capacity = std::max(-dh * speed * water * capacity_factor, min_capacity);
      if (sediment > capacity || dh > 0) {
        const float amount = dh > 0 ? std::min(dh, sediment) : (sediment - capacity) * deposit_rate;
        sediment -= amount;
        H(i, j) += amount * (1 - tx) * (1 - ty);
        H(i + 1, j) += amount * tx * (1 - ty);
        H(i, j + 1) += amount * (1 - tx) * ty;
        H(i + 1, j + 1) += amount * tx * ty;
      } else {
        const float amount = std::min((capacity - sediment) * erode_rate, -dh);
        const size_t c = size_t(j) * n + i;
        for (const auto& [off, w] : brush) {
          float& cellh = hc[size_t(int64_t(c) + off)];
          const float take = std::min(cellh, amount * w);
          cellh -= take;
          sediment += take;
        }
      }
      speed = std::sqrt(std::max(speed * speed + dh * gravity, 0.0f));
      water *= 1 - evaporate;
    }
  }
  for (size_t k = 0; k < hc.size(); ++k) r.h[k] = float(hc[k] * r.cell);
}

// Material slides wherever a slope exceeds the talus angle (screes under cliffs).
void thermal_erosion(Raster& r, int iterations, double talus) {
  const int n = r.n;
  const float limit = float(talus * r.cell);
  for (int it = 0; it < iterations; ++it)
    for (int j = 1; j < n - 1; ++j)
      for (int i = 1; i < n - 1; ++i) {
        float& h = r.at(i, j);
        for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
          float& o = r.at(i + di, j + dj);
          const float diff = h - o - limit;
          if (diff > 0) {
            h -= diff * 0.25f;
            o += diff * 0.25f;
          }
        }
      }
}

// --- Output -----------------------------------------------------------------------------------------

struct Rgb {
  double r, g, b;
};
Rgb mix(Rgb a, Rgb b, double t) {
  return {a.r + (b.r - a.r) * t, a.g + (b.g - a.g) * t, a.b + (b.b - a.b) * t};
}

// Albedo (linear) from height, slope (rise over run) and noise: grass, forest, rock, scree, snow.
Rgb ground_colour(double h, double slope, double n1, double n2, double erosion) {
  const Rgb grass{0.105, 0.16, 0.045}, dry{0.20, 0.19, 0.09}, forest{0.045, 0.075, 0.03},
      rock{0.21, 0.19, 0.17}, dark_rock{0.10, 0.095, 0.09}, snow{0.80, 0.82, 0.85}, silt{0.17, 0.15, 0.11};
  Rgb c = mix(grass, dry, std::clamp(0.5 + 0.8 * n1, 0.0, 1.0));
  c = mix(c, forest,
          smoothstep(0.05, 0.35, n2) * (1 - smoothstep(1100, 1700, h)) * smoothstep(0.08, 0.2, slope));
  c = mix(c, silt, std::clamp(erosion * 0.08, 0.0, 0.7));  // deposits along eroded channels
  c = mix(c, mix(rock, dark_rock, std::clamp(0.5 + n1, 0.0, 1.0)), smoothstep(0.45, 0.75, slope + 0.1 * n2));
  const double snowline = 2050 + 180 * n1;
  c = mix(c, snow, smoothstep(snowline, snowline + 250, h) * (1 - smoothstep(0.7, 1.0, slope)));
  return c;
}

uint8_t srgb(double linear) {
  return welkin::linear_to_srgb8(float(std::clamp(linear, 0.0, 1.0)));
}

std::vector<uint8_t> encode_jpeg(const std::vector<uint8_t>& rgb, int w, int h, int quality) {
  std::vector<uint8_t> out;
  stbi_write_jpg_to_func(
      [](void* ctx, void* data, int size) {
        auto* v = static_cast<std::vector<uint8_t>*>(ctx);
        v->insert(v->end(), static_cast<uint8_t*>(data), static_cast<uint8_t*>(data) + size);
      },
      &out, w, h, 3, rgb.data(), quality);
  if (out.empty()) throw welkin::Error("JPEG encoding failed");
  return out;
}

// Grid coordinate with spacing growing from the centre: s(u) = half (a u + (1 - a) u^3), u in [-1, 1].
double stretched(double u, double half) {
  constexpr double a = 0.3;
  return half * (a * u + (1 - a) * u * u * u);
}

glm::vec3 to_gltf(double x, double y, double z) {
  return glm::vec3(float(x), float(z), float(-y));
}

struct Options {
  uint32_t seed = 1;
  std::string out = "assets/terrain/valley.glb";
  std::string report;
  std::string preview;
  int grid = 1024;     // tile cells per side
  int texture = 4096;  // tile base colour size (~10 m per texel)
  int raster = 1024;   // erosion raster cells per side
  int droplets = 700000;
  bool quick = false;
};

int run(Options o) {
  if (o.quick) o.grid = 256, o.texture = 512, o.raster = 256, o.droplets = std::min(o.droplets, 15000);
  Terrain terrain(o.seed);
  std::fprintf(stderr, "terrain: seed %u, raster %d^2 ...\n", o.seed, o.raster + 1);

  // Raster of the tile: analytic heights, eroded; erosion fades out at the border (so the ring meets
  // the tile) and inside the flat zone (the runway stays flat).
  Raster base;
  base.n = o.raster + 1;
  base.cell = 2 * kTileHalf / o.raster;
  base.h.resize(size_t(base.n) * base.n);
  for (int j = 0; j < base.n; ++j)
    for (int i = 0; i < base.n; ++i) base.at(i, j) = float(terrain.natural(base.world_x(i), base.world_y(j)));
  Raster eroded = base;
  std::fprintf(stderr, "terrain: %d erosion droplets ...\n", o.droplets);
  hydraulic_erosion(eroded, o.seed + 7, o.droplets);
  if (o.droplets > 0) thermal_erosion(eroded, 8, 0.9);
  Raster delta = base;
  double carved = 0, deposited = 0;
  for (size_t k = 0; k < delta.h.size(); ++k) {
    delta.h[k] = eroded.h[k] - base.h[k];
    carved = std::min(carved, double(delta.h[k])), deposited = std::max(deposited, double(delta.h[k]));
  }
  auto height = [&](double x, double y) {
    const double border = std::min(kTileHalf - std::abs(x), kTileHalf - std::abs(y));
    const double fade = smoothstep(0.0, 1500.0, border) * (1.0 - Terrain::flat_weight(x, y));
    return terrain.flattened(x, y) + (fade > 0 ? fade * delta.sample(x, y) : 0.0);
  };

  GlbWriter w;
  DracoSettings draco{.enabled = true, .position_bits = 16, .normal_bits = 10, .uv_bits = 14, .speed = 0};
  welkin::assets::Sampler clamp{.mag_filter = 9729, .min_filter = 9987, .wrap_s = 33071, .wrap_t = 33071};

  // Tile base colour from a height raster at texture resolution.
  std::fprintf(stderr, "terrain: %d^2 texture ...\n", o.texture);
  const int T = o.texture;
  const double texel = 2 * kTileHalf / T;
  std::vector<float> th(size_t(T + 2) * (T + 2));
  for (int j = 0; j < T + 2; ++j)
    for (int i = 0; i < T + 2; ++i)
      th[size_t(j) * (T + 2) + i] =
          float(height(-kTileHalf + (i - 0.5) * texel, kTileHalf - (j - 0.5) * texel));
  std::vector<uint8_t> rgb(size_t(T) * T * 3);
  double max_height = -1e9, min_height = 1e9;
  for (int j = 0; j < T; ++j)
    for (int i = 0; i < T; ++i) {
      const double x = -kTileHalf + (i + 0.5) * texel, y = kTileHalf - (j + 0.5) * texel;
      auto at = [&](int a, int b) { return double(th[size_t(j + 1 + b) * (T + 2) + (i + 1 + a)]); };
      const double h = at(0, 0);
      max_height = std::max(max_height, h), min_height = std::min(min_height, h);
      const double sx = (at(1, 0) - at(-1, 0)) / (2 * texel), sy = (at(0, 1) - at(0, -1)) / (2 * texel);
      const double slope = std::sqrt(sx * sx + sy * sy);
      const double n1 = fbm(x / 900.0, y / 900.0, o.seed + 606, 5),
                   n2 = fbm(x / 2500.0, y / 2500.0, o.seed + 707, 4);
      Rgb c = ground_colour(h, slope, n1, n2, std::max(0.0, double(delta.sample(x, y))) / 10.0);
      const double rw =
          std::max(std::abs(x) - kRunwayHalfLength, 0.0) + std::max(std::abs(y) - kRunwayHalfWidth, 0.0);
      if (rw < texel) c = mix(c, Rgb{0.06, 0.06, 0.065}, 1 - rw / texel);  // asphalt
      uint8_t* p = &rgb[(size_t(j) * T + i) * 3];
      p[0] = srgb(c.r), p[1] = srgb(c.g), p[2] = srgb(c.b);
    }
  const int tile_image = w.add_image(encode_jpeg(rgb, T, T, 88), "image/jpeg", "valley_base_color");
  welkin::assets::Material tile_mat;
  tile_mat.name = "valley_ground";
  tile_mat.roughness_factor = 0.95f;
  tile_mat.metallic_factor = 0.0f;
  tile_mat.base_color.texture = w.add_texture(tile_image, clamp);
  const int tile_material = w.add_material(tile_mat);

  // Tile mesh: stretched grid plus a 300 m skirt along the border hiding seams with the ring.
  std::fprintf(stderr, "terrain: %d^2 tile grid ...\n", o.grid + 1);
  MeshData tile;
  tile.name = "valley_tile";
  tile.material = tile_material;
  const int G = o.grid;
  std::vector<double> coord(size_t(G) + 1);
  for (int k = 0; k <= G; ++k) coord[size_t(k)] = stretched(-1.0 + 2.0 * k / G, kTileHalf);
  auto uv = [](double x, double y, double half) {
    return glm::vec2(float((x + half) / (2 * half)), float((half - y) / (2 * half)));
  };
  for (int j = 0; j <= G; ++j)
    for (int i = 0; i <= G; ++i) {
      const double x = coord[size_t(i)], y = coord[size_t(j)];
      tile.positions.push_back(to_gltf(x, y, height(x, y)));
      tile.uv0.push_back(uv(x, y, kTileHalf));
    }
  for (int j = 0; j < G; ++j)
    for (int i = 0; i < G; ++i) {
      const uint32_t a = uint32_t(j * (G + 1) + i), b = a + 1, c = a + uint32_t(G + 1), d = c + 1;
      tile.indices.insert(tile.indices.end(), {a, b, c, b, d, c});
    }
  std::vector<uint32_t> ring_loop;  // border vertices, counter-clockwise from above
  for (int i = 0; i < G; ++i) ring_loop.push_back(uint32_t(i));
  for (int j = 0; j < G; ++j) ring_loop.push_back(uint32_t(j * (G + 1) + G));
  for (int i = G; i > 0; --i) ring_loop.push_back(uint32_t(G * (G + 1) + i));
  for (int j = G; j > 0; --j) ring_loop.push_back(uint32_t(j * (G + 1)));
  const uint32_t skirt0 = uint32_t(tile.positions.size());
  for (uint32_t v : ring_loop) {
    glm::vec3 p = tile.positions[v];
    p.y -= 300.0f;
    tile.positions.push_back(p);
    tile.uv0.push_back(tile.uv0[v]);
  }
  for (size_t k = 0; k < ring_loop.size(); ++k) {
    const uint32_t a = ring_loop[k], b = ring_loop[(k + 1) % ring_loop.size()];
    const uint32_t a2 = skirt0 + uint32_t(k), b2 = skirt0 + uint32_t((k + 1) % ring_loop.size());
    const glm::vec3 n =
        glm::cross(tile.positions[b] - tile.positions[a], tile.positions[a2] - tile.positions[a]);
    const glm::vec3 out(tile.positions[a].x, 0.0f, tile.positions[a].z);
    if (glm::dot(n, out) >= 0)
      tile.indices.insert(tile.indices.end(), {a, b, a2, b, b2, a2});
    else
      tile.indices.insert(tile.indices.end(), {a, a2, b, b, a2, b2});
  }

  // Ring: 1 km grid from 20 to 60 km, analytic heights (no erosion at this scale), own small texture.
  std::fprintf(stderr, "terrain: horizon ring ...\n");
  const int R = o.quick ? 60 : 120;
  const double rc = 2 * kRingHalf / R;
  MeshData ring;
  ring.name = "horizon_ring";
  std::vector<int> ring_index(size_t(R + 1) * (R + 1), -1);
  auto ring_vertex = [&](int i, int j) {
    int& slot = ring_index[size_t(j) * (R + 1) + i];
    if (slot < 0) {
      const double x = -kRingHalf + i * rc, y = -kRingHalf + j * rc;
      slot = int(ring.positions.size());
      ring.positions.push_back(to_gltf(x, y, terrain.natural(x, y)));
      ring.uv0.push_back(uv(x, y, kRingHalf));
    }
    return uint32_t(slot);
  };
  for (int j = 0; j < R; ++j)
    for (int i = 0; i < R; ++i) {
      const double cx = -kRingHalf + (i + 0.5) * rc, cy = -kRingHalf + (j + 0.5) * rc;
      if (std::abs(cx) < kTileHalf && std::abs(cy) < kTileHalf) continue;
      const uint32_t a = ring_vertex(i, j), b = ring_vertex(i + 1, j), c = ring_vertex(i, j + 1),
                     d = ring_vertex(i + 1, j + 1);
      ring.indices.insert(ring.indices.end(), {a, b, c, b, d, c});
    }
  const int RT = o.quick ? 256 : 1024;
  std::vector<uint8_t> ring_rgb(size_t(RT) * RT * 3);
  const double rtexel = 2 * kRingHalf / RT;
  for (int j = 0; j < RT; ++j)
    for (int i = 0; i < RT; ++i) {
      const double x = -kRingHalf + (i + 0.5) * rtexel, y = kRingHalf - (j + 0.5) * rtexel;
      const double h = terrain.natural(x, y);
      const double sx = (terrain.natural(x + rtexel, y) - terrain.natural(x - rtexel, y)) / (2 * rtexel);
      const double sy = (terrain.natural(x, y + rtexel) - terrain.natural(x, y - rtexel)) / (2 * rtexel);
      const Rgb c =
          ground_colour(h, std::sqrt(sx * sx + sy * sy), fbm(x / 3000.0, y / 3000.0, o.seed + 606, 3),
                        fbm(x / 6000.0, y / 6000.0, o.seed + 707, 3), 0.0);
      uint8_t* p = &ring_rgb[(size_t(j) * RT + i) * 3];
      p[0] = srgb(c.r), p[1] = srgb(c.g), p[2] = srgb(c.b);
    }
  welkin::assets::Material ring_mat = tile_mat;
  ring_mat.name = "horizon_ground";
  ring_mat.base_color.texture = w.add_texture(
      w.add_image(encode_jpeg(ring_rgb, RT, RT, 85), "image/jpeg", "horizon_base_color"), clamp);
  ring.material = w.add_material(ring_mat);

  // Runway surface (0.3 m above the flat strip) and box buildings on the apron north of it.
  const double z0 = terrain.runway_height();
  MeshData built;
  built.name = "runway_and_buildings";
  auto box = [&](double cx, double cy, double sx, double sy, double sz, double base) {
    const glm::vec3 c0 = to_gltf(cx - sx / 2, cy - sy / 2, base),
                    c1 = to_gltf(cx + sx / 2, cy + sy / 2, base + sz);
    const glm::vec3 lo = glm::min(c0, c1), hi = glm::max(c0, c1);
    const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const glm::vec3& n : normals) {
      if (sz < 1.0 && n.y < 0.5f) continue;  // flat slab (the runway): top face only
      const int axis = n.x != 0 ? 0 : n.y != 0 ? 1 : 2;
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const uint32_t s = uint32_t(built.positions.size());
      for (int k = 0; k < 4; ++k) {
        glm::vec3 p;
        p[axis] = n[axis] > 0 ? hi[axis] : lo[axis];
        p[u] = (k == 1 || k == 2) ? hi[u] : lo[u];
        p[v] = (k >= 2) ? hi[v] : lo[v];
        built.positions.push_back(p);
        built.normals.push_back(n);
        built.uv0.emplace_back(float(k == 1 || k == 2), float(k >= 2));
      }
      const glm::vec3 fn = glm::cross(built.positions[s + 1] - built.positions[s],
                                      built.positions[s + 2] - built.positions[s]);
      if (glm::dot(fn, n) > 0)
        built.indices.insert(built.indices.end(), {s, s + 1, s + 2, s, s + 2, s + 3});
      else
        built.indices.insert(built.indices.end(), {s, s + 2, s + 1, s, s + 3, s + 2});
    }
  };
  box(0, 0, 2 * kRunwayHalfLength, 2 * kRunwayHalfWidth, 0.3, z0);
  box(-600, 210, 70, 45, 16, z0);  // hangars
  box(-500, 210, 70, 45, 16, z0);
  box(-350, 230, 110, 28, 11, z0);                                                   // terminal
  box(-240, 200, 9, 9, 32, z0);                                                      // control tower
  box(-150, 260, 40, 25, 8, z0);                                                     // fire station
  for (int k = 0; k < 6; ++k) box(250 + 70 * k, 320 + 20 * (k % 2), 18, 12, 7, z0);  // houses
  welkin::assets::Material built_mat;
  built_mat.name = "concrete";
  built_mat.base_color_factor = {0.32f, 0.31f, 0.30f, 1.0f};
  built_mat.roughness_factor = 0.85f;
  built_mat.metallic_factor = 0.0f;
  built.material = w.add_material(built_mat);

  std::fprintf(stderr, "terrain: Draco encoding ...\n");
  const auto wt = w.add_mesh(tile, draco);
  const auto wr = w.add_mesh(ring, DracoSettings{.enabled = true, .position_bits = 14, .uv_bits = 12});
  const auto wb =
      w.add_mesh(built, DracoSettings{.enabled = true, .position_bits = 16, .normal_bits = 8, .uv_bits = 8});
  const int root = w.add_node("valley", -1);
  w.add_node("valley_tile", wt.mesh, glm::vec3(0.0f), glm::quat(1.0f, 0.0f, 0.0f, 0.0f), glm::vec3(1.0f),
             root);
  w.add_node("horizon_ring", wr.mesh, glm::vec3(0.0f), glm::quat(1.0f, 0.0f, 0.0f, 0.0f), glm::vec3(1.0f),
             root);
  w.add_node("runway_and_buildings", wb.mesh, glm::vec3(0.0f), glm::quat(1.0f, 0.0f, 0.0f, 0.0f),
             glm::vec3(1.0f), root);
  nlohmann::json extras = {
      {"generator", "welkin-terrain-gen"},
      {"seed", o.seed},
      {"frame",
       "glTF X = east, Y = up, Z = south; engine (x, y, z) = (X, -Z, Y); metres; origin = runway centre"},
      {"runway",
       {{"centre", {0, 0, z0}},
        {"length_m", 2 * kRunwayHalfLength},
        {"width_m", 2 * kRunwayHalfWidth},
        {"heading_deg", 90},
        {"elevation_m", z0}}},
      {"tile_half_extent_m", kTileHalf},
      {"ring_half_extent_m", kRingHalf}};
  w.document()["asset"]["extras"] = extras;
  const std::string bytes = w.glb();
  welkin::write_file_atomically(o.out, bytes);

  nlohmann::json report = {{"file", o.out},
                           {"seed", o.seed},
                           {"bytes", bytes.size()},
                           {"runway_elevation_m", z0},
                           {"tile_height_range_m", {min_height, max_height}},
                           {"erosion_range_m", {carved, deposited}},
                           {"meshes", nlohmann::json::array()},
                           {"images",
                            {{{"name", "valley_base_color"}, {"width", T}, {"height", T}},
                             {{"name", "horizon_base_color"}, {"width", RT}, {"height", RT}}}}};
  uint64_t vertices = 0, triangles = 0;
  for (const auto& [name, m] :
       {std::pair{"valley_tile", wt}, {"horizon_ring", wr}, {"runway_and_buildings", wb}}) {
    report["meshes"].push_back(
        {{"name", name}, {"vertices", m.vertices}, {"triangles", m.triangles}, {"draco_bytes", m.bytes}});
    vertices += m.vertices, triangles += m.triangles;
  }
  report["vertices"] = vertices;
  report["triangles"] = triangles;
  if (!o.report.empty()) welkin::write_file_atomically(o.report, report.dump(2) + "\n");
  std::printf("%s\n", report.dump(2).c_str());

  if (!o.preview.empty()) {  // top-down hillshade of the tile (north up), for eyeballing
    const int P = 1024;
    welkin::ImageU8 img;
    img.width = img.height = P;
    img.rgba.resize(size_t(P) * P * 4);
    const double step = 2 * kTileHalf / P;
    for (int j = 0; j < P; ++j)
      for (int i = 0; i < P; ++i) {
        const double x = -kTileHalf + (i + 0.5) * step, y = kTileHalf - (j + 0.5) * step;
        const double h = height(x, y);
        const double sx = (height(x + step, y) - h) / step, sy = (height(x, y + step) - h) / step;
        const glm::dvec3 n = glm::normalize(glm::dvec3(-sx, -sy, 1.0));
        const double shade = std::clamp(glm::dot(n, glm::normalize(glm::dvec3(-1, 1, 1.2))), 0.0, 1.0);
        // The base colour texture (sRGB), lit by the hillshade.
        const uint8_t* c = &rgb[(size_t(j * T / P) * T + size_t(i * T / P)) * 3];
        uint8_t* p = &img.rgba[(size_t(j) * P + i) * 4];
        for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::min(255.0, c[k] * (0.35 + 0.9 * shade)));
        p[3] = 255;
      }
    welkin::write_png(o.preview, img);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Generate the sample valley terrain as a Draco-compressed glTF (.glb)"};
  Options o;
  app.add_option("--seed", o.seed, "Random seed; the same seed gives the same bytes")->capture_default_str();
  app.add_option("--out", o.out, "Output .glb (written atomically)")->capture_default_str();
  app.add_option("--report", o.report, "Also write the counts as JSON here");
  app.add_option("--preview", o.preview, "Also write a top-down hillshade PNG of the tile here");
  app.add_flag("--quick", o.quick, "Low resolution, for tests");
  app.add_option("--droplets", o.droplets, "Hydraulic erosion droplets (0 disables erosion)")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const welkin::Error& e) {
    std::fprintf(stderr, "welkin-terrain-gen: %s\n", e.what());
    return 1;
  }
}
