#include "welkin/godrays/components.h"

namespace welkin::godrays {

void describe(TypeBuilder<GodRays>& t) {
  t.tooltip("Light shafts: the sunlight shadowed air does not scatter, taken from the aerial perspective");
  t.field("method", &GodRays::method).values({{"marched", 0}, {"screen_space", 1}})
      .tooltip("marched: physical, through every shadow; screen_space: cheap, sun on screen, geometry only");
  t.field("resolution_divisor", &GodRays::resolution_divisor)
      .range(1, 8)
      .tooltip("Shafts at 1/d of the frame, upsampled");
  t.field("max_distance_m", &GodRays::max_distance_m)
      .unit("m")
      .range(1, 1e6)
      .tooltip("Air beyond is taken as lit");
  t.field("steps", &GodRays::steps)
      .range(1, kMaxStepsPerRay)
      .tooltip("marched: shadow samples per ray (whole segments of four)");
  t.field("screen_samples", &GodRays::screen_samples)
      .range(1, kMaxStepsPerRay)
      .tooltip("screen_space: depth taps toward the sun");
  t.field("screen_reach", &GodRays::screen_reach)
      .range(0, 1)
      .tooltip("screen_space: how far toward the sun's image the taps go");
  t.field("jitter", &GodRays::jitter).tooltip("Per-pixel sample offsets (off: step midpoints, banded)");
  t.field("air_steps", &GodRays::air_steps)
      .range(1, kMaxStepsPerRay)
      .tooltip("screen_space: segments of the air's unshadowed light");
}

void describe(TypeBuilder<Haze>& t) {
  t.tooltip("Sparse fog over the ground (takram's haze), added to the aerial perspective");
  t.field("density_per_m", &Haze::density_per_m).unit("1/m").range(0, 1).tooltip("Density at the ground");
  t.field("scale_height_m", &Haze::scale_height_m)
      .unit("m")
      .range(1, 100000)
      .tooltip("Height over which the density falls by e");
  t.field("scattering", &Haze::scattering).range(0, 10).tooltip("Scattering per unit density");
  t.field("absorption", &Haze::absorption).range(0, 10).tooltip("Absorption per unit density");
  t.field("phase_g", &Haze::phase_g)
      .range(-0.999, 0.999)
      .tooltip("Henyey-Greenstein asymmetry of the aerosol");
}

}  // namespace welkin::godrays
