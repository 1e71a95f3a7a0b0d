#include "welkin/clouds/blue_noise.h"

#include <cmath>
#include <random>
#include <stdexcept>

namespace welkin::clouds {

namespace {

// Gaussian energy of a pattern on a torus, updated point by point.
class Energy {
 public:
  Energy(int size, double sigma) : n_(size), e_(size_t(size) * size, 0.0), kernel_(size_t(size) * size) {
    for (int y = 0; y < n_; ++y)
      for (int x = 0; x < n_; ++x) {
        const int dx = std::min(x, n_ - x), dy = std::min(y, n_ - y);
        kernel_[size_t(y) * n_ + x] = std::exp(-(dx * dx + dy * dy) / (2.0 * sigma * sigma));
      }
  }
  void add(int p, double sign) {
    const int px = p % n_, py = p / n_;
    for (int y = 0; y < n_; ++y)
      for (int x = 0; x < n_; ++x)
        e_[size_t(y) * n_ + x] +=
            sign * kernel_[size_t((y - py + n_) % n_) * n_ + size_t((x - px + n_) % n_)];
  }
  // The set pixel of highest energy (tightest cluster) or the unset one of lowest (largest void).
  int extreme(const std::vector<uint8_t>& bits, bool cluster) const {
    int best = -1;
    for (int i = 0; i < n_ * n_; ++i) {
      if (bool(bits[size_t(i)]) != cluster) continue;
      if (best < 0 || (cluster ? e_[size_t(i)] > e_[size_t(best)] : e_[size_t(i)] < e_[size_t(best)]))
        best = i;
    }
    return best;
  }

 private:
  int n_;
  std::vector<double> e_, kernel_;
};

}  // namespace

std::vector<float> void_and_cluster(int size, uint32_t seed, double sigma) {
  if (size < 4 || size > 256) throw std::invalid_argument("void_and_cluster: size must be 4..256");
  const int count = size * size;
  std::vector<uint8_t> bits(size_t(count), 0);
  Energy energy(size, sigma);
  // Initial pattern: a tenth of the pixels at random, then moved from clusters to voids until stable.
  std::mt19937 rng(seed);
  int ones = 0;
  while (ones < count / 10) {
    const int p = int(rng() % uint32_t(count));
    if (bits[size_t(p)]) continue;
    bits[size_t(p)] = 1, energy.add(p, 1.0), ++ones;
  }
  for (int guard = 0; guard < count; ++guard) {
    const int c = energy.extreme(bits, true);
    bits[size_t(c)] = 0, energy.add(c, -1.0);
    const int v = energy.extreme(bits, false);
    bits[size_t(v)] = 1, energy.add(v, 1.0);
    if (v == c) break;
  }
  std::vector<int> rank(size_t(count), -1);
  // Ranks below the initial count: take clusters away from a copy.
  {
    std::vector<uint8_t> b = bits;
    Energy e = energy;
    for (int r = ones - 1; r >= 0; --r) {
      const int c = e.extreme(b, true);
      b[size_t(c)] = 0, e.add(c, -1.0);
      rank[size_t(c)] = r;
    }
  }
  // The rest: fill the largest void each time.
  for (int r = ones; r < count; ++r) {
    const int v = energy.extreme(bits, false);
    bits[size_t(v)] = 1, energy.add(v, 1.0);
    rank[size_t(v)] = r;
  }
  std::vector<float> out(static_cast<size_t>(count));
  for (int i = 0; i < count; ++i) out[size_t(i)] = (float(rank[size_t(i)]) + 0.5f) / float(count);
  return out;
}

}  // namespace welkin::clouds
