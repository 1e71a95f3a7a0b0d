#pragma once
// The clouds' shadow cascades: beer shadow maps across the sun's direction, nearest first, which
// every material reads through the light environment (light_term.cpp).
#include "welkin/clouds/gpu.h"

namespace welkin::clouds {

// Places this frame's cascades (gpu.shadow) and marks those whose key went stale for a rebuild.
void place_shadow_cascades(CloudsGpu& gpu, const VolumetricClouds& clouds, const CloudsContext& ctx,
                           const PackedLayers& layers, const FrameBlock& block, const FrameView& view);

}  // namespace welkin::clouds
