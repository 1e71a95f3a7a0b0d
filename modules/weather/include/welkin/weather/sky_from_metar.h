#pragma once
// What a decoded report means for the scene: cloud layers from the cloud groups, haze from the
// visibility, the layers' drift from the wind, the clock from the day and time. Pure functions, so
// the mapping is tested without a world.
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "welkin/clouds/components.h"
#include "welkin/weather/metar.h"

namespace welkin::weather {

// The height where the WMO's cloud étages meet in temperate regions: low clouds below 6500 ft
// (2 km), middle up to 20 000 ft (6 km), high above.
inline constexpr int kMiddleCloudsFromFt = 6500;
inline constexpr int kHighCloudsFromFt = 20000;

// The genus a cloud group stands for: CB cumulonimbus, TCU towering cumulus (cumulus, thick);
// otherwise by height and amount: low FEW/SCT cumulus, BKN stratocumulus, OVC stratocumulus (stratus
// below 1000 ft, nimbostratus with rain or snow); middle altocumulus (OVC altostratus); high cirrus
// (OVC cirrostratus). VV (sky obscured) is stratus from the ground.
clouds::Genus genus_of(const MetarCloud& cloud, const MetarReport& report);

// The fraction of the sky the group covers: the middle of its oktas over eight (FEW 1.5/8,
// SCT 3.5/8, BKN 6/8, OVC and VV 8/8).
float sky_fraction_of(const MetarCloud& cloud);
// The clouds' coverage parameter whose layer covers `sky_fraction` of the sky as seen from above:
// the noise erodes thin coverage, so the parameter is not the fraction (0.45 covers 35%). Inverts
// a measured curve (kSeenFraction in the source; docs/weather.md says how it was measured).
float coverage_parameter_for(float sky_fraction);
// Both together: the layer's coverage for a cloud group.
float coverage_of(const MetarCloud& cloud);

// Drift of the clouds, toward where the wind blows (east, north), m/s; a variable wind (VRB) has no
// direction and drifts nothing.
glm::vec2 drift_of(const MetarWind& wind);

// Aerosol (Mie) extinction at the ground, 1/km, that makes `visibility_m` the meteorological optical
// range: Koschmieder's contrast law at WMO's 5% threshold, extinction = ln(20) / MOR, less what the
// air itself (Rayleigh, at 550 nm) takes out.
double haze_extinction_per_km(double visibility_m, double rayleigh_per_km_550nm);
// Earth's Rayleigh scattering at sea level in the green (the atmosphere's default, Hillaire 2020),
// for showing a report's haze without a scene.
inline constexpr double kEarthRayleighPerKmGreen = 13.558e-3;

struct SkyFromReport {
  std::vector<clouds::CloudLayer> layers;  // lowest first, one per cloud group
  glm::vec2 wind_mps{0.0f};
  // Set only when the visibility is below 10 km (10 km or more is the clear air the scene has).
  std::optional<double> visibility_m;
  int day = 1;
  double utc_time_h = 0.0;
};
SkyFromReport sky_from_metar(const MetarReport& report);

}  // namespace welkin::weather
