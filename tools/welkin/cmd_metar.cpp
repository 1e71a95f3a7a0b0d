// welkin metar REPORT | --file FILE [--json]: decodes a METAR report and prints what it says and the
// cloud layers, haze and drift the weather module makes of it (a summary, or everything as JSON).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "session.h"
#include "welkin/clouds/components.h"
#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/weather/metar.h"
#include "welkin/weather/sky_from_metar.h"

namespace welkin::cli {

namespace {

struct MetarOptions {
  std::string report, file;
  bool json = false;
};

template <class T>
nlohmann::json optional_json(const std::optional<T>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json();
}

nlohmann::json decoded_json(const weather::MetarReport& r) {
  using nlohmann::json;
  json j{{"type", r.type},
         {"station", r.station},
         {"day", r.day},
         {"hour", r.hour},
         {"minute", r.minute},
         {"auto", r.automatic},
         {"cavok", r.cavok},
         {"sky_clear", r.sky_clear},
         {"runway_visual_ranges", r.runway_visual_ranges},
         {"temperature_c", optional_json(r.temperature_c)},
         {"dew_point_c", optional_json(r.dew_point_c)},
         {"altimeter_hpa", optional_json(r.altimeter_hpa)},
         {"altimeter_inhg", optional_json(r.altimeter_inhg)}};
  if (r.wind)
    j["wind"] = {{"direction_deg", optional_json(r.wind->direction_deg)},
                 {"speed", r.wind->speed_as_reported},
                 {"unit", r.wind->unit},
                 {"speed_mps", r.wind->speed_mps},
                 {"gust_mps", optional_json(r.wind->gust_mps)},
                 {"variable_from_deg", optional_json(r.wind->variable_from_deg)},
                 {"variable_to_deg", optional_json(r.wind->variable_to_deg)}};
  if (r.visibility)
    j["visibility"] = {{"metres", r.visibility->metres},
                       {"at_least", r.visibility->at_least},
                       {"less_than", r.visibility->less_than},
                       {"statute_miles", r.visibility->statute_miles}};
  j["weather"] = json::array();
  for (const auto& w : r.weather)
    j["weather"].push_back({{"text", w.text},
                            {"intensity", w.intensity},
                            {"descriptor", w.descriptor},
                            {"phenomena", w.phenomena}});
  j["clouds"] = json::array();
  for (const auto& c : r.clouds)
    j["clouds"].push_back({{"cover", weather::cover_code(c.cover)},
                           {"base_ft", c.base_ft},
                           {"type", c.type},
                           {"oktas", {c.oktas_min(), c.oktas_max()}}});
  return j;
}

nlohmann::json sky_json(const weather::SkyFromReport& sky) {
  nlohmann::json layers = nlohmann::json::array();
  for (const auto& l : sky.layers)
    layers.push_back({{"genus", clouds::genus_name(l.genus)},
                      {"base_altitude_m", l.base_altitude_m},
                      {"thickness_m", l.thickness_m},
                      {"coverage", l.coverage},
                      {"density_per_m", l.density_per_m}});
  nlohmann::json j{{"layers", layers},
                   {"wind_mps", {sky.wind_mps.x, sky.wind_mps.y}},
                   {"utc_time_h", sky.utc_time_h},
                   {"day", sky.day},
                   {"visibility_m", optional_json(sky.visibility_m)}};
  if (sky.visibility_m)
    j["haze_extinction_per_km"] =
        weather::haze_extinction_per_km(*sky.visibility_m, weather::kEarthRayleighPerKmGreen);
  return j;
}

void print_summary(const weather::MetarReport& r, const weather::SkyFromReport& sky) {
  std::fprintf(stdout, "%s %s, day %d, %02d:%02d UTC\n", r.type.c_str(), r.station.c_str(), r.day, r.hour,
               r.minute);
  if (r.wind)
    std::fprintf(
        stdout, "wind: %s at %.1f m/s; the clouds drift %.2f m/s east, %.2f m/s north\n",
        r.wind->direction_deg ? (std::to_string(*r.wind->direction_deg) + " deg").c_str() : "variable",
        r.wind->speed_mps, sky.wind_mps.x, sky.wind_mps.y);
  if (sky.visibility_m)
    std::fprintf(stdout, "visibility: %.0f m; haze: aerosol extinction %.4f /km at the ground\n",
                 *sky.visibility_m,
                 weather::haze_extinction_per_km(*sky.visibility_m, weather::kEarthRayleighPerKmGreen));
  else if (r.visibility)
    std::fprintf(stdout, "visibility: 10 km or more (the scene's air is kept)\n");
  else
    std::fprintf(stdout, "visibility: not reported (the scene's air is kept)\n");
  for (size_t i = 0; i < sky.layers.size(); ++i) {
    const auto& l = sky.layers[i];
    const auto& c = r.clouds[i];
    std::fprintf(stdout, "layer %zu: %s%03d%s -> %s, base %.0f m, %.0f m thick, coverage %.3f\n", i,
                 weather::cover_code(c.cover), c.base_ft / 100, c.type.c_str(), clouds::genus_name(l.genus),
                 l.base_altitude_m, l.thickness_m, l.coverage);
  }
  if (sky.layers.empty()) std::fprintf(stdout, "no cloud layers\n");
}

int run_metar(const MetarOptions& o) {
  if (o.report.empty() == o.file.empty())
    throw Error(ErrorInfo{.path = "welkin metar",
                          .expected = "a report or --file FILE (one of them)",
                          .found = o.report.empty() ? "neither" : "both"});
  std::string text = o.report;
  if (!o.file.empty()) text = read_file_text(o.file, weather::kMaxMetarBytes);
  weather::MetarReport r;
  try {
    r = weather::parse_metar(text);
  } catch (const Error& e) {
    throw o.file.empty() ? e.with_path_prefix("metar") : e.with_file(o.file);
  }
  weather::SkyFromReport sky = weather::sky_from_metar(r);
  if (o.json) {
    nlohmann::json j = decoded_json(r);
    j["sky"] = sky_json(sky);
    std::fprintf(stdout, "%s\n", j.dump(2).c_str());
  } else {
    print_summary(r, sky);
  }
  return kOk;
}

}  // namespace

void add_metar_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<MetarOptions>();
  CLI::App* cmd =
      app.add_subcommand("metar", "Decode a METAR report and show the sky the weather module makes of it");
  cmd->add_option("report", opts->report,
                  "The report, in quotes: \"KSFO 271756Z 28012KT 10SM FEW008 18/12 A3001\"");
  cmd->add_option("-f,--file", opts->file, "Read the report from a file");
  cmd->add_flag("--json", opts->json, "Print the decoded report and its sky as JSON");
  cmd->callback([opts, &exit_code] { exit_code = run_metar(*opts); });
}

}  // namespace welkin::cli
