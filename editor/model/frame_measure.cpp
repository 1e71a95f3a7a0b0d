#include "model/frame_measure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numeric>

#include "welkin/core/error.h"

namespace welkin::editor {

namespace {

constexpr const char* kUsage = "usage: measure-frames N [still | fly SPEED_M_S TURN_DEG_S]";

[[noreturn]] void bad(const std::string& what, const std::string& found) {
  throw Error(ErrorInfo{.expected = what, .found = "'" + found + "'", .message = kUsage});
}

double number_in(const std::string& s, double lo, double hi, const std::string& what) {
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || !std::isfinite(x) || x < lo || x > hi) bad(what, s);
  return x;
}

std::string fixed(double x, int digits) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, x);
  return text;
}

}  // namespace

MeasureRequest parse_measure_request(const std::vector<std::string>& args) {
  if (args.empty() || args.size() > 4) throw Error(ErrorInfo{.message = kUsage});
  MeasureRequest r;
  const std::string& n = args[0];
  if (n.empty() || n.size() > 6 || n.find_first_not_of("0123456789") != std::string::npos || std::stoi(n) < 1 ||
      std::stoi(n) > kMaxMeasuredFrames)
    bad("a frame count from 1 to " + std::to_string(kMaxMeasuredFrames), n);
  r.frames = std::stoi(n);
  if (args.size() == 1) return r;
  if (args[1] == "still") {
    if (args.size() != 2) throw Error(ErrorInfo{.message = kUsage});
    return r;
  }
  if (args[1] != "fly") bad("still or fly", args[1]);
  if (args.size() != 4) throw Error(ErrorInfo{.message = kUsage});
  r.fly = true;
  r.speed_mps = number_in(args[2], 0.0, 1e6, "a speed from 0 to 1e6 m/s");
  r.turn_deg_s = number_in(args[3], -3600.0, 3600.0, "a turn from -3600 to 3600 deg/s");
  return r;
}

FrameTimeSummary summarize_frame_times(std::vector<double> ms) {
  FrameTimeSummary s;
  s.frames = int(ms.size());
  if (ms.empty()) return s;
  std::sort(ms.begin(), ms.end());
  const size_t n = ms.size();
  s.mean_ms = std::accumulate(ms.begin(), ms.end(), 0.0) / double(n);
  s.median_ms = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
  s.p90_ms = ms[size_t(std::ceil(0.9 * double(n))) - 1];
  s.min_ms = ms.front();
  s.max_ms = ms.back();
  s.fps = s.mean_ms > 0 ? 1000.0 / s.mean_ms : 0.0;
  return s;
}

void FrameMeasurement::add(const MeasuredFrame& frame) {
  if (done()) return;
  frame_ms_.push_back(frame.frame_ms);
  for (const MeasuredPass& p : frame.passes) {
    PassTotal& t = passes_[p.name];
    t.gpu_ms += p.gpu_ms;
    ++t.frames;
  }
  reduced_frames_ += frame.reduced ? 1 : 0;
  kept_frames_ += frame.kept ? 1 : 0;
}

std::string FrameMeasurement::report(const std::string& context, size_t max_passes) const {
  const FrameTimeSummary s = summary();
  std::string out = "measure-frames: " + std::to_string(s.frames) + " frames " +
                    (request_.fly ? "flying " + fixed(request_.speed_mps, 1) + " m/s turning " + fixed(request_.turn_deg_s, 1) + " deg/s"
                                  : std::string("still")) +
                    (context.empty() ? "" : ", " + context) + ": mean " + fixed(s.mean_ms, 1) + " ms, median " +
                    fixed(s.median_ms, 1) + " ms, p90 " + fixed(s.p90_ms, 1) + " ms, min " + fixed(s.min_ms, 1) + " ms, max " +
                    fixed(s.max_ms, 1) + " ms, " + fixed(s.fps, 1) + " fps; " + std::to_string(reduced_frames_) +
                    " rendered smaller, " + std::to_string(kept_frames_) + " kept (settled)\n";
  std::vector<std::pair<std::string, PassTotal>> by_cost(passes_.begin(), passes_.end());
  std::stable_sort(by_cost.begin(), by_cost.end(), [](const auto& a, const auto& b) { return a.second.gpu_ms > b.second.gpu_ms; });
  if (by_cost.size() > max_passes) by_cost.resize(max_passes);
  if (by_cost.empty() || s.frames == 0) return out;
  out += "measure-frames: passes, GPU ms per frame (frames run):";
  for (const auto& [name, t] : by_cost)
    out += " " + name + " " + fixed(t.gpu_ms / s.frames, 2) + " (" + std::to_string(t.frames) + ")";
  return out + "\n";
}

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  double a = 0, b = 0, c = 0;
  if (!(in >> a >> b >> c)) return "";
  return fixed(a, 2) + " " + fixed(b, 2) + " " + fixed(c, 2);
}

}  // namespace welkin::editor
