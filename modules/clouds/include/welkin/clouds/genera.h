#pragma once
// The cloud genera (WMO), one row each. Adding a genus is a row here and its preset file
// presets/genera/<name>.json; the Genus enum, the names the JSON reads and writes and the density
// field's shape model all come from this table, and a test checks the table against the preset folder.
#include <cstddef>

// X(name, dome, weather_frequency, thickness_m, density_per_m, casts_shadow, billow, wisp, edge,
//   streak, hook_s, anvil_start, anvil_spread)
//   dome: 0 a sheet .. 1 domes with flat bases; weather_frequency: the layer's weather frequency
//   relative to VolumetricClouds::weather_period_m;
//   thickness_m, density_per_m, casts_shadow: a typical layer of the genus where only its base is
//   known (a weather report gives bases, not tops: fair-weather cumulus about 1 km deep, sheets a few
//   hundred metres; the weather module builds its layers from them);
//   billow, wisp: how deep the detail noise erodes the layer's upper part into rounded billows
//   (cauliflower tops: the inverted Worley noise) and its base into wisps (the Worley noise), as a
//   fraction of the density (Schneider 2015's height blend; heaps billow, cirrus is wisps, sheets
//   hardly either); edge: how fast the density rises inside the noise's edge (crisp heaps, soft veils);
//   streak: how far the shape and detail noise are stretched along the layer's wind (1: not; cirrus's
//   fibres); hook_s: the wind's shear across the layer, as the seconds of wind by which its base trails
//   its top (fall streaks hooked downwind; 0: none); anvil_start: where, as a fraction of the
//   thickness, the cloud starts to spread out under the layer's ceiling into a flat, smooth anvil
//   (cumulonimbus; 0: no anvil); anvil_spread: how far it spreads, the fraction of the clear sky around
//   the towers its top covers.
#define WELKIN_CLOUD_GENERA(X)                                                                  \
  X(cumulus, 1.0f, 2.5f, 1000.0f, 0.05f, true, 0.35f, 0.3f, 3.0f, 1.0f, 0.0f, 0.0f, 0.0f)       \
  X(stratus, 0.0f, 0.5f, 400.0f, 0.03f, true, 0.1f, 0.2f, 1.5f, 1.0f, 0.0f, 0.0f, 0.0f)         \
  X(stratocumulus, 0.4f, 1.6f, 600.0f, 0.04f, true, 0.3f, 0.25f, 2.5f, 1.0f, 0.0f, 0.0f, 0.0f)  \
  X(cumulonimbus, 1.0f, 0.4f, 9000.0f, 0.08f, true, 0.4f, 0.3f, 3.0f, 1.0f, 0.0f, 0.72f, 1.2f)  \
  X(altocumulus, 0.5f, 4.0f, 500.0f, 0.02f, true, 0.3f, 0.25f, 2.0f, 1.0f, 0.0f, 0.0f, 0.0f)    \
  X(altostratus, 0.0f, 0.7f, 1200.0f, 0.005f, true, 0.05f, 0.15f, 1.0f, 1.0f, 0.0f, 0.0f, 0.0f) \
  X(nimbostratus, 0.1f, 0.4f, 2500.0f, 0.04f, true, 0.1f, 0.2f, 1.5f, 1.0f, 0.0f, 0.0f, 0.0f)   \
  X(cirrus, 0.2f, 2.5f, 800.0f, 0.002f, false, 0.4f, 0.5f, 1.6f, 6.0f, 120.0f, 0.0f, 0.0f)      \
  X(cirrostratus, 0.0f, 0.5f, 600.0f, 0.0008f, false, 0.0f, 0.1f, 1.0f, 3.0f, 0.0f, 0.0f, 0.0f) \
  X(cirrocumulus, 0.3f, 8.0f, 300.0f, 0.004f, false, 0.3f, 0.2f, 1.5f, 1.0f, 0.0f, 0.0f, 0.0f)

namespace welkin::clouds {

// The genus picks the shape model of a layer (domes with flat bases, sheets, rolls, streaks) and the
// defaults of its preset file. Values are the rows' order.
enum class Genus : int {
#define WELKIN_GENUS_ENUMERATOR(name, ...) name,
  WELKIN_CLOUD_GENERA(WELKIN_GENUS_ENUMERATOR)
#undef WELKIN_GENUS_ENUMERATOR
};

struct GenusTraits {
  Genus genus;
  const char* name;
  float dome;               // 0 a sheet .. 1 domes with flat bases
  float weather_frequency;  // relative to the weather's period
  float thickness_m;        // a typical layer's
  float density_per_m;
  bool casts_shadow;
  float billow;        // the detail noise's erosion at the top (rounded billows)
  float wisp;          // and at the base (wisps)
  float edge;          // the density's rise inside the edge
  float streak;        // the noise's stretch along the wind (1: none)
  float hook_s;        // the base's lag behind the top, in seconds of the layer's wind (fall streaks)
  float anvil_start;   // where the anvil starts (a fraction of the thickness; 0: no anvil)
  float anvil_spread;  // the fraction of the clear sky around the towers the anvil covers
};

inline constexpr GenusTraits kGenera[] = {
#define WELKIN_GENUS_ROW(name, dome, frequency, thickness, density, shadow, billow, wisp, edge, streak, \
                         hook, anvil_start, anvil_spread)                                               \
  {Genus::name, #name, dome, frequency, thickness, density,     shadow,                                 \
   billow,      wisp,  edge, streak,    hook,      anvil_start, anvil_spread},
    WELKIN_CLOUD_GENERA(WELKIN_GENUS_ROW)
#undef WELKIN_GENUS_ROW
};
inline constexpr int kGenusCount = int(sizeof(kGenera) / sizeof(kGenera[0]));

// The row of a genus; throws Error for a value outside the table (an int cast to Genus).
const GenusTraits& genus_traits(Genus genus);

}  // namespace welkin::clouds
