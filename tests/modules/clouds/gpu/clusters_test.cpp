// The mesh clusters (clouds.CloudClusters): the proxy mesh, placement from the very field the march
// reads, the far-to-near order, the march through the columns converging, stiff cases, bad input and
// golden images.
#include <numeric>

#include "clouds_test_support.h"
#include "golden.h"
#include "validation/cloud_field.h"
#include "welkin/core/error.h"

namespace welkin::clouds::test {
namespace {

using nlohmann::json;

// ---- The proxy mesh ----

TEST(CloudClusters, ProxyMeshEnclosesTheUnitSphereAndFacesOutward) {
  for (int level = 1; level <= 4; ++level) {
    const std::vector<glm::vec4> mesh = puff_proxy_mesh(level);
    ASSERT_EQ(mesh.size() % 3, 0u);
    ASSERT_GE(mesh.size(), size_t(6 * 4 * 2 * 3)) << "level " << level;
    double nearest = 1e9, farthest = 0.0;
    for (size_t t = 0; t < mesh.size(); t += 3) {
      const glm::dvec3 a(mesh[t]), b(mesh[t + 1]), c(mesh[t + 2]);
      const glm::dvec3 n = glm::normalize(glm::cross(b - a, c - a));
      EXPECT_GT(glm::dot(n, a + b + c), 0.0) << "counter-clockwise seen from outside";
      nearest = std::min(nearest, glm::dot(n, a));
      farthest = std::max({farthest, glm::length(a), glm::length(b), glm::length(c)});
    }
    EXPECT_GE(nearest, 1.0 - 1e-5) << "every face's plane clears the unit sphere, level " << level;
    // And hugs it: the corners stick out less as the level rises.
    EXPECT_LT(farthest, level == 1 ? 1.6 : level == 2 ? 1.15 : 1.05) << "level " << level;
  }
}

// ---- In a world ----

// A camera on the ground looking along the horizon, cumulus in the default layers, the clusters
// taking the cumulus over beyond `near_m`.
json cluster_scene(const json& clusters, double sun_elevation_deg = 40.0, const json& clouds = json::object()) {
  json doc = scene({{"core.Camera", {{"position_m", {0, 0, 100}}, {"heading_deg", 200}, {"pitch_deg", 3}, {"ev100", 14}}},
                    {"atmosphere.Atmosphere", json::object()},
                    {"atmosphere.Sun", {{"azimuth_deg", 230}, {"elevation_deg", sun_elevation_deg}}},
                    {"clouds.VolumetricClouds", clouds},
                    {"clouds.CloudClusters", clusters}});
  return doc;
}

const json kClusters = {{"near_m", 3000}, {"crossfade_m", 1000}, {"far_m", 30000}, {"cell_m", 3000}};

// kClusters with some fields changed.
json clusters_with(const json& changes) {
  json c = kClusters;
  c.update(changes);
  return c;
}

std::vector<ClusterPuffGpu> read_puffs(Rendered& r) {
  const ClustersGpu& c = r.world->resource<CloudsGpu>().clusters;
  std::vector<ClusterPuffGpu> puffs(size_t(c.puff_count));
  if (!puffs.empty()) glGetNamedBufferSubData(c.puffs->id(), 0, GLsizeiptr(puffs.size() * sizeof(ClusterPuffGpu)), puffs.data());
  return puffs;
}

std::vector<glm::uvec2> read_order(Rendered& r) {
  const ClustersGpu& c = r.world->resource<CloudsGpu>().clusters;
  std::vector<glm::uvec2> order(size_t(c.puff_count));
  if (!order.empty()) glGetNamedBufferSubData(c.order->id(), 0, GLsizeiptr(order.size() * sizeof(glm::uvec2)), order.data());
  return order;
}

size_t live_puffs(const std::vector<ClusterPuffGpu>& puffs) {
  return size_t(std::count_if(puffs.begin(), puffs.end(), [](const ClusterPuffGpu& p) { return p.extinction_per_density > 0.0f; }));
}

// The sort's key: the distance across the ground (a ray meets the columns of a grid in its order).
double sort_key(const ClusterPuffGpu& p, const glm::dvec3& up) {
  if (p.extinction_per_density <= 0.0f) return -1.0;
  const glm::dvec3 c(p.centre);
  return glm::length(c - glm::dot(c, up) * up);
}

// a before b beyond float's rounding of the GPU's key (columns of a grid tie in distance)
bool nearly_less(double a, double b) { return a < b - 1e-6 * std::abs(b); }

TEST(CloudClusters, PuffsTileTheCellsWhereTheLayersFieldHoldsCloudAndAreDrawnFarToNear) {
  json four = kClusters;
  four["puffs_per_cluster"] = 4;  // 2 x 2 columns per cell
  Rendered r = render(cluster_scene(four), 160, 90);
  ASSERT_TRUE(r.ran("clouds.clusters_place"));
  ASSERT_TRUE(r.ran("clouds.clusters_draw"));
  const std::vector<ClusterPuffGpu> puffs = read_puffs(r);
  ASSERT_EQ(puffs.size(), size_t(40 * 4));
  const size_t live = live_puffs(puffs);
  EXPECT_GT(live, puffs.size() / 4) << "the default cumulus (coverage 0.45) fills most cells in view";
  // Against the CPU's copy of the field (double precision over the same noise): each live puff is a
  // column of half a cell, within the layer's heights and the clusters' ring, whose extinction per
  // unit of the field's is the medium's; and the field holds cloud inside it (8 x 8 x 8 points).
  const CloudsGpu& gpu = r.world->resource<CloudsGpu>();
  const CloudField field(read_noise(gpu), gpu.block, gpu.layers);
  const VolumetricClouds& clouds = r.clouds();
  const double per_density = clouds.scattering_coefficient + clouds.absorption_coefficient;
  const CloudLayer& cumulus = clouds.layers[0];
  const glm::dvec3 up = glm::normalize(glm::dvec3(gpu.block.up));
  // The grid's axes: east is the world's x in the camera's tangent plane (src/placement.cpp).
  const glm::dvec3 east = glm::normalize(glm::dvec3(1, 0, 0) - up * up.x), north = glm::cross(up, east);
  int checked = 0, empty = 0;
  for (const ClusterPuffGpu& p : puffs) {
    if (p.extinction_per_density <= 0.0f) continue;
    const glm::dvec3 c(p.centre), radii(p.radii);
    EXPECT_NEAR(p.extinction_per_density, per_density, 1e-6 * per_density);
    EXPECT_NEAR(radii.x, 0.25 * 3000.0, 1e-3);
    EXPECT_NEAR(radii.y, 0.25 * 3000.0, 1e-3);
    const double rho = glm::length(c);
    EXPECT_GE(rho + glm::length(radii), 3000.0 - 500.0 - 1.0);
    EXPECT_LE(rho - glm::length(radii), 30000.0 + 1.0);
    const double low = field.altitude(c - radii.z * up), high = field.altitude(c + radii.z * up);
    EXPECT_GE(low, cumulus.base_altitude_m - cumulus.base_variation_m - 40.0);
    EXPECT_LE(high, cumulus.base_altitude_m + cumulus.thickness_m + cumulus.base_variation_m + 40.0);
    bool cloud = false;
    for (int i = 0; i < 512 && !cloud; ++i) {
      const glm::dvec3 q = glm::dvec3(i % 8, (i / 8) % 8, i / 64) * (2.0 / 7.0) - 1.0;
      cloud = field.extinction(c + q.x * radii.x * east + q.y * radii.y * north + q.z * radii.z * up, false) > 0.0;
    }
    ++checked;
    empty += !cloud;
  }
  EXPECT_GT(checked, 0);
  EXPECT_LE(empty, checked / 10) << "columns without cloud";

  // The draw order: every slot once, live puffs far to near.
  const std::vector<glm::uvec2> order = read_order(r);
  std::vector<int> seen(puffs.size(), 0);
  double previous = 1e30;
  for (const glm::uvec2& o : order) {
    ASSERT_LT(o.y, puffs.size());
    ++seen[o.y];
    const ClusterPuffGpu& p = puffs[o.y];
    const double d = sort_key(p, up);
    EXPECT_LE(d, previous + 1e-6 * std::abs(previous)) << "far to near";
    previous = d;
  }
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; })) << "a permutation";
}

TEST(CloudClusters, OrderIsSortedAcrossSeveralBlocksOfTheSort) {
  // 48 x 50 = 2400 puffs: a sort of 4096 slots, merged across blocks of 1024.
  json c = kClusters;
  c["clusters"] = 48, c["puffs_per_cluster"] = 50, c["subdivision_level"] = 1;
  Rendered r = render(cluster_scene(c, 40.0, {{"coverage", 1.0}}), 32, 18);
  const std::vector<ClusterPuffGpu> puffs = read_puffs(r);
  const std::vector<glm::uvec2> order = read_order(r);
  ASSERT_EQ(order.size(), size_t(2400));
  EXPECT_GT(live_puffs(puffs), size_t(1024));
  std::vector<double> keys;
  const glm::dvec3 up = glm::normalize(glm::dvec3(r.world->resource<CloudsGpu>().block.up));
  for (const glm::uvec2& o : order) keys.push_back(sort_key(puffs[o.y], up));
  EXPECT_TRUE(std::is_sorted(keys.rbegin(), keys.rend(), nearly_less));
}

TEST(CloudClusters, OrderIsSortedWhenTheSortIsSmallerThanItsRegisterWindow) {
  // 2 x 1, 2 x 3 and 2 x 7 puffs: sorts of 2, 8 and 16 slots, where each invocation's window of pairs
  // (16) is clamped to the whole block.
  for (int puffs_per_cluster : {1, 3, 7}) {
    json c = kClusters;
    c["clusters"] = 2, c["puffs_per_cluster"] = puffs_per_cluster;
    Rendered r = render(cluster_scene(c, 40.0, {{"coverage", 1.0}}), 32, 18);
    const std::vector<ClusterPuffGpu> puffs = read_puffs(r);
    const std::vector<glm::uvec2> order = read_order(r);
    ASSERT_EQ(order.size(), size_t(2 * puffs_per_cluster));
    std::vector<int> seen(puffs.size(), 0);
    std::vector<double> keys;
    const glm::dvec3 up = glm::normalize(glm::dvec3(r.world->resource<CloudsGpu>().block.up));
    for (const glm::uvec2& o : order) {
      ASSERT_LT(o.y, puffs.size());
      ++seen[o.y];
      keys.push_back(sort_key(puffs[o.y], up));
    }
    EXPECT_GE(live_puffs(puffs), size_t(puffs_per_cluster > 1 ? 2 : 1)) << puffs_per_cluster;
    EXPECT_TRUE(std::is_sorted(keys.rbegin(), keys.rend(), nearly_less)) << puffs_per_cluster;
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; })) << puffs_per_cluster;
  }
}

TEST(CloudClusters, ThePuffsMarchConvergesAsItsStepsGrow) {
  auto frame = [](int samples) {
    json c = kClusters;
    c["samples"] = samples;
    Rendered r = render(cluster_scene(c, 15.0), 160, 90);
    return r.renderer->read_hdr();
  };
  const ImageF reference = frame(16);
  std::vector<double> errors;
  for (int samples : {1, 2, 4}) {
    const ImageF img = frame(samples);
    double sum = 0.0;
    for (size_t i = 0; i < img.rgba.size(); ++i)
      if (i % 4 != 3) sum += (double(img.rgba[i]) - reference.rgba[i]) * (double(img.rgba[i]) - reference.rgba[i]);
    errors.push_back(std::sqrt(sum / double(img.rgba.size())));
  }
  EXPECT_GT(errors[0], 0.0);
  EXPECT_LT(errors[1], errors[0]);
  EXPECT_LT(errors[2], errors[1]);
}

TEST(CloudClusters, TheProxyDecidesOnlyWhichPixelsAreTried) {
  // The camera-facing quad and the OpenSubdiv mesh (from its far side) both cover every pixel of
  // every puff, and each pixel's puff is computed exactly: the frames agree.
  auto frame = [](const char* proxy) {
    Rendered r = render(cluster_scene(clusters_with({{"proxy", proxy}})), 96, 54);
    return r.renderer->read_hdr();
  };
  const ImageF quad = frame("quad"), mesh = frame("mesh");
  ASSERT_EQ(quad.rgba.size(), mesh.rgba.size());
  double largest = 0.0, worst = 0.0;
  for (size_t i = 0; i < quad.rgba.size(); ++i) {
    largest = std::max(largest, double(quad.rgba[i]));
    worst = std::max(worst, std::abs(double(quad.rgba[i]) - mesh.rgba[i]));
  }
  EXPECT_LT(worst, 2e-3 * largest);
}

TEST(CloudClusters, NoPuffsLeaveTheFrameAsWithoutTheComponent) {
  json none = kClusters;
  none["clusters"] = 0;
  Rendered with = render(cluster_scene(none), 64, 36);
  EXPECT_FALSE(with.ran("clouds.clusters_draw"));
  json doc = cluster_scene(kClusters);
  remove_entity_with(doc, "clouds.CloudClusters");
  Rendered without = render(doc, 64, 36);
  EXPECT_EQ(with.renderer->read_hdr().rgba, without.renderer->read_hdr().rgba);
}

TEST(CloudClusters, StiffCasesStayFiniteAndNonNegative) {
  struct Case {
    const char* name;
    json clusters, clouds;
    double sun_deg = 40.0;
    glm::dvec3 camera{0, 0, 100};
  };
  json many = {{"clusters", 4000}, {"puffs_per_cluster", 25}, {"cell_m", 1000}, {"far_m", 60000}, {"near_m", 0}, {"subdivision_level", 1}};
  json inside = {{"near_m", 0}, {"crossfade_m", 0}, {"far_m", 20000}, {"cell_m", 2000}};
  const Case cases[] = {
      {"100 000 puffs, overcast", many, {{"coverage", 1.0}}},
      {"coverage 0", kClusters, {{"coverage", 0.0}}},
      {"coverage 1", kClusters, {{"coverage", 1.0}}},
      {"the camera among the puffs", inside, {{"coverage", 1.0}}, 40.0, {0, 0, 2200}},
      {"sun on the horizon", kClusters, json::object(), 0.0},
      {"sun far below (the moon's light)", kClusters, json::object(), -30.0},
      {"16 columns per cell, 100 times as dense", clusters_with({{"puffs_per_cluster", 16}, {"density_scale", 100.0}}), json::object()},
      {"one step", clusters_with({{"samples", 1}}), json::object()},
  };
  for (const Case& c : cases) {
    Rendered r = render_stiff_case(cluster_scene(c.clusters, c.sun_deg, c.clouds), c.camera, c.name);
    const std::vector<ClusterPuffGpu> puffs = read_puffs(r);
    for (const ClusterPuffGpu& p : puffs)
      if (p.extinction_per_density > 0.0f) {
        ASSERT_TRUE(std::isfinite(p.light_depth) && p.light_depth >= 0.0f) << c.name;
        ASSERT_TRUE(std::isfinite(p.light.x) && p.light.x >= 0.0f) << c.name;
      }
    const std::string name = c.name;
    if (name == "coverage 0") {
      EXPECT_EQ(live_puffs(puffs), 0u);
    } else if (name == "coverage 1") {
      EXPECT_GT(live_puffs(puffs), puffs.size() / 2);
    } else if (name == "100 000 puffs, overcast") {
      EXPECT_EQ(puffs.size(), size_t(100000));
    }
  }
}

TEST(CloudClusters, BadSettingsAreOneErrorNamingTheField) {
  auto message = [](const json& doc) -> std::string {
    try {
      Rendered r = render(doc, 16, 9);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  json doc = cluster_scene(kClusters);
  remove_entity_with(doc, "clouds.VolumetricClouds");
  EXPECT_NE(message(doc).find("clouds.VolumetricClouds"), std::string::npos);
  EXPECT_NE(message(cluster_scene(clusters_with({{"layer", 7}}))).find("/layer"), std::string::npos);
  EXPECT_NE(message(cluster_scene(clusters_with({{"clusters", 4096}, {"puffs_per_cluster", 256}}))).find("/puffs_per_cluster"),
            std::string::npos);
  EXPECT_NE(message(cluster_scene(clusters_with({{"far_m", 1000}}))).find("/far_m"), std::string::npos);
  json lod = cluster_scene(kClusters);
  lod["entities"].push_back({{"name", "lod"}, {"components", {{"clouds.CloudLod", {{"min_near_m", 5000}, {"max_near_m", 4000}}}}}});
  EXPECT_NE(message(lod).find("/max_near_m"), std::string::npos);
  EXPECT_NE(message(cluster_scene(clusters_with({{"cell_m", 100}, {"far_m", 1e6}}))).find("/cell_m"), std::string::npos);
}

TEST(CloudLod, TheHandOverFollowsTheFramesBudget) {
  // A budget no frame meets pulls the hand-over in to min_near_m; one every frame meets pushes it
  // out to max_near_m; a frame rendered alone (a sequence's) keeps the clusters' own near_m.
  for (const auto& [budget_ms, expected] : {std::pair{1e-4, 2000.0}, std::pair{1000.0, 20000.0}}) {
    json doc = cluster_scene(kClusters);
    doc["entities"].push_back({{"name", "lod"},
                               {"components", {{"clouds.CloudLod", {{"budget_ms", budget_ms}, {"min_near_m", 2000}, {"max_near_m", 20000}, {"rate", 0.5}}}}}});
    Rendered r = render(doc, 32, 18);
    for (int i = 0; i < 8; ++i) r.frame(32, 18);
    const CloudsGpu& gpu = r.world->resource<CloudsGpu>();
    EXPECT_NEAR(gpu.clusters_near_m, expected, 1e-3 * expected) << "budget " << budget_ms << " ms";
    ASSERT_GE(gpu.clusters_layer, 0);
    EXPECT_NEAR(gpu.layers[size_t(gpu.clusters_layer)].handover_near_m, expected, 1e-3 * expected) << "the march's hand-over";
    r.renderer->render_frame({.index = 50, .alone = true}, 32, 18);
    EXPECT_EQ(gpu.clusters_near_m, 3000.0f) << "a frame rendered alone";
  }
}

// Clusters at noon and at sunset, looked at before they were committed.
TEST(CloudClustersGolden, NoonAndSunset) {
  const welkin::testing::GoldenTolerance tolerance{.max_channel_difference = 10, .max_failing_fraction = 0.02};
  for (const auto& [sun, name] : {std::pair{40.0, "clouds/clusters_noon"}, std::pair{4.0, "clouds/clusters_sunset"}}) {
    Rendered r = render(cluster_scene(kClusters, sun), 160, 90);
    r.renderer->render_frame({.index = 1, .alone = true}, 160, 90);
    const auto res = welkin::testing::compare_with_golden(r.renderer->read_output(), name, tolerance);
    EXPECT_TRUE(res.passed) << name << ": " << res.message;
  }
}

}  // namespace
}  // namespace welkin::clouds::test
