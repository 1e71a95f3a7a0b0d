#pragma once
// Components of the clouds module. Plain reflected structs: the reflection in src/components.cpp is
// the single source of their JSON form, units, ranges, the editor inspector and sequence tracks
// (`clouds.VolumetricClouds/layers/0/coverage`). Lengths are metres, extinction 1/m.
#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "welkin/clouds/genera.h"
#include "welkin/core/reflection.h"

namespace welkin::clouds {

// One layer of clouds. Density at a point = weather (coverage) x vertical envelope x profile,
// eroded by the shape and detail noise, times density_per_m.
struct CloudLayer {
  static constexpr std::string_view kTypeName = "clouds.CloudLayer";
  Genus genus = Genus::cumulus;
  float base_altitude_m = 1500.0f;  // above the planet's surface
  float thickness_m = 1500.0f;      // 0 disables the layer
  float coverage = 0.45f;           // fraction of the sky the layer covers, 0..1
  float density_per_m = 0.05f;      // extinction at full density (1/m): cumulus 0.02-0.1
  float shape_amount = 1.0f;        // erosion by the Perlin-Worley shape noise
  float detail_amount = 1.0f;       // erosion by the Worley detail noise at the edges
  float coverage_filter_width = 0.6f;  // 0: hard edge at the weather signal, 1: a linear ramp
  float base_variation_m = 150.0f;     // the base rises and falls with the weather (bases do not line up)
  // Density over the height fraction h in [0, 1]: exp_term * exp(exponent * h) + linear_term * h +
  // constant_term.
  float profile_exp_term = 0.0f;
  float profile_exponent = 0.0f;
  float profile_linear_term = 0.75f;
  float profile_constant_term = 0.25f;
  glm::vec2 wind_mps{0.0f, 0.0f};  // drift of this layer's weather (east, north)
  bool casts_shadow = true;
  // the painted coverage map (VolumetricClouds::coverage_map) adds to its coverage
  bool follows_coverage_map = true;
  // Drawn or not, as in a mixer: while any layer is soloed, only soloed layers are drawn. A layer
  // looks the same alone as among the others (it keeps its place in the weather).
  bool visible = true;
  bool solo = false;
};
void describe(TypeBuilder<CloudLayer>& t);

enum class Quality : int { low = 0, medium = 1, high = 2, ultra = 3, custom = 4 };
// Dual-lobe Henyey-Greenstein, or Jendersie & d'Eon 2023's fit of Mie scattering by water droplets
// (a Henyey-Greenstein and a Draine lobe, parameterised by the droplet diameter).
enum class PhaseModel : int { dual_lobe_hg = 0, droplet_mie = 1 };
// Light scattered more than once: Wrenninge 2015's octaves (takram's, Frostbite's), or single
// scattering plus the diffuse light of a conservative slab (the two-stream transmittance toward the
// light, 1 / (1 + 0.75 (1 - g) tau), less its direct part), which stays right in thick decks where
// the octaves' exponentials starve.
enum class MultipleScattering : int { octaves = 0, diffusion = 1 };
// How the air between the camera and the clouds is applied: at every sample (each sample's light
// through the air in front of it, and the air's light in front of each opacity step), or once at the
// opacity-weighted mean distance (takram's: cheaper, wrong where distant sparse clouds overlap).
enum class CloudAerialPerspective : int { per_sample = 0, mean_depth = 1 };

struct VolumetricClouds {
  static constexpr std::string_view kTypeName = "clouds.VolumetricClouds";
  Quality quality = Quality::high;
  float coverage = 1.0f;  // scales every layer's coverage (sequences drive it)
  // Scattering and absorption per unit of a layer's density (single-scattering albedo ~ 1 for water).
  float scattering_coefficient = 1.0f;
  float absorption_coefficient = 0.0f;
  PhaseModel phase = PhaseModel::dual_lobe_hg;
  float phase_g_forward = 0.7f;
  float phase_g_backward = -0.2f;
  float phase_mix = 0.5f;            // weight of the forward lobe
  float droplet_diameter_um = 10.0f; // droplet_mie: 5-50 um
  MultipleScattering multiple_scattering = MultipleScattering::diffusion;
  int multiscattering_octaves = 8;   // Wrenninge's octaves (1: single scattering only)
  float powder = 0.0f;               // Schneider's "beer-powder" darkening of thin edges (0: off)
  float ground_albedo = 0.3f;        // ground bounce lighting the cloud bases
  CloudAerialPerspective aerial_perspective = CloudAerialPerspective::per_sample;
  // Marching (quality custom; the presets set them otherwise).
  int max_steps = 384;
  float min_step_m = 40.0f;
  float max_step_m = 800.0f;
  float step_growth = 0.004f;  // steps lengthen by this many metres per metre of distance
  int light_steps = 4;
  float light_step_m = 80.0f;  // first step toward the sun; each next one doubles
  float max_distance_m = 200000.0f;
  bool shape_detail = true;
  float resolution_scale = 0.5f;  // the march runs at this fraction of the frame's width and height
  // March one pixel of each block (temporal_block x temporal_block: 2 or 4) per frame and reproject
  // the rest from the last frame, clipped to this frame's samples (not where the camera is in a cloud).
  bool temporal_upscaling = true;
  int temporal_block = 2;  // quality custom
  bool temporal_clipping = true;  // off: plain reprojection (for measuring what clipping saves)
  // With temporal upscaling in 2 x 2 blocks (`high`, `ultra`): the pixels next to the last frame's
  // strongest silhouettes (its opacity changes by more than 0.5 within 3 x 3 pixels) are listed and
  // marched every frame too, not reprojected (issue 35): a sixth of the error there
  // (docs/performance.md, "Silhouettes after the temporal upscaling").
  bool march_silhouettes = true;
  // With temporal upscaling: each ray starts where the last frame's rays around it met no cloud, less
  // how far the camera and the clouds moved; one block in eight is marched whole each frame in turn.
  // Off by default: on llvmpipe it saved nothing measurable (README, "Empty space in front").
  bool skip_empty_front = false;
  // Shadows on every material (a beer shadow map from the sun around the camera) and sky occlusion.
  bool shadows = true;
  int shadow_map_size = 256;          // per cascade
  float shadow_distance_m = 30000.0f;  // half the side of the largest cascade
  int shadow_cascades = 3;             // each nearer one a quarter of the last one's side
  // Noise: generated on the GPU from the seed, tileable; each texture repeats over its period.
  int seed = 1;
  float shape_period_m = 4000.0f;
  float detail_period_m = 300.0f;
  float weather_period_m = 40000.0f;
  // Weather systems: a signal g over thousands of kilometres (fronts and highs) that raises every
  // layer's coverage where g > 0.5 and lowers it where g < 0.5, by up to amount x 4 c (1 - c), so
  // that a view from orbit or a long flight shows regions of more and less cloud instead of the local
  // weather repeating. g is 0.5 at the scene's origin (its layers have their own coverage there) and
  // the systems do not drift; 0 and 1 stay clear and overcast, and the planet's mean coverage stays c
  // (the fraction of sky the eye sees covered rises: the noise erodes thin coverage more). 0: off.
  float weather_system_amount = 0.5f;
  float weather_system_period_m = 3.0e6f;
  glm::vec2 wind_mps{6.0f, 2.0f};  // drift of the shape noise (east, north)
  // Curl turbulence (quality custom; high and ultra on, low and medium off, as takram): a
  // divergence-free field (repeating with the shape noise) displaces where the detail noise is read,
  // by up to turbulence_displacement_m at a layer's base, fading out over its lowest 30% (Schneider
  // 2015), so bases look stirred by the wind; the displacement moves the noise without compressing it.
  bool turbulence = true;
  float turbulence_displacement_m = 350.0f;  // takram's default
  // Coverage painted over the planet (the editor's brush; welkin/scene/painted_map.h): a grey PNG,
  // a square of coverage_map_size_m centred on the ground below the scene's origin. A texel v adds
  // (v - 128) / 127 to the coverage of the layers that follow it: 128 changes nothing, 255 makes
  // them overcast, 0 clears them. It stays where it was painted (the wind moves the noise, not it).
  std::string coverage_map;  // file name; empty: none
  float coverage_map_size_m = 100000.0f;
  std::vector<CloudLayer> layers = default_layers();

  // Partly cloudy: cumulus at 1.5 km and a thin altostratus at 5.5 km.
  static std::vector<CloudLayer> default_layers();
};
void describe(TypeBuilder<VolumetricClouds>& t);

// How overlapping puffs are composited: drawn back to front by their centres' distance (sorted on
// the GPU each frame), or in the order they were placed (kept to show what sorting fixes).
enum class ClusterCompositing : int { sorted = 0, unsorted = 1 };
// What each puff rasterises: a quad over its box's screen rectangle, or the OpenSubdiv-refined closed
// mesh around the box (its far side). Each pixel marches the box's chord either way; the proxy only
// decides which pixels are tried, and what that costs.
enum class PuffProxy : int { quad = 0, mesh = 1 };

// Mesh-cluster clouds: one layer of the VolumetricClouds drawn at mid range in the cells of a grid
// that drifts with its wind, where that layer's weather holds cloud: each cell's puffs are boxes that
// tile it in columns through the layer (instanced, one draw), and each pixel marches the layer's own
// field through them in a few steps, lit by the clouds' shadow map. The volumetric
// path draws the layer nearer than near_m and beyond far_m, and cross-fades with the puffs over
// crossfade_m at both ends (their densities add up to the field's). Clusters fill the ring nearest
// first: far_m should leave room for about clusters / coverage cells of cell_m.
struct CloudClusters {
  static constexpr std::string_view kTypeName = "clouds.CloudClusters";
  int layer = 0;                 // index in clouds.VolumetricClouds/layers
  int clusters = 40;             // at most this many, nearest first, where the layer's weather holds cloud
  int puffs_per_cluster = 1;     // n x n columns tile each cell (n: the integer square root)
  float cell_m = 4000.0f;  // at most one cluster per cell of this side (cells drift with the layer's wind)
  float near_m = 8000.0f;        // the volumetric path draws the layer nearer than this
  float crossfade_m = 2000.0f;   // over which the two paths hand over
  float far_m = 25000.0f;        // and beyond this
  float density_scale = 1.0f;    // the puffs' extinction per unit of the field's
  int samples = 1;               // equal steps of each pixel's march through a puff
  ClusterCompositing compositing = ClusterCompositing::sorted;
  PuffProxy proxy = PuffProxy::quad;
  int subdivision_level = 2;     // of the puff's proxy mesh (OpenSubdiv, Catmull-Clark from a cube)
  float resolution_scale = 0.25f; // the puffs are drawn at this fraction of the frame's width and height
  int seed = 7;
};
void describe(TypeBuilder<CloudClusters>& t);
// What the billboards draw: the impostor (the atlas, relit), or the reference it is measured
// against (each pixel marched through the archetype's baked volume and lit through a march).
enum class BillboardRender : int { impostor = 0, volume = 1 };

// Billboard clouds: one layer of the VolumetricClouds drawn far away as impostors. A few archetype
// clouds are baked from the layer's own field (its genus, profile and noise, at its coverage) into
// small extinction volumes, and from those into an atlas of views holding what relighting needs at
// any time of day (optical depth, the depth and height of the point that hides half of the
// opacity, and the diffuse transmittance toward every direction as spherical harmonics), never a
// colour. Each frame a billboard stands in each of the nearest cells (of cell_m) whose weather
// holds cloud, with an archetype drawn from the cell's hash, and is lit like the march. Beyond the
// mesh clusters of the same layer they start where those end; without them at near_m. The raymarch
// draws the layer again beyond far_m. The bake is remade when the layer's description, its
// coverage (to 0.05) or these settings change.
struct CloudBillboards {
  static constexpr std::string_view kTypeName = "clouds.CloudBillboards";
  int layer = 0;                  // index in clouds.VolumetricClouds/layers
  int billboards = 64;            // at most this many, nearest first, where the layer's weather holds cloud
  float cell_m = 8000.0f;         // one billboard per cell of this side; the archetypes' box is as wide
  float near_m = 25000.0f;        // without clusters on the layer: the raymarch draws it nearer than this
  float crossfade_m = 3000.0f;
  // the raymarch draws the layer again beyond this (64 billboards of 8 km reach about 50 km)
  float far_m = 50000.0f;
  float density_scale = 1.0f;     // scales the archetypes' optical depth
  int archetypes = 4;
  int atlas_resolution = 32;      // texels per side of a view (and voxels across an archetype's volume)
  int view_azimuths = 8;
  int view_elevations = 5;        // rows of views from 37 degrees below the horizon to 37 above
  BillboardRender render = BillboardRender::impostor;
  float resolution_scale = 0.5f;  // drawn at this fraction of the frame's width and height
  int seed = 11;
};
void describe(TypeBuilder<CloudBillboards>& t);
// The most billboards one frame may draw, and the most atlas layers (archetypes x views x 2).
inline constexpr int kMaxBillboards = 16384;
inline constexpr int kMaxBillboardAtlasLayers = 2048;  // within GL's least GL_MAX_ARRAY_TEXTURE_LAYERS (2048)
// The most memory the archetypes' volumes and the atlas may take (software rasterisers refuse
// larger 3D textures).
inline constexpr int64_t kMaxBillboardVolumeBytes = int64_t(16) << 20;
inline constexpr int64_t kMaxBillboardAtlasBytes = int64_t(32) << 20;
void validate(const CloudBillboards& billboards);

// Which path draws what, by the frame's budget: with budget_ms > 0 the distance where the
// volumetric path hands the clusters' layer over moves each frame, from the GPU time the clouds'
// systems took in the last frame (the render graph's timers): nearer when over budget, farther when
// well under it, within [min_near_m, max_near_m]. A frame rendered alone (a sequence's) keeps the
// clusters' own near_m, so that any machine renders a sequence alike.
struct CloudLod {
  static constexpr std::string_view kTypeName = "clouds.CloudLod";
  float budget_ms = 0.0f;        // GPU time for the clouds' systems together; 0: distances as set
  float min_near_m = 2000.0f;
  float max_near_m = 20000.0f;
  float rate = 0.1f;             // fraction the hand-over moves per frame
};
void describe(TypeBuilder<CloudLod>& t);
void validate(const CloudLod& lod);

// The most puffs one frame may draw (clusters x puffs_per_cluster), and the most candidate cells
// (far_m / cell_m per side): work and memory bounded before they are spent.
inline constexpr int64_t kMaxClusterPuffs = 131072;
inline constexpr int kMaxClusterGrid = 256;
// Throws Error naming the field for values that fail together.
void validate(const CloudClusters& clusters);

// The marching parameters a quality preset stands for (custom: the component's own).
struct ResolvedQuality {
  int max_steps;
  float min_step_m, max_step_m;
  int light_steps;
  float light_step_m;
  bool shape_detail;
  float resolution_scale;  // of the march; the composite upsamples
  float step_growth;       // metres of step per metre of distance (a pixel's footprint grows so)
  int temporal_block;      // with temporal upscaling, one pixel of each block this wide is marched per frame
  bool turbulence;         // the curl field displaces the noise
};
ResolvedQuality resolve_quality(const VolumetricClouds& clouds);
// The most density samples one ray may take at quality custom (march steps x (1 + light steps)):
// twelve times ultra's, so that no setting makes a frame that never finishes.
inline constexpr int64_t kMaxSamplesPerRay = 65536;

// Throws Error naming the field for values that fail together (ranges are checked by reflection).
void validate(const VolumetricClouds& clouds);

// The genus's name in the table (genera.h); throws Error for a value outside it.
const char* genus_name(Genus genus);

}  // namespace welkin::clouds
