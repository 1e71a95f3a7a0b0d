#pragma once
// Whether a reader's work grows linearly with its input: the same work timed on an input of size n,
// 10n and 100n, one after the other in this process, each the best of a few runs. The time is this
// thread's CPU time, so other processes on a busy machine do not count. Tests compare the ratios
// (about 10 and 10 when linear, 100 and 100 when quadratic) with a generous factor, never a time
// against a fixed limit, so a slow machine changes the times but not the verdict.
#include <algorithm>
#include <cstdio>
#include <ctime>
#include <functional>
#include <string>

namespace welkin::testing {

struct Growth {
  double t1 = 0, t10 = 0, t100 = 0;  // seconds, at n, 10n and 100n
  // Ratios of the larger inputs' times to the smaller ones'.
  double x10() const { return t10 / t1; }
  double x100() const { return t100 / t10; }
  std::string describe() const {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.3g ms, %.3g ms, %.3g ms: x%.1f then x%.1f", t1 * 1e3, t10 * 1e3,
                  t100 * 1e3, x10(), x100());
    return buf;
  }
  // Each step of 10x in the input costs at most `factor` times 10x in time (quadratic work: 100x).
  bool linear(double factor = 3.5) const { return x10() < 10 * factor && x100() < 10 * factor; }
};

inline double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// `make(size)` builds an input (not timed); `run(input)` is the work under test (timed).
template <class Make, class Run>
Growth measure_growth(size_t n, Make make, Run run) {
  auto best_of = [&](size_t size, int repeats) {
    auto input = make(size);
    double best = 1e30;
    for (int r = 0; r < repeats; ++r) {
      const double start = thread_seconds();
      run(input);
      best = std::min(best, thread_seconds() - start);
    }
    return std::max(best, 1e-7);  // a clock tick at least
  };
  best_of(n, 1);  // warm up: first touches of code and allocator
  Growth g;
  g.t1 = best_of(n, 7);
  g.t10 = best_of(10 * n, 4);
  g.t100 = best_of(100 * n, 2);
  std::printf("[  growth  ] %s\n", g.describe().c_str());  // the figures, in the test log
  return g;
}

}  // namespace welkin::testing
