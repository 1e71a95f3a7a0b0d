// The clouds' light model against the path tracer: the fit of its weights (`welkin accuracy clouds
// --fit`) and its error term by term.
#pragma once
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "validation/cloud_probe.h"

namespace welkin::cli {

// The clouds and the sun measured: a scene file's (after one update, so that a time of day has placed
// the sun), or the built-in cumulus layer under a sun 40 degrees up.
struct MeasuredCase {
  clouds::VolumetricClouds clouds;
  double sun_azimuth_deg = 200.0, sun_elevation_deg = 40.0;
  Camera camera;
};
// The scene file's case ("": the built-in cumulus layer).
MeasuredCase case_from_scene(const std::string& file);

// A set of rays through one scene, their path-traced references and the probe that marches them.
struct RaySet {
  std::string name;
  MeasuredCase measured;
  std::vector<clouds::CloudView> views;
  std::vector<clouds::reference::CloudRadianceEstimate> refs;
  std::unique_ptr<clouds::CloudProbe> probe;
  bool kept_back = false;  // marched and reported, not fitted (--fit-kept-back)
};

// The terms --fit-terms names (every term where it names none), sorted; one clear error for a number
// that names no term.
std::vector<size_t> fit_candidate_terms(const CloudAccuracyOptions& o);

// Solves for the weights of the light model's multiple-scattering terms (light_model_fit.glsl) over
// the sets of rays at the qualities given (each set's errors relative to its own mean reference), and
// writes light_model_fit.glsl into o.out.
int fit_light_model(const CloudAccuracyOptions& o, std::vector<RaySet>& sets, const std::map<std::string, clouds::Quality>& names);

// Prints the error term by term (single scattering, with and without the detail noise in the light
// march; the multiple-scattering estimate) and writes accuracy-clouds-terms.csv.
void write_term_budget(clouds::CloudProbe& probe, const std::vector<clouds::CloudView>& views,
                       const std::vector<clouds::reference::CloudRadianceEstimate>& refs,
                       const std::map<std::string, clouds::Quality>& names, const CloudAccuracyOptions& o,
                       clouds::reference::PathTraceSettings settings);

// The sky's share alone (CloudProbe::Light::sky) against the path tracer at each quality, relative to
// the mean reference of that light; writes accuracy-clouds-sky.csv.
void write_sky_budget(clouds::CloudProbe& probe, const std::vector<clouds::CloudView>& views,
                      const std::map<std::string, clouds::Quality>& names, const CloudAccuracyOptions& o,
                      const clouds::reference::PathTraceSettings& settings);

}  // namespace welkin::cli
