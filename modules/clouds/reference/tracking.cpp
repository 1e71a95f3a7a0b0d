#include "reference/tracking.h"

#include <algorithm>
#include <cmath>

namespace welkin::clouds::reference {

namespace {

// Exponential step with rate `majorant`; 1 - xi is in (0, 1], so the log is finite.
double exponential_step(RandomStream& rng, double majorant) {
  return -std::log(1.0 - rng.uniform()) / majorant;
}

}  // namespace

double sample_free_flight(const Medium& medium, const Ray& ray, RandomStream& rng, TrackingBudget& budget) {
  for (const MajorantSegment& segment : medium.segments(ray)) {
    if (!(segment.majorant > 0.0)) continue;
    double t = segment.t0;
    for (;;) {
      // Memoryless: a step that overshoots this stretch restarts at the next one.
      t += exponential_step(rng, segment.majorant);
      if (!(t < segment.t1)) break;
      if (budget.remaining_steps == 0) return kInfinity;
      --budget.remaining_steps;
      const double sigma = medium.extinction(ray.at(t));
      if (sigma > segment.majorant) ++budget.majorant_violations;
      if (rng.uniform() * segment.majorant < sigma) return t;
    }
  }
  return kInfinity;
}

double ratio_tracking_transmittance(const Medium& medium, const Ray& ray, double t_max, RandomStream& rng,
                                    TrackingBudget& budget) {
  constexpr double kRouletteThreshold = 0.1;
  double estimate = 1.0;
  for (const MajorantSegment& segment : medium.segments(ray)) {
    if (segment.t0 >= t_max) break;
    if (!(segment.majorant > 0.0)) continue;
    const double end = std::min(segment.t1, t_max);
    double t = segment.t0;
    for (;;) {
      t += exponential_step(rng, segment.majorant);
      if (!(t < end)) break;
      if (budget.remaining_steps == 0) return 0.0;
      --budget.remaining_steps;
      const double sigma = medium.extinction(ray.at(t));
      if (sigma > segment.majorant) ++budget.majorant_violations;
      estimate *= std::max(0.0, 1.0 - sigma / segment.majorant);
      if (estimate < kRouletteThreshold) {
        // Survive with probability estimate / threshold, carrying the threshold: unbiased.
        if (!(rng.uniform() * kRouletteThreshold < estimate)) return 0.0;
        estimate = kRouletteThreshold;
      }
    }
  }
  return estimate;
}

}  // namespace welkin::clouds::reference
