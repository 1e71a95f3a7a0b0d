#include "terrain_system.h"
#include "welkin/core/module.h"
#include "welkin/terrain/components.h"

namespace welkin::terrain {

void describe(TypeBuilder<Terrain>& t) {
  t.tooltip("glTF terrain or scenery on the planet (Draco, LOD chunks, PBR)");
  t.field("file", &Terrain::file).tooltip(".glb or .gltf; external files only beside it");
  t.field("anchor", &Terrain::anchor).values({{"scene_origin", 0}, {"offset", 1}, {"geodetic", 2}});
  t.field("offset_m", &Terrain::offset_m)
      .unit("m")
      .range(-1e8, 1e8)
      .tooltip("Model origin in the scene (anchor = offset)");
  t.field("latitude_deg", &Terrain::latitude_deg).unit("deg").range(-90, 90).tooltip("Anchor = geodetic");
  t.field("longitude_deg", &Terrain::longitude_deg).unit("deg").range(-180, 180).tooltip("Anchor = geodetic");
  t.field("height_m", &Terrain::height_m).unit("m").range(-12000, 1e6);
  t.field("heading_deg", &Terrain::heading_deg).unit("deg").range(-360, 360);
  t.field("follow_curvature", &Terrain::follow_curvature).tooltip("Bend the model onto the planet's surface");
  t.field("planet_radius_km", &Terrain::planet_radius_km)
      .unit("km")
      .range(1, 1e5)
      .tooltip("When the scene has no atmosphere");
  t.field("chunks_per_side", &Terrain::chunks_per_side).range(1, 128);
  t.field("lod_levels", &Terrain::lod_levels).range(1, 10);
  t.field("lod_pixel_error", &Terrain::lod_pixel_error).unit("px").range(0.1, 100);
  t.field("compress_images", &Terrain::compress_images)
      .tooltip("BC1 compression: 1/8 of the GPU memory of RGBA8, a small colour error (docs/terrain.md)");
  t.field("cast_shadows", &Terrain::cast_shadows).tooltip("Cascaded shadow maps from the sun");
  t.field("shadow_map_size", &Terrain::shadow_map_size).unit("px").range(64, 8192);
  t.field("shadow_distance_m", &Terrain::shadow_distance_m).unit("m").range(10, 1e6);
  t.field("refine", &Terrain::refine).tooltip("OpenSubdiv refinement at load");
  t.field("refine_levels", &Terrain::refine_levels).range(0, 4);
  t.field("refine_max_triangles", &Terrain::refine_max_triangles).range(1000, 50000000);
}

}  // namespace welkin::terrain

namespace welkin::modules {
void register_terrain(ModuleContext& ctx) {
  ctx.component<welkin::terrain::Terrain>();
  welkin::terrain::add_light_term(ctx.world());
  ctx.system({.name = "terrain.draw",
              .stage = Stage::geometry,
              .reads = {type_id<welkin::terrain::Terrain>()},
              .run = welkin::terrain::terrain_system});
}
}  // namespace welkin::modules
