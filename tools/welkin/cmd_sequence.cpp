// welkin sequence SCENE SEQUENCE --out DIR [--fps N] [--size WxH] [--from S] [--to S] [--exr]
//                 [--video out.mp4] [--contact-sheet sheet.png] [--overwrite]
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "commands.h"
#include "session.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::cli {

namespace {

struct SequenceOptions {
  std::string scene, sequence, out_dir, size = "320x180", video, contact_sheet;
  double fps = 24.0, from = 0.0, to = -1.0;
  bool exr = false, overwrite = false;
};

// Frames per run: frame_%05d names stay five digits, and a run stays under about 70 minutes of
// 24 fps video however large --to or the sequence's duration is.
constexpr double kMaxSequenceFrames = 100000;
constexpr int kContactSheetFrames = 12, kContactSheetColumns = 4, kContactSheetGap = 4;

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
// Checked before use: a file's 1e300 must not become a frame count.
double sequence_duration(const std::string& path) {
  nlohmann::json doc = read_json_file(path);
  auto checked = [&](const nlohmann::json& v, const std::string& where) {
    const double d = v.get<double>();
    if (!(d >= 0.0 && d <= 1e7))
      throw Error(ErrorInfo{.file = path, .path = where, .expected = "0 to 1e7 seconds", .found = describe_json(v)});
    return d;
  };
  if (doc.is_object() && doc.contains("duration_s") && doc["duration_s"].is_number()) return checked(doc["duration_s"], "/duration_s");
  double last = 0;
  if (doc.is_object() && doc.contains("tracks") && doc["tracks"].is_array())
    for (size_t i = 0; i < doc["tracks"].size(); ++i) {
      const auto& t = doc["tracks"][i];
      if (t.is_object() && t.contains("keys") && t["keys"].is_array())
        for (size_t j = 0; j < t["keys"].size(); ++j) {
          const auto& k = t["keys"][j];
          if (k.is_object() && k.contains("t") && k["t"].is_number())
            last = std::max(last, checked(k["t"], "/tracks/" + std::to_string(i) + "/keys/" + std::to_string(j) + "/t"));
        }
    }
  return last;
}

// Frames in [from, to] at fps, computed in double and bounded before it becomes an int.
int frame_count(double from, double to, double fps) {
  const double n = std::floor((to - from) * fps + 1e-9) + 1;
  if (!(n >= 1 && n <= kMaxSequenceFrames))
    throw Error(ErrorInfo{.path = "--fps/--from/--to",
                          .expected = "at most " + std::to_string(int(kMaxSequenceFrames)) + " frames",
                          .found = std::to_string(to - from) + " s at " + std::to_string(fps) + " fps"});
  return int(n);
}

// The contact sheet's size, checked before any frame is rendered (its pixels are allocated at the end).
void check_contact_sheet_size(int frames, int w, int h) {
  const int64_t n = std::min(frames, kContactSheetFrames), cols = std::min<int64_t>(kContactSheetColumns, n),
                rows = (n + cols - 1) / cols;
  const int64_t sw = cols * w + (cols + 1) * kContactSheetGap, sh = rows * h + (rows + 1) * kContactSheetGap;
  if (sw > kMaxImageSide || sh > kMaxImageSide || uint64_t(sw * sh) > kMaxImagePixels)
    throw Error(ErrorInfo{.path = "--contact-sheet",
                          .expected = "a sheet of at most " + std::to_string(kMaxImageSide) + " pixels a side (use a smaller --size)",
                          .found = std::to_string(sw) + "x" + std::to_string(sh)});
}

// Frames this command writes, and only those, are what --overwrite removes.
bool is_frame_file(const std::string& name) {
  static const std::regex re(R"(frame_\d{5,}\.(png|exr))");
  return std::regex_match(name, re);
}

// Two runs never mix their frames into one video: a folder holding anything is refused, unless
// --overwrite, which deletes the frames an earlier run wrote (nothing else) before rendering.
void prepare_out_dir(const std::string& dir, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec))
    throw Error(ErrorInfo{.file = dir, .message = "cannot create the output folder" + (ec ? ": " + ec.message() : "")});
  std::vector<fs::path> frames;
  size_t others = 0;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (is_frame_file(e.path().filename().string()) && !e.is_directory()) frames.push_back(e.path());
    else ++others;
  }
  if (ec) throw Error(ErrorInfo{.file = dir, .message = "cannot list the output folder: " + ec.message()});
  if (!overwrite && (others || !frames.empty()))
    throw Error(ErrorInfo{.file = dir,
                          .message = "the output folder is not empty (" + std::to_string(frames.size() + others) +
                                     " entries); choose an empty folder, or pass --overwrite to replace earlier frames"});
  for (const fs::path& f : frames)
    if (!fs::remove(f, ec) && ec) throw Error(ErrorInfo{.file = f.string(), .message = "cannot remove an earlier frame: " + ec.message()});
}

// Thumbnails of up to 12 evenly spaced frames, 4 per row.
ImageU8 make_contact_sheet(const std::vector<ImageU8>& frames) {
  int cols = std::min<int>(kContactSheetColumns, int(frames.size())), rows = (int(frames.size()) + cols - 1) / cols;
  int w = frames[0].width, h = frames[0].height, gap = kContactSheetGap;
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
  const int count = frame_count(o.from, to, o.fps);
  if (!o.contact_sheet.empty()) check_contact_sheet_size(count, w, h);

  std::unique_ptr<GlContext> gl;  // before the world: the world's GL objects die first
  auto world = make_world();
  load_scene_file(*world, o.scene);
  apply_assignment(*world, "timeofday.SequencePlayer/file=" + nlohmann::json(o.sequence).dump());
  apply_assignment(*world, "timeofday.SequencePlayer/playing=false");
  gl = create_headless_context();
  Renderer renderer(*world);
  std::vector<ImageU8> thumbs;
  // Up to 12 frames evenly spread over the range, first and last included.
  std::vector<int> wanted;
  for (int k = 0, n = std::min(count, kContactSheetFrames); k < n; ++k) wanted.push_back(n == 1 ? 0 : int(std::lround(k * (count - 1) / double(n - 1))));
  for (int i = 0; i < count; ++i) {
    double t = o.from + i / o.fps;
    // Every frame is a scrub to its time: the result never depends on the frames before it.
    apply_assignment(*world, "timeofday.SequencePlayer/time_s=" + nlohmann::json(t).dump());
    renderer.render_frame(FrameInfo{.time_s = t, .dt_s = 0.0, .index = uint64_t(i)}, w, h);
    // After the first frame: a bad scene or sequence (checked as it is applied) leaves the folder alone.
    if (i == 0) prepare_out_dir(o.out_dir, o.overwrite);
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
  cmd->add_flag("--overwrite", o->overwrite, "Delete the frames of an earlier run in --out first (else a non-empty folder is refused)");
  cmd->add_option("--video", o->video, "Also encode an MP4 with ffmpeg, where installed");
  cmd->add_option("--contact-sheet", o->contact_sheet, "Also write a PNG of up to 12 thumbnails");
  cmd->callback([o, &exit_code] { exit_code = run_sequence(*o); });
}

}  // namespace welkin::cli
