#include "welkin/clouds/components.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "welkin/core/error.h"

namespace welkin::clouds {

namespace {
// The enum's names for JSON, the inspector and sequences, from the genus table.
std::vector<EnumValue> genus_values() {
  std::vector<EnumValue> values;
  for (const GenusTraits& g : kGenera) values.push_back({g.name, int(g.genus)});
  return values;
}
}  // namespace

const GenusTraits& genus_traits(Genus genus) {
  const int i = int(genus);
  if (i < 0 || i >= kGenusCount)
    throw Error(ErrorInfo{.path = "genus",
                          .expected = "one of the " + std::to_string(kGenusCount) + " genera",
                          .found = std::to_string(i)});
  return kGenera[i];
}

const char* genus_name(Genus genus) {
  return genus_traits(genus).name;
}

void describe(TypeBuilder<CloudLayer>& t) {
  t.tooltip("One layer of clouds: altitude, thickness, genus, coverage, density and its profile over height");
  t.field("genus", &CloudLayer::genus)
      .values(genus_values())
      .tooltip("Shape model: domes with flat bases, sheets, rolls or streaks");
  t.field("base_altitude_m", &CloudLayer::base_altitude_m)
      .unit("m")
      .range(0, 100000)
      .tooltip("Cloud base above the surface");
  t.field("thickness_m", &CloudLayer::thickness_m).unit("m").range(0, 20000).tooltip("0 disables the layer");
  t.field("coverage", &CloudLayer::coverage)
      .range(0, 1)
      .tooltip("Fraction of the sky covered (0 clear, 1 overcast)");
  t.field("density_per_m", &CloudLayer::density_per_m)
      .unit("1/m")
      .range(0, 100)
      .tooltip("Extinction at full density");
  t.field("shape_amount", &CloudLayer::shape_amount).range(0, 1);
  t.field("detail_amount", &CloudLayer::detail_amount).range(0, 1);
  t.field("coverage_filter_width", &CloudLayer::coverage_filter_width)
      .range(0.01, 1)
      .tooltip("Softness of the weather's edge");
  t.field("base_variation_m", &CloudLayer::base_variation_m)
      .unit("m")
      .range(0, 5000)
      .tooltip("How far the base moves with the weather");
  t.field("profile_exp_term", &CloudLayer::profile_exp_term).range(-100, 100);
  t.field("profile_exponent", &CloudLayer::profile_exponent).range(-100, 100);
  t.field("profile_linear_term", &CloudLayer::profile_linear_term).range(-100, 100);
  t.field("profile_constant_term", &CloudLayer::profile_constant_term).range(-100, 100);
  t.field("wind_mps", &CloudLayer::wind_mps)
      .unit("m/s")
      .range(-200, 200)
      .tooltip("Drift of the layer's weather (east, north)");
  t.field("casts_shadow", &CloudLayer::casts_shadow)
      .tooltip(
          "Included in the shadow map on materials (off, above every layer that casts: a deck that still "
          "dims the clouds under it)");
  t.field("follows_coverage_map", &CloudLayer::follows_coverage_map)
      .tooltip("The painted coverage map adds to this layer's coverage");
  t.field("visible", &CloudLayer::visible).tooltip("Drawn (and casting its shadow)");
  t.field("solo", &CloudLayer::solo).tooltip("While any layer is soloed, only soloed layers are drawn");
}

std::vector<CloudLayer> VolumetricClouds::default_layers() {
  return {CloudLayer{
              .genus = Genus::cumulus, .base_altitude_m = 1500.0f, .thickness_m = 1400.0f, .coverage = 0.45f},
          CloudLayer{.genus = Genus::altostratus,
                     .base_altitude_m = 5500.0f,
                     .thickness_m = 600.0f,
                     .coverage = 0.3f,
                     .density_per_m = 0.004f,
                     .shape_amount = 0.5f,
                     .detail_amount = 0.3f,
                     .coverage_filter_width = 0.8f,
                     .base_variation_m = 300.0f,
                     .profile_linear_term = 0.0f,
                     .profile_constant_term = 1.0f,
                     .wind_mps = {12.0f, 3.0f},
                     .casts_shadow = false}};
}

void describe(TypeBuilder<VolumetricClouds>& t) {
  t.tooltip("Volumetric cloud layers on the spherical planet, raymarched and lit by the atmosphere");
  t.validate(validate);
  t.field("quality", &VolumetricClouds::quality)
      .values({{"low", 0}, {"medium", 1}, {"high", 2}, {"ultra", 3}, {"custom", 4}});
  t.field("coverage", &VolumetricClouds::coverage).range(0, 1).tooltip("Scales every layer's coverage");
  t.field("scattering_coefficient", &VolumetricClouds::scattering_coefficient).range(0, 10);
  t.field("absorption_coefficient", &VolumetricClouds::absorption_coefficient).range(0, 10);
  t.field("phase", &VolumetricClouds::phase).values({{"dual_lobe_hg", 0}, {"droplet_mie", 1}});
  t.field("phase_g_forward", &VolumetricClouds::phase_g_forward).range(-0.9999, 0.9999);
  t.field("phase_g_backward", &VolumetricClouds::phase_g_backward).range(-0.9999, 0.9999);
  t.field("phase_mix", &VolumetricClouds::phase_mix).range(0, 1).tooltip("Weight of the forward lobe");
  t.field("droplet_diameter_um", &VolumetricClouds::droplet_diameter_um)
      .unit("um")
      .range(5, 50)
      .tooltip("droplet_mie only");
  t.field("multiple_scattering", &VolumetricClouds::multiple_scattering)
      .values({{"octaves", 0}, {"diffusion", 1}});
  t.field("multiscattering_octaves", &VolumetricClouds::multiscattering_octaves).range(1, 16);
  t.field("powder", &VolumetricClouds::powder)
      .range(0, 1)
      .tooltip("Darkens thin edges facing the sun (not physical; 0: off)");
  t.field("aerial_perspective", &VolumetricClouds::aerial_perspective)
      .values({{"per_sample", 0}, {"mean_depth", 1}})
      .tooltip(
          "Air in front of the clouds: per sample, or at their mean distance (cheaper, wrong where sparse "
          "clouds overlap)");
  t.field("ground_albedo", &VolumetricClouds::ground_albedo)
      .range(0, 1)
      .tooltip("Ground bounce on the cloud bases");
  t.field("max_steps", &VolumetricClouds::max_steps).range(1, 4096).tooltip("quality custom");
  t.field("min_step_m", &VolumetricClouds::min_step_m).unit("m").range(1, 100000).tooltip("quality custom");
  t.field("max_step_m", &VolumetricClouds::max_step_m).unit("m").range(1, 100000).tooltip("quality custom");
  t.field("step_growth", &VolumetricClouds::step_growth)
      .range(0, 0.1)
      .tooltip("quality custom: metres of step per metre of distance");
  t.field("light_steps", &VolumetricClouds::light_steps).range(0, 64).tooltip("quality custom");
  t.field("light_step_m", &VolumetricClouds::light_step_m)
      .unit("m")
      .range(1, 100000)
      .tooltip("quality custom");
  t.field("max_distance_m", &VolumetricClouds::max_distance_m).unit("m").range(100, 1e8);
  t.field("shape_detail", &VolumetricClouds::shape_detail).tooltip("quality custom");
  t.field("resolution_scale", &VolumetricClouds::resolution_scale)
      .range(0.0625, 1)
      .tooltip("quality custom: fraction of the frame marched");
  t.field("temporal_upscaling", &VolumetricClouds::temporal_upscaling)
      .tooltip("March one pixel of each block per frame, reproject the rest");
  t.field("temporal_block", &VolumetricClouds::temporal_block)
      .range(2, 4)
      .tooltip("quality custom: 2 (a quarter of the pixels per frame) or 4 (a sixteenth)");
  t.field("temporal_clipping", &VolumetricClouds::temporal_clipping)
      .tooltip("Clip reprojected history to this frame's samples (against ghosting)");
  t.field("march_silhouettes", &VolumetricClouds::march_silhouettes)
      .tooltip("March every frame the pixels next to the last frame's silhouettes (temporal upscaling)");
  t.field("skip_empty_front", &VolumetricClouds::skip_empty_front)
      .tooltip("Start each ray where the last frame's rays around it met no cloud (temporal upscaling)");
  t.field("shadows", &VolumetricClouds::shadows).tooltip("Cloud shadows and sky occlusion on every material");
  t.field("shadow_map_size", &VolumetricClouds::shadow_map_size).unit("px").range(16, 4096);
  t.field("shadow_distance_m", &VolumetricClouds::shadow_distance_m).unit("m").range(100, 1e6);
  t.field("shadow_cascades", &VolumetricClouds::shadow_cascades)
      .range(1, 4)
      .tooltip("Each nearer cascade covers a quarter of the side of the last");
  t.field("seed", &VolumetricClouds::seed).range(0, 1 << 30);
  t.field("shape_period_m", &VolumetricClouds::shape_period_m).unit("m").range(10, 1e6);
  t.field("detail_period_m", &VolumetricClouds::detail_period_m).unit("m").range(1, 1e5);
  t.field("weather_period_m", &VolumetricClouds::weather_period_m).unit("m").range(100, 1e8);
  t.field("weather_system_amount", &VolumetricClouds::weather_system_amount)
      .range(0, 1)
      .tooltip(
          "Weight of the planet-scale weather systems in every layer's weather (0: the local weather alone)");
  t.field("weather_system_period_m", &VolumetricClouds::weather_system_period_m)
      .unit("m")
      .range(1e4, 1e8)
      .tooltip("The weather systems' signal repeats over this");
  t.field("wind_mps", &VolumetricClouds::wind_mps).unit("m/s").range(-200, 200);
  t.field("turbulence", &VolumetricClouds::turbulence)
      .tooltip("quality custom: curl noise stirs the cloud bases");
  t.field("turbulence_displacement_m", &VolumetricClouds::turbulence_displacement_m)
      .unit("m")
      .range(0, 10000)
      .tooltip("How far the curl field moves the detail noise at a layer's base (none above its lowest 30%)");
  t.field("coverage_map", &VolumetricClouds::coverage_map)
      .tooltip(
          "Grey PNG of painted coverage around the scene's origin (128: unchanged, 255: overcast, 0: clear); "
          "the editor paints it");
  t.field("coverage_map_size_m", &VolumetricClouds::coverage_map_size_m)
      .unit("m")
      .range(1000, 2e7)
      .tooltip("Side of the square the coverage map covers");
  t.field("layers", &VolumetricClouds::layers).max_count(256);
}

void describe(TypeBuilder<CloudClusters>& t) {
  t.tooltip(
      "Mid-range clouds: one volumetric layer drawn as clusters of lit puffs, handed over from the raymarch "
      "by distance");
  t.validate(validate);
  t.field("layer", &CloudClusters::layer)
      .range(0, 255)
      .tooltip("Index of the clouds.VolumetricClouds layer the clusters draw");
  t.field("clusters", &CloudClusters::clusters).range(0, 4096).tooltip("At most this many, nearest first");
  t.field("puffs_per_cluster", &CloudClusters::puffs_per_cluster).range(0, 256);
  t.field("cell_m", &CloudClusters::cell_m)
      .unit("m")
      .range(100, 100000)
      .tooltip("At most one cluster per cell of this side");
  t.field("near_m", &CloudClusters::near_m)
      .unit("m")
      .range(0, 1e6)
      .tooltip("The raymarch draws the layer nearer than this");
  t.field("crossfade_m", &CloudClusters::crossfade_m)
      .unit("m")
      .range(0, 1e5)
      .tooltip("Width of the hand-over between the two paths");
  t.field("far_m", &CloudClusters::far_m)
      .unit("m")
      .range(100, 1e6)
      .tooltip("The raymarch draws the layer again beyond this");
  t.field("density_scale", &CloudClusters::density_scale)
      .range(0, 100)
      .tooltip("The puffs' extinction per unit of the field's");
  t.field("samples", &CloudClusters::samples)
      .range(1, 16)
      .tooltip("Steps of each pixel's march through a puff");
  t.field("compositing", &CloudClusters::compositing)
      .values({{"sorted", 0}, {"unsorted", 1}})
      .tooltip("Back to front (sorted on the GPU), or in placement order (shows what sorting fixes)");
  t.field("proxy", &CloudClusters::proxy)
      .values({{"quad", 0}, {"mesh", 1}})
      .tooltip(
          "What each puff rasterises: a screen-facing quad, or the OpenSubdiv-refined mesh (the surface is "
          "exact either way)");
  t.field("subdivision_level", &CloudClusters::subdivision_level)
      .range(1, 4)
      .tooltip("The puff proxy mesh's OpenSubdiv level");
  t.field("resolution_scale", &CloudClusters::resolution_scale)
      .range(0.25, 1)
      .tooltip("Fraction of the frame's width and height the puffs are drawn at");
  t.field("seed", &CloudClusters::seed).range(0, 1 << 30);
}

// The placement grid reaches far_m on every side of the camera in cells of cell_m: at most
// kMaxClusterGrid across.
static void check_cell_grid(float far_m, float cell_m) {
  if (2.0 * std::ceil(double(far_m) / cell_m) > kMaxClusterGrid)
    throw Error(ErrorInfo{.path = "/cell_m",
                          .expected = "at least far_m / " + std::to_string(kMaxClusterGrid / 2) + " (" +
                                      std::to_string(far_m / float(kMaxClusterGrid / 2)) + " m): at most " +
                                      std::to_string(kMaxClusterGrid) + " cells across",
                          .found = std::to_string(cell_m)});
}

void validate(const CloudClusters& c) {
  if (int64_t(c.clusters) * c.puffs_per_cluster > kMaxClusterPuffs)
    throw Error(ErrorInfo{.path = "/puffs_per_cluster",
                          .expected = "clusters x puffs_per_cluster at most " +
                                      std::to_string(kMaxClusterPuffs) + " (at most " +
                                      std::to_string(kMaxClusterPuffs / std::max(c.clusters, 1)) + " with " +
                                      std::to_string(c.clusters) + " clusters)",
                          .found = std::to_string(c.puffs_per_cluster)});
  if (!(c.far_m > c.near_m))
    throw Error(ErrorInfo{.path = "/far_m",
                          .expected = "more than near_m (" + std::to_string(c.near_m) + ")",
                          .found = std::to_string(c.far_m)});
  check_cell_grid(c.far_m, c.cell_m);
}

void describe(TypeBuilder<CloudBillboards>& t) {
  t.tooltip("Far clouds: one volumetric layer drawn as relightable impostors baked from its own field");
  t.validate(validate);
  t.field("layer", &CloudBillboards::layer)
      .range(0, 255)
      .tooltip("Index of the clouds.VolumetricClouds layer the billboards draw");
  t.field("billboards", &CloudBillboards::billboards)
      .range(0, kMaxBillboards)
      .tooltip("At most this many, nearest first");
  t.field("cell_m", &CloudBillboards::cell_m)
      .unit("m")
      .range(500, 100000)
      .tooltip("One billboard per cell of this side; an archetype is as wide");
  t.field("near_m", &CloudBillboards::near_m)
      .unit("m")
      .range(0, 1e7)
      .tooltip("Without clusters on the layer, the raymarch draws it nearer than this");
  t.field("crossfade_m", &CloudBillboards::crossfade_m)
      .unit("m")
      .range(0, 1e5)
      .tooltip("Width of the hand-overs");
  t.field("far_m", &CloudBillboards::far_m)
      .unit("m")
      .range(100, 1e7)
      .tooltip("The raymarch draws the layer again beyond this");
  t.field("density_scale", &CloudBillboards::density_scale)
      .range(0, 100)
      .tooltip("Scales the archetypes' optical depth");
  t.field("archetypes", &CloudBillboards::archetypes)
      .range(1, 16)
      .tooltip("Clouds baked from the layer's field");
  t.field("atlas_resolution", &CloudBillboards::atlas_resolution)
      .range(4, 128)
      .tooltip("Texels per side of each view");
  t.field("view_azimuths", &CloudBillboards::view_azimuths)
      .range(1, 32)
      .tooltip("Views around each archetype");
  t.field("view_elevations", &CloudBillboards::view_elevations)
      .range(1, 8)
      .tooltip("Rows of views, 37 degrees below the horizon to 37 above");
  t.field("render", &CloudBillboards::render)
      .values({{"impostor", 0}, {"volume", 1}})
      .tooltip(
          "The impostor, or the reference it is measured against (each pixel marched through the baked "
          "volume)");
  t.field("resolution_scale", &CloudBillboards::resolution_scale)
      .range(0.25, 1)
      .tooltip("Fraction of the frame's width and height the billboards are drawn at");
  t.field("seed", &CloudBillboards::seed).range(0, 1 << 30);
}

void validate(const CloudBillboards& b) {
  const int64_t layers = int64_t(b.archetypes) * b.view_azimuths * b.view_elevations * 2;
  if (layers > kMaxBillboardAtlasLayers)
    throw Error(ErrorInfo{.path = "/view_azimuths",
                          .expected = "archetypes x view_azimuths x view_elevations at most " +
                                      std::to_string(kMaxBillboardAtlasLayers / 2),
                          .found = std::to_string(layers / 2)});
  // Memory bounded before it is spent: the archetypes' volumes (up to atlas_resolution voxels on
  // every side, 4 bytes each) and the atlas (8 bytes a texel). The fill beside each (a byte a voxel
  // and a texel, src/billboards.cpp) is a quarter of the one and a sixteenth of the other, each a
  // texture of its own within the same bound.
  const int64_t r = b.atlas_resolution;
  if (r * r * r * b.archetypes * 4 > kMaxBillboardVolumeBytes)
    throw Error(ErrorInfo{
        .path = "/archetypes",
        .expected = "archetypes x atlas_resolution^3 x 4 bytes at most " +
                    std::to_string(kMaxBillboardVolumeBytes >> 20) + " MiB (at most " +
                    std::to_string(std::max<int64_t>(kMaxBillboardVolumeBytes / (r * r * r * 4), 0)) +
                    " archetypes at " + std::to_string(r) + " texels)",
        .found = std::to_string(b.archetypes)});
  if (r * r * layers * 8 > kMaxBillboardAtlasBytes)
    throw Error(
        ErrorInfo{.path = "/atlas_resolution",
                  .expected = "atlas_resolution^2 x archetypes x views x 2 layers x 8 bytes at most " +
                              std::to_string(kMaxBillboardAtlasBytes >> 20) + " MiB",
                  .found = std::to_string(r) + " (" + std::to_string((r * r * layers * 8) >> 20) + " MiB)"});
  if (!(b.far_m > b.near_m))
    throw Error(ErrorInfo{.path = "/far_m",
                          .expected = "more than near_m (" + std::to_string(b.near_m) + ")",
                          .found = std::to_string(b.far_m)});
  check_cell_grid(b.far_m, b.cell_m);
}

void describe(TypeBuilder<CloudLod>& t) {
  t.tooltip(
      "Moves the raymarch's hand-over to the mesh clusters to keep the clouds within a GPU budget per frame");
  t.validate(validate);
  t.field("budget_ms", &CloudLod::budget_ms)
      .unit("ms")
      .range(0, 1000)
      .tooltip("GPU time for the clouds' systems together; 0: the clusters' distances as set");
  t.field("min_near_m", &CloudLod::min_near_m)
      .unit("m")
      .range(0, 1e6)
      .tooltip("The hand-over comes no nearer than this");
  t.field("max_near_m", &CloudLod::max_near_m).unit("m").range(0, 1e6).tooltip("and goes no farther");
  t.field("rate", &CloudLod::rate).range(0.001, 0.5).tooltip("Fraction the hand-over moves per frame");
}

void validate(const CloudLod& c) {
  if (!(c.max_near_m >= c.min_near_m))
    throw Error(ErrorInfo{.path = "/max_near_m",
                          .expected = "at least min_near_m (" + std::to_string(c.min_near_m) + ")",
                          .found = std::to_string(c.max_near_m)});
}

ResolvedQuality resolve_quality(const VolumetricClouds& c) {
  switch (c.quality) {
    case Quality::low:
      return {64, 120.0f, 2000.0f, 2, 150.0f, false, 0.25f, 0.012f, 4, false};
    case Quality::medium:
      return {128, 70.0f, 1200.0f, 3, 100.0f, true, 0.4f, 0.008f, 4, false};
    case Quality::high:
      return {256, 40.0f, 800.0f, 3, 80.0f, true, 0.5f, 0.005f, 2, true};
    case Quality::ultra:
      return {768, 20.0f, 500.0f, 6, 50.0f, true, 1.0f, 0.002f, 2, true};
    case Quality::custom:
      break;
  }
  return {c.max_steps,    c.min_step_m,       c.max_step_m,  c.light_steps,    c.light_step_m,
          c.shape_detail, c.resolution_scale, c.step_growth, c.temporal_block, c.turbulence};
}

void validate(const VolumetricClouds& c) {
  if (c.shadow_map_size * c.shadow_cascades > 8192)
    throw Error(ErrorInfo{.path = "/shadow_map_size",
                          .expected = "at most 8192 / shadow_cascades (" +
                                      std::to_string(8192 / c.shadow_cascades) +
                                      "): the cascades lie side by side in one texture",
                          .found = std::to_string(c.shadow_map_size)});
  if (c.temporal_block != 2 && c.temporal_block != 4)
    throw Error(ErrorInfo{
        .path = "/temporal_block", .expected = "2 or 4", .found = std::to_string(c.temporal_block)});
  if (c.max_step_m < c.min_step_m)
    throw Error(ErrorInfo{.path = "/max_step_m",
                          .expected = "at least min_step_m (" + std::to_string(c.min_step_m) + ")",
                          .found = std::to_string(c.max_step_m)});
  // A ray's work is bounded before it is spent: each march step may run a light march.
  if (c.quality == Quality::custom && int64_t(c.max_steps) * (1 + c.light_steps) > kMaxSamplesPerRay)
    throw Error(
        ErrorInfo{.path = "/max_steps",
                  .expected = "max_steps x (1 + light_steps) at most " + std::to_string(kMaxSamplesPerRay) +
                              " density samples per ray (at most " +
                              std::to_string(kMaxSamplesPerRay / (1 + c.light_steps)) + " steps with " +
                              std::to_string(c.light_steps) + " light steps; ultra takes 5376)",
                  .found = std::to_string(c.max_steps)});
  if (c.detail_period_m > c.shape_period_m)
    throw Error(ErrorInfo{.path = "/detail_period_m",
                          .expected = "at most shape_period_m (" + std::to_string(c.shape_period_m) +
                                      "): detail is finer than shape",
                          .found = std::to_string(c.detail_period_m)});
}

}  // namespace welkin::clouds
