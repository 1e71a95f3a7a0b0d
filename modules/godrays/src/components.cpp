#include "welkin/godrays/components.h"

namespace welkin::godrays {

void describe(TypeBuilder<GodRays>& t) {
  t.tooltip("Light shafts: the sunlight shadowed air does not scatter, taken from the aerial perspective");
  t.field("method", &GodRays::method).values({{"marched", 0}, {"screen_space", 1}})
      .tooltip("marched: physical, through every shadow; screen_space: cheap, sun on screen, geometry only");
  t.field("resolution_divisor", &GodRays::resolution_divisor).range(1, 8).tooltip("Shafts at 1/d of the frame, upsampled");
  t.field("max_distance_m", &GodRays::max_distance_m).unit("m").range(1, 1e6).tooltip("Air beyond is taken as lit");
  t.field("steps", &GodRays::steps).range(1, kMaxStepsPerRay).tooltip("marched: samples per ray");
  t.field("screen_samples", &GodRays::screen_samples).range(1, kMaxStepsPerRay).tooltip("screen_space: depth taps toward the sun");
  t.field("screen_reach", &GodRays::screen_reach).range(0, 1).tooltip("screen_space: how far toward the sun's image the taps go");
  t.field("jitter", &GodRays::jitter).tooltip("Per-pixel sample offsets (off: step midpoints, banded)");
  t.field("air_steps", &GodRays::air_steps).range(1, kMaxStepsPerRay).tooltip("screen_space: steps of the air's unshadowed light");
}

}  // namespace welkin::godrays
