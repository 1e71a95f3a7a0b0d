// welkin sequence SCENE SEQUENCE --out DIR [--fps N] [--size WxH] [--from S] [--to S] [--exr]
//                 [--video out.mp4] [--contact-sheet sheet.png]
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "commands.h"
#include "session.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::cli {

namespace {

struct SequenceOptions {
  std::string scene, sequence, out_dir, size = "320x180", video, contact_sheet;
  double fps = 24.0, from = 0.0, to = -1.0;
  bool exr = false;
};

extern "C" char** environ;

// Runs a program found on PATH with an argument vector, never through a shell, so file names are
// passed to it literally. Returns its exit status, or -1 where it could not be started (not installed).
int run_program(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// A file argument starting with '-' would read as an ffmpeg option.
std::string literal_file_argument(const std::string& path) { return path.starts_with('-') ? "./" + path : path; }

// Sequence duration without loading the module's code: the document's own keys.
double sequence_duration(const std::string& path) {
  nlohmann::json doc = read_json_file(path);
  if (doc.is_object() && doc.contains("duration_s") && doc["duration_s"].is_number()) return doc["duration_s"].get<double>();
  double last = 0;
  if (doc.is_object() && doc.contains("tracks") && doc["tracks"].is_array())
    for (const auto& t : doc["tracks"])
      if (t.is_object() && t.contains("keys") && t["keys"].is_array())
        for (const auto& k : t["keys"])
          if (k.is_object() && k.contains("t") && k["t"].is_number()) last = std::max(last, k["t"].get<double>());
  return last;
}

// Thumbnails of up to 12 evenly spaced frames, 4 per row.
ImageU8 make_contact_sheet(const std::vector<ImageU8>& frames) {
  int cols = std::min<int>(4, int(frames.size())), rows = (int(frames.size()) + cols - 1) / cols;
  int w = frames[0].width, h = frames[0].height, gap = 4;
  ImageU8 sheet{cols * w + (cols + 1) * gap, rows * h + (rows + 1) * gap, {}};
  sheet.rgba.assign(size_t(sheet.width) * sheet.height * 4, 255);
  for (size_t i = 0; i < frames.size(); ++i) {
    int ox = gap + int(i % cols) * (w + gap), oy = gap + int(i / cols) * (h + gap);
    for (int y = 0; y < h; ++y)
      std::copy_n(frames[i].pixel(0, y), size_t(w) * 4, &sheet.rgba[(size_t(oy + y) * sheet.width + ox) * 4]);
  }
  return sheet;
}

int run_sequence(const SequenceOptions& o) {
  int w = 0, h = 0;
  parse_size(o.size, w, h);
  double duration = sequence_duration(o.sequence);
  double to = o.to < 0 ? duration : o.to;
  if (!(to >= o.from)) throw Error(ErrorInfo{.path = "--from/--to", .expected = "from <= to", .found = std::to_string(o.from) + " > " + std::to_string(to)});
  int count = int(std::floor((to - o.from) * o.fps + 1e-9)) + 1;

  std::unique_ptr<GlContext> gl;  // before the world: the world's GL objects die first
  auto world = make_world();
  load_scene_file(*world, o.scene);
  apply_assignment(*world, "timeofday.SequencePlayer/file=" + nlohmann::json(o.sequence).dump());
  apply_assignment(*world, "timeofday.SequencePlayer/playing=false");
  gl = create_headless_context();
  Renderer renderer(*world);
  std::filesystem::create_directories(o.out_dir);
  std::vector<ImageU8> thumbs;
  // Up to 12 frames evenly spread over the range, first and last included.
  std::vector<int> wanted;
  for (int k = 0, n = std::min(count, 12); k < n; ++k) wanted.push_back(n == 1 ? 0 : int(std::lround(k * (count - 1) / double(n - 1))));
  for (int i = 0; i < count; ++i) {
    double t = o.from + i / o.fps;
    // Every frame is a scrub to its time: the result never depends on the frames before it.
    apply_assignment(*world, "timeofday.SequencePlayer/time_s=" + nlohmann::json(t).dump());
    renderer.render_frame(FrameInfo{.time_s = t, .dt_s = 0.0, .index = uint64_t(i)}, w, h);
    char name[64];
    std::snprintf(name, sizeof name, "frame_%05d.%s", i, o.exr ? "exr" : "png");
    std::string path = (std::filesystem::path(o.out_dir) / name).string();
    ImageU8 ldr = renderer.read_output();
    if (o.exr) write_exr(path, renderer.read_hdr());
    else write_png(path, ldr);
    if (!o.contact_sheet.empty() && std::find(wanted.begin(), wanted.end(), i) != wanted.end()) thumbs.push_back(std::move(ldr));
    int bar = (i + 1) * 30 / count;
    std::fprintf(stderr, "\r[%.*s%*s] frame %d/%d  t=%.2f s", bar, "==============================", 30 - bar, "", i + 1, count, t);
  }
  std::fprintf(stderr, "\n");
  std::printf("wrote %d frames to %s\n", count, o.out_dir.c_str());
  if (!o.contact_sheet.empty()) {
    write_png(o.contact_sheet, make_contact_sheet(thumbs));
    std::printf("wrote contact sheet %s\n", o.contact_sheet.c_str());
  }
  if (!o.video.empty()) {
    if (o.exr) throw Error(ErrorInfo{.path = "--video", .message = "needs PNG frames (drop --exr)"});
    const int status = run_program({"ffmpeg", "-loglevel", "error", "-y", "-framerate", std::to_string(o.fps), "-i",
                                    literal_file_argument(o.out_dir + "/frame_%05d.png"), "-pix_fmt", "yuv420p", "-vf",
                                    "scale=trunc(iw/2)*2:trunc(ih/2)*2", literal_file_argument(o.video)});
    if (status < 0) {
      std::fprintf(stderr, "welkin: ffmpeg is not installed; frames are in %s, no video written\n", o.out_dir.c_str());
      return kFailure;
    }
    if (status != 0) throw Error(ErrorInfo{.file = o.video, .message = "ffmpeg failed"});
    std::printf("wrote %s\n", o.video.c_str());
  }
  return kOk;
}

}  // namespace

void add_sequence_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SequenceOptions>();
  CLI::App* cmd = app.add_subcommand("sequence", "Render a time-of-day sequence over a scene to numbered frames");
  cmd->add_option("scene", o->scene, "Scene file")->required()->check(CLI::ExistingFile);
  cmd->add_option("sequence", o->sequence, "Sequence file")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--out", o->out_dir, "Folder for the frames")->required();
  cmd->add_option("--fps", o->fps, "Frames per second of sequence time")->check(CLI::Range(0.001, 1000.0))->capture_default_str();
  cmd->add_option("-s,--size", o->size, "Frame size WxH")->capture_default_str();
  cmd->add_option("--from", o->from, "Start time, seconds")->check(CLI::Range(0.0, 1e7));
  cmd->add_option("--to", o->to, "End time, seconds (default: the sequence's duration)")->check(CLI::Range(0.0, 1e7));
  cmd->add_flag("--exr", o->exr, "Write linear HDR OpenEXR frames instead of PNG");
  cmd->add_option("--video", o->video, "Also encode an MP4 with ffmpeg, where installed");
  cmd->add_option("--contact-sheet", o->contact_sheet, "Also write a PNG of up to 12 thumbnails");
  cmd->callback([o, &exit_code] { exit_code = run_sequence(*o); });
}

}  // namespace welkin::cli
