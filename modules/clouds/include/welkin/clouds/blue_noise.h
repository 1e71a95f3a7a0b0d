#pragma once
// Blue noise for the march's jitter, made by the project's own generator (Ulichney 1993's
// void-and-cluster on a torus), deterministic from a seed: no third-party noise textures.
#include <cstdint>
#include <vector>

namespace welkin::clouds {

// A size x size tileable threshold map: every rank 0..size^2-1 once, as (rank + 0.5) / size^2,
// row-major. Sizes 4..256.
std::vector<float> void_and_cluster(int size, uint32_t seed, double sigma = 1.5);

}  // namespace welkin::clouds
