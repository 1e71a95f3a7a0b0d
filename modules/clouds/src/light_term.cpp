// The clouds as a term of the world's light environment: their shadow cascades and sky occlusion,
// read by every material (shaders/clouds/light_term.glsl).
#include "light_term.h"

#include <cstdint>

#include "clouds_gpu.h"
#include "welkin/core/world.h"
#include "welkin/gfx/light_environment.h"

namespace welkin::clouds {

void add_light_term(World& world) {
  world.resource<LightEnvironment>().add(LightTerm{
      .name = "clouds.shadows",
      .include = "clouds/light_term.glsl",
      .light_visibility = "clouds_light_visibility",
      .sky_visibility = "clouds_sky_visibility",
      .added_irradiance = "clouds_added_irradiance",
      .surface_light = "clouds_surface_light",
      .textures = {"clouds.shadow_map"},
      .blocks = {"clouds.shadow"},
      .bind =
          [&world](const LightEnvironment& env) {
            CloudsGpu& gpu = world.resource<CloudsGpu>();
            ShadowBlock s = gpu.shadow;
            if (!gpu.shadow_map) s.cascade_count = 0;
            env.bind_block("clouds.shadow", gpu.shadow_buffer, &s, sizeof(s));
            if (gpu.shadow_map) glBindTextureUnit(env.unit("clouds.shadow_map"), gpu.shadow_map->id());
          },
      // The block, the cascades remade so far and those this frame remakes.
      .state =
          [&world] {
            const CloudsGpu& gpu = world.resource<CloudsGpu>();
            return fnv1a_64_of(
                gpu.shadow,
                fnv1a_64_of(gpu.shadow_builds,
                            fnv1a_64_of(gpu.shadow_rebuild, fnv1a_64_of(uintptr_t(gpu.shadow_map.get())))));
          }});
}

}  // namespace welkin::clouds
