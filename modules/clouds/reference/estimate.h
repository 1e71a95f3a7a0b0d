// Sample mean with its 95% confidence half-width, and the running sums that produce it.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace welkin::clouds::reference {

// A Monte Carlo estimate: the mean and 1.96 standard errors of it (normal approximation).
struct Estimate {
  double mean = 0.0;
  double ci95 = 0.0;
};

// Sum and sum of squares of the samples; merged in a fixed order for reproducible results.
struct SampleSums {
  double sum = 0.0;
  double sum_sq = 0.0;
  std::uint64_t count = 0;

  void add(double x) {
    sum += x;
    sum_sq += x * x;
    ++count;
  }
  void merge(const SampleSums& other) {
    sum += other.sum;
    sum_sq += other.sum_sq;
    count += other.count;
  }
  Estimate estimate() const {
    if (count == 0) return {};
    const double n = static_cast<double>(count);
    const double mean = sum / n;
    if (count < 2) return {mean, 0.0};
    const double variance = std::max(0.0, (sum_sq - sum * mean) / (n - 1.0));
    return {mean, 1.96 * std::sqrt(variance / n)};
  }
};

}  // namespace welkin::clouds::reference
