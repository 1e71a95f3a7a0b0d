// The genera's own shapes (welkin/clouds/genera.h) through the CPU mirror of the field (the GPU's own
// noise, read back): cirrus streaks along its wind, a cumulonimbus spreads into an anvil under its
// ceiling, and the genera without either pack and compile exactly as before.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "clouds_test_support.h"
#include "density_field.h"
#include "validation/cloud_field.h"
#include "welkin/gfx/compute.h"

namespace welkin::clouds {
namespace {

using nlohmann::json;

struct Layer {
  test::Rendered rendered;
  std::unique_ptr<CloudField> field;
  LayerBlock block;
};

// One layer of `genus` at a base and thickness, the camera at the scene's origin on the ground.
Layer layer(const std::string& genus, double base_m, double thickness_m, double coverage, json wind) {
  json d = test::noon({{"temporal_upscaling", false},
                       {"weather_system_amount", 0.0},  // the coverage is the layer's everywhere
                       {"layers", json::array({{{"genus", genus},
                                                {"coverage", coverage},
                                                {"base_altitude_m", base_m},
                                                {"thickness_m", thickness_m},
                                                {"base_variation_m", 0},
                                                {"wind_mps", wind}}})}});
  Layer L{test::render(d, 8, 4), nullptr, {}};
  const CloudsGpu& gpu = L.rendered.world->resource<CloudsGpu>();
  L.field = std::make_unique<CloudField>(read_noise(gpu), gpu.block, gpu.layers);
  L.block = gpu.layers.at(0);
  return L;
}

// The correlation of the extinction at height h between points `lag` apart along `dir` (horizontal),
// over a grid of side 40 km around the camera.
double correlation(const CloudField& f, double h, const glm::dvec3& lag) {
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  int n = 0;
  for (int j = 0; j < 80; ++j)
    for (int i = 0; i < 80; ++i) {
      const glm::dvec3 x(-20000.0 + 500.0 * i + 17.0 * j, -20000.0 + 500.0 * j, h);
      const double a = f.extinction(x), b = f.extinction(x + lag);
      sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b, ++n;
    }
  const double ma = sa / n, mb = sb / n;
  const double va = saa / n - ma * ma, vb = sbb / n - mb * mb;
  return va > 0.0 && vb > 0.0 ? (sab / n - ma * mb) / std::sqrt(va * vb) : 0.0;
}

TEST(CloudsGenera, CirrusStreaksAlongItsWind) {
  const Layer ci = layer("cirrus", 8500.0, 800.0, 0.35, {25.0, 5.0});
  const GenusTraits& g = genus_traits(Genus::cirrus);
  const glm::dvec3 along = glm::normalize(glm::dvec3(25.0, 5.0, 0.0)), across(-along.y, along.x, 0.0);
  EXPECT_NEAR(glm::length(glm::dvec3(ci.block.streak_axis) - along), 0.0, 1e-6);
  EXPECT_EQ(ci.block.streak, g.streak);
  EXPECT_NEAR(ci.block.hook_m, g.hook_s * std::sqrt(25.0 * 25.0 + 5.0 * 5.0), 1e-2);
  // Two kilometres apart, the cloud along the wind is much the same, across it another one.
  const double h = 8500.0 + 0.5 * 800.0 - 100.0;  // camera-relative (the camera 100 m up)
  const double c_along = correlation(*ci.field, h, 2000.0 * along);
  const double c_across = correlation(*ci.field, h, 2000.0 * across);
  std::printf("cirrus: correlation 2 km along the wind %.3f, across %.3f\n", c_along, c_across);
  EXPECT_GT(c_along, 0.5);
  EXPECT_LT(c_across, 0.5 * c_along);

  // Without wind there is no direction to streak along: cirrus is then as round as any genus.
  const Layer still = layer("cirrus", 8500.0, 800.0, 0.35, {0.0, 0.0});
  EXPECT_EQ(glm::length(still.block.streak_axis), 0.0f);
  EXPECT_EQ(still.block.hook_m, 0.0f);
  // ... and it packs no stretch, so that its field compiles no streak code (an own shape and weather
  // fetch per sample: 12% of the peer scene's frame at `high`, whose cirrus has no wind).
  EXPECT_EQ(still.block.streak, 1.0f);
  EXPECT_EQ(field_defines(still.rendered.world->resource<CloudsGpu>()).at("CLOUDS_STREAKS"), "0");
  const double s_along = correlation(*still.field, h, 2000.0 * along);
  const double s_across = correlation(*still.field, h, 2000.0 * across);
  EXPECT_NEAR(s_along, s_across, 0.15);
}

// The covered fraction of the layer at height t (a fraction of its thickness), over a grid of side
// 120 km around the camera (the cumulonimbus's weather repeats every 100 km).
double covered(const Layer& L, double t) {
  int cloud = 0, n = 0;
  const double h = L.block.base_m + t * L.block.thickness_m - 100.0;
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 100; ++i, ++n)
      cloud += L.field->extinction({-60000.0 + 1200.0 * i + 31.0 * j, -60000.0 + 1200.0 * j, h}) > 0.0;
  return double(cloud) / n;
}

TEST(CloudsGenera, CumulonimbusSpreadsIntoAFlatAnvilUnderItsCeiling) {
  const Layer cb = layer("cumulonimbus", 1000.0, 9000.0, 0.35, {8.0, 0.0});
  const GenusTraits& g = genus_traits(Genus::cumulonimbus);
  EXPECT_EQ(cb.block.anvil_start, g.anvil_start);
  EXPECT_EQ(cb.block.anvil_spread, g.anvil_spread);
  EXPECT_EQ(cb.block.streak, 1.0f);  // no streaks: it reads the noise where every genus does
  // The towers thin out as they rise (the domes' tops); under the ceiling the tallest spread out
  // wider than the towers are anywhere below the anvil; at the ceiling the top is flat (nothing above).
  const double base = covered(cb, 0.2), below = covered(cb, 0.65), anvil = covered(cb, 0.92),
               top = covered(cb, 0.999);
  std::printf("cumulonimbus: covered at 20%% %.3f, 65%% %.3f, 92%% %.3f, 99.9%% %.3f\n", base, below, anvil,
              top);
  EXPECT_GT(base, 0.2);
  EXPECT_LT(below, base);
  EXPECT_GT(anvil, 1.5 * below);
  EXPECT_GT(anvil, base);
  EXPECT_LT(top, 0.02);
}

// The other genera have neither: their layers pack streak 1 and no anvil, and their field compiles
// no code for either (they read the noise exactly as before).
TEST(CloudsGenera, TheOtherGeneraCompileNeitherStreaksNorAnvils) {
  for (const GenusTraits& g : kGenera) {
    if (g.streak > 1.0f || g.hook_s > 0.0f || g.anvil_start > 0.0f) continue;
    const Layer L = layer(g.name, 2000.0, 800.0, 0.5, {10.0, 0.0});
    EXPECT_EQ(L.block.streak, 1.0f) << g.name;
    EXPECT_EQ(L.block.hook_m, 0.0f) << g.name;
    EXPECT_EQ(L.block.anvil_start, 0.0f) << g.name;
    const ShaderDefines d = field_defines(L.rendered.world->resource<CloudsGpu>());
    EXPECT_EQ(d.at("CLOUDS_STREAKS"), "0") << g.name;
    EXPECT_EQ(d.at("CLOUDS_ANVILS"), "0") << g.name;
  }
}

// The shader's field (density.glsl, compiled as the march compiles it) at camera-relative points.
std::vector<float> gpu_density(Layer& L, const std::vector<glm::vec4>& points) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "welkin-genera-probe";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "genera_probe.comp") << R"(
layout(local_size_x = 64) in;
#include "clouds/density.glsl"
layout(std430, binding = 5) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 6) writeonly buffer Values { float values[]; };
uniform int u_count;
void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= u_count) return;
  clouds_load();
  values[i] = clouds_density(points[i].xyz, true, false);
}
)";
  auto& rc = L.rendered.world->resource<RenderContext>();
  rc.shaders.add_search_dir(dir);
  const CloudsGpu& gpu = L.rendered.world->resource<CloudsGpu>();
  const Program& p = rc.shaders.compute("genera_probe.comp", field_defines(gpu));
  Buffer in(points.size() * sizeof(glm::vec4), points.data()), out(points.size() * sizeof(float));
  bind_field(gpu);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, in.id());
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, out.id());
  p.use();
  p.set("u_count", int(points.size()));
  dispatch_compute(p, group_count(int(points.size()), 64), 1);
  std::vector<float> v(points.size());
  glGetNamedBufferSubData(out.id(), 0, GLsizeiptr(v.size() * sizeof(float)), v.data());
  return v;
}

// The shader and its CPU mirror (what the path tracer marches) agree on the streaked and the anvil
// field: the same cloud at the same places, within the GPU's float and 8-bit filtering.
TEST(CloudsGenera, TheShaderAndTheCpuMirrorAgreeOnStreaksAndAnvils) {
  struct Case {
    const char* name;
    Layer L;
    double extent_m;
  };
  Case cases[] = {{"cirrus", layer("cirrus", 8500.0, 800.0, 0.35, {25.0, 5.0}), 20000.0},
                  {"cumulonimbus", layer("cumulonimbus", 1000.0, 9000.0, 0.35, {8.0, 0.0}), 60000.0}};
  for (Case& c : cases) {
    const LayerBlock& B = c.L.block;
    std::vector<glm::vec4> points;
    for (int k = 0; k < 4096; ++k) {
      const double t = 0.02 + 0.96 * ((k * 37) % 97) / 96.0;
      const double u = ((k * 61) % 128) / 128.0, v = ((k * 29) % 32 + (k / 128) / 32.0) / 32.0;
      points.push_back({float(c.extent_m * (2.0 * u - 1.0)), float(c.extent_m * (2.0 * v - 1.0)),
                        float(B.base_m + t * B.thickness_m - 100.0), 0.0f});
    }
    const std::vector<float> g = gpu_density(c.L, points);
    const FrameBlock& f = c.L.field->frame();
    const double per_density = 1.0 / (double(f.scattering) + double(f.absorption));
    int cloud_gpu = 0, cloud_cpu = 0, both = 0, far = 0;
    double diff = 0.0;
    for (size_t k = 0; k < points.size(); ++k) {
      const double cpu = c.L.field->extinction(glm::dvec3(points[k])) * per_density;
      cloud_gpu += g[k] > 0.0f, cloud_cpu += cpu > 0.0, both += g[k] > 0.0f && cpu > 0.0;
      const double e = std::abs(double(g[k]) - cpu) / B.density_per_m;
      diff += e, far += e > 0.05;
    }
    std::printf(
        "%s: cloud at %d points on the GPU, %d on the CPU, %d both; mean difference %.4f of the "
        "layer's density, %d points over 5%%\n",
        c.name, cloud_gpu, cloud_cpu, both, diff / points.size(), far);
    EXPECT_GT(cloud_cpu, 200);
    EXPECT_GT(both, 0.95 * std::max(cloud_gpu, cloud_cpu));
    EXPECT_LT(diff / points.size(), 0.005);
    EXPECT_LT(far, int(points.size()) / 100);
  }
}

}  // namespace
}  // namespace welkin::clouds
