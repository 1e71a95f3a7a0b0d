#pragma once
// The `measure-frames` script verb's model: its arguments, and what N frames of the viewport cost
// (frame times from main loop to main loop, the renderer's per-pass GPU times, how many frames were
// rendered smaller while the view moved). No GL: the application feeds it one frame at a time.
#include <map>
#include <string>
#include <vector>

namespace welkin::editor {

// measure-frames N [still | fly SPEED_M_S TURN_DEG_S]
struct MeasureRequest {
  int frames = 0;
  bool fly = false;           // still: the view is held where it is
  double speed_mps = 0.0;     // forward along the view, per second of wall time
  double turn_deg_s = 0.0;    // heading, clockwise, per second of wall time
};
inline constexpr int kMaxMeasuredFrames = 100000;
// The verb's arguments (after the verb). Throws Error with the usage on anything else: N must be a
// whole number in [1, kMaxMeasuredFrames], SPEED in [0, 1e6] m/s, TURN in [-3600, 3600] deg/s.
MeasureRequest parse_measure_request(const std::vector<std::string>& args);

// Statistics of a list of frame times (ms). Median of an even count: the mean of the middle two;
// p90: the nearest rank (the smallest time at or above 90% of the frames). fps = 1000 / mean.
struct FrameTimeSummary {
  int frames = 0;
  double mean_ms = 0, median_ms = 0, p90_ms = 0, min_ms = 0, max_ms = 0, fps = 0;
};
FrameTimeSummary summarize_frame_times(std::vector<double> frame_ms);

// One frame as the renderer reported it.
struct MeasuredPass {
  std::string name;
  double gpu_ms = 0;
};
struct MeasuredFrame {
  double frame_ms = 0;  // wall time of the editor's whole frame (events, script, render, UI, swap)
  std::vector<MeasuredPass> passes;
  bool reduced = false;  // rendered smaller than the viewport (a moving view)
  bool kept = false;     // not rendered: the settled view's last frame shown again
};

class FrameMeasurement {
 public:
  explicit FrameMeasurement(MeasureRequest request) : request_(request) {}
  const MeasureRequest& request() const { return request_; }
  void add(const MeasuredFrame& frame);
  bool done() const { return int(frame_ms_.size()) >= request_.frames; }
  FrameTimeSummary summary() const { return summarize_frame_times(frame_ms_); }
  // One line of figures, then the passes by their mean GPU time per frame (the most expensive
  // first, `max_passes` of them) with the number of frames each ran in. `context` goes after the
  // verb (the viewport's size, the machine's load).
  std::string report(const std::string& context, size_t max_passes = 8) const;

 private:
  struct PassTotal {
    double gpu_ms = 0;
    int frames = 0;
  };
  MeasureRequest request_;
  std::vector<double> frame_ms_;
  std::map<std::string, PassTotal> passes_;
  int reduced_frames_ = 0, kept_frames_ = 0;
};

// The 1, 5 and 15 minute load averages from /proc/loadavg ("" where it cannot be read): timings
// on a shared machine mean little without them.
std::string load_average();

}  // namespace welkin::editor
