#pragma once
// The painted coverage map (the editor's brush) as the density field reads it.
#include "clouds_gpu.h"

namespace welkin {
class World;
}

namespace welkin::clouds {

// Uploads the scene's painted map when a stroke changed it (a 1 x 1 neutral texel stands for none)
// and tells `ctx` what it holds.
void upload_coverage_map(World& world, const VolumetricClouds& clouds, CloudsGpu& gpu, CloudsContext& ctx);

}  // namespace welkin::clouds
