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
  // marched: shadow samples along each ray (jittered per pixel), in segments of four whose ends look
  // the air up; rounded up to whole segments
  int steps = 8;
  int screen_samples = 16;           // screen_space: depth taps toward the sun's image
  float screen_reach = 0.5f;         // screen_space: fraction of the way to the sun's image the taps cover
  int air_steps = 2;                 // screen_space: segments of the unshadowed air light along the ray
  // Samples offset per pixel and frame (interleaved gradient noise): banding becomes fine noise. Off:
  // at the steps' midpoints (the reference march of `welkin accuracy godrays`).
  bool jitter = true;
};
void describe(TypeBuilder<GodRays>& t);

// Haze: takram's sparse fog, an exponential layer of aerosol over the ground added to what the
// atmosphere's aerial perspective gives every material (density_per_m e^{-h / scale_height_m}; extinction
// (scattering + absorption) x density). Lit by the sun through the atmosphere (a Henyey-Greenstein
// lobe; shadowed by the marched god rays where the scene has them) and by the sky's irradiance.
struct Haze {
  static constexpr std::string_view kTypeName = "godrays.Haze";
  float density_per_m = 3e-5f;     // at the ground (takram's hazeDensityScale)
  float scale_height_m = 1000.0f;  // takram's hazeExponent 1e-3 /m
  float scattering = 0.9f;         // per unit density
  float absorption = 0.5f;
  float phase_g = 0.6f;            // forward scattering of the aerosol
};
void describe(TypeBuilder<Haze>& t);

// The most samples one ray may take (steps, or screen taps plus air steps): a frame always finishes.
inline constexpr int kMaxStepsPerRay = 1024;

}  // namespace welkin::godrays
