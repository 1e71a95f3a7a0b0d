// The billboard clouds (clouds.CloudBillboards): the bake depends on the settings alone, the impostor
// against its reference (the same archetypes marched), placement on the layer's weather, the
// hand-over with the clusters and the march, stiff cases, bad input and golden images.
#include <algorithm>
#include <numeric>

#include "clouds_test_support.h"
#include "golden.h"
#include "validation/cloud_field.h"
#include "welkin/core/error.h"

namespace welkin::clouds::test {
namespace {

using nlohmann::json;

// A camera on the ground looking along the horizon at the default cumulus; the billboards take the
// layer over beyond `near_m`.
const json kBillboards = {{"near_m", 6000}, {"crossfade_m", 1000}, {"far_m", 40000}, {"billboards", 64}, {"atlas_resolution", 16}};

json billboard_scene(const json& billboards, double sun_elevation_deg = 40.0, const json& clouds = json::object()) {
  return scene({{"core.Camera", {{"position_m", {0, 0, 100}}, {"heading_deg", 200}, {"pitch_deg", 3}, {"ev100", 14}}},
                {"atmosphere.Atmosphere", json::object()},
                {"atmosphere.Sun", {{"azimuth_deg", 230}, {"elevation_deg", sun_elevation_deg}}},
                {"clouds.VolumetricClouds", clouds},
                {"clouds.CloudBillboards", billboards}});
}
json billboards_with(const json& changes) {
  json b = kBillboards;
  b.update(changes);
  return b;
}

std::vector<BillboardGpu> read_billboards(Rendered& r) {
  const BillboardsGpu& b = r.world->resource<CloudsGpu>().billboards;
  std::vector<BillboardGpu> out(size_t(b.drawn));
  if (!out.empty()) glGetNamedBufferSubData(b.billboards->id(), 0, GLsizeiptr(out.size() * sizeof(BillboardGpu)), out.data());
  return out;
}
size_t live(const std::vector<BillboardGpu>& billboards) {
  return size_t(std::count_if(billboards.begin(), billboards.end(), [](const BillboardGpu& b) { return b.depth_scale > 0.0f; }));
}

double luminance(const float* p) { return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2]; }
// Luminance RMSE of `a` against `b`, relative to b's mean difference from `clear`.
double relative_rmse(const ImageF& a, const ImageF& b, const ImageF& clear) {
  double sq = 0.0, mean = 0.0;
  const size_t n = a.rgba.size() / 4;
  for (size_t i = 0; i < n; ++i) {
    const double e = luminance(&a.rgba[i * 4]) - luminance(&b.rgba[i * 4]);
    sq += e * e;
    mean += std::abs(luminance(&b.rgba[i * 4]) - luminance(&clear.rgba[i * 4]));
  }
  return std::sqrt(sq / double(n)) / (mean / double(n));
}

TEST(CloudBillboards, TheBakeDependsOnTheSettingsNotOnTheCameraOrTheTime) {
  auto atlas = [](Rendered& r) {
    const BillboardsGpu& b = r.world->resource<CloudsGpu>().billboards;
    std::vector<float> all;
    for (int layer = 0; layer < b.atlas->desc().depth; ++layer) {
      const ImageF img = read_texture_float(*b.atlas, layer);
      all.insert(all.end(), img.rgba.begin(), img.rgba.end());
    }
    return all;
  };
  Rendered here = render(billboard_scene(kBillboards), 32, 18);
  ASSERT_TRUE(here.ran("clouds.billboards_bake"));
  const std::vector<float> first = atlas(here);
  // The texels hold cloud: some optical depth, and transmittances within [0, 1] toward the light's side.
  EXPECT_GT(*std::max_element(first.begin(), first.end()), 1.0f);
  // More frames, a camera 30 km away and an hour later: no new bake, the same atlas.
  for (int i = 0; i < 3; ++i) here.frame(32, 18);
  EXPECT_EQ(here.world->resource<CloudsGpu>().billboards.bakes, 1);
  json moved = billboard_scene(kBillboards, 40.0, {{"wind_mps", {20, -5}}});
  entity_with(moved, "core.Camera")["components"]["core.Camera"]["position_m"] = {30000, -12000, 900};
  Rendered there = render(moved, 32, 18);
  there.renderer->render_frame({.time_s = 3600.0, .index = 3600 * 30, .alone = true}, 32, 18);
  EXPECT_EQ(atlas(there), first) << "scrubbing equals playing: the bake reads the noise in a frame of its own";
  // A coverage 0.2 higher is another bake.
  here.clouds().coverage = 0.8f;
  here.frame(32, 18);
  EXPECT_EQ(here.world->resource<CloudsGpu>().billboards.bakes, 2);
  EXPECT_NE(atlas(here), first);
}

TEST(CloudBillboards, TheImpostorMatchesTheMarchedArchetypesAndMoreViewsErrLess) {
  // The billboards far away (as they are used), the other layer hidden; the reference marches each
  // pixel through the same baked archetype, lit through a march toward the sun.
  const json far = billboards_with({{"near_m", 20000}, {"far_m", 60000}, {"billboards", 128}, {"atlas_resolution", 32}});
  const json clouds = {{"layers", {{{"genus", "cumulus"}, {"base_altitude_m", 1500}, {"thickness_m", 2000}, {"coverage", 0.45}}}}};
  auto frame = [&](const json& changes) {
    json b = far;
    b.update(changes);
    json doc = billboard_scene(b, 35.0, clouds);
    entity_with(doc, "core.Camera")["components"]["core.Camera"]["pitch_deg"] = 1;
    Rendered r = render(doc, 192, 108);
    return r.renderer->read_hdr();
  };
  json clear_doc = billboard_scene(far, 35.0, clouds);
  remove_entity_with(clear_doc, "clouds.CloudBillboards");
  clear_doc["entities"].erase(std::remove_if(clear_doc["entities"].begin(), clear_doc["entities"].end(),
                                             [](const json& e) { return e["components"].contains("clouds.VolumetricClouds"); }),
                              clear_doc["entities"].end());
  const ImageF clear = render(clear_doc, 192, 108).renderer->read_hdr();
  const ImageF reference = frame({{"render", "volume"}});
  const double fine = relative_rmse(frame({{"view_azimuths", 8}, {"view_elevations", 5}}), reference, clear);
  const double coarse = relative_rmse(frame({{"view_azimuths", 4}, {"view_elevations", 1}}), reference, clear);
  // welkin accuracy billboards measures 10% at 320x180 from 25 km on; nearer and coarser here.
  EXPECT_LT(fine, 0.2) << "the default views";
  std::printf("impostor against the reference: %.1f%% (8 x 5 views), %.1f%% (4 x 1)\n", 100.0 * fine, 100.0 * coarse);
  EXPECT_LT(fine, coarse) << "more views err less";
  EXPECT_GT(fine, 1e-4) << "the two paths are computed apart";
}

TEST(CloudBillboards, BillboardsStandOnTheLayersWeatherWithinTheirRingFarToNear) {
  Rendered r = render(billboard_scene(kBillboards), 64, 36);
  ASSERT_TRUE(r.ran("clouds.billboards_place"));
  ASSERT_TRUE(r.ran("clouds.billboards_draw"));
  const std::vector<BillboardGpu> billboards = read_billboards(r);
  ASSERT_EQ(billboards.size(), size_t(64));
  EXPECT_GT(live(billboards), size_t(32)) << "the default cumulus (coverage 0.45) fills most cells";
  const CloudsGpu& gpu = r.world->resource<CloudsGpu>();
  const glm::vec4 fade = gpu.billboards_fade;
  EXPECT_NEAR(fade.x, 5500.0f, 1e-3f);
  EXPECT_NEAR(fade.w, 40000.0f, 1e-3f);
  const CloudField field(read_noise(gpu), gpu.block, gpu.layers);
  const CloudLayer& cumulus = r.clouds().layers[0];
  for (const BillboardGpu& b : billboards) {
    if (b.depth_scale <= 0.0f) continue;
    const glm::dvec3 c(b.centre);
    EXPECT_GE(glm::length(c), fade.x - 1.0);
    EXPECT_LE(glm::length(c), fade.w + 1.0);
    EXPECT_NEAR(field.altitude(c), cumulus.base_altitude_m + 0.5 * cumulus.thickness_m, 1.0) << "the layer's middle";
    EXPECT_LT(b.archetype, 4u) << "an archetype";
    EXPECT_LE(b.depth_scale, 1.0f) << "the cross-fades and the weather only thin";
  }
  // Every chosen cell's weather allows cloud.
  const PlacementBuffers& p = gpu.billboards.placement;
  std::vector<int32_t> chosen(64);
  glGetNamedBufferSubData(p.chosen->id(), 0, GLsizeiptr(chosen.size() * sizeof(int32_t)), chosen.data());
  std::vector<float> cells(size_t(p.cell_order_grid) * size_t(p.cell_order_grid));
  glGetNamedBufferSubData(p.cells->id(), 0, GLsizeiptr(cells.size() * sizeof(float)), cells.data());
  for (int32_t c : chosen)
    if (c >= 0) EXPECT_GT(cells[size_t(c)], 0.0f);
  // The draw order: every slot once, live billboards far to near.
  std::vector<glm::uvec2> order(billboards.size());
  glGetNamedBufferSubData(gpu.billboards.order->id(), 0, GLsizeiptr(order.size() * sizeof(glm::uvec2)), order.data());
  std::vector<int> seen(billboards.size(), 0);
  double previous = 1e30;
  for (const glm::uvec2& o : order) {
    ASSERT_LT(o.y, billboards.size());
    ++seen[o.y];
    const BillboardGpu& b = billboards[o.y];
    const double d = b.depth_scale > 0.0f ? glm::length(glm::dvec3(b.centre)) : -1.0;
    EXPECT_LE(d, previous + 1e-6 * std::abs(previous));
    previous = d;
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; })) << "a permutation";
}

TEST(CloudBillboards, BeyondTheClustersTheyTakeOverWhereThePuffsFadeOut) {
  json doc = billboard_scene(billboards_with({{"far_m", 60000}}));
  doc["entities"].push_back({{"name", "clusters"},
                             {"components", {{"clouds.CloudClusters", {{"near_m", 3000}, {"crossfade_m", 1000}, {"far_m", 20000}}}}}});
  Rendered r = render(doc, 32, 18);
  const CloudsGpu& gpu = r.world->resource<CloudsGpu>();
  ASSERT_GE(gpu.billboards_layer, 0);
  EXPECT_EQ(gpu.billboards_layer, gpu.clusters_layer);
  EXPECT_EQ(gpu.billboards_fade, glm::vec4(19000.0f, 20000.0f, 59000.0f, 60000.0f));
  const LayerBlock& handed = gpu.layers[size_t(gpu.billboards_layer)];
  EXPECT_EQ(glm::vec3(handed.handover_near_m, handed.handover_crossfade_m, handed.handover_far_m),
            glm::vec3(3000.0f, 1000.0f, 60000.0f))
      << "the march draws the layer nearer than the clusters and beyond the billboards";
  EXPECT_TRUE(r.ran("clouds.billboards_draw"));
  EXPECT_TRUE(r.ran("clouds.clusters_draw"));
}

TEST(CloudBillboards, NoBillboardsLeaveTheFrameAsWithoutTheComponent) {
  Rendered with = render(billboard_scene(billboards_with({{"billboards", 0}})), 64, 36);
  EXPECT_FALSE(with.ran("clouds.billboards_draw"));
  json doc = billboard_scene(kBillboards);
  remove_entity_with(doc, "clouds.CloudBillboards");
  Rendered without = render(doc, 64, 36);
  EXPECT_EQ(with.renderer->read_hdr().rgba, without.renderer->read_hdr().rgba);
}

TEST(CloudBillboards, StiffCasesStayFiniteAndNonNegative) {
  struct Case {
    const char* name;
    json billboards, clouds;
    double sun_deg = 40.0;
    glm::dvec3 camera{0, 0, 100};
  };
  const Case cases[] = {
      {"coverage 0", kBillboards, {{"coverage", 0.0}}},
      {"coverage 1", kBillboards, {{"coverage", 1.0}}},
      {"the camera inside a billboard (at the near plane)", billboards_with({{"near_m", 0}, {"crossfade_m", 0}}), {{"coverage", 1.0}}, 40.0,
       {0, 0, 2500}},
      {"billboards at 200 km", billboards_with({{"near_m", 190000}, {"far_m", 250000}, {"billboards", 256}}), json::object()},
      {"sun on the horizon", kBillboards, json::object(), 0.0},
      {"sun far below (the moon's light)", kBillboards, json::object(), -30.0},
      {"100 times as dense", billboards_with({{"density_scale", 100.0}}), json::object()},
      {"one view, 4 texels", billboards_with({{"view_azimuths", 1}, {"view_elevations", 1}, {"atlas_resolution", 4}}), json::object()},
      {"the reference, from inside", billboards_with({{"near_m", 0}, {"crossfade_m", 0}, {"render", "volume"}}), {{"coverage", 1.0}}, 40.0,
       {0, 0, 2500}},
  };
  for (const Case& c : cases) {
    Rendered r = render_stiff_case(billboard_scene(c.billboards, c.sun_deg, c.clouds), c.camera, c.name);
    const std::vector<BillboardGpu> billboards = read_billboards(r);
    for (const BillboardGpu& b : billboards)
      if (b.depth_scale > 0.0f) {
        ASSERT_TRUE(std::isfinite(b.light.x) && b.light.x >= 0.0f) << c.name;
        ASSERT_TRUE(std::isfinite(b.ap_transmittance.x) && b.ap_transmittance.x >= 0.0f) << c.name;
      }
    const std::string name = c.name;
    if (name == "coverage 0") EXPECT_EQ(live(billboards), 0u);
    if (name == "coverage 1") EXPECT_GT(live(billboards), billboards.size() * 3 / 4);
    if (name == "billboards at 200 km") {
      EXPECT_GT(live(billboards), 0u);
      for (const BillboardGpu& b : billboards)
        if (b.depth_scale > 0.0f) EXPECT_GT(glm::length(glm::dvec3(b.centre)), 185000.0);
    }
  }
}

TEST(CloudBillboards, BadSettingsAreOneErrorNamingTheField) {
  auto message = [](const json& doc) -> std::string {
    try {
      Rendered r = render(doc, 16, 9);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  json doc = billboard_scene(kBillboards);
  remove_entity_with(doc, "clouds.VolumetricClouds");
  EXPECT_NE(message(doc).find("clouds.VolumetricClouds"), std::string::npos);
  EXPECT_NE(message(billboard_scene(billboards_with({{"layer", 7}}))).find("/layer"), std::string::npos);
  EXPECT_NE(message(billboard_scene(billboards_with({{"archetypes", 16}, {"view_azimuths", 32}, {"view_elevations", 8}}))).find("/view_azimuths"),
            std::string::npos);
  EXPECT_NE(message(billboard_scene(billboards_with({{"far_m", 1000}}))).find("/far_m"), std::string::npos);
  EXPECT_NE(message(billboard_scene(billboards_with({{"cell_m", 500}, {"far_m", 1e6}}))).find("/cell_m"), std::string::npos);
  EXPECT_NE(message(billboard_scene(billboards_with({{"atlas_resolution", 100000}}))).find("/atlas_resolution"), std::string::npos);
  // Memory bounded before it is spent: 4 volumes of 128^3 (32 MiB), an atlas of 64 MiB.
  EXPECT_NE(message(billboard_scene(billboards_with({{"atlas_resolution", 128}}))).find("/archetypes"), std::string::npos);
  EXPECT_NE(message(billboard_scene(billboards_with({{"atlas_resolution", 64}, {"archetypes", 16}, {"view_azimuths", 32}, {"view_elevations", 2}})))
                .find("/atlas_resolution"),
            std::string::npos);
}

// Billboards at noon and at sunset, looked at before they were committed.
TEST(CloudBillboardsGolden, NoonAndSunset) {
  const welkin::testing::GoldenTolerance tolerance{.max_channel_difference = 10, .max_failing_fraction = 0.02};
  for (const auto& [sun, name] : {std::pair{40.0, "clouds/billboards_noon"}, std::pair{4.0, "clouds/billboards_sunset"}}) {
    Rendered r = render(billboard_scene(kBillboards, sun), 160, 90);
    r.renderer->render_frame({.index = 1, .alone = true}, 160, 90);
    const auto res = welkin::testing::compare_with_golden(r.renderer->read_output(), name, tolerance);
    EXPECT_TRUE(res.passed) << name << ": " << res.message;
  }
}

}  // namespace
}  // namespace welkin::clouds::test
