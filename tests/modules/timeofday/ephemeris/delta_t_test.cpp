// Delta-T polynomials (Espenak & Meeus, Five Millennium Canon of Solar Eclipses, 2006).
#include "welkin/timeofday/delta_t.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace welkin::timeofday {
namespace {

// The canon's decimal year for the middle of a month.
double mid_month(double year, int month) { return year + (month - 0.5) / 12.0; }

TEST(DeltaT, ValuesTabulatedFromTheNasaPolynomials) {
  // Reference values of the same polynomials from pvlib's SPA test-suite (test_spa.py), one per
  // era, so a transcription slip in any coefficient shows.
  struct Case {
    double year;
    int month;
    double delta_t;
  };
  const Case cases[] = {
      {-499, 1, 17184.831},  {500, 2, 5708.8051},   {1000, 3, 1573.0419},  {1500, 4, 198.01820},
      {1800, 5, 13.596506},  {1860, 6, 7.8316585},  {1900, 6, -2.1171894}, {1950, 7, 29.289261},
      {1970, 8, 40.824887},  {1985, 9, 54.724581},  {1990, 10, 57.426651}, {2000, 11, 64.108015},
      {2005, 12, 65.038015}, {2050, 12, 94.952955}, {2150, 12, 330.50693}, {1985, 2, 54.413442486}};
  for (const Case& c : cases) {
    EXPECT_NEAR(delta_t_espenak_meeus(mid_month(c.year, c.month)), c.delta_t, 2e-3)
        << c.year << "-" << c.month;
  }
}

TEST(DeltaT, MonthlyTable2017) {
  // NASA-polynomial estimates for 2017 tabulated by neoprogrammics.com's Delta-T estimator
  // (January 70.03 s, June 70.25 s, December 70.51 s).
  EXPECT_NEAR(delta_t_espenak_meeus(mid_month(2017, 1)), 70.03, 0.006);
  EXPECT_NEAR(delta_t_espenak_meeus(mid_month(2017, 6)), 70.25, 0.006);
  EXPECT_NEAR(delta_t_espenak_meeus(mid_month(2017, 12)), 70.51, 0.006);
}

TEST(DeltaT, CloseToObservedValues) {
  // Observed Delta-T (NASA eclipse site's table from IERS/USNO data); the canon fits them to ~1 s.
  EXPECT_NEAR(delta_t_espenak_meeus(1900.0), -2.72, 1.0);
  EXPECT_NEAR(delta_t_espenak_meeus(1950.0), 29.15, 1.0);
  EXPECT_NEAR(delta_t_espenak_meeus(1975.0), 45.48, 1.0);
  EXPECT_NEAR(delta_t_espenak_meeus(2000.0), 63.83, 1.0);
  EXPECT_NEAR(delta_t_espenak_meeus(2005.0), 64.69, 1.0);
}

TEST(DeltaT, ModernErasJoinSmoothly) {
  // From 1700 on, where Delta-T is known to seconds, neighbouring pieces meet within 1 s.
  for (double boundary :
       {1800.0, 1860.0, 1900.0, 1920.0, 1941.0, 1961.0, 1986.0, 2005.0, 2050.0, 2150.0}) {
    EXPECT_NEAR(delta_t_espenak_meeus(boundary - 1e-9), delta_t_espenak_meeus(boundary), 1.0)
        << boundary;
  }
}

TEST(DeltaT, OutsideTheCanonIsAnError) {
  EXPECT_NO_THROW(delta_t_espenak_meeus(-1999.0));
  EXPECT_NO_THROW(delta_t_espenak_meeus(3000.99));
  EXPECT_THROW(delta_t_espenak_meeus(-2000.0), std::invalid_argument);
  EXPECT_THROW(delta_t_espenak_meeus(3001.0), std::invalid_argument);
  EXPECT_THROW(delta_t_espenak_meeus(std::nan("")), std::invalid_argument);
  try {
    delta_t_espenak_meeus(4000.0);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("-1999..3000"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace welkin::timeofday
