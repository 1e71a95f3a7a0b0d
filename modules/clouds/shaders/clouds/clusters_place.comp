// The mesh clusters' placement, in stages (CLUSTERS_STAGE), each frame from the layer's own weather
// and noise (clouds/density.glsl), so that a cluster stands where the volumetric cloud would:
//   0 cells:  how much cloud the weather allows in each candidate cell (cells drift with the layer's wind);
//   1 choose: the nearest cells that hold any, up to the cluster budget (one invocation);
//   2 puffs:  the puffs tile their cell in columns through the layer; those whose weather allows
//             cloud live (the draw reads the field's extinction inside them);
//   3 light:  each puff's optical depth toward the light as the march finds it, half way up and down
//             its column, the light, sky and air at its centre, and its sort key (distance).
#include "clouds/density.glsl"
#include "clouds/clusters.glsl"
#include "clouds/placement.glsl"
#if CLUSTERS_STAGE == 3
#include "welkin/lighting.glsl"
#include "clouds/phase.glsl"
// What light_march.glsl's source needs (only its optical depth is used here).
#include "clouds/light_model.glsl"
#include "clouds/light_march.glsl"
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

uniform int u_layer;              // the packed layer the clusters draw
uniform int u_clusters, u_puffs;  // budget, puffs per cluster
uniform vec4 u_range;             // near m, cross-fade m, far m
uniform vec2 u_ring;   // stage 0: the cells whose centres lie this far from the camera (m) are candidates
uniform int u_in_view;  // stage 0: 1: only cells whose column reaches into the view (the clusters)
uniform float u_density_scale;
uniform int u_order_size;         // the sort's power-of-two size
uniform vec3 u_light_dir;         // toward the marched light
uniform int u_light;              // 0 sun, 1 moon

#if CLUSTERS_STAGE == 2
// The heights (m) between which the layer's weather allows cloud in the column of a puff (before the
// noise erodes it): the lowest base and the highest top over 5 x 5 points across it (x > y: none).
vec2 column_cloud_heights(CloudLayerGpu L, vec2 en, float half_width) {
  vec2 heights = vec2(3.4e38, -3.4e38);
  for (int i = 0; i < 25; ++i) {
    vec2 at = en + (vec2(i % 5, i / 5) - 2.0) * (0.45 * half_width);
    // Just over the lowest base the weather allows: the weather is read there.
    vec3 x = layer_point(at, L.base_m - L.base_variation_m + 1.0);
    clouds_system_g = clouds_weather_system_at(x);
    clouds_painted_sample = 2.0;
    vec4 w4 = clouds_weather_fetch(L, x);
    float base = L.base_m + L.base_variation_m * (w4.a - 0.5) * 2.0;
    // The envelope's weather term d0 (its height terms aside), a third of the way up.
    float t, d0;
    vec3 y = layer_point(at, base + 0.33 * L.thickness_m);
    clouds_layer_envelope(L, w4, L.follows_map > 0.5, y, clouds_altitude(y), t, d0);
    if (d0 <= 0.0) continue;
    float top = mix(1.0, max(d0, 0.05), L.dome);
    heights = vec2(min(heights.x, base), max(heights.y, base + top * L.thickness_m));
  }
  return heights;
}
#endif

#if CLUSTERS_STAGE == 0
// Whether a sphere (camera-relative centre, radius m) reaches into the view: the side planes of the
// view-projection's frustum (Gribb and Hartmann), so that the cluster budget is spent where the
// camera looks.
bool sphere_in_view(vec3 c, float r) {
  mat4 m = inverse(cl.inverse_view_projection);
  vec4 rows[4] = vec4[4](vec4(m[0][0], m[1][0], m[2][0], m[3][0]), vec4(m[0][1], m[1][1], m[2][1], m[3][1]),
                         vec4(m[0][2], m[1][2], m[2][2], m[3][2]), vec4(m[0][3], m[1][3], m[2][3], m[3][3]));
  for (int k = 0; k < 4; ++k) {
    vec4 plane = rows[3] + (k % 2 == 0 ? 1.0 : -1.0) * rows[k / 2];
    if (dot(plane.xyz, c) + plane.w < -r * length(plane.xyz)) return false;
  }
  return true;
}
#endif

void main() {
  clouds_load();
  int id = int(gl_GlobalInvocationID.x);
  CloudLayerGpu L = cl_layers[u_layer];
  float base = L.base_m, thickness = L.thickness_m;
  // The weather is scored at the cell's centre and four points 0.35 cells from it where the clusters'
  // columns tile the whole cell, 0.21 cells where a billboard's cloud stands in its middle.
  float cluster_radius = (u_in_view != 0 ? 0.7 : 0.42) * u_cell_m;
#if CLUSTERS_STAGE == 0
  if (id >= u_grid * u_grid) return;
  vec2 en = cell_centre_en(id);
  float rho = length(en);
  float score = 0.0;
  // The cell's column through the layer (its corners and the base's variation included).
  vec3 middle = layer_point(en, L.base_m + 0.5 * L.thickness_m);
  float reach = length(vec2(0.7072 * u_cell_m, 0.5 * L.thickness_m + L.base_variation_m));
  if (rho > u_ring.x && rho < u_ring.y && (u_in_view == 0 || sphere_in_view(middle, reach))) {
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
  puff.extinction_per_density = 0.0;
  puff.radii = vec3(1.0);
  puff.light_depth = puff.distance_m = puff.system_signal = 0.0;
  puff.light = puff.sky = puff.ap_inscattering = puff.light_depth_gradient = vec3(0.0);
  puff.ap_transmittance = vec3(1.0);
  puff.inscattering_unused = puff.transmittance_unused = puff.gradient_unused = 0.0;
  // The puffs tile their cell: n x n columns through the layer (n^2 <= the puffs per cluster; the
  // rest stay empty), boxes that meet face to face, so that the field is drawn once wherever it has
  // cloud. The draw reads the field's own extinction along each pixel's ray inside them.
  int n = int(floor(sqrt(float(u_puffs)) + 1e-3));
  if (cell >= 0 && index < n * n) {
    float half_width = 0.5 * u_cell_m / float(n);
    vec2 column = vec2(index % n, index / n) + 0.5 - 0.5 * float(n);
    vec2 puff_en = cell_centre_en(cell) + column * (2.0 * half_width);
    // From the lowest base to the highest top the weather allows in the column, and a little more
    // (the planet's curvature across it).
    vec2 heights = column_cloud_heights(L, puff_en, half_width);
    vec3 x = layer_point(puff_en, 0.5 * (heights.x + heights.y));
    vec3 radii = vec3(half_width, half_width, 0.5 * (heights.y - heights.x) + 10.0);
    // Outside the distances the clusters draw (the draw fades each sample as the march's complement).
    float rho = length(x), reach = length(radii);
    bool in_range = rho + reach > u_range.x - 0.5 * u_range.y && rho - reach < u_range.z;
    if (in_range && heights.x < heights.y) {
      // w: the extinction per unit of the field's density (the field's own, times density_scale).
      puff.centre = x;
      puff.extinction_per_density = (cl.scattering + cl.absorption) * u_density_scale;
      puff.radii = radii;
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
  if (puff.extinction_per_density > 0.0) {
    vec3 c = puff.centre;
    // The march's own optical depth toward the light (its light steps through the field, then the
    // clouds' shadow map) half way up and down the column: the draw takes it linear in height.
    float extinction_per_density = cl.scattering + cl.absorption;
    vec3 half_up = 0.5 * puff.radii.z * u_axis_up;
    clouds_system_g = clouds_weather_system_at(c);
    float clear, deck;  // the draw reads the light's depth and the decks' light alone
    float below = clouds_light_optical_depth(c - half_up, u_light_dir, extinction_per_density, clear, deck);
    float above = clouds_light_optical_depth(c + half_up, u_light_dir, extinction_per_density, clear, deck);
    // Only this stage's fields are written: the other invocations read the centres and radii.
    cp_puffs[id].light_depth = 0.5 * (below + above);
    // per unit of the column's normalised height
    cp_puffs[id].light_depth_gradient = vec3(0.0, 0.0, above - below);
    cp_puffs[id].system_signal = clouds_system_g;
    vec3 up = normalize(cl.up * cl.camera_radius_m + c);
    vec3 light = u_light == 1 ? welkin_moon_irradiance(c) : welkin_sun_irradiance(c);
    vec3 sky = welkin_sky_irradiance(up);
    clouds_deck_light(deck, light, sky);
    cp_puffs[id].light = light, cp_puffs[id].sky = sky;
    cp_puffs[id].distance_m = length(c);
    vec3 t;
    cp_puffs[id].ap_inscattering = welkin_aerial_perspective(c, t);
    cp_puffs[id].ap_transmittance = t;
    // The horizontal distance: a ray meets the columns of a grid in its order (their tops differ).
    key = length(c - dot(c, u_axis_up) * u_axis_up);
  }
  cp_order[id] = uvec2(floatBitsToUint(key), uint(id));
#endif
}
