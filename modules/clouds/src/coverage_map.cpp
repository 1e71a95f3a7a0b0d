// The painted coverage map (coverage_map.h).
#include "coverage_map.h"

#include <string>

#include "welkin/core/error.h"
#include "welkin/core/world.h"
#include "welkin/gfx/compute.h"
#include "welkin/scene/painted_map.h"

namespace welkin::clouds {

// The painted coverage map (the editor's brush), uploaded again only when a stroke changed it; a
// 1 x 1 neutral texel stands for none.
void upload_coverage_map(World& world, const VolumetricClouds& clouds, CloudsGpu& gpu, CloudsContext& ctx) {
  auto upload = [&gpu](int side, const uint8_t* texels) {
    ensure_texture(gpu.coverage_map, {.width = side, .height = side, .format = TextureFormat::r8});
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(gpu.coverage_map->id(), 0, 0, 0, side, side, GL_RED, GL_UNSIGNED_BYTE, texels);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  };
  if (clouds.coverage_map.empty()) {
    if (!gpu.coverage_map || !gpu.coverage_map_file.empty()) {
      upload(1, &kPaintedMapNeutral);
      gpu.coverage_map_file.clear();
    }
    return;
  }
  const PaintedMap* map = nullptr;
  try {
    map = &world.resource<PaintedMaps>().get(clouds.coverage_map);
  } catch (const Error& e) {
    throw e.with_path_prefix(std::string(VolumetricClouds::kTypeName) + "/coverage_map");
  }
  if (gpu.coverage_map_file != clouds.coverage_map || gpu.coverage_map_revision != map->revision) {
    upload(map->side, map->texels.data());
    gpu.coverage_map_file = clouds.coverage_map;
    gpu.coverage_map_revision = map->revision;
    gpu.coverage_map_raise = float(painted_coverage_offset(map->maximum()));
  }
  ctx.has_coverage_map = true;
  ctx.coverage_map_raise = gpu.coverage_map_raise;
  ctx.coverage_map_revision = map->revision;
}

}  // namespace welkin::clouds
