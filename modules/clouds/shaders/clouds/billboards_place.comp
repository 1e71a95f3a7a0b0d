// The billboards' instances, each frame: one per cell the clusters' placement chose (cells scored by
// the layer's weather, nearest first, clouds/clusters_place.comp stages 0 and 1): the archetype
// whose weather matches the cell's, its box centred over the cell at the layer's middle height, its
// optical depth scaled by the cross-fades and by how much cloud the cell's weather allows against the
// archetype's own place, turned about the vertical by the hash; the light, sky and air at its centre; its
// sort key (distance).
#include "clouds/density.glsl"
#include "clouds/placement.glsl"
#include "clouds/billboards.glsl"
#include "welkin/lighting.glsl"
#include "clouds/phase.glsl"
#include "clouds/light_model.glsl"
#include "clouds/light_march.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 1) buffer Billboards { Billboard bb_billboards[]; };
layout(std430, binding = 2) readonly buffer ClusterCells { float bb_cells[]; };
layout(std430, binding = 3) readonly buffer ClusterChosen { int bb_chosen[]; };
layout(std430, binding = 5) buffer ClusterOrder { uvec2 bb_order[]; };
layout(std430, binding = 7) readonly buffer BillboardArchetypes { BillboardArchetype bb_archetypes[]; };
uniform int u_layer;
uniform int u_count;          // billboards
uniform int u_order_size;     // the sort's power-of-two size
uniform vec4 u_fade;          // in from x to y, out from z to w (view distance m)
uniform float u_density_scale;
uniform int u_light;          // 0 sun, 1 moon

void main() {
  clouds_load();
  int id = int(gl_GlobalInvocationID.x);
  if (id >= u_order_size) return;
  if (id >= u_count) {
    bb_order[id] = uvec2(floatBitsToUint(-2.0), uint(id));  // padding: sorts after every billboard
    return;
  }
  CloudLayerGpu L = cl_layers[u_layer];
  Billboard b;
  b.centre = b.light = b.sky = b.ap_inscattering = vec3(0.0);
  b.depth_scale = b.distance_m = b.turn_rad = b.transmittance_unused = 0.0;
  b.archetype = 0u;
  b.ap_transmittance = vec3(1.0);
  float key = -1.0;
  int cell = bb_chosen[id];
  if (cell >= 0) {
    ivec2 global_cell = u_first_cell + ivec2(cell % u_grid, cell / u_grid);
    vec4 u = random4(global_cell, 0, 3u);
    vec2 en = cell_centre_en(cell) + (u.xy - 0.5) * 0.3 * u_cell_m;
    // No nearer than the fade-in's middle (where the chosen cells' centres begin).
    float inner = 0.5 * (u_fade.x + u_fade.y);
    if (length(en) < inner) en *= inner / max(length(en), 1e-3);
    vec3 c = layer_point(en, L.base_m + u_volume.y);
    float rho = length(c);
    // The archetype whose own weather is nearest the cell's (of two equally near, one by the hash).
    float score = bb_cells[cell], nearest = 3.4e38, weakest = 3.4e38;
    int archetype = 0;
    for (int k = 0; k < u_atlas.z; ++k) {
      float miss = abs(bb_archetypes[k].score - score) + 1e-3 * fract(u.z * 7.0 + float(k) * 0.618);
      if (bb_archetypes[k].score > 0.0 && miss < nearest) nearest = miss, archetype = k;
      if (bb_archetypes[k].score > 0.0) weakest = min(weakest, bb_archetypes[k].score);
    }
    float fade =
        smoothstep(u_fade.x, u_fade.y + 1e-3, rho) * (1.0 - smoothstep(u_fade.z - 1e-3, u_fade.w, rho));
    // A cell weaker than the weakest archetype thins it (only then: a cell between two archetypes
    // shows the nearer whole, as the field shows smaller clouds, not thinner ones).
    float weather = clamp(score / max(weakest, 1e-6), 0.0, 1.0);
    float scale = u_density_scale * fade * weather;
    if (scale > 0.0) {
      vec3 up = normalize(cl.up * cl.camera_radius_m + c);
      b.centre = c;
      b.depth_scale = scale;
      b.light = u_light == 1 ? welkin_moon_irradiance(c) : welkin_sun_irradiance(c);
      b.distance_m = rho;
      b.sky = welkin_sky_irradiance(up);
      float depth;  // the decks over the casters dim the sun here as over the march's clouds
      float deck = u_light == 1 ? 0.0 : clouds_shadow_column(c, depth).far.w * clouds_deck_share(c);
      clouds_deck_light(deck, b.light, b.sky);
      b.archetype = uint(archetype);
      b.ap_inscattering = welkin_aerial_perspective(c, b.ap_transmittance);
      b.turn_rad = 6.2831853 * u.w;
      key = rho;
    }
  }
  bb_billboards[id] = b;
  bb_order[id] = uvec2(floatBitsToUint(key), uint(id));
}
