// Free-flight sampling and transmittance estimation against piecewise-constant majorants: the
// building blocks of the path tracer and of the slab flux estimator, public so that tests check
// them directly.
#pragma once

#include <cstdint>

#include "reference/medium.h"
#include "reference/random_stream.h"

namespace welkin::clouds::reference {

// Work allowance and bookkeeping shared by every tracking call of one path.
struct TrackingBudget {
  std::uint64_t remaining_steps = 1'000'000;  // Tentative collisions left to this path.
  std::uint64_t majorant_violations = 0;      // Points where extinction exceeded its majorant.
  bool exhausted() const { return remaining_steps == 0; }
};

// Distance to the next real collision by delta (Woodcock) tracking, or kInfinity when the ray
// leaves the medium (or the budget runs out: check budget.exhausted()).
double sample_free_flight(const Medium& medium, const Ray& ray, RandomStream& rng, TrackingBudget& budget);

// Unbiased estimate of the transmittance between t = 0 and t_max by ratio tracking, with
// Russian roulette once the estimate falls below 0.1 (so opaque media end quickly).
double ratio_tracking_transmittance(const Medium& medium, const Ray& ray, double t_max, RandomStream& rng,
                                    TrackingBudget& budget);

}  // namespace welkin::clouds::reference
