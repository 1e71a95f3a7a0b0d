// Eclipse geometry: exact two-disc overlap, limb darkening, and the total solar eclipses of
// 2017-08-21 and 2024-04-08 as published by NASA's eclipse predictions (Espenak).
#include "welkin/timeofday/eclipse.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "welkin/timeofday/coordinates.h"
#include "welkin/timeofday/sky.h"

namespace welkin::timeofday {
namespace {

TEST(EclipseGeometry, ConcentricDiscs) {
  EXPECT_DOUBLE_EQ(sun_visible_fraction(1.0, 1.0, 0.0), 0.0);    // total, equal discs
  EXPECT_DOUBLE_EQ(sun_visible_fraction(1.0, 1.05, 0.0), 0.0);   // total
  EXPECT_DOUBLE_EQ(sun_visible_fraction(1.0, 1.05, 0.04), 0.0);  // total, off-centre
  // Annular: the uncovered ring is 1 - (rm/rs)^2.
  EXPECT_NEAR(sun_visible_fraction(1.0, 0.9, 0.0), 1.0 - 0.81, 1e-15);
  EXPECT_NEAR(sun_visible_fraction(0.2666, 0.2500, 0.01), 1.0 - std::pow(0.25 / 0.2666, 2), 1e-15);
  EXPECT_DOUBLE_EQ(sun_visible_fraction(1.0, 0.0, 0.0), 1.0);
}

TEST(EclipseGeometry, SeparatedDiscs) {
  EXPECT_DOUBLE_EQ(sun_visible_fraction(1.0, 1.0, 2.0), 1.0);  // touching
  EXPECT_DOUBLE_EQ(sun_visible_fraction(1.0, 1.0, 5.0), 1.0);
  EXPECT_DOUBLE_EQ(sun_visible_fraction(0.27, 0.26, 0.53), 1.0);
}

TEST(EclipseGeometry, HalfOverlapOfEqualDiscs) {
  // Equal discs one radius apart share r^2 (2 pi / 3 - sqrt(3) / 2), so 1/3 + sqrt(3)/(2 pi) of
  // the sun stays visible.
  const double expected = 1.0 / 3.0 + std::sqrt(3.0) / (2.0 * kPi);
  EXPECT_NEAR(sun_visible_fraction(1.0, 1.0, 1.0), expected, 1e-14);
  EXPECT_NEAR(sun_visible_fraction(0.25, 0.25, 0.25), expected, 1e-14);
}

TEST(EclipseGeometry, ContinuousAndMonotoneInSeparation) {
  for (double rm : {0.8, 1.0, 1.1}) {
    double previous = -1.0;
    for (double d = 0.0; d <= rm + 1.1; d += 0.001) {
      const double v = sun_visible_fraction(1.0, rm, d);
      // The lens formula's arccos near internal tangency limits precision to ~1e-8.
      EXPECT_GE(v, previous - 1e-7) << rm << " " << d;
      EXPECT_LE(std::abs(v - previous), previous < 0.0 ? 2.0 : 0.01) << rm << " " << d;
      previous = v;
    }
  }
  // Just inside first contact almost nothing is covered; just past internal contact the annulus.
  EXPECT_NEAR(sun_visible_fraction(1.0, 0.9, 1.9 - 1e-9), 1.0, 1e-9);
  EXPECT_NEAR(sun_visible_fraction(1.0, 0.9, 0.1 + 1e-9), 0.19, 1e-6);
}

TEST(EclipseGeometry, FluxWithoutLimbDarkeningIsArea) {
  for (double rm : {0.5, 0.95, 1.0, 1.03, 1.5}) {
    for (double d = 0.0; d <= rm + 1.05; d += 0.0173) {
      EXPECT_NEAR(sun_visible_flux_fraction(1.0, rm, d, 0.0), sun_visible_fraction(1.0, rm, d),
                  1e-9)
          << rm << " " << d;
    }
  }
}

TEST(EclipseGeometry, LimbDarkenedCentralCover) {
  // A central disc of radius p covers, for I = 1 - u (1 - mu), the flux
  // pi [(1 - u) p^2 + (2u/3)(1 - (1 - p^2)^(3/2))] out of pi (1 - u/3).
  const double u = 0.6;
  for (double p : {0.1, 0.5, 0.9, 0.99}) {
    const double covered = (1.0 - u) * p * p + 2.0 * u / 3.0 * (1.0 - std::pow(1.0 - p * p, 1.5));
    EXPECT_NEAR(sun_visible_flux_fraction(1.0, p, 0.0, u), 1.0 - covered / (1.0 - u / 3.0), 1e-9)
        << p;
    // The bright centre is covered, so more light is lost than area.
    EXPECT_LT(sun_visible_flux_fraction(1.0, p, 0.0, u), sun_visible_fraction(1.0, p, 0.0));
  }
  // Grazing the dark limb removes less light than area.
  EXPECT_GT(sun_visible_flux_fraction(1.0, 1.0, 1.8, u), sun_visible_fraction(1.0, 1.0, 1.8));
  EXPECT_DOUBLE_EQ(sun_visible_flux_fraction(1.0, 1.02, 0.0, u), 0.0);
  EXPECT_DOUBLE_EQ(sun_visible_flux_fraction(1.0, 1.0, 2.5, u), 1.0);
}

TEST(EclipseGeometry, RejectsBadInput) {
  EXPECT_THROW(sun_visible_fraction(0.0, 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(sun_visible_fraction(1.0, -1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(sun_visible_fraction(1.0, 1.0, -0.1), std::invalid_argument);
  EXPECT_THROW(sun_visible_fraction(std::nan(""), 1.0, 0.0), std::invalid_argument);
  EXPECT_THROW(sun_visible_flux_fraction(1.0, 1.0, 0.5, 1.5), std::invalid_argument);
  EXPECT_THROW(sun_visible_flux_fraction(1.0, 1.0, 0.5, std::nan("")), std::invalid_argument);
}

// Seconds of totality within +/-400 s of `centre`, scanned at 0.25 s, and the mid-time.
struct Totality {
  double seconds = 0.0;
  double middle_offset_s = 0.0;
};

Totality totality(const Observer& observer, const UtcTime& centre) {
  double first = 1e9, last = -1e9;
  for (double s = -400.0; s <= 400.0; s += 0.25) {
    if (compute_sky(observer, centre.plus_seconds(s)).sun_visible_fraction == 0.0) {
      first = std::min(first, s);
      last = std::max(last, s);
    }
  }
  if (last < first) return {};
  return {last - first + 0.25, 0.5 * (first + last)};
}

// NASA: greatest eclipse of 2017-08-21 at 36 58.0'N 87 40.3'W, 18:25:32 UT, 2m40.2s of totality.
constexpr Observer kHopkinsville{.latitude_deg = 36.9667, .longitude_deg = -87.6717};
// NASA: greatest eclipse of 2024-04-08 at 25 17.4'N 104 08.3'W, 18:17:16 UT, 4m28.1s of totality.
constexpr Observer kNazas{.latitude_deg = 25.29, .longitude_deg = -104.1383, .elevation_m = 1300.0};

TEST(SolarEclipse, Total2017AtGreatestEclipse) {
  const UtcTime greatest = UtcTime::parse("2017-08-21T18:25:32Z");
  const SkyState sky = compute_sky(kHopkinsville, greatest);
  EXPECT_LT(sky.sun_visible_fraction, 0.01);
  EXPECT_LT(sky.sun.illuminance_lux, 1.0);
  // From Earth's centre the same instant is only a partial eclipse: the moon's parallax matters.
  const double geocentric_separation = angular_separation_deg({sky.sun.ra_deg, sky.sun.dec_deg},
                                                              {sky.moon.ra_deg, sky.moon.dec_deg});
  EXPECT_GT(geocentric_separation, 0.3);
  EXPECT_GT(sun_visible_fraction(sky.sun.angular_radius_deg, sky.moon.angular_radius_deg,
                                 geocentric_separation),
            0.2);
  const Totality t = totality(kHopkinsville, greatest);
  EXPECT_NEAR(t.seconds, 160.2, 5.0);
  EXPECT_NEAR(t.middle_offset_s, 0.0, 15.0);
  // Three hours later the eclipse is long over.
  EXPECT_GT(compute_sky(kHopkinsville, greatest.plus_seconds(3 * 3600.0)).sun_visible_fraction,
            0.99);
}

TEST(SolarEclipse, Partial2017BeginsOnTime) {
  // The partial phase at Hopkinsville began at 11:56 CDT (16:56 UT); an hour before totality a
  // large part of the sun, but not all, is covered.
  EXPECT_DOUBLE_EQ(
      compute_sky(kHopkinsville, UtcTime::parse("2017-08-21T16:55:00Z")).sun_visible_fraction, 1.0);
  EXPECT_LT(compute_sky(kHopkinsville, UtcTime::parse("2017-08-21T16:58:00Z")).sun_visible_fraction,
            1.0);
  const double f =
      compute_sky(kHopkinsville, UtcTime::parse("2017-08-21T17:25:32Z")).sun_visible_fraction;
  EXPECT_GT(f, 0.05);
  EXPECT_LT(f, 0.95);
}

TEST(SolarEclipse, SydneySeesNothingOf2017) {
  const Observer sydney{.latitude_deg = -33.8688, .longitude_deg = 151.2093};
  const UtcTime start = UtcTime::parse("2017-08-21T15:00:00Z");
  for (int i = 0; i <= 48; ++i) {
    EXPECT_DOUBLE_EQ(compute_sky(sydney, start.plus_seconds(i * 600.0)).sun_visible_fraction, 1.0);
  }
}

TEST(SolarEclipse, Total2024AtGreatestEclipse) {
  const UtcTime greatest = UtcTime::parse("2024-04-08T18:17:16Z");
  EXPECT_LT(compute_sky(kNazas, greatest).sun_visible_fraction, 0.01);
  const Totality t = totality(kNazas, greatest);
  EXPECT_NEAR(t.seconds, 268.1, 5.0);
  EXPECT_NEAR(t.middle_offset_s, 0.0, 15.0);
}

TEST(SolarEclipse, Total2024StartsInTexasOnTime) {
  // NASA: totality reaches Texas near Eagle Pass at 1:27:21 pm CDT (18:27:21 UT).
  const Observer eagle_pass{
      .latitude_deg = 28.7091, .longitude_deg = -100.4995, .elevation_m = 240.0};
  const UtcTime start = UtcTime::parse("2024-04-08T18:27:21Z");
  EXPECT_GT(compute_sky(eagle_pass, start.plus_seconds(-30.0)).sun_visible_fraction, 0.0);
  EXPECT_EQ(compute_sky(eagle_pass, start.plus_seconds(30.0)).sun_visible_fraction, 0.0);
  EXPECT_EQ(compute_sky(eagle_pass, start.plus_seconds(200.0)).sun_visible_fraction, 0.0);
}

}  // namespace
}  // namespace welkin::timeofday
