// Rendering with the atmosphere: every material the engine draws gets aerial perspective, and the
// sample terrain renders with the module's PBR material.
#include <unistd.h>

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>

#include "cache_folder.h"
#include "depth_readback.h"
#include "terrain_gpu.h"
#include "welkin/assets/glb_writer.h"
#include "welkin/assets/gltf_loader.h"
#include "welkin/core/world.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"
#include "golden.h"
#include "scratch_folder.h"

namespace welkin::modules {
const ModuleDefinition& atmosphere_module();
const ModuleDefinition& terrain_module();
const ModuleDefinition& timeofday_module();
const ModuleDefinition& clouds_module();
}  // namespace welkin::modules

namespace {

using namespace welkin;
using nlohmann::json;

class TerrainRender : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { gl_ = create_headless_context().release(); }
  static void TearDownTestSuite() { delete gl_; }
  static GlContext* gl_;
};
GlContext* TerrainRender::gl_ = nullptr;

json atmosphere_preset(const std::string& name) {
  return read_json_file(WELKIN_SOURCE_DIR "/modules/atmosphere/presets/" + name + ".json");
}

// Linear radiance at the image centre looking north along the horizon, with or without a grey box
// `distance_m` away that fills the centre (its size grows with distance: same pixels every time).
glm::vec3 centre_radiance(const json& atmosphere, double distance_m, bool with_box) {
  World world;
  world.modules().add_static(modules::atmosphere_module());
  json ents = json::array({
      json{{"components", {{"core.Camera", {{"position_m", {0, 0, 2}}, {"heading_deg", 0}, {"pitch_deg", 0}, {"vertical_fov_deg", 30}}}}}},
      json{{"components", {{"atmosphere.Atmosphere", atmosphere}}}},
      json{{"components", {{"atmosphere.Sun", {{"azimuth_deg", 100}, {"elevation_deg", 30}, {"disc", false}}}}}}});
  if (with_box) {
    double s = distance_m * 0.05;
    ents.push_back(json{{"components", {{"core.DebugShape", {{"shape", "box"}, {"position_m", {0, distance_m, 2}}, {"size_m", {s, 1, s}}, {"albedo", {0.3, 0.3, 0.3}}}}}}});
  }
  load_scene(world, json{{"welkin_scene", 1}, {"entities", ents}}, "aerial.json");
  Renderer r(world);
  r.render_frame({}, 33, 19);
  ImageF hdr = r.read_hdr();
  const float* p = hdr.pixel(16, 9);
  return {p[0], p[1], p[2]};
}

double relative_distance(const glm::vec3& a, const glm::vec3& b) { return glm::length(a - b) / glm::length(b); }

TEST_F(TerrainRender, FarObjectsTakeTheSkyColourWithDistanceAndHaze) {
  json earth = atmosphere_preset("earth");
  glm::vec3 sky = centre_radiance(earth, 0, false);
  double previous = 1e9;
  for (double d : {300.0, 3000.0, 15000.0, 60000.0}) {
    double gap = relative_distance(centre_radiance(earth, d, true), sky);
    EXPECT_LT(gap, previous) << "at " << d << " m the box must be closer to the sky colour than nearer";
    previous = gap;
  }
  EXPECT_LT(previous, 0.35) << "60 km of air makes the box mostly sky";
  json hazy = atmosphere_preset("earth-hazy");
  glm::vec3 hazy_sky = centre_radiance(hazy, 0, false);
  double clear_gap = relative_distance(centre_radiance(earth, 3000, true), sky);
  double hazy_gap = relative_distance(centre_radiance(hazy, 3000, true), hazy_sky);
  EXPECT_LT(hazy_gap, clear_gap) << "haze hides the same box at the same distance more";
}

// The sample valley seen from 2 km south, 600 m up, under a plain light; `terrain` adds settings.
void load_valley(World& world, json terrain = json::object()) {
  world.modules().add_static(modules::terrain_module());
  terrain["file"] = WELKIN_SOURCE_DIR "/assets/terrain/valley.glb";
  json doc{{"welkin_scene", 1},
           {"entities",
            json::array({json{{"components", {{"core.Camera", {{"position_m", {0, -2000, 600}}, {"pitch_deg", -8}, {"ev100", 14}}}}}},
                         json{{"components", {{"core.DirectionalLight", {{"elevation_deg", 40}}}}}},
                         json{{"components", {{"terrain.Terrain", terrain}}}}})}};
  load_scene(world, doc, "terrain.json");
}

// The terrain reports the pixels its chunks may cover (FrameTargets::geometry): the aerial
// perspective is applied inside them only, so every pixel it wrote depth to must lie inside.
TEST_F(TerrainRender, GeometryRectangleHoldsEveryPixelOfTheTerrain) {
  World world;
  load_valley(world);
  auto depth = welkin::testing::read_depth_after_geometry(world);
  Renderer r(world);
  Camera& camera = *world.registry().get<Camera>(world.registry().first<Camera>());
  for (float pitch : {-8.0f, 6.0f}) {  // looking down on it, and over it with sky above
    camera.pitch_deg = pitch;
    const FrameResult fr = r.render_frame({}, 64, 36);
    ASSERT_EQ(depth->depth.size(), size_t(64 * 36));
    EXPECT_GT(depth->covered(), 64 * 36 / 5) << pitch;
    EXPECT_EQ(depth->outside(fr.geometry), 0) << pitch;
    if (pitch > 0) {
      EXPECT_LT(fr.geometry.y1, 36) << "the sky above the terrain is left out";
    }
  }
}

// Radiance of a metallic-roughness surface with normal n seen along -v under the default lights
// (a sun of irradiance `sun` from l, a sky of irradiance sky (0.5 + 0.5 n.z)), in double: Karis 2013
// (GGX, height-correlated Smith, Schlick), the sky's specular from the irradiance toward the
// reflection, as welkin/shading.glsl states it.
glm::dvec3 pbr_reference(const glm::dvec3& base, double metallic, double roughness, const glm::dvec3& n,
                         const glm::dvec3& v, const glm::dvec3& l, const glm::dvec3& sun, const glm::dvec3& sky,
                         double occlusion = 1.0) {
  const double pi = 3.14159265358979323846;
  const glm::dvec3 f0 = glm::mix(glm::dvec3(0.04), base, metallic);
  glm::dvec3 direct(0.0);
  const double n_l = std::max(glm::dot(n, l), 0.0);
  if (n_l > 0.0) {
    const glm::dvec3 h = glm::normalize(v + l);
    const double n_v = std::max(glm::dot(n, v), 1e-4), n_h = std::max(glm::dot(n, h), 0.0), v_h = std::max(glm::dot(v, h), 0.0);
    const double a = std::max(roughness * roughness, 1e-3), a2 = a * a;
    const double d = a2 / (pi * std::pow(n_h * n_h * (a2 - 1.0) + 1.0, 2.0));
    const double vis = 0.5 / (n_l * std::sqrt(n_v * n_v * (1.0 - a2) + a2) + n_v * std::sqrt(n_l * n_l * (1.0 - a2) + a2));
    const glm::dvec3 f = f0 + (1.0 - f0) * std::pow(1.0 - v_h, 5.0);
    direct = ((1.0 - f) * (1.0 - metallic) * base / pi + d * vis * f) * sun * n_l;
  }
  auto sky_irradiance = [&](const glm::dvec3& d) { return sky * (0.5 + 0.5 * d.z); };
  const glm::dvec3 r = glm::reflect(-v, n);
  return direct + (sky_irradiance(n) * (1.0 - metallic) * base / pi + sky_irradiance(r) / pi * f0 * (1.0 - roughness * 0.7)) * occlusion;
}

// A flat ground 4 km square of one material, written with `w` to `file`: glTF's (x, 0, z) from -2000
// to 2000 m, its uv (x / 4000 + 0.5, z / 4000 + 0.5); the scene's north is glTF's -z.
void write_ground(assets::GlbWriter& w, const assets::Material& material, const std::string& file) {
  assets::MeshData plane;
  plane.name = "ground";
  const int n = 16;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      plane.positions.emplace_back((float(i) / n - 0.5f) * 4000.0f, 0.0f, (float(j) / n - 0.5f) * 4000.0f);
      plane.normals.emplace_back(0.0f, 1.0f, 0.0f);
      plane.uv0.emplace_back(float(i) / n, float(j) / n);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = uint32_t(j * (n + 1) + i), b = a + 1, c = a + uint32_t(n + 1), d = c + 1;
      plane.indices.insert(plane.indices.end(), {a, c, b, b, c, d});
    }
  plane.material = w.add_material(material);
  w.add_node("ground", w.add_mesh(plane).mesh);
  w.write(file);
}

// The ground of `file` seen from 120 m above the scene origin's south (pitched 25° down), lit by a
// sun of 10 000 lx at azimuth 20°, elevation 25° (unshadowed): the HDR frame and its view.
std::pair<ImageF, FrameView> render_ground(const std::string& file, int width, int height) {
  World world;
  world.modules().add_static(modules::terrain_module());
  json doc{{"welkin_scene", 1},
           {"entities",
            json::array({json{{"components", {{"core.Camera", {{"position_m", {0, -100, 120}}, {"pitch_deg", -25}, {"vertical_fov_deg", 60}}}}}},
                         json{{"components", {{"core.DirectionalLight", {{"azimuth_deg", 20}, {"elevation_deg", 25}, {"illuminance_lux", 10000}}}}}},
                         json{{"components", {{"terrain.Terrain", {{"file", file}, {"follow_curvature", false}, {"cast_shadows", false},
                                                                {"compress_images", false}}}}}}})}};
  load_scene(world, doc, "ground.json");
  Renderer r(world);
  r.render_frame({}, width, height);
  return {r.read_hdr(), make_frame_view(*world.registry().get<Camera>(world.registry().first<Camera>()), width, height)};
}

// The sun and sky of render_ground, as the CPU reference takes them.
struct GroundLight {
  glm::dvec3 l, sun, sky;
};
GroundLight ground_light() {
  DirectionalLight light;  // the scene's: a sun dimmer than the default, its highlight within half floats
  light.illuminance_lux = 10000.0f;
  const glm::dvec3 sun = glm::dvec3(light.color) * double(light.illuminance_lux);
  return {direction_from_azimuth_elevation(20.0, 25.0), sun, sun * double(light.ambient_fraction)};
}

// A flat ground of one material, unshadowed, under the default lights: every pixel that sees it
// carries the CPU reference's radiance (its point from the pixel's ray, the sun's highlight ahead),
// plus the material's own light where it has some (a factor, or a factor times a texture), to
// half-float precision. The light is computed after the surface is drawn (position from the depth,
// the surface's inputs packed per pixel), so this is also what bounds the packing.
TEST_F(TerrainRender, GroundShadesAsTheCpuReference) {
  const std::filesystem::path& dir = welkin::testing::scratch_folder("welkin-terrain-pbr");
  // An emissive texture of one colour (sRGB 132, 65, 206) multiplies the factor.
  ImageU8 glow;
  glow.width = glow.height = 2;
  for (int i = 0; i < 4; ++i) glow.rgba.insert(glow.rgba.end(), {132, 65, 206, 255});
  const std::vector<uint8_t> glow_png = encode_png(glow);
  auto srgb = [](double c) { c /= 255.0; return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
  const glm::dvec3 glow_linear(srgb(132), srgb(65), srgb(206));
  for (const auto& [factor, textured] : {std::pair{glm::dvec3(0.0), false}, std::pair{glm::dvec3(2000.0, 4000.0, 1000.0), false},
                                        std::pair{glm::dvec3(2000.0, 4000.0, 1000.0), true}}) {
    const glm::dvec3 emissive = textured ? factor * glow_linear : factor;
    assets::GlbWriter w;
    assets::Material material;
    material.base_color_factor = {0.45f, 0.3f, 0.15f, 1.0f};
    material.metallic_factor = 0.2f;
    material.roughness_factor = 0.35f;
    material.emissive_factor = glm::vec3(factor / 4000.0);
    material.emissive_strength = 4000.0f;
    if (textured) material.emissive.texture = w.add_texture(w.add_image(glow_png, "image/png", "glow"));
    const std::string file = (dir / "plane.glb").string();
    write_ground(w, material, file);
    const int width = 48, height = 27;
    const auto [hdr, view] = render_ground(file, width, height);
    const auto [l, sun, sky] = ground_light();
    size_t ground = 0;
    double worst = 0.0, brightest = 0.0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const glm::dvec3 d = glm::dvec3(pixel_direction(view, x + 0.5, y + 0.5));
        if (d.z > -0.02) continue;
        const glm::dvec3 p = d * (120.0 / -d.z);  // camera-relative point on the ground
        if (std::abs(p.x) > 1500.0 || std::abs(p.y - 100.0) > 1500.0) continue;
        const glm::dvec3 expected = emissive + pbr_reference(glm::dvec3(0.45, 0.3, 0.15), 0.2, 0.35, glm::dvec3(0, 0, 1),
                                                             -glm::normalize(p), l, sun, sky);
        const float* got = hdr.pixel(x, y);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] - expected[c]) / expected[c]);
        brightest = std::max(brightest, expected.y);
        ++ground;
      }
    std::printf("emissive %.0f%s: %zu ground pixels, worst relative difference %.2e (brightest %.0f)\n", emissive.y,
                textured ? " (textured)" : "", ground, worst, brightest);
    EXPECT_GT(ground, size_t(width * height / 3));
    // With the texture, its light is 0.27% low in blue: the texel as the GL driver decodes (sRGB) and
    // filters it, which the reference takes from the exact curve.
    EXPECT_LT(worst, textured ? 4e-3 : 2e-3) << "emissive " << emissive.y << (textured ? " (textured)" : "");
  }
  std::filesystem::remove_all(dir);
}

// Each texture of a material takes its own KHR_texture_transform, and occlusion its strength. The
// emissive texture, red on its left half and blue on its right, is offset by 0.05 (its edge 200 m
// west of the view's centre line, instead of on it); the
// base colour (one grey) is turned a quarter turn and the occlusion (one value) scaled, so that the
// emissive read with either's transform would put the colours elsewhere. Every ground pixel away
// from the colours' edge carries the CPU reference (emissive, and the PBR light with occlusion
// 1 + strength (texel - 1)).
TEST_F(TerrainRender, EachTextureTakesItsOwnTransform) {
  const std::filesystem::path& dir = welkin::testing::scratch_folder("welkin-terrain-uv");
  auto image = [](int side, auto colour) {
    ImageU8 img;
    img.width = img.height = side;
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const std::array<uint8_t, 4> c = colour(x, side);
        img.rgba.insert(img.rgba.end(), c.begin(), c.end());
      }
    return img;
  };
  const ImageU8 halves = image(64, [](int x, int side) { return x < side / 2 ? std::array<uint8_t, 4>{255, 0, 0, 255} : std::array<uint8_t, 4>{0, 0, 255, 255}; });
  const ImageU8 grey = image(64, [](int, int) { return std::array<uint8_t, 4>{128, 128, 128, 255}; });
  assets::GlbWriter w;
  assets::Material material;
  material.base_color_factor = {1.0f, 1.0f, 1.0f, 1.0f};
  material.metallic_factor = 0.0f;
  material.roughness_factor = 0.6f;
  material.emissive_factor = {1.0f, 1.0f, 1.0f};
  material.emissive_strength = 3000.0f;
  material.base_color.texture = w.add_texture(w.add_image(encode_png(grey), "image/png", "grey"));
  material.base_color.transform = {.present = true, .offset = {1.0f, 0.0f}, .rotation = 1.5707963f};
  material.occlusion.texture = w.add_texture(w.add_image(encode_png(grey), "image/png", "ao"));
  material.occlusion.scale = 0.5f;
  material.occlusion.transform = {.present = true, .scale = {3.0f, 3.0f}};
  material.emissive.texture = w.add_texture(w.add_image(encode_png(halves), "image/png", "halves"));
  material.emissive.transform = {.present = true, .offset = {0.05f, 0.0f}};
  const std::string file = (dir / "plane.glb").string();
  write_ground(w, material, file);
  const int width = 192, height = 108;  // fine pixels: the far ground reads levels of a few texels
  const auto [hdr, view] = render_ground(file, width, height);
  const auto [l, sun, sky] = ground_light();
  const double grey_linear = std::pow((128.0 / 255.0 + 0.055) / 1.055, 2.4), occlusion = 1.0 + 0.5 * (128.0 / 255.0 - 1.0);
  size_t red = 0, blue = 0;
  double worst = 0.0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 d = glm::dvec3(pixel_direction(view, x + 0.5, y + 0.5));
      if (d.z > -0.02) continue;
      const glm::dvec3 p = d * (120.0 / -d.z);  // camera-relative point on the ground
      if (glm::length(p) > 1300.0) continue;  // nearer: the colours' edge stays within a few pixels
      // The plane's u there (x east, from -2000 to 2000 m), and the emissive's: offset by 0.05.
      const double u = p.x / 4000.0 + 0.5, emissive_u = u + 0.05;
      if (std::abs(emissive_u - 0.5) < 0.03) continue;  // the colours' edge, blended by the filter
      const glm::dvec3 colour = emissive_u < 0.5 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 0, 1);
      (emissive_u < 0.5 ? red : blue) += 1;
      const glm::dvec3 expected = 3000.0 * colour + pbr_reference(glm::dvec3(grey_linear), 0.0, 0.6, glm::dvec3(0, 0, 1),
                                                                   -glm::normalize(p), l, sun, sky, occlusion);
      const float* got = hdr.pixel(x, y);
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(got[c] - expected[c]) / expected[c]);
    }
  std::printf("%zu red and %zu blue ground pixels, worst relative difference %.2e\n", red, blue, worst);
  EXPECT_GT(red, size_t(400));
  EXPECT_GT(blue, size_t(400));
  EXPECT_LT(worst, 4e-3);
  std::filesystem::remove_all(dir);
}

TEST_F(TerrainRender, SampleTerrainRendersWithItsMaterial) {
  World world;
  load_valley(world);
  Renderer r(world);
  FrameResult fr = r.render_frame({}, 48, 27);
  bool drew = false;
  for (const auto& t : fr.timings) drew = drew || t.name == "terrain";
  EXPECT_TRUE(drew);
  ImageU8 img = r.read_output();
  // The lower half is lit ground (green-brown terrain texture), not the black clear colour.
  const uint8_t* g = img.pixel(24, 22);
  EXPECT_GT(int(g[0]) + g[1] + g[2], 60);
  EXPECT_GE(g[1], g[2]) << "vegetation, not sky";
}

// Once the GPU holds the mesh, its CPU arrays give their memory back (assigning `{}` to a vector
// would keep it: 34 MB of the demo's vertices and indices stayed allocated).
TEST_F(TerrainRender, CpuCopiesOfTheMeshAreReleasedOnceUploaded) {
  const welkin::testing::CacheFolder no_cache("");  // built, not read: the arrays are the mesh's own
  World world;
  load_valley(world);
  Renderer r(world);
  r.render_frame({}, 16, 9);
  auto& cache = world.resource<terrain::TerrainCache>();
  ASSERT_EQ(cache.terrains.size(), 1u);
  const terrain::TerrainMesh& mesh = cache.terrains.begin()->second->mesh;
  EXPECT_FALSE(mesh.chunks.empty()) << "the chunks' bounds and levels stay";
  EXPECT_EQ(mesh.positions.capacity(), 0u);
  EXPECT_EQ(mesh.normals.capacity(), 0u);
  EXPECT_EQ(mesh.uvs.capacity(), 0u);
  EXPECT_EQ(mesh.indices.capacity(), 0u);
}

// A start that finds the built mesh and the compressed images in the disk cache reads them instead of
// decoding and building them, and draws the same frame, bit for bit; other build settings miss the
// mesh but not the images.
TEST_F(TerrainRender, MeshReadFromTheDiskCacheBitForBit) {
  const std::filesystem::path folder = welkin::testing::scratch_folder("welkin-terrain-cache") / "cache";
  std::filesystem::remove_all(folder);
  const welkin::testing::CacheFolder cache(folder.string());
  size_t image_reads = 0;
  auto render = [&](int lod_levels, size_t& reads) {
    World world;
    load_valley(world, {{"lod_levels", lod_levels}});
    Renderer r(world);
    r.render_frame({}, 48, 27);
    reads = world.resource<terrain::TerrainCache>().mesh_cache_reads;
    image_reads = world.resource<terrain::TerrainCache>().image_cache_reads;
    return r.read_hdr();
  };
  size_t reads = 0;
  const ImageF built = render(4, reads);
  EXPECT_EQ(reads, 0u);
  EXPECT_EQ(image_reads, 0u);
  const ImageF read = render(4, reads);
  EXPECT_EQ(reads, 1u);
  EXPECT_EQ(image_reads, 2u) << "both images' compressed levels (the valley's and the horizon's), not decoded again";
  EXPECT_EQ(read.rgba, built.rgba);
  render(3, reads);
  EXPECT_EQ(reads, 0u) << "other settings build their own mesh";
  EXPECT_EQ(image_reads, 2u) << "and share the images";
  std::filesystem::remove_all(folder);
}

// The base colour as the GPU holds it (BC1, decoded by the driver) against the file's decoded image,
// its levels against the image's mean light, and the frame against one drawn with the image uncompressed.
TEST_F(TerrainRender, CompressedBaseColourStaysCloseToTheImage) {
  World world;
  load_valley(world);
  Renderer r(world);
  r.render_frame({}, 320, 180);
  const ImageF compressed = r.read_hdr();
  const terrain::GpuTerrain& gpu = *world.resource<terrain::TerrainCache>().terrains.begin()->second;
  const GLuint id = gpu.materials.front().base_color.id();
  ASSERT_NE(id, 0u);
  GLint is_compressed = 0, width = 0, height = 0, stored = 0;
  glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_COMPRESSED, &is_compressed);
  glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_WIDTH, &width);
  glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_HEIGHT, &height);
  glGetTextureLevelParameteriv(id, 0, GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &stored);
  EXPECT_TRUE(is_compressed);
  EXPECT_EQ(int64_t(stored), int64_t(width) * height / 2) << "4 bits a texel";
  const assets::Model model = assets::load_gltf(WELKIN_SOURCE_DIR "/assets/terrain/valley.glb");
  const assets::Image& image = model.images.at(size_t(model.textures.at(size_t(model.materials.at(0).base_color.texture)).image));
  ASSERT_EQ(image.width, width);
  std::vector<uint8_t> back(size_t(width) * size_t(height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(id, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(back.size()), back.data());
  const double psnr = image_difference({width, height, back}, {image.width, image.height, image.rgba}).psnr_db;
  World plain;
  load_valley(plain, {{"compress_images", false}});
  Renderer rp(plain);
  rp.render_frame({}, 320, 180);
  const ImageF uncompressed = rp.read_hdr();
  double diff = 0.0, total = 0.0;
  for (size_t i = 0; i < compressed.rgba.size(); ++i)
    if (i % 4 != 3) diff += std::abs(double(compressed.rgba[i]) - uncompressed.rgba[i]), total += uncompressed.rgba[i];
  // Every level holds the light of level 0: its mean (linear, all three channels), against the decoded
  // file's in double precision. GL's own glGenerateMipmap drifted to +4% at 16x16 here.
  auto linear = [](double v) { v /= 255.0; return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); };
  auto mean_light = [&](const uint8_t* rgba, size_t texels) {
    double m = 0.0;
    for (size_t i = 0; i < texels * 4; ++i)
      if (i % 4 != 3) m += linear(rgba[i]);
    return m / double(texels * 3);
  };
  const double light0 = mean_light(image.rgba.data(), size_t(width) * size_t(height));
  const GLuint plain_id = plain.resource<terrain::TerrainCache>().terrains.begin()->second->materials.front().base_color.id();
  for (int level = 1; (width >> level) >= 16; ++level)
    for (const GLuint t : {id, plain_id}) {
      const size_t side = size_t(width >> level);
      std::vector<uint8_t> texels(side * side * 4);
      glGetTextureImage(t, level, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(texels.size()), texels.data());
      const double drift = mean_light(texels.data(), side * side) / light0 - 1.0;
      EXPECT_LT(std::abs(drift), t == id ? 0.01 : 0.005) << "level " << level << (t == id ? " BC1" : " RGBA8");
    }
  std::printf("valley base colour in BC1: PSNR %.1f dB; frame's mean relative difference %.2e\n", psnr, diff / total);
  EXPECT_GT(psnr, 34.0);
  EXPECT_LT(diff / total, 0.02) << "1.2% measured: BC1 errs most in the coarse, noisy levels the far valley samples";
  EXPECT_GT(diff / total, 0.0) << "the two frames sample different textures";
}

// A still camera under a still sun casts the same shadows: the cascades are drawn once, and a frame
// that keeps them is the frame that draws them afresh, bit for bit. A turn of the light draws them again.
// Each cascade is drawn again only when its place (on a grid fixed in the scene), the sun or its
// casters change: kept through a still frame and a small turn of the camera, the same frame a fresh
// world draws, bit for bit; turning the light draws all three.
TEST_F(TerrainRender, ShadowCascadesAreDrawnAgainOnlyWhenTheirInputsChange) {
  World world;
  load_valley(world);
  Renderer r(world);
  auto& cache = world.resource<terrain::TerrainCache>();
  r.render_frame({}, 48, 27);
  EXPECT_EQ(cache.cascade_draws, 3u);
  r.render_frame({}, 48, 27);
  EXPECT_EQ(cache.cascade_draws, 3u) << "nothing moved";
  auto fresh = [](float heading_offset) {
    World f;
    load_valley(f);
    f.registry().get<Camera>(f.registry().first<Camera>())->heading_deg += heading_offset;
    Renderer fr(f);
    fr.render_frame({}, 48, 27);
    return fr.read_hdr().rgba;
  };
  EXPECT_EQ(r.read_hdr().rgba, fresh(0.0f));
  Registry& reg = world.registry();
  reg.get<Camera>(reg.first<Camera>())->heading_deg += 0.5f;
  r.render_frame({}, 48, 27);
  EXPECT_EQ(cache.cascade_draws, 3u) << "a small turn keeps every cascade on its grid";
  EXPECT_EQ(r.read_hdr().rgba, fresh(0.5f));
  const std::vector<float> turned = r.read_hdr().rgba;
  reg.get<DirectionalLight>(reg.first<DirectionalLight>())->azimuth_deg += 20.0f;
  r.render_frame({}, 48, 27);
  EXPECT_EQ(cache.cascade_draws, 6u) << "the light turned";
  EXPECT_NE(r.read_hdr().rgba, turned);
}

// A cascade kept while the camera moves holds depths drawn from where the camera was: they differ
// from a fresh drawing's by float rounding only, far below the shadows' bias.
TEST_F(TerrainRender, CascadesKeptWhileTheCameraMovesShadeAsFreshOnes) {
  auto frame = [](bool moved_after_first) {
    World world;
    load_valley(world);
    Renderer r(world);
    Camera& camera = *world.registry().get<Camera>(world.registry().first<Camera>());
    if (!moved_after_first) camera.position_m.x += 3.0;
    r.render_frame({}, 48, 27);
    const size_t first = world.resource<terrain::TerrainCache>().cascade_draws;
    if (moved_after_first) {
      camera.position_m.x += 3.0;
      r.render_frame({}, 48, 27);
      EXPECT_LT(world.resource<terrain::TerrainCache>().cascade_draws, first + 3) << "some cascade was kept";
    }
    return r.read_hdr();
  };
  const ImageF kept = frame(true), drawn = frame(false);
  double worst = 0.0;
  for (size_t i = 0; i < kept.rgba.size(); ++i)
    worst = std::max(worst, std::abs(double(kept.rgba[i]) - drawn.rgba[i]) / std::max(1e-3, double(drawn.rgba[i])));
  std::printf("kept cascades against fresh ones, worst relative difference: %.2e\n", worst);
  EXPECT_LT(worst, 1e-3);
}

// A turning or flying camera keeps each cascade where it is while the cascade's slice of the view
// stays inside it (up to a whole grid step from its centre), not only while the slice's centre snaps
// to the same grid point: the cascades are drawn again half as often or less, and a frame drawn
// through kept cascades shades as one drawn afresh (a fresh world puts them on the grid).
TEST_F(TerrainRender, CascadesStayWhileTheirSliceStaysInside) {
  // A low sun: long shadows over the hills, so that where the cascades sit shows in the frame.
  auto low_sun = [](World& w) { w.registry().get<DirectionalLight>(w.registry().first<DirectionalLight>())->elevation_deg = 8.0f; };
  World world;
  load_valley(world);
  low_sun(world);
  Renderer r(world);
  Camera& camera = *world.registry().get<Camera>(world.registry().first<Camera>());
  r.render_frame({}, 96, 54);
  auto& cache = world.resource<terrain::TerrainCache>();
  const size_t first = cache.cascade_draws;
  double worst = 0.0, mean = 0.0;
  size_t over_one_percent = 0, values = 0;
  for (int turn = 1; turn <= 24; ++turn) {
    camera.heading_deg += 1.0f;
    camera.position_m.y += 20.0;
    r.render_frame({}, 96, 54);
    if (turn % 8 == 0) {
      World fresh;
      load_valley(fresh);
      low_sun(fresh);
      Camera& c = *fresh.registry().get<Camera>(fresh.registry().first<Camera>());
      c.heading_deg = camera.heading_deg, c.position_m = camera.position_m;
      Renderer fr(fresh);
      fr.render_frame({}, 96, 54);
      const ImageF a = r.read_hdr(), b = fr.read_hdr();
      for (size_t i = 0; i < a.rgba.size(); ++i) {
        if (i % 4 == 3) continue;
        const double d = std::abs(double(a.rgba[i]) - b.rgba[i]) / std::max(1e-3, double(b.rgba[i]));
        worst = std::max(worst, d);
        mean += d, over_one_percent += d > 0.01;
        ++values;
      }
    }
  }
  const size_t drawn = cache.cascade_draws - first;
  mean /= double(values);
  std::printf("24 frames turning 1 degree and flying 20 m each: %zu cascades drawn; against fresh frames: mean relative "
              "difference %.2e, worst %.2e, %.3f%% of values over 1%%\n",
              drawn, mean, worst, 100.0 * double(over_one_percent) / double(values));
  EXPECT_LE(drawn, 8u) << "of 72 (snapping to the grid alone: 11; with the slice's radius computed from turned corners: 32)";
  // Kept cascades sit off the grid by up to a step: the same texels, another phase, so shadow edges
  // filter a little differently; nothing else changes.
  EXPECT_LT(mean, 1e-3);
  EXPECT_LT(double(over_one_percent) / double(values), 0.01);
  EXPECT_LT(worst, 0.1);
}

// A still view under a still sun draws its terrain until it is drawn twice alike (a frame that draws
// the shadow cascades counts as changed in the next), then takes the kept colour and depth: the frame
// is the drawn one bit for bit, colour and depth, with the sky above the ridge where it was. Whatever
// the terrain is drawn from changing draws it again: the camera turning or moving, the sun, the
// terrain's placement, the frame's size.
TEST_F(TerrainRender, StillViewTakesTheTerrainDrawnLast) {
  World world;
  load_valley(world);
  auto depth = welkin::testing::read_depth_after_geometry(world);
  Renderer r(world);
  Camera& camera = *world.registry().get<Camera>(world.registry().first<Camera>());
  camera.pitch_deg = 4.0f;  // sky above the ridge: the kept colour must leave it alone
  auto& cache = world.resource<terrain::TerrainCache>();
  struct Frame {
    std::vector<float> hdr, depth;
  };
  auto render = [&](int w = 64, int h = 36) {
    r.render_frame({}, w, h);
    return Frame{r.read_hdr().rgba, depth->depth};
  };
  // Renders still frames until two in a row are kept; the frame drawn last and the draws it took.
  auto settle = [&](const Frame& first, const char* what) {
    const size_t start = cache.view_draws;
    for (int i = 0; i < 2; ++i) render();
    const size_t drawn = cache.view_draws - start;
    EXPECT_LE(drawn, 2u) << what << ": drawn again at most until the cascades and the view are drawn twice alike";
    for (int i = 0; i < 3; ++i) {
      const Frame kept = render();
      EXPECT_EQ(kept.hdr, first.hdr) << what << ", frame " << i << ": the kept colour is the drawn one bit for bit";
      EXPECT_EQ(kept.depth, first.depth) << what << ", frame " << i;
    }
    EXPECT_EQ(cache.view_draws - start, drawn) << what << ": still frames take the kept terrain";
  };
  const Frame drawn = render();
  EXPECT_GT(depth->covered(), 64 * 36 / 5);
  EXPECT_LT(depth->covered(), 64 * 36) << "the sky shows above the ridge";
  settle(drawn, "the first view");

  // What is drawn before the terrain and changes while the terrain does not (a sky, say) stays where
  // there is no terrain: the kept colour goes only where the kept depth holds terrain.
  auto paint = std::make_shared<float>(0.0f);
  world.scheduler().add(SystemDesc{.name = "test.paint", .stage = Stage::light_maps, .run = [paint](SystemContext& sc) {
    const FrameTargets t = *sc.targets;
    sc.graph->add_pass("test.paint", [&](PassBuilder& b) { b.read(t.color); b.write(t.color); }, [t, paint](PassContext& pc) {
      Framebuffer fb(&pc.texture(t.color), nullptr);
      fb.bind();
      glClearColor(*paint, 2.0f * *paint, 3.0f * *paint, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT);
      glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
    });
  }});
  for (float p : {100.0f, 200.0f}) {
    *paint = p;
    const size_t draws = cache.view_draws;
    const Frame f = render();
    EXPECT_EQ(cache.view_draws, draws) << "the terrain is kept";
    size_t sky = 0;
    for (size_t y = 0; y < 36; ++y)
      for (size_t x = 0; x < 64; ++x) {
        const bool open = f.depth[y * 64 + x] == 0.0f;  // GL's rows, bottom up; the image's top down
        const size_t i = ((35 - y) * 64 + x) * 4;
        sky += open;
        for (size_t c = 0; c < 3; ++c)
          ASSERT_EQ(f.hdr[i + c], open ? p * float(c + 1) : drawn.hdr[i + c]) << x << "," << y << (open ? " (sky)" : " (terrain)");
      }
    EXPECT_GT(sky, 64u);
  }

  // Each input in turn: drawn again, and kept again once still.
  auto& terrain = *world.registry().get<terrain::Terrain>(world.registry().first<terrain::Terrain>());
  auto& sun = *world.registry().get<DirectionalLight>(world.registry().first<DirectionalLight>());
  const std::vector<std::pair<const char*, std::function<void()>>> changes = {
      {"the camera turns", [&] { camera.heading_deg += 0.5f; }},
      {"the camera turns a little (the same chunks drawn)", [&] { camera.heading_deg += 0.02f; }},
      {"the camera moves", [&] { camera.position_m.x += 1.0; }},
      {"the sun moves", [&] { sun.elevation_deg += 0.5f; }},
      {"the sun brightens", [&] { sun.illuminance_lux *= 1.01f; }},
      {"the terrain turns", [&] { terrain.heading_deg += 0.1f; }},
  };
  for (const auto& [what, change] : changes) {
    const Frame before = render();
    const size_t draws = cache.view_draws;
    change();
    const Frame after = render();
    EXPECT_EQ(cache.view_draws, draws + 1) << what;
    EXPECT_NE(after.hdr, before.hdr) << what;
    settle(after, what);
  }
  const size_t draws = cache.view_draws;
  render(48, 27);
  EXPECT_EQ(cache.view_draws, draws + 1) << "another frame size";
}

TEST_F(TerrainRender, DefaultDemoSceneMatchesGolden) {
  // Terrain, sky, clouds and their shadows, time of day and aerial perspective, at a small size.
  World world;
  world.modules().add_static(modules::atmosphere_module());
  world.modules().add_static(modules::terrain_module());
  world.modules().add_static(modules::timeofday_module());
  world.modules().add_static(modules::clouds_module());
  json doc = read_json_file(WELKIN_SOURCE_DIR "/assets/scenes/default.json");
  for (auto& e : doc["entities"])  // the scene names the terrain relative to the repository root
    if (e["components"].contains("terrain.Terrain"))
      e["components"]["terrain.Terrain"]["file"] = WELKIN_SOURCE_DIR "/assets/terrain/valley.glb";
  load_scene(world, doc, "default.json");
  Renderer r(world);
  r.render_frame({}, 160, 90);
  auto res = welkin::testing::compare_with_golden(r.read_output(), "terrain/default_scene",
                                                  {.max_channel_difference = 10, .max_failing_fraction = 0.02});
  EXPECT_TRUE(res.passed) << res.message;
}

}  // namespace
