// The observer on Earth and the one topocentric pipeline (parallax, hour angle, horizontal
// coordinates, refraction) that both the sun and the moon go through.
#pragma once

#include <optional>
#include <string>

#include "welkin/timeofday/coordinates.h"
#include "welkin/timeofday/earth_orientation.h"

namespace welkin::timeofday {

// Where and in what air the sky is seen from. Longitude is positive east of Greenwich.
struct Observer {
  double latitude_deg = 0.0;       // geodetic, [-90, 90]
  double longitude_deg = 0.0;      // [-180, 180]
  double elevation_m = 0.0;        // above the reference ellipsoid
  double pressure_mbar = 1013.25;  // local, for refraction; 0 means no air
  double temperature_c = 15.0;     // local, for refraction
};

// Ranges accepted by validate(); wide enough for aircraft and spacecraft, narrow enough that the
// formulas stay meaningful (the refraction model divides by absolute temperature).
inline constexpr double kMinElevationM = -11000.0;  // deepest ocean floor
inline constexpr double kMaxElevationM = 1.0e8;     // well beyond geostationary orbit
inline constexpr double kMaxPressureMbar = 2000.0;
inline constexpr double kMinTemperatureC = -100.0;
inline constexpr double kMaxTemperatureC = 100.0;

// Why `observer` is unusable (NaN, latitude beyond +/-90, longitude beyond +/-180, elevation,
// pressure or temperature out of range), or nullopt when it is fine. Nothing is ever clamped.
std::optional<std::string> validate(const Observer& observer);

// How refraction is applied. The SPA paper's defaults: no correction once the body's upper limb is
// more than `horizon_refraction_deg` below the true horizon, where the formula is meaningless.
struct RefractionSettings {
  bool enabled = true;
  double body_radius_deg = 0.26667;        // apparent radius of the body's disc
  double horizon_refraction_deg = 0.5667;  // refraction at sunrise/sunset
};

// Refraction correction in degrees to add to a true (airless) elevation, from local pressure and
// temperature (SPA eq. 42, after Bennett / Saemundsson). Zero below the cut-off of `settings`.
double refraction_correction_deg(double true_elevation_deg, double pressure_mbar,
                                 double temperature_c, const RefractionSettings& settings = {});

// A body as seen from the observer. Angles in degrees; azimuth clockwise from north in [0, 360).
struct TopocentricPosition {
  double hour_angle_deg = 0.0;              // H, geocentric local hour angle, west of south
  double ra_parallax_deg = 0.0;             // Delta-alpha, topocentric minus geocentric RA
  Equatorial equatorial;                    // topocentric RA/dec
  double topocentric_hour_angle_deg = 0.0;  // H'
  double distance_ratio = 1.0;              // topocentric over geocentric distance
  double true_elevation_deg = 0.0;          // e0, without refraction
  double refraction_deg = 0.0;              // Delta-e
  double elevation_deg = 0.0;               // e, apparent
  double zenith_deg = 0.0;                  // 90 - e
  double azimuth_deg = 0.0;                 // Phi, clockwise from north
};

// Takes a geocentric apparent RA/dec to the observer: rigorous parallax for an oblate Earth (Meeus
// ch. 40; SPA eqs. 25-37), then horizontal coordinates and refraction. `sin_parallax` is the sine
// of the body's equatorial horizontal parallax (Earth's equatorial radius over its distance).
TopocentricPosition observe(const Equatorial& geocentric, double sin_parallax,
                            const EarthOrientation& earth, const Observer& observer,
                            const RefractionSettings& refraction = {});

}  // namespace welkin::timeofday
