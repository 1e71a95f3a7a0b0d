// The layers' hand-over from the march to the mesh clusters and the billboards (layer_handover.h).
#include "layer_handover.h"

#include <algorithm>

#include "welkin/core/world.h"
#include "welkin/gfx/renderer.h"

namespace welkin::clouds {

namespace {

// The march leaves layer `b` to another path from view distance near_m to far_m, cross-fading.
void hand_over(LayerBlock& b, float near_m, float crossfade_m, float far_m) {
  b.handover_near_m = near_m, b.handover_crossfade_m = crossfade_m, b.handover_far_m = far_m;
  b.handover_unused = 0.0f;
}

// Where the march hands the clusters' layer over this frame: the clusters' near_m, or with a
// clouds.CloudLod budget, last frame's distance moved by the clouds' measured GPU time.
float handover_distance(World& world, const SystemContext& sc, const CloudClusters& clusters,
                        CloudsGpu& gpu) {
  Registry& reg = world.registry();
  const Entity le = reg.first<CloudLod>();
  const CloudLod* lod = le.is_null() ? nullptr : reg.get<CloudLod>(le);
  if (!lod || !(lod->budget_ms > 0.0f) || sc.frame.alone) {
    gpu.lod_near_m = -1.0f;
    return clusters.near_m;
  }
  check_component(*lod);
  const float lo = lod->min_near_m,
              hi = std::min(lod->max_near_m, std::max(clusters.far_m - clusters.crossfade_m, lo));
  if (gpu.lod_near_m < 0.0f) gpu.lod_near_m = std::clamp(clusters.near_m, lo, hi);
  double ms = 0.0;
  bool measured = false;
  for (const PassTiming& t : world.resource<RenderContext>().last_timings)
    if (t.system.rfind("clouds.", 0) == 0) ms += t.gpu_ms, measured = true;
  // Over budget: the clusters take over nearer; well under it (15% to spare): farther.
  if (measured && ms > lod->budget_ms)
    gpu.lod_near_m *= 1.0f - lod->rate;
  else if (measured && ms < 0.85 * lod->budget_ms)
    gpu.lod_near_m *= 1.0f + lod->rate;
  gpu.lod_near_m = std::clamp(gpu.lod_near_m, lo, hi);
  return gpu.lod_near_m;
}

}  // namespace

void hand_over_layers(World& world, const SystemContext& sc, CloudsGpu& gpu, PackedLayers& layers) {
  gpu.clusters_layer = gpu.billboards_layer = -1;
  Registry& reg = world.registry();
  const Entity ce = reg.first<CloudClusters>(), be = reg.first<CloudBillboards>();
  const CloudClusters* clusters = ce.is_null() ? nullptr : reg.get<CloudClusters>(ce);
  const CloudBillboards* billboards = be.is_null() ? nullptr : reg.get<CloudBillboards>(be);
  if (clusters && !(clusters->clusters > 0 && clusters->puffs_per_cluster > 0)) clusters = nullptr;
  if (billboards && !(billboards->billboards > 0)) billboards = nullptr;
  const float near_m = clusters ? handover_distance(world, sc, *clusters, gpu) : 0.0f;
  for (size_t i = 0; i < layers.layers.size(); ++i) {
    const int source = layers.source_index[i];
    const bool clustered = clusters && source == clusters->layer;
    const bool far = billboards && source == billboards->layer;
    if (clustered) {
      gpu.clusters_layer = int(i);
      gpu.clusters_near_m = near_m;
      hand_over(layers.layers[i], std::max(near_m, 1e-3f), clusters->crossfade_m, clusters->far_m);
    }
    if (far) {
      gpu.billboards_layer = int(i);
      const float end = billboards->far_m;
      if (clustered) {
        // In where the puffs fade out (the last cross-fade before their far_m), out as the march
        // comes back: over the clusters' cross-fade, the one width the layer's hand-over has.
        const float w = clusters->crossfade_m;
        gpu.billboards_fade = {clusters->far_m - w, clusters->far_m, std::max(end - w, clusters->far_m),
                               std::max(end, clusters->far_m + 1.0f)};
        layers.layers[i].handover_far_m = gpu.billboards_fade.w;
      } else {
        const float w = billboards->crossfade_m;
        gpu.billboards_fade = {billboards->near_m - 0.5f * w, billboards->near_m + 0.5f * w, end - w, end};
        hand_over(layers.layers[i], std::max(billboards->near_m, 1e-3f), w, end);
      }
    }
  }
}

}  // namespace welkin::clouds
