// The star field: its frame against the textbook altitude/azimuth formulas, its catalogue, the flux a
// rendered star delivers, the ground hiding it, no cost by day, and the time of day turning it.
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "gpu_test_support.h"
#include "welkin/atmosphere/stars.h"

#if WELKIN_HAVE_TIMEOFDAY
namespace welkin::modules {
const ModuleDefinition& timeofday_module();
}
#endif

namespace welkin::atmosphere {
namespace {

using nlohmann::json;

TEST(Stars, CelestialFrameMatchesAltitudeAzimuthFormulas) {
  // sin h = sin phi sin d + cos phi cos d cos H; with azimuth A from north towards east,
  // cos h sin A = -cos d sin H and cos h cos A = sin d cos phi - cos d cos H sin phi.
  for (double lat : {-60.0, 0.0, 46.5, 89.0})
    for (double lst : {0.0, 97.0, 250.0})
      for (double ra : {0.0, 33.0, 181.0})
        for (double dec : {-70.0, -5.0, 0.0, 40.0, 88.0}) {
          const double phi = glm::radians(lat), d = glm::radians(dec), h_angle = glm::radians(lst - ra);
          const glm::dvec3 expected(-std::cos(d) * std::sin(h_angle),
                                    std::sin(d) * std::cos(phi) - std::cos(d) * std::cos(h_angle) * std::sin(phi),
                                    std::sin(phi) * std::sin(d) + std::cos(phi) * std::cos(d) * std::cos(h_angle));
          const glm::dvec3 celestial(std::cos(d) * std::cos(glm::radians(ra)),
                                     std::cos(d) * std::sin(glm::radians(ra)), std::sin(d));
          const glm::dvec3 local = celestial_to_local(lst, lat) * celestial;
          EXPECT_NEAR(glm::length(local - expected), 0.0, 1e-12) << lat << " " << lst << " " << ra << " " << dec;
        }
}

TEST(Stars, CatalogueIsDeterministicUniformAndFollowsTheMagnitudeCounts) {
  Stars s;
  s.count = 20000;
  const std::vector<Star> a = make_star_catalogue(s), b = make_star_catalogue(s);
  ASSERT_EQ(a.size(), 20000u);
  glm::dvec3 mean(0.0);
  int brighter_than_3_5 = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].direction, b[i].direction);
    EXPECT_EQ(a[i].illuminance_lux, b[i].illuminance_lux);
    const glm::dvec3 d(a[i].direction);
    EXPECT_NEAR(glm::length(d), 1.0, 1e-6);
    mean += d;
    const double magnitude = -2.5 * std::log10(a[i].illuminance_lux / 2.54e-6);
    EXPECT_GE(magnitude, -1.46 - 1e-3);
    EXPECT_LE(magnitude, 6.5 + 1e-3);
    brighter_than_3_5 += magnitude < 3.5;
    EXPECT_NEAR(glm::dot(glm::dvec3(a[i].color), glm::dvec3(0.2126, 0.7152, 0.0722)), 1.0, 1e-5);
  }
  // Uniform on the sphere: the mean direction is within a few standard errors (1 / sqrt(3 N)) of 0.
  EXPECT_LT(glm::length(mean / double(a.size())), 4.0 / std::sqrt(3.0 * a.size()));
  // N(< m) ~ 10^(0.48 m): 10^(-1.44) = 3.6% of the stars are brighter than 3.5.
  EXPECT_NEAR(brighter_than_3_5 / double(a.size()), std::pow(10.0, -1.44), 0.005);
  s.seed = 2;
  EXPECT_NE(make_star_catalogue(s)[0].direction, a[0].direction);
}

// A night scene without air (so the transmittance is 1), looking at one star from `count` = 1.
struct OneStar {
  Stars stars;
  glm::dvec3 local;  // the star's direction in the scene
};

OneStar one_star_above(double min_elevation_deg, float latitude_deg = 46.5f) {
  OneStar o;
  o.stars.count = 1;
  o.stars.latitude_deg = latitude_deg;
  o.stars.brightness = 1e6f;  // well inside half-float precision
  for (int seed = 1;; ++seed) {
    o.stars.seed = seed;
    const Star s = make_star_catalogue(o.stars)[0];
    o.local =
        celestial_to_local(o.stars.local_sidereal_time_deg, o.stars.latitude_deg) * glm::dvec3(s.direction);
    if (o.local.z > std::sin(glm::radians(min_elevation_deg))) return o;
  }
}

json stars_json(const Stars& s) {
  return {{"count", s.count}, {"brightness", s.brightness}, {"seed", s.seed},
          {"local_sidereal_time_deg", s.local_sidereal_time_deg}, {"latitude_deg", s.latitude_deg}};
}

// Flux (radiance times each pixel's solid angle) over a render looking along `look`.
glm::dvec3 rendered_flux(const json& stars, const glm::dvec3& look, double sun_elevation, const json& air) {
  const double heading = glm::degrees(std::atan2(look.x, look.y));
  const double pitch = glm::degrees(std::asin(look.z));
  json doc = test::scene({{"position_m", {0, 0, 2}}, {"heading_deg", heading}, {"pitch_deg", pitch},
                          {"vertical_fov_deg", 20}},
                         air, {{"elevation_deg", sun_elevation}, {"disc", false}});
  doc["entities"].push_back({{"name", "stars"}, {"components", {{"atmosphere.Stars", stars}}}});
  const int w = 33, h = 33;
  auto r = test::render(doc, w, h);
  const ImageF img = r.renderer->read_hdr();
  const double f = h / (2.0 * std::tan(glm::radians(10.0)));
  glm::dvec3 flux(0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // Solid angle of the pixel: cos^3 of its angle off the axis over f^2.
      const double dx = x + 0.5 - w / 2.0, dy = y + 0.5 - h / 2.0;
      const double c = f / std::sqrt(f * f + dx * dx + dy * dy);
      for (int ch = 0; ch < 3; ++ch) flux[ch] += img.pixel(x, y)[ch] * c * c * c / (f * f);
    }
  return flux;
}

json no_air() {
  return {{"rayleigh_scattering", {0, 0, 0}}, {"mie_scattering", {0, 0, 0}}, {"mie_extinction", {0, 0, 0}},
          {"absorption_extinction", {0, 0, 0}}};
}

TEST(Stars, ARenderedStarDeliversItsIlluminance) {
  const OneStar o = one_star_above(20.0);
  const Star s = make_star_catalogue(o.stars)[0];
  // Off the optical axis by a fraction of a pixel in both directions, between pixel centres.
  const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), o.local));
  const glm::dvec3 look = glm::normalize(o.local + 0.0031 * east + 0.0017 * glm::cross(o.local, east));
  const glm::dvec3 flux = rendered_flux(stars_json(o.stars), look, -30.0, no_air());
  std::printf("star of %.4g lux: rendered flux %.6g %.6g %.6g, expected %.6g %.6g %.6g\n", s.illuminance_lux,
              flux.x, flux.y, flux.z, s.illuminance_lux * s.color.r, s.illuminance_lux * s.color.g,
              s.illuminance_lux * s.color.b);
  for (int ch = 0; ch < 3; ++ch)
    EXPECT_NEAR(flux[ch], double(s.illuminance_lux) * s.color[ch], 0.005 * s.illuminance_lux) << ch;
}

TEST(Stars, TheGroundHidesAStarBelowTheHorizonAndDaylightSkipsThem) {
  // On the equator every star sets: half a sidereal day later this one is as far below the horizon
  // as it was above. Looking straight at it, it is seen at first and hidden by the ground then.
  OneStar o = one_star_above(20.0, 0.0f);
  EXPECT_GT(rendered_flux(stars_json(o.stars), o.local, -30.0, no_air()).y, 0.0) << "the control";
  o.stars.local_sidereal_time_deg += 180.0f;
  const glm::dvec3 below = celestial_to_local(o.stars.local_sidereal_time_deg, o.stars.latitude_deg) *
                           glm::dvec3(make_star_catalogue(o.stars)[0].direction);
  ASSERT_LT(below.z, -0.3);
  EXPECT_EQ(rendered_flux(stars_json(o.stars), below, -30.0, no_air()), glm::dvec3(0.0));
  // By day the field is not drawn at all: the same frame with and without it is identical.
  o.stars.local_sidereal_time_deg -= 180.0f;
  const glm::dvec3 with = rendered_flux(stars_json(o.stars), o.local, 20.0, json::object());
  const glm::dvec3 without = rendered_flux(stars_json(Stars{.count = 0}), o.local, 20.0, json::object());
  EXPECT_EQ(with, without);
}

#if WELKIN_HAVE_TIMEOFDAY
TEST(Stars, TheTimeOfDayTurnsThem) {
  // Meeus, example 12.a: mean sidereal time at Greenwich, 1987 April 10, 0h UT = 13h10m46.3668s.
  World world;
  world.modules().add_static(welkin::modules::atmosphere_module());
  world.modules().add_static(welkin::modules::timeofday_module());
  json doc = test::scene(json::object(), json::object());
  doc["entities"].push_back(
      {{"name", "clock"},
       {"components",
        {{"timeofday.TimeOfDay", {{"year", 1987}, {"month", 4}, {"day", 10}, {"local_time_h", 0.0},
                                  {"utc_offset_h", 0}, {"latitude_deg", -33.0}, {"longitude_deg", 0.0}}},
         {"atmosphere.Stars", json::object()}}}});
  load_scene(world, doc, "stars.json");
  world.update({});
  const Stars* s = world.registry().get<Stars>(world.registry().first<Stars>());
  EXPECT_NEAR(s->local_sidereal_time_deg, (13.0 + 10.0 / 60 + 46.3668 / 3600) * 15.0, 1e-3);
  EXPECT_EQ(s->latitude_deg, -33.0f);
}
#endif

}  // namespace
}  // namespace welkin::atmosphere
