// The mesh clusters' placement, in stages (CLUSTERS_STAGE), each frame from the layer's own weather
// and noise (clouds/density.glsl), so that a cluster stands where the volumetric cloud would:
//   0 cells:  how much cloud the weather allows in each candidate cell (cells drift with the layer's wind);
//   1 choose: the nearest cells that hold any, up to the cluster budget (one invocation);
//   2 puffs:  each puff at a place drawn from its cell and index by the genus's profile, with the
//             field's extinction there as its own;
//   3 light:  each puff's optical depth toward the light through its cluster's other puffs, the
//             light, sky and air at its centre, and its sort key (distance).
#include "clouds/density.glsl"
#include "clouds/clusters.glsl"
#include "clouds/placement.glsl"
#if CLUSTERS_STAGE == 3
#include "welkin/lighting.glsl"
#endif

layout(local_size_x = 64) in;

layout(std430, binding = 1) buffer ClusterPuffs { ClusterPuff cp_puffs[]; };
// each cell's cloud (mean extinction, 1/m)
layout(std430, binding = 2) buffer ClusterCells { float cp_cells[]; };
// the cell of each cluster (-1: none)
layout(std430, binding = 3) buffer ClusterChosen { int cp_chosen[]; };
layout(std430, binding = 4) readonly buffer ClusterCellOrder { int cp_cell_order[]; };  // cells nearest first
// (sort key bits, puff) per instance
layout(std430, binding = 5) buffer ClusterOrder { uvec2 cp_order[]; };

uniform vec2 u_wind_en;           // the wind's direction in (east, north)
uniform int u_layer;              // the packed layer the clusters draw
uniform int u_clusters, u_puffs;  // budget, puffs per cluster
uniform vec4 u_range;             // near m, cross-fade m, far m, puff size
uniform vec2 u_ring;   // stage 0: the cells whose centres lie this far from the camera (m) are candidates
uniform vec4 u_genus;  // dome (0 sheet .. 1 dome), form (0 heaps, 1 sheets, 2 streaks), density scale
uniform int u_order_size;         // the sort's power-of-two size
uniform vec3 u_light_dir;         // toward the marched light
uniform int u_light;              // 0 sun, 1 moon

float field_at(vec3 x) {
  clouds_system_g = clouds_weather_system_at(x);
  return clouds_density(x, false, false);
}

#if CLUSTERS_STAGE == 2
// A puff's radii, its offset from the cluster's centre (along the wind, across it, m) and its centre's
// height above the base (m), from its random numbers u and v, by the genus's form.
void puff_shape(vec4 u, vec4 v, float cluster_radius, float thickness, float size, out vec3 radii,
                out vec2 offset, out float height) {
  int form = int(u_genus.y);
  if (form == 2) {
    // Streaks: long along the wind, narrow across, thin.
    radii = vec3(0.5, 0.12, 0.0) * cluster_radius * size;
    radii.z = min(0.4 * thickness, radii.y);
    offset = vec2((u.x - 0.5) * 2.0 * cluster_radius, (u.y - 0.5) * 0.5 * cluster_radius);
    height = radii.z + u.z * max(thickness - 2.0 * radii.z, 0.0);
  } else {
    // Heaps (a dome over a flat base, higher in the middle) or sheets (flattened puffs filling the layer).
    float r = cluster_radius * sqrt(u.x), angle = 6.2831853 * u.y;
    offset = r * vec2(cos(angle), sin(angle));
    float horizontal = (form == 1 ? 0.45 : 0.38) * cluster_radius * size * (0.75 + 0.5 * v.x);
    float vertical = min(form == 1 ? 0.4 * horizontal : horizontal, 0.45 * thickness);
    radii = vec3(horizontal, horizontal, vertical);
    float top = thickness * mix(1.0, 1.0 - (r * r) / (cluster_radius * cluster_radius), u_genus.x);
    // Centres from a third of a radius above the base (the draw cuts each puff at the base).
    height = 0.35 * vertical + u.z * max(top - 1.35 * vertical, 0.0);
  }
}
#endif

void main() {
  clouds_load();
  int id = int(gl_GlobalInvocationID.x);
  CloudLayerGpu L = cl_layers[u_layer];
  float base = L.base_m, thickness = L.thickness_m;
  float cluster_radius = 0.42 * u_cell_m;
#if CLUSTERS_STAGE == 0
  if (id >= u_grid * u_grid) return;
  vec2 en = cell_centre_en(id);
  float rho = length(en);
  float score = 0.0;
  if (rho > u_ring.x && rho < u_ring.y) {
    score = weather_score(L, en, cluster_radius);
  }
  cp_cells[id] = score;
#elif CLUSTERS_STAGE == 1
  if (id != 0) return;
  int k = 0;
  for (int j = 0; j < u_grid * u_grid && k < u_clusters; ++j) {
    int cell = cp_cell_order[j];
    if (cp_cells[cell] > 0.0) cp_chosen[k++] = cell;
  }
  for (; k < u_clusters; ++k) cp_chosen[k] = -1;
#elif CLUSTERS_STAGE == 2
  if (id >= u_clusters * u_puffs) return;
  int cluster = id / u_puffs, index = id % u_puffs;
  int cell = cp_chosen[cluster];
  ClusterPuff puff;
  puff.centre = vec3(0.0);
  puff.extinction_per_m = 0.0;
  puff.radii = vec3(1.0);
  puff.light_depth = puff.distance_m = puff.height_m = 0.0;
  puff.light = puff.sky = puff.ap_inscattering = puff.light_depth_gradient = vec3(0.0);
  puff.ap_transmittance = vec3(1.0);
  puff.inscattering_unused = puff.transmittance_unused = puff.gradient_unused = 0.0;
  if (cell >= 0) {
    ivec2 global_cell = u_first_cell + ivec2(cell % u_grid, cell / u_grid);
    vec4 u = random4(global_cell, index, 0u), v = random4(global_cell, index, 1u);
    vec2 centre_en = cell_centre_en(cell);
    vec2 across_en = vec2(-u_wind_en.y, u_wind_en.x);
    float size = u_range.w;
    vec3 radii;
    vec2 offset;  // along the wind, across it (m)
    float height;  // of the centre above the base (m)
    puff_shape(u, v, cluster_radius, thickness, size, radii, offset, height);
    vec2 puff_en = centre_en + offset.x * u_wind_en + offset.y * across_en;
    // The base rises and falls with the weather, as in the field: read once at the cluster's centre.
    vec3 at_centre = layer_point(centre_en, base);
    float weather_base = base + L.base_variation_m * (clouds_weather_fetch(L, at_centre).a - 0.5) * 2.0;
    vec3 x = layer_point(puff_en, weather_base + height);
    float rho = length(x);
    // The volumetric path hands the layer over across [near - w/2, near + w/2]; the puffs fade out
    // over the last cross-fade before far.
    float fade = smoothstep(u_range.x - 0.5 * u_range.y, u_range.x + 0.5 * u_range.y + 1e-3, rho) *
                 (1.0 - smoothstep(u_range.z - u_range.y - 1e-3, u_range.z, rho));
    // The field's extinction where the puff stands: the largest of its centre and two points half
    // its radius to either side along the wind (one point alone is often where the noise erodes).
    float field = field_at(x);
    field = max(field, field_at(layer_point(puff_en + 0.5 * radii.x * u_wind_en, weather_base + height)));
    field = max(field, field_at(layer_point(puff_en - 0.5 * radii.x * u_wind_en, weather_base + height)));
    float sigma = field * (cl.scattering + cl.absorption) * u_genus.z * fade;
    if (sigma > 0.0) {
      puff.centre = x;
      puff.extinction_per_m = sigma;
      puff.radii = radii;
      puff.height_m = height;  // above the cluster's base, where the draw cuts it
    }
  }
  cp_puffs[id] = puff;
#elif CLUSTERS_STAGE == 3
  if (id >= u_order_size) return;
  int count = u_clusters * u_puffs;
  if (id >= count) {
    cp_order[id] = uvec2(floatBitsToUint(-2.0), uint(id));  // padding: sorts after every puff
    return;
  }
  ClusterPuff puff = cp_puffs[id];
  float key = -1.0;
  if (puff.extinction_per_m > 0.0) {
    vec3 c = puff.centre;
    int first = (id / u_puffs) * u_puffs;
    // At the centre and half a radius to either side along each axis (the draw interpolates, so
    // the shade does not jump from puff to puff).
    float tau[7] = float[7](0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for (int q = first; q < first + u_puffs; ++q) {
      if (q == id) continue;
      float other_sigma = cp_puffs[q].extinction_per_m;
      if (other_sigma <= 0.0) continue;
      vec3 other_centre = cp_puffs[q].centre, other_radii = cp_puffs[q].radii;
      // In the other puff's normalised frame (the puffs share their axes): the light's direction,
      // this puff's centre, and the half-radius steps along each axis, found once for the 7 points.
      vec3 light_local = puff_direction(u_light_dir, other_radii),
           centre_local = puff_local(c, other_centre, other_radii);
      vec3 step_local = 0.5 * puff.radii / other_radii;
      tau[0] += other_sigma * puff_optical_depth(puff_chord_local(centre_local, light_local), 0.0, 3.4e38);
      for (int a = 0; a < 3; ++a)
        for (int side = 0; side < 2; ++side) {
          vec3 x = centre_local;
          x[a] += side == 0 ? step_local[a] : -step_local[a];
          tau[1 + 2 * a + side] +=
              other_sigma * puff_optical_depth(puff_chord_local(x, light_local), 0.0, 3.4e38);
        }
    }
    // Only this stage's fields are written: the other invocations read the centres and radii.
    cp_puffs[id].light_depth = tau[0];
    cp_puffs[id].light_depth_gradient = vec3(tau[1] - tau[2], tau[3] - tau[4], tau[5] - tau[6]);
    vec3 up = normalize(cl.up * cl.camera_radius_m + c);
    cp_puffs[id].light = u_light == 1 ? welkin_moon_irradiance(c) : welkin_sun_irradiance(c);
    cp_puffs[id].distance_m = length(c);
    cp_puffs[id].sky = welkin_sky_irradiance(up);
    vec3 t;
    cp_puffs[id].ap_inscattering = welkin_aerial_perspective(c, t);
    cp_puffs[id].ap_transmittance = t;
    key = length(c);
  }
  cp_order[id] = uvec2(floatBitsToUint(key), uint(id));
#endif
}
