#include "cloud_light_fit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlopt.h>
#include <sstream>

#include "welkin/core/error.h"
#include "session.h"
#include "welkin/core/files.h"

namespace welkin::cli {

namespace {

namespace fs = std::filesystem;
using clouds::CloudView;
using Coefficients = std::map<std::string, double>;

// The model's constants that the fit keeps (their physical values; see light_model.glsl).
struct Constant {
  const char* name;
  double value;
  const char* meaning;
};
constexpr Constant kConstants[] = {
    {"CLOUDS_MS_DIFFUSION", 0.15, "k in 1 / (1 + k tau) for the ground's shading: 0.75 (1 - g), g = 0.8"},
    {"CLOUDS_DIRECT_DEPTH", 1.0, "the light march's optical depth as the direct beam sees it"},
    {"CLOUDS_MS_POWDER", 10.0, "n in the estimate's fade 1 - exp(-n sigma_t l_1) where the cloud around is thin"},
    {"CLOUDS_SS_WEIGHT", 1.0, "single scattering's weight (0 only while the fit measures the other terms)"},
};
// The multiple-scattering terms' weights, in light_model.glsl's order.
constexpr const char* kTerms[] = {
    "CLOUDS_MS_W0",  "CLOUDS_MS_W1",  "CLOUDS_MS_W2",  "CLOUDS_MS_W3",  "CLOUDS_MS_W4",  "CLOUDS_MS_W5",
    "CLOUDS_MS_W6",  "CLOUDS_MS_W7",  "CLOUDS_MS_W8",  "CLOUDS_MS_W9",  "CLOUDS_MS_W10", "CLOUDS_MS_W11",
    "CLOUDS_MS_W12", "CLOUDS_MS_W13", "CLOUDS_MS_W14", "CLOUDS_MS_W15", "CLOUDS_MS_W16", "CLOUDS_MS_W17",
    "CLOUDS_MS_W18", "CLOUDS_MS_W19", "CLOUDS_MS_W20", "CLOUDS_MS_W21", "CLOUDS_MS_W22", "CLOUDS_MS_W23",
    "CLOUDS_MS_W24", "CLOUDS_MS_W25", "CLOUDS_MS_W26", "CLOUDS_MS_W27", "CLOUDS_MS_W28", "CLOUDS_MS_W29",
    "CLOUDS_MS_W30", "CLOUDS_MS_W31", "CLOUDS_MS_W32", "CLOUDS_MS_W33", "CLOUDS_MS_W34", "CLOUDS_MS_W35",
    "CLOUDS_MS_W36", "CLOUDS_MS_W37", "CLOUDS_MS_W38", "CLOUDS_MS_W39", "CLOUDS_MS_W40", "CLOUDS_MS_W41",
    "CLOUDS_MS_W42", "CLOUDS_MS_W43", "CLOUDS_MS_W44", "CLOUDS_MS_W45", "CLOUDS_MS_W46", "CLOUDS_MS_W47",
    "CLOUDS_MS_W48", "CLOUDS_MS_W49", "CLOUDS_MS_W50", "CLOUDS_MS_W51"};
constexpr const char* kTermMeaning[] = {
    "D = T_d(tau) - T(tau): the diffuse light beyond the direct beam, toward the light",
    "D S(tau_b): ... gathered from the cloud below",
    "D p_2(mu): ... forward-peaked",
    "mu_0 T_d(tau_a): the light the top takes in, let down through the cloud above",
    "mu_0 T_d(tau_a) S(tau_b): ... and reflected back up from below",
    "T_d(tau): the diffuse light toward the light, direct beam included",
    "T_d(tau) S(tau_b): ... gathered from the cloud below",
    "D T_d(tau_a): the diffuse light toward the light that the column above lets by",
    "exp(-tau / 4): an octave",
    "exp(-tau / 16): an octave",
    "exp(-tau / 4) p_2(mu): an octave, forward-peaked",
    "D S(tau_B): the diffuse light gathered from the cloud's body below",
    "mu_0 T_d(tau_A): the light let down through the body above",
    "T_d(tau) S(tau_B)",
    "mu_0 T_d(tau_A) S(tau_B)",
    "exp(-tau / 16) S(tau_B)",
    "mu_0 (1 + 2k tau_B) / (1 + k (tau_A + tau_B)): the diffuse light in a lit slab",
    "mu_0 (1 + 2k tau_b) / (1 + k (tau_a + tau_b)): the same with the sample's own depths",
    "mu_0 D: the diffuse light beyond the direct beam, per unit area of a deck's lit top",
    "mu_0 D S(tau_b)",
    "mu_0 T_d(tau) S(tau_b)",
    "mu_0 D T_d(tau_a)",
    "mu_0 exp(-tau / 16)",
    "c D, c = clamp(tau_A / tau, mu_0, 1): the cosine at which the light entered the lit surface",
    "c D S(tau_b)",
    "f D, f the clear fraction of the light march: light let in through gaps and the soft edge",
    "f D S(tau_b)",
    "mu_0 exp(-tau / 4)",
    "T_d(tau) (1 - mu) / 2: the diffuse light seen from the light's side (a lit surface's reflection)",
    "D (1 - mu) / 2",
    "F mu_0 D S(tau_b), F the sample's density over its un-eroded envelope's: light leaks between billows",
    "F c D S(tau_b)",
    "E F mu_0 D S(tau_b), E = k tau_e / (1 + k tau_e), tau_e the optical depth to the cloud's side: "
    "the diffuse light falls toward the side where it escapes",
    "E F c D S(tau_b)",
    "E c D",
    "E mu_0 (1 + 2k tau_B) / (1 + k (tau_A + tau_B))",
    "E T_d(tau) (1 - mu) / 2",
    "E mu_0 exp(-tau / 16)",
    "max(n.l, 0) D, n the outward normal of the un-eroded envelope (the cloud's body) at the sample: "
    "a face lit by the light",
    "max(-n.l, 0) D: a face in the cloud's own shadow",
    "max(n.l, 0) T_d(tau) S(tau_b)",
    "(1 + n.l) / 2 T_d(tau)",
    "(1 + n.l) / 2 (1 + n.(-v)) / 2 D, v the view ray: the lit face turned toward the camera",
    "F max(n.l, 0) D S(tau_b)",
    "(1 + n.(-v)) / 2 D: the face turned toward the camera",
    "A = max(N - M, 0), N the direct beam's mean transmittance over the columns 300 m across the light from "
    "the sample's, M its own column's: sunlight let into the cloud around the sample that its own column does not get",
    "A S(tau_b)",
    "A (1 - mu) / 2: seen from the light's side",
    "A with the columns 1.2 km away",
    "A S(tau_b), the columns 1.2 km away",
    "A (1 - mu) / 2, the columns 1.2 km away",
    "A T_d(tau), the columns 1.2 km away: their light diffused through the sample's own column"};
static_assert(std::size(kTermMeaning) == std::size(kTerms));
constexpr size_t kTermCount = std::size(kTerms);

Coefficients constants() {
  Coefficients c;
  for (const Constant& k : kConstants) c[k.name] = k.value;
  return c;
}

// Every term's weight 0 but `term`'s, single scattering at `single`. A term is marched at the weight
// kTermScale and scaled back: at weight 1 a term under a 100 klx sun overflows the half-float frame.
constexpr double kTermScale = 1.0 / 64.0;
Coefficients only(int term, double single) {
  Coefficients c = constants();
  c["CLOUDS_SS_WEIGHT"] = single;
  for (size_t k = 0; k < kTermCount; ++k) c[kTerms[k]] = int(k) == term ? kTermScale : 0.0;
  return c;
}

std::vector<double> march(clouds::CloudProbe& probe, const std::vector<CloudView>& views, const Coefficients& c) {
  probe.set_light_model_fit(c);
  std::vector<double> r;
  for (const CloudView& v : views) r.push_back(probe.gpu_radiance(v));
  return r;
}

// The march is linear in the weights: radiance = single + sum_k w_k term_k, ray by ray. The least
// squares of the relative errors (each against its set's mean reference), with the weights
// non-negative (each term is light, never taken away), is convex; NLopt's L-BFGS with bounds finds
// its minimum.
struct Row {
  double single = 0.0, reference = 0.0, scale = 1.0;  // scale: 1 / the set's mean reference
  std::vector<double> terms;
};
struct LinearProblem {
  std::vector<Row> rows;
  double objective(const double* w, double* gradient) const {
    double f = 0.0;
    if (gradient) std::fill(gradient, gradient + kTermCount, 0.0);
    const double n = double(rows.size());
    for (const Row& r : rows) {
      double e = r.single - r.reference;
      for (size_t k = 0; k < kTermCount; ++k) e += w[k] * r.terms[k];
      e *= r.scale;
      f += e * e / n;
      if (gradient)
        for (size_t k = 0; k < kTermCount; ++k) gradient[k] += 2.0 * e * r.terms[k] * r.scale / n;
    }
    return f;
  }
};

double linear_objective(unsigned, const double* w, double* gradient, void* data) {
  return static_cast<const LinearProblem*>(data)->objective(w, gradient);
}

struct Error2 {
  double rmse = 0.0, worst = 0.0;
};
Error2 error_of(const std::vector<double>& gpu, const std::vector<double>& reference, double mean_reference) {
  Error2 e;
  for (size_t i = 0; i < gpu.size(); ++i) {
    const double d = (gpu[i] - reference[i]) / mean_reference;
    e.rmse += d * d / double(gpu.size()), e.worst = std::max(e.worst, std::abs(d));
  }
  e.rmse = std::sqrt(e.rmse);
  return e;
}

int settings_paths(const CloudAccuracyOptions& o) { return o.quick ? 1024 : 8192; }

std::string glsl_number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  std::string s = text;
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

}  // namespace

double mean_radiance(const std::vector<clouds::reference::CloudRadianceEstimate>& refs) {
  double m = 0.0;
  for (const auto& r : refs) m += r.radiance() / double(refs.size());
  return m;
}

std::vector<size_t> fit_candidate_terms(const CloudAccuracyOptions& o) {
  std::vector<size_t> k;
  for (int t : o.fit_terms) {
    if (t < 0 || size_t(t) >= kTermCount)
      throw Error(ErrorInfo{.path = "--fit-terms", .expected = "term numbers from 0 to " + std::to_string(kTermCount - 1),
                            .found = std::to_string(t)});
    if (std::find(k.begin(), k.end(), size_t(t)) == k.end()) k.push_back(size_t(t));
  }
  if (o.fit_terms.empty())
    for (size_t t = 0; t < kTermCount; ++t) k.push_back(t);
  std::sort(k.begin(), k.end());
  return k;
}

namespace {

// The weights are fitted per group of qualities: `low` marches without the detail noise (a smoother,
// denser field than the path tracer's), the others with it; light_model_fit.glsl keeps both
// (CLOUDS_SHAPE_DETAIL chooses).
bool reads_detail(clouds::Quality q) {
  clouds::VolumetricClouds c;
  c.quality = q;
  return clouds::resolve_quality(c).shape_detail;
}

std::vector<double> solve(const LinearProblem& p) {
  std::vector<double> w(kTermCount, 0.0), lo(kTermCount, 0.0), hi(kTermCount, 100.0);
  if (p.rows.empty()) return w;
  nlopt_opt opt = nlopt_create(NLOPT_LD_LBFGS, unsigned(kTermCount));
  nlopt_set_lower_bounds(opt, lo.data());
  nlopt_set_upper_bounds(opt, hi.data());
  nlopt_set_min_objective(opt, linear_objective, const_cast<LinearProblem*>(&p));
  nlopt_set_ftol_rel(opt, 1e-12);
  nlopt_set_maxeval(opt, 20000);
  double best = 0.0;
  const nlopt_result result = nlopt_optimize(opt, w.data(), &best);
  nlopt_destroy(opt);
  if (result < 0) throw Error("the light model's fit failed (NLopt result " + std::to_string(int(result)) + ")");
  return w;
}

// `// text` in lines of at most 110 columns (the project's limit holds for the file the fit writes).
std::string comment(const std::string& text, const std::string& indent = "") {
  std::string out, line = indent;
  std::istringstream words(text);
  for (std::string word; words >> word;) {
    if (line.size() > indent.size() && 3 + line.size() + 1 + word.size() > 110) out += "// " + line + "\n", line = indent;
    line += (line.size() > indent.size() ? " " : "") + word;
  }
  return out + "// " + line + "\n";
}

// A guarded define with its meaning above it.
void write_define(std::ostringstream& glsl, const std::string& name, const std::string& meaning, double value) {
  glsl << comment(name + ": " + meaning) << "#ifndef " << name << "\n#define " << name << " " << glsl_number(value)
       << "\n#endif\n";
}

void write_weights(std::ostringstream& glsl, const std::vector<double>& w) {
  for (size_t k = 0; k < kTermCount; ++k) write_define(glsl, kTerms[k], kTermMeaning[k], w[k]);
}

}  // namespace

int fit_light_model(const CloudAccuracyOptions& o, std::vector<RaySet>& sets, const std::map<std::string, clouds::Quality>& names) {
  const auto started = std::chrono::steady_clock::now();
  const std::vector<size_t> candidates = fit_candidate_terms(o);
  LinearProblem problem[2];  // [0]: qualities without the detail noise, [1]: with it
  std::map<std::pair<size_t, std::string>, std::vector<Row>> marched;  // every set's rows, by set and quality
  std::ostringstream csv;  // the problem itself, ray by ray: what the march gives with each term alone (weight 1)
  csv << "set,kept_back,quality,view,altitude_m,heading_deg,pitch_deg,reference,single";
  for (size_t k : candidates) csv << "," << kTerms[k];
  csv << "\n";
  size_t rays = 0;
  for (size_t s = 0; s < sets.size(); ++s) {
    RaySet& set = sets[s];
    clouds::CloudProbe& probe = *set.probe;
    probe.clouds().multiple_scattering = clouds::MultipleScattering::diffusion;
    const double scale = 1.0 / mean_radiance(set.refs);
    if (!set.kept_back) rays += set.views.size();
    for (const std::string& q : o.qualities) {
      probe.clouds().quality = names.at(q);
      const std::vector<double> single = march(probe, set.views, only(-1, 1.0));
      // What no weight scales (the air's light in front of the clouds, the sky's and the ground's):
      // in every term's march once, taken out before the term is scaled back.
      const std::vector<double> unweighted = march(probe, set.views, only(-1, 0.0));
      std::vector<std::vector<double>> terms(kTermCount, std::vector<double>(set.views.size(), 0.0));
      for (size_t k : candidates) {
        terms[k] = march(probe, set.views, only(int(k), 0.0));
        for (size_t i = 0; i < terms[k].size(); ++i) terms[k][i] = (terms[k][i] - unweighted[i]) / kTermScale;
        std::fprintf(stderr, "\rset %zu/%zu, %s: term %zu marched", s + 1, sets.size(), q.c_str(), k);
      }
      for (size_t i = 0; i < set.views.size(); ++i) {
        Row r{single[i], set.refs[i].radiance(), scale, {}};
        const CloudView& v = set.views[i];
        csv << s << "," << (set.kept_back ? 1 : 0) << "," << q << "," << v.name << "," << v.altitude_m << "," << v.heading_deg
            << "," << v.pitch_deg << "," << r.reference << "," << r.single;
        for (size_t k = 0; k < kTermCount; ++k) r.terms.push_back(terms[k][i]);
        for (size_t k : candidates) csv << "," << terms[k][i];
        csv << "\n";
        marched[{s, q}].push_back(r);
        if (!set.kept_back) problem[reads_detail(names.at(q)) ? 1 : 0].rows.push_back(std::move(r));
      }
    }
  }
  std::fprintf(stderr, "\n");
  write_file_atomically((fs::path(o.out) / "light-model-terms.csv").string(), csv.str());
  // A group no quality asked for takes the other's weights.
  std::vector<double> w[2] = {solve(problem[0]), solve(problem[1])};
  if (problem[0].rows.empty()) w[0] = w[1];
  if (problem[1].rows.empty()) w[1] = w[0];

  // The weights compiled in, each set and quality marched again: the figures are the march's, not the sum's.
  // The sum's own prediction beside it: where the two part, a term's column held light that is not its
  // own and the weights were solved for another march.
  std::ostringstream figures;
  double sum_off = 0.0;  // the largest difference between the sum and the march, over a set's mean reference
  for (size_t si = 0; si < sets.size(); ++si) {
    RaySet& set = sets[si];
    figures << comment((set.kept_back ? "kept back: " : "") + set.name + ", " + std::to_string(set.views.size()) + " rays:", "  ")
            << "//    ";
    std::vector<double> reference;
    for (const auto& r : set.refs) reference.push_back(r.radiance());
    for (const std::string& q : o.qualities) {
      set.probe->clouds().quality = names.at(q);
      Coefficients fitted = constants();
      for (size_t k = 0; k < kTermCount; ++k) fitted[kTerms[k]] = w[reads_detail(names.at(q)) ? 1 : 0][k];
      const std::vector<double> gpu = march(*set.probe, set.views, fitted);
      const Error2 e = error_of(gpu, reference, mean_radiance(set.refs));
      const std::vector<Row>& rows = marched.at({si, q});
      for (size_t i = 0; i < gpu.size(); ++i) {
        double sum = rows[i].single;
        for (size_t k = 0; k < kTermCount; ++k) sum += fitted[kTerms[k]] * rows[i].terms[k];
        sum_off = std::max(sum_off, std::abs(sum - gpu[i]) * rows[i].scale);
      }
      figures << " " << q << " " << std::lround(1000 * e.rmse) / 10.0 << "% (worst " << std::lround(1000 * e.worst) / 10.0 << "%)";
    }
    figures << "\n";
    set.probe->set_light_model_fit({});
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::ostringstream glsl;  // each define guarded alone: a partial override (the term budget's) keeps the rest
  glsl << "#pragma once\n// The light model's weights (light_model.glsl), fitted to the project's path tracer by\n"
          "// `welkin accuracy clouds --fit` (tools/welkin/cloud_light_fit.cpp), which wrote this file: "
       << rays << " rays,\n// " << settings_paths(o) << " paths each; the march's relative RMSE after the fit:\n" << figures.str()
       << "// The fit overrides them with defines while it measures.\n";
  for (const Constant& k : kConstants) write_define(glsl, k.name, k.meaning, k.value);
  glsl << "#ifndef CLOUDS_SHAPE_DETAIL  // the march reads the detail noise (light_model_defines; not low)\n"
          "#define CLOUDS_SHAPE_DETAIL 1\n#endif\n#if CLOUDS_SHAPE_DETAIL\n";
  write_weights(glsl, w[1]);
  glsl << "#else  // without the detail noise (low): a smoother field than the path tracer's\n";
  write_weights(glsl, w[0]);
  glsl << "#endif\n";
  const std::string file = (fs::path(o.out) / "light_model_fit.glsl").string();
  write_file_atomically(file, glsl.str());
  std::printf("the fitted sum against the march of its weights: %.2f%% of a set's mean at most\n", 100.0 * sum_off);
  std::printf("fit over %zu rays", rays);
  for (int g = 1; g >= 0; --g) {
    std::printf("\n%s weights:", g ? "with the detail noise" : "without");
    for (size_t k : candidates) std::printf(" W%zu=%.4g", k, w[g][k]);
  }
  std::printf("\nthe sums' relative RMSE %.1f%% (with detail), %.1f%% (without); marched:%s\n%.0f s; wrote %s\n",
              100 * std::sqrt(problem[1].objective(w[1].data(), nullptr)),
              100 * std::sqrt(problem[0].objective(w[0].data(), nullptr)), figures.str().c_str(), seconds, file.c_str());
  return kOk;
}

void write_term_budget(clouds::CloudProbe& probe, const std::vector<CloudView>& views,
                       const std::vector<clouds::reference::CloudRadianceEstimate>& refs,
                       const std::map<std::string, clouds::Quality>& names, const CloudAccuracyOptions& o,
                       clouds::reference::PathTraceSettings settings) {
  settings.max_orders = 1;
  std::vector<double> single_ref, reference;
  double mean_reference = 0.0;
  for (size_t i = 0; i < views.size(); ++i) {
    single_ref.push_back(probe.reference_radiance(views[i], settings).radiance());
    reference.push_back(refs[i].radiance());
    mean_reference += refs[i].radiance() / double(views.size());
  }
  probe.clouds().multiple_scattering = clouds::MultipleScattering::diffusion;
  std::ostringstream csv;
  csv << "quality,view,altitude_m,heading_deg,pitch_deg,gpu,gpu_single,gpu_single_no_light_detail,"
         "gpu_single_every_step_detail,reference,reference_single\n";
  std::printf("\nthe diffusion model term by term (relative RMSE / worst over the rays; sun only: no sky, no ground)\n"
              "| quality | total | single scattering | single, light march without detail | single, every light step "
              "with detail | multiple-scattering estimate |\n|---|---|---|---|---|---|\n");
  // The light march's steps that read the detail noise (light_march.glsl): none, and every one (the
  // model reads it in the first alone: its single scattering 11% too dark on a broken deck, every
  // step's 1.6%; docs/clouds-light.md).
  Coefficients single_only = only(-1, 1.0), no_detail = only(-1, 1.0), every_step = only(-1, 1.0);
  no_detail["CLOUDS_LIGHT_DETAIL"] = 0.0, every_step["CLOUDS_LIGHT_DETAIL"] = 64.0;
  for (const std::string& q : o.qualities) {
    probe.clouds().quality = names.at(q);
    const std::vector<double> full = march(probe, views, {});
    const std::vector<double> single = march(probe, views, single_only);
    const std::vector<double> plain = march(probe, views, no_detail);
    const std::vector<double> every = march(probe, views, every_step);
    std::vector<double> rest(views.size()), rest_ref(views.size());
    for (size_t i = 0; i < views.size(); ++i) {
      rest[i] = full[i] - single[i], rest_ref[i] = reference[i] - single_ref[i];
      csv << q << "," << views[i].name << "," << views[i].altitude_m << "," << views[i].heading_deg << "," << views[i].pitch_deg
          << "," << full[i] << "," << single[i] << "," << plain[i] << "," << every[i] << "," << reference[i] << ","
          << single_ref[i] << "\n";
    }
    const Error2 e[5] = {error_of(full, reference, mean_reference), error_of(single, single_ref, mean_reference),
                         error_of(plain, single_ref, mean_reference), error_of(every, single_ref, mean_reference),
                         error_of(rest, rest_ref, mean_reference)};
    std::printf("| %s |", q.c_str());
    for (const Error2& x : e) std::printf(" %.1f%% / %.1f%% |", 100 * x.rmse, 100 * x.worst);
    std::printf("\n");
  }
  probe.set_light_model_fit({});
  write_file_atomically((fs::path(o.out) / "accuracy-clouds-terms.csv").string(), csv.str());
}

void write_sky_budget(clouds::CloudProbe& probe, const std::vector<CloudView>& views,
                      const std::map<std::string, clouds::Quality>& names, const CloudAccuracyOptions& o,
                      const clouds::reference::PathTraceSettings& settings) {
  probe.set_light(clouds::CloudProbe::Light::sky);
  // The light the clouds scatter: the sky seen through them is the march's background, not its
  // clouds' (the probe draws no sky behind them).
  std::vector<double> reference;
  double mean_reference = 0.0;
  for (const CloudView& v : views) {
    reference.push_back(probe.reference_radiance(v, settings).scattered.mean);
    mean_reference += reference.back() / double(views.size());
  }
  std::ostringstream csv;
  csv << "quality,view,altitude_m,heading_deg,pitch_deg,gpu,reference\n";
  std::printf("\nthe sky alone (a uniform sky over a black ground, %.0f%% of the sun's illuminance on a plane facing up)\n"
              "| quality | sky: relative RMSE / worst |\n|---|---|\n",
              100 * clouds::CloudProbe::kSkyFraction);
  for (const std::string& q : o.qualities) {
    probe.clouds().quality = names.at(q);
    const std::vector<double> gpu = march(probe, views, {});
    for (size_t i = 0; i < views.size(); ++i)
      csv << q << "," << views[i].name << "," << views[i].altitude_m << "," << views[i].heading_deg << ","
          << views[i].pitch_deg << "," << gpu[i] << "," << reference[i] << "\n";
    const Error2 e = error_of(gpu, reference, mean_reference);
    std::printf("| %s | %.1f%% / %.1f%% |\n", q.c_str(), 100 * e.rmse, 100 * e.worst);
  }
  probe.set_light(clouds::CloudProbe::Light::sun);
  write_file_atomically((fs::path(o.out) / "accuracy-clouds-sky.csv").string(), csv.str());
}

}  // namespace welkin::cli
