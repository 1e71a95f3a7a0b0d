// Entry point of the clouds module: its components, its light term and its render systems.
#include "welkin/clouds/components.h"
#include "billboards.h"
#include "clusters.h"
#include "light_term.h"
#include "march.h"
#include "shadow_cascades.h"
#include "welkin/core/module.h"
#include "welkin/core/world.h"

namespace welkin::modules {

void register_clouds(ModuleContext& ctx) {
  using namespace welkin::clouds;
  ctx.component<VolumetricClouds>();
  ctx.component<CloudClusters>();
  ctx.component<CloudBillboards>();
  ctx.component<CloudLod>();
  add_light_term(ctx.world());
  // The shadow map before any material draws (a light map); the clouds after the geometry, the
  // atmosphere's aerial perspective on it and the god rays (their stages come before the clouds'), so
  // clouds cover them and carry the air in front of them.
  ctx.system({.name = "clouds.shadows", .stage = Stage::light_maps, .reads = {type_id<VolumetricClouds>()},
              .run = shadow_system});
  // The billboards first: the mesh clusters draw over them (the billboards lie beyond).
  ctx.system({.name = "clouds.billboards",
              .stage = Stage::clouds,
              .reads = {type_id<CloudBillboards>()},
              .optional_reads = {type_id<VolumetricClouds>()},
              .run = billboards_system});
  // The mesh clusters before the march, which stops where they turn opaque and composites the nearer
  // volumetric clouds over them.
  ctx.system({.name = "clouds.clusters",
              .stage = Stage::clouds,
              .after = {"clouds.billboards"},
              .reads = {type_id<CloudClusters>()},
              .optional_reads = {type_id<VolumetricClouds>()},
              .run = clusters_system});
  ctx.system({.name = "clouds.march",
              .stage = Stage::clouds,
              .after = {"clouds.clusters"},
              .reads = {type_id<VolumetricClouds>()},
              .run = clouds_system});
}

}  // namespace welkin::modules
