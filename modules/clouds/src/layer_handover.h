#pragma once
// Where the march hands layers over to the mesh clusters and the billboards this frame.
#include "clouds_gpu.h"

namespace welkin {
class World;
struct SystemContext;
}  // namespace welkin

namespace welkin::clouds {

// The layers the mesh clusters and the billboards draw are handed over to them: the clusters from
// their near_m (or the budget's distance) to their far_m, the billboards from there (or from their
// own near_m without clusters on the layer) to their far_m, beyond which the march resumes. Each
// hand-over cross-fades: the march's density and the paths' add up to the field's.
void hand_over_layers(World& world, const SystemContext& sc, CloudsGpu& gpu, PackedLayers& layers);

}  // namespace welkin::clouds
