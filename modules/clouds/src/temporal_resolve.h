#pragma once
// The march's result made whole and laid over the frame: the temporal resolve (one pixel of each
// block marched per frame, the others reprojected from the history) and the composite.
#include <array>
#include <memory>

#include "clouds_gpu.h"
#include "welkin/gfx/renderer.h"

namespace welkin::clouds {

// What the march writes this frame: its colour and its distances (mean, opaque from, clear up to), at
// the march's resolution (one pixel of each block).
struct MarchOutput {
  ResourceHandle color, distance;
  // At the march's whole size, the pixels next to the last frame's silhouettes marched again (-1
  // elsewhere; silhouette_march.h), when they were.
  ResourceHandle silhouettes;
};

// The resolve into the history (gpu.history_color, and the scene's depth each pixel was marched
// against into gpu.history_depth) at the march's size w x h, the march having written pixel `offset`
// of each block of n x n (every pixel when not `partial`). Returns what to composite; `clusters` (the
// mesh clusters' and billboards' colour) is laid in when it has the march's size, and is then
// cleared. `clear`: also the distances up to which each pixel's ray met no cloud, into gpu.first_hit
// (first_hit_skip.h). `scene_depth`: the frame's depth the march stopped at.
ResourceHandle add_resolve_pass(RenderGraph& g, RenderContext& rc, CloudsGpu& gpu,
                                const VolumetricClouds& clouds, const MarchOutput& current,
                                ResourceHandle scene_depth, glm::ivec2 offset, bool partial, int n, int w,
                                int h, ResourceHandle& clusters, bool clear);
// The clouds (and the clusters or billboards behind them, where not merged already) over the frame.
void composite_clouds(RenderGraph& g, RenderContext& rc, const FrameTargets& t, ResourceHandle result,
                      ResourceHandle clusters);

}  // namespace welkin::clouds
