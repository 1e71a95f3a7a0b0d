#pragma once
// Issue 35: the pixels next to the last frame's silhouettes marched again each frame, at the march's
// whole size, for the resolve to take as they are (silhouette_march.cpp).
#include <glm/glm.hpp>

#include "temporal_resolve.h"

namespace welkin {
struct SystemContext;
}

namespace welkin::clouds {

// Two passes: clouds.silhouettes_mark lists the marked pixels (clouds/silhouettes_mark.comp) and
// clears the w x h result to -1; clouds.march_silhouettes marches the list, dispatched from its head
// (clouds/march_silhouettes.comp). Returns the result (march_pixel.glsl's colour where marched).
// `defines`: the march's without the empty-space skipping; `front`/`front_unit`: the mesh clusters'
// front as the march binds it.
ResourceHandle add_silhouette_march(SystemContext& sc, CloudsGpu& gpu, ShaderDefines defines,
                                    glm::ivec3 stride_offset, const MarchOutput& current, int w, int h,
                                    ResourceHandle front, GLuint front_unit);

}  // namespace welkin::clouds
