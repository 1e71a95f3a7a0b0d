// Bitonic sort of the puffs' (key, index) pairs, far first, so that the instanced draw composites
// them back to front. CLUSTERS_SORT_MODE
//   0: sorts each block of 1024 in shared memory (every k up to min(1024, size));
//   1: the steps j < 1024 of merge k for each block, in shared memory;
//   2: one step (k, j >= 1024) across the whole buffer.
#if CLUSTERS_SORT_MODE == 2
layout(local_size_x = 512) in;
#else
// Few invocations, each taking several pairs per step: llvmpipe runs a work group on one thread and
// switches between its SIMD groups of invocations at every barrier.
const int kThreads = 64;
layout(local_size_x = kThreads) in;
#endif
layout(std430, binding = 5) buffer ClusterOrder { uvec2 cp_order[]; };
uniform int u_size;  // a power of two
uniform int u_k, u_j;

// Whether the pair at (i, i + j) is out of order: descending where bit k of i is clear.
bool out_of_order(uvec2 a, uvec2 b, int i, int k) {
  float ka = uintBitsToFloat(a.x), kb = uintBitsToFloat(b.x);
  return (i & k) == 0 ? ka < kb : ka > kb;
}

#if CLUSTERS_SORT_MODE == 2
void main() {
  int t = int(gl_GlobalInvocationID.x);
  if (t >= u_size / 2) return;
  int i = (t / u_j) * 2 * u_j + t % u_j, l = i + u_j;
  uvec2 a = cp_order[i], b = cp_order[l];
  if (out_of_order(a, b, i, u_k)) cp_order[i] = b, cp_order[l] = a;
}
#else
shared uvec2 s_pairs[1024];
void main() {
  int block = int(gl_WorkGroupID.x) * 1024, t = int(gl_LocalInvocationID.x);
  int n = min(u_size, 1024);
  for (int e = t; e < n; e += kThreads) s_pairs[e] = cp_order[block + e];
  barrier();
#if CLUSTERS_SORT_MODE == 0
  for (int k = 2; k <= n; k *= 2) {
    for (int j = k / 2; j > 0; j /= 2) {
#else
  {
    int k = u_k;
    for (int j = 512; j > 0; j /= 2) {
#endif
      for (int q = t; q < n / 2; q += kThreads) {
        int i = (q / j) * 2 * j + q % j, l = i + j;
        uvec2 a = s_pairs[i], b = s_pairs[l];
        if (out_of_order(a, b, block + i, k)) s_pairs[i] = b, s_pairs[l] = a;
      }
      barrier();
    }
  }
  for (int e = t; e < n; e += kThreads) cp_order[block + e] = s_pairs[e];
}
#endif
