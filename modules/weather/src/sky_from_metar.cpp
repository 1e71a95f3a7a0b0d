// The mapping from a report to the sky. Thicknesses and densities are typical of each genus as a
// report implies it (a report gives bases, not tops): the genus table's (welkin/clouds/genera.h),
// towering cumulus 4 km, cumulonimbus up to the tropopause (about 11 km).
#include "welkin/weather/sky_from_metar.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>

#include "welkin/clouds/genera.h"

namespace welkin::weather {

namespace {

constexpr double kMetresPerFoot = 0.3048;
constexpr float kTropopauseM = 11000.0f;

bool precipitating(const MetarReport& r) {
  return r.has_weather("RA") || r.has_weather("SN") || r.has_weather("DZ") || r.has_weather("PL");
}

}  // namespace

clouds::Genus genus_of(const MetarCloud& c, const MetarReport& r) {
  using clouds::Genus;
  if (c.cover == CloudCover::vertical_visibility) return Genus::stratus;
  if (c.type == "CB") return Genus::cumulonimbus;
  if (c.type == "TCU") return Genus::cumulus;
  bool overcast = c.cover == CloudCover::overcast;
  if (c.base_ft >= kHighCloudsFromFt) return overcast ? Genus::cirrostratus : Genus::cirrus;
  if (c.base_ft >= kMiddleCloudsFromFt) return overcast ? Genus::altostratus : Genus::altocumulus;
  if (c.cover == CloudCover::few || c.cover == CloudCover::scattered) return Genus::cumulus;
  if (c.cover == CloudCover::broken) return Genus::stratocumulus;
  if (precipitating(r)) return Genus::nimbostratus;
  return c.base_ft < 1000 ? Genus::stratus : Genus::stratocumulus;
}

float sky_fraction_of(const MetarCloud& c) {
  return 0.5f * float(c.oktas_min() + c.oktas_max()) / 8.0f;
}

namespace {
// The fraction of pixels brighter than the ground seen straight down from 15 km on a cumulus layer
// (base 1372 m, 1000 m thick, 0.05/m, sun at 70 degrees, 200x200 pixels, 70 degrees field of view)
// per coverage parameter, rendered with `welkin render` at Welkin's main of 2026-11-27. A
// stratocumulus and an altocumulus layer measured within 0.06 of it.
struct SeenFraction {
  float coverage, seen;
};
constexpr SeenFraction kSeenFraction[] = {{0.15f, 0.0f},   {0.25f, 0.021f}, {0.35f, 0.171f},
                                          {0.45f, 0.353f}, {0.55f, 0.53f},  {0.65f, 0.688f},
                                          {0.75f, 0.834f}, {0.85f, 0.978f}, {0.95f, 1.0f}};
}  // namespace

float coverage_parameter_for(float fraction) {
  if (fraction <= 0.0f) return 0.0f;
  if (fraction >= 1.0f) return 1.0f;  // overcast: no gaps at all
  for (size_t i = 1; i < std::size(kSeenFraction); ++i) {
    const SeenFraction &a = kSeenFraction[i - 1], &b = kSeenFraction[i];
    if (fraction <= b.seen)
      return a.coverage + (b.coverage - a.coverage) * (fraction - a.seen) / (b.seen - a.seen);
  }
  return 1.0f;
}

float coverage_of(const MetarCloud& c) {
  return coverage_parameter_for(sky_fraction_of(c));
}

glm::vec2 drift_of(const MetarWind& w) {
  if (!w.direction_deg) return glm::vec2(0.0f);
  double from = *w.direction_deg * std::numbers::pi / 180.0;
  // A wind from the west (270) blows toward the east.
  return glm::vec2(float(-w.speed_mps * std::sin(from)), float(-w.speed_mps * std::cos(from)));
}

double haze_extinction_per_km(double visibility_m, double rayleigh_per_km_550nm) {
  double total = std::log(20.0) / (std::max(visibility_m, 1.0) / 1000.0);
  return std::max(total - rayleigh_per_km_550nm, 0.0);
}

SkyFromReport sky_from_metar(const MetarReport& r) {
  SkyFromReport sky;
  if (r.wind) sky.wind_mps = drift_of(*r.wind);
  if (r.visibility && !(r.visibility->at_least && r.visibility->metres >= 9000.0) &&
      r.visibility->metres < 10000.0)
    sky.visibility_m = std::max(r.visibility->metres, 1.0);
  sky.day = r.day;
  sky.utc_time_h = r.hour + r.minute / 60.0;
  for (const MetarCloud& c : r.clouds) {
    clouds::CloudLayer layer;
    layer.genus = genus_of(c, r);
    const clouds::GenusTraits& look = clouds::kGenera[int(layer.genus)];  // genus_of gives a row
    float base_m = float(c.base_ft * kMetresPerFoot);
    layer.base_altitude_m = c.cover == CloudCover::vertical_visibility ? 0.0f : base_m;
    layer.thickness_m = look.thickness_m;
    if (c.type == "TCU") layer.thickness_m = 4000.0f;
    if (layer.genus == clouds::Genus::cumulonimbus)
      layer.thickness_m = std::max(kTropopauseM - base_m, 6000.0f);
    if (c.cover == CloudCover::vertical_visibility) layer.thickness_m = base_m + look.thickness_m;
    layer.coverage = coverage_of(c);
    layer.density_per_m = look.density_per_m;
    layer.casts_shadow = look.casts_shadow;
    layer.wind_mps = sky.wind_mps;
    sky.layers.push_back(layer);
  }
  return sky;
}

}  // namespace welkin::weather
