// The moon against Meeus, Astronomical Algorithms 2nd ed.: examples 47.a (position), 48.a
// (illuminated fraction) and 40.a (topocentric parallax, the code the moon and sun share).
#include "welkin/timeofday/moon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "welkin/timeofday/observer.h"
#include "welkin/timeofday/sun.h"

namespace welkin::timeofday {
namespace {

constexpr double kArcsec = 1.0 / 3600.0;

// 1992 April 12, 0h TD.
EarthOrientation example_47a() { return earth_orientation(2448724.5, 0.0); }

TEST(Moon, MeeusExample47aEclipticPosition) {
  const MoonGeocentric m = moon_geocentric(example_47a());
  EXPECT_NEAR(m.mean_longitude_deg, 134.290182, 1e-6);
  EXPECT_NEAR(m.longitude_deg, 133.162655, 1e-6);
  EXPECT_NEAR(m.latitude_deg, -3.229126, 1e-6);
  EXPECT_NEAR(m.distance_km, 368409.7, 0.05);
  EXPECT_NEAR(m.horizontal_parallax_deg, 0.991990, 1e-6);
}

TEST(Moon, MeeusExample47aApparentPosition) {
  const EarthOrientation e = example_47a();
  EXPECT_NEAR(e.nutation.longitude_deg, 0.004610, 5e-7);
  EXPECT_NEAR(e.true_obliquity_deg, 23.440636, 2e-6);
  const MoonGeocentric m = moon_geocentric(e);
  EXPECT_NEAR(m.apparent_longitude_deg, 133.167265, 1.5e-6);
  EXPECT_NEAR(m.equatorial.ra_deg, 134.688470, 1.5e-6);
  EXPECT_NEAR(m.equatorial.dec_deg, 13.768368, 1.5e-6);
}

TEST(Moon, MeeusExample48aIlluminatedFraction) {
  // Same instant; Meeus takes the sun from ch. 25 (alpha0 = 20.6579, delta0 = 8.6964 degrees,
  // R = 149 971 520 km); this library takes it from SPA.
  const EarthOrientation e = example_47a();
  const SunGeocentric sun = sun_geocentric(e);
  EXPECT_NEAR(sun.equatorial.ra_deg, 20.6579, 1e-4);
  EXPECT_NEAR(sun.equatorial.dec_deg, 8.6964, 1.5e-4);
  // Meeus' low-accuracy solar theory of ch. 25 differs from VSOP87 by ~1e-6 AU.
  EXPECT_NEAR(sun.distance_au * kAstronomicalUnitKm, 149971520.0, 150.0);
  const LunarPhase phase = lunar_phase(moon_geocentric(e), sun);
  EXPECT_NEAR(phase.elongation_deg, 110.7929, 1e-4);
  EXPECT_NEAR(phase.phase_angle_deg, 69.0756, 2e-4);
  EXPECT_NEAR(phase.illuminated_fraction, 0.6786, 5e-5);
}

TEST(Moon, MeeusExample40aTopocentricParallax) {
  // Mars from Palomar (33 21'22" N, 7h47m27s W, 1706 m) on 2003 August 28, 3h17m UT:
  // geocentric alpha 339.530208, delta -15.771083 degrees, distance 0.37276 AU, hour angle
  // 288.7958 degrees. Meeus finds alpha' = 22h38m08.54s and delta' = -15 46'30.0".
  const Observer palomar{.latitude_deg = 33.0 + 21.0 / 60 + 22.0 / 3600,
                         .longitude_deg = -(7.0 + 47.0 / 60 + 27.0 / 3600) * 15.0,
                         .elevation_m = 1706.0,
                         .pressure_mbar = 0.0};
  const Equatorial mars{339.530208, -15.771083};
  EarthOrientation earth;
  earth.apparent_sidereal_time_deg =
      normalize_degrees(288.7958 + mars.ra_deg - palomar.longitude_deg);
  const TopocentricPosition t = observe(mars, sun_sin_parallax(0.37276), earth, palomar,
                                        RefractionSettings{.enabled = false});
  EXPECT_NEAR(t.hour_angle_deg, 288.7958, 1e-9);
  EXPECT_NEAR(t.ra_parallax_deg * 240.0, 1.29, 0.005);  // seconds of time
  EXPECT_NEAR(t.equatorial.ra_deg, (22.0 + 38.0 / 60 + 8.54 / 3600) * 15.0, 0.01 * 15 * kArcsec);
  EXPECT_NEAR(t.equatorial.dec_deg, -(15.0 + 46.0 / 60 + 30.0 / 3600), 0.1 * kArcsec);
}

TEST(Moon, ParallaxLowersTheMoonByItsHorizontalParallaxOnTheHorizon) {
  // Parallax in altitude is pi cos(h): a moon on the geocentric horizon is seen almost a full
  // degree lower by an observer on the surface.
  const EarthOrientation e = example_47a();
  const MoonGeocentric m = moon_geocentric(e);
  Observer observer{.latitude_deg = 0.0, .pressure_mbar = 0.0};
  // Put the observer where the moon's geocentric hour angle is 90 degrees: it is setting.
  observer.longitude_deg =
      normalize_degrees_signed(90.0 + m.equatorial.ra_deg - e.apparent_sidereal_time_deg);
  const TopocentricPosition geo = observe(m.equatorial, 0.0, e, observer);
  const TopocentricPosition topo =
      observe(m.equatorial, kEarthEquatorialRadiusKm / m.distance_km, e, observer);
  EXPECT_NEAR(geo.true_elevation_deg - topo.true_elevation_deg,
              m.horizontal_parallax_deg * std::cos(geo.true_elevation_deg * kDegToRad), 0.002);
  EXPECT_GT(topo.distance_ratio, 0.99);
  EXPECT_LT(std::abs(topo.distance_ratio - 1.0), 0.001);
}

TEST(Moon, AngularRadius) {
  // Meeus ch. 55: the geocentric semi-diameter is 358 473 400 / Delta arc-seconds (Delta in km).
  for (double distance : {356500.0, 384400.0, 406700.0}) {
    EXPECT_NEAR(angular_radius_deg(kMoonRadiusKm, distance), 358473400.0 / distance * kArcsec,
                0.5 * kArcsec);
  }
  EXPECT_THROW(angular_radius_deg(kMoonRadiusKm, 1000.0), std::invalid_argument);
  EXPECT_THROW(angular_radius_deg(kMoonRadiusKm, std::nan("")), std::invalid_argument);
}

TEST(Moon, PhaseCoversAFullLunation) {
  // Across a synodic month the phase angle sweeps 0-180 degrees and k = (1 + cos i) / 2.
  double min_phase = 180.0, max_phase = 0.0;
  for (double jd = 2460400.5; jd < 2460430.5; jd += 0.25) {
    const EarthOrientation e = earth_orientation(jd, 69.0);
    const LunarPhase p = lunar_phase(moon_geocentric(e), sun_geocentric(e));
    min_phase = std::min(min_phase, p.phase_angle_deg);
    max_phase = std::max(max_phase, p.phase_angle_deg);
    EXPECT_NEAR(p.illuminated_fraction, (1.0 + std::cos(p.phase_angle_deg * kDegToRad)) / 2.0,
                1e-12);
  }
  EXPECT_LT(min_phase, 5.0);
  EXPECT_GT(max_phase, 175.0);
}

}  // namespace
}  // namespace welkin::timeofday
