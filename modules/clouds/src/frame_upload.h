#pragma once
// This frame's block and layers, read from the scene and uploaded before the geometry.
#include "clouds_gpu.h"

namespace welkin {
class World;
struct SystemContext;
}  // namespace welkin

namespace welkin::clouds {

// The scene's clouds (the first entity's), or null.
const VolumetricClouds* first_clouds(World& world);
// Uploads this frame's block and layers and places the shadow cascades; false when no layer can
// hold cloud (nothing to draw).
bool upload_frame(World& world, const SystemContext& sc, const VolumetricClouds& clouds, FrameBlock& block);
// The camera above the atmosphere's top.
bool camera_in_space(World& world, const FrameBlock& f);

}  // namespace welkin::clouds
