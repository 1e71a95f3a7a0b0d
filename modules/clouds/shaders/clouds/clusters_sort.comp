// Bitonic sort of the puffs' (key, index) pairs, far first, so that the instanced draw composites
// them back to front. CLUSTERS_SORT_MODE
//   0: sorts each block of CLUSTERS_SORT_BLOCK (<= 1024) in shared memory;
//   1: the narrow steps (j < the block) of merge u_k for each block, in shared memory;
//   2: one wide step (u_k, u_j >= the block) across the whole buffer.
layout(std430, binding = 5) buffer ClusterOrder { uvec2 cp_order[]; };
uniform int u_size;  // a power of two
uniform int u_k, u_j;

// Whether the pair at (i, i + j) is out of order: descending where bit k of i is clear.
bool out_of_order(uvec2 a, uvec2 b, int i, int k) {
  float ka = uintBitsToFloat(a.x), kb = uintBitsToFloat(b.x);
  return (i & k) == 0 ? ka < kb : ka > kb;
}

#if CLUSTERS_SORT_MODE == 2
layout(local_size_x = 512) in;
void main() {
  int t = int(gl_GlobalInvocationID.x);
  if (t >= u_size / 2) return;
  int i = 2 * t - (t & (u_j - 1)), l = i + u_j;  // (t / j) 2j + t % j for j a power of two
  uvec2 a = cp_order[i], b = cp_order[l];
  if (out_of_order(a, b, i, u_k)) cp_order[i] = b, cp_order[l] = a;
}
#else
// The steps run in rounds (CLUSTERS_SORT_ROUNDS, listed by src/placement.cpp). In a round each
// invocation holds in registers the kPer pairs whose indices differ from one another only in a window
// of kBits bits starting at `low`, and does every consecutive step that compares across those bits
// (j = 2^(low + b)) there. Shared memory is read and written once per round instead of once per step:
// llvmpipe reads and writes it one lane at a time.
const int kBlock = CLUSTERS_SORT_BLOCK, kPer = CLUSTERS_SORT_PER, kBits = CLUSTERS_SORT_BITS;
const int kThreads = kBlock / kPer;
layout(local_size_x = kThreads) in;
shared uvec2 s_pairs[kBlock];
uvec2 r[kPer];
int block, t;

// The index of the invocation's m-th pair: m's bits inserted into t's at bit `low`.
int window_index(int m, int low) {
  int below = t & ((1 << low) - 1);
  return ((t >> low) << (low + kBits)) | (m << low) | below;
}
void round_begin(int low) {
  for (int m = 0; m < kPer; ++m) r[m] = s_pairs[window_index(m, low)];
}
void round_step(int k, int low, int b) {
  const int d = 1 << b;
  for (int m = 0; m < kPer; ++m) {
    if ((m & d) != 0) continue;
    uvec2 a = r[m], c = r[m + d];
    bool swap = out_of_order(a, c, block + window_index(m, low), k);
    r[m] = swap ? c : a;
    r[m + d] = swap ? a : c;
  }
}
void round_end(int low) {
  for (int m = 0; m < kPer; ++m) s_pairs[window_index(m, low)] = r[m];
  barrier();
}
#define SORT_ROUND_BEGIN(low) round_begin(low);
#define SORT_STEP(k, low, b) round_step(k, low, b);
#define SORT_ROUND_END(low) round_end(low);

void main() {
  block = int(gl_WorkGroupID.x) * kBlock, t = int(gl_LocalInvocationID.x);
  for (int e = t; e < kBlock; e += kThreads) s_pairs[e] = cp_order[block + e];
  barrier();
  CLUSTERS_SORT_ROUNDS
  for (int e = t; e < kBlock; e += kThreads) cp_order[block + e] = s_pairs[e];
}
#endif
