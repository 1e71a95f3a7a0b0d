#pragma once
// Components of the god-rays module (reflection in src/components.cpp: JSON, ranges, the inspector,
// sequence tracks). Lengths are metres.
#include <string_view>

#include "welkin/core/reflection.h"

namespace welkin::godrays {

// How the shadowed part of the air's light is found:
//   marched      along each view ray through the light environment (the clouds' shadow map, the
//                terrain's cascades, whatever casts shadows), energy-conserving per step: physical
//   screen_space the fraction of the screen toward the sun's image that geometry hides (Mitchell
//                2007), times the air's unshadowed sunlight along the ray: cheap, only with the sun
//                on screen, and blind to what the depth buffer does not hold (clouds)
enum class ShaftMethod : int { marched = 0, screen_space = 1 };

// The atmosphere's aerial perspective adds the sunlight scattered by all the air in front of a
// surface, lit or not; god rays take back what the air in shadow does not scatter (the dark beams
// between the bright ones). Intensities are the atmosphere's: nothing to expose by hand.
struct GodRays {
  static constexpr std::string_view kTypeName = "godrays.GodRays";
  ShaftMethod method = ShaftMethod::marched;
  int resolution_divisor = 4;        // the shafts run at 1/d of the frame's width and height, then upsample
  float max_distance_m = 30000.0f;   // the air beyond is taken as lit (shadow maps end near there)
  int steps = 16;                    // marched: samples along each ray (jittered per pixel)
  int screen_samples = 24;           // screen_space: depth taps toward the sun's image
  float screen_reach = 0.5f;         // screen_space: fraction of the way to the sun's image the taps cover
  int air_steps = 4;                 // screen_space: steps of the unshadowed air light along the ray
  // Samples offset per pixel and frame (interleaved gradient noise): banding becomes fine noise. Off:
  // at the steps' midpoints (the reference march of `welkin accuracy godrays`).
  bool jitter = true;
};
void describe(TypeBuilder<GodRays>& t);

// The most samples one ray may take (steps, or screen taps plus air steps): a frame always finishes.
inline constexpr int kMaxStepsPerRay = 1024;

}  // namespace welkin::godrays
