// welkin sequence SCENE SEQUENCE --out DIR [--fps N] [--size WxH] [--from S] [--to S] [--exr]
//                 [--video out.mp4] [--contact-sheet sheet.png] [--overwrite]
//                 [--frames A:B] [--shard I/N] [--resume]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "program.h"
#include "run_folder.h"
#include "session.h"
#include "welkin/core/error.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/field_path.h"
#include "welkin/scene/scene_file.h"

namespace welkin::cli {

namespace {

struct SequenceOptions {
  RunSettings run;
  std::string out_dir, video, contact_sheet, frames, shard;
  bool overwrite = false, resume = false;
};

constexpr int kContactSheetFrames = 12, kContactSheetColumns = 4, kContactSheetGap = 4;

// A file argument starting with '-' would read as an ffmpeg option.
std::string literal_file_argument(const std::string& path) { return path.starts_with('-') ? "./" + path : path; }

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

// Two runs never mix their frames into one video: a whole run refuses a folder holding anything,
// unless --overwrite, which deletes the frames and the manifest an earlier run wrote (nothing else)
// before this run's manifest is written.
void prepare_out_dir(const std::string& dir, const RunManifest& run, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir, ec))
    throw Error(ErrorInfo{.file = dir, .message = "cannot create the output folder" + (ec ? ": " + ec.message() : "")});
  std::vector<fs::path> earlier;
  size_t others = 0;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if ((is_frame_file(name) || name == kRunManifestName) && !e.is_directory()) earlier.push_back(e.path());
    else ++others;
  }
  if (ec) throw Error(ErrorInfo{.file = dir, .message = "cannot list the output folder: " + ec.message()});
  if (!overwrite && (others || !earlier.empty()))
    throw Error(ErrorInfo{.file = dir,
                          .message = "the output folder is not empty (" + std::to_string(earlier.size() + others) +
                                     " entries); choose an empty folder, pass --resume to finish the run it holds, or --overwrite to replace earlier frames"});
  for (const fs::path& f : earlier)
    if (!fs::remove(f, ec) && ec) throw Error(ErrorInfo{.file = f.string(), .message = "cannot remove an earlier frame: " + ec.message()});
  if (!create_file_exclusively((fs::path(dir) / kRunManifestName).string(), manifest_json(run)))
    throw Error(ErrorInfo{.file = dir, .message = "another run started writing into the output folder"});
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
  namespace fs = std::filesystem;
  const RunManifest run = describe_run(o.run);
  const std::optional<FrameRange> range = o.frames.empty() ? std::nullopt : std::optional(parse_frame_range(o.frames));
  const std::optional<Shard> shard = o.shard.empty() ? std::nullopt : std::optional(parse_shard(o.shard));
  const std::vector<int> selected = select_frames(run.frames, range, shard);
  const bool partial = range || shard;
  if (partial && (!o.contact_sheet.empty() || !o.video.empty()))
    throw Error(ErrorInfo{.path = o.video.empty() ? "--contact-sheet" : "--video",
                          .message = "needs every frame: make it in a run without --frames and --shard once the shards are done "
                                     "(with --resume it renders only what is missing), as `welkin farm slurm` does"});
  if (o.overwrite && (shard || o.resume))
    throw Error(ErrorInfo{.path = "--overwrite", .message = "cannot be combined with --shard or --resume (it would delete the frames other shards wrote)"});
  check_assembly_options(run, o.video, o.contact_sheet);
  int w = 0, h = 0;
  parse_size(run.size, w, h);
  // Shards and resumed runs share the folder with frames of the same run; a whole run starts afresh.
  const bool joining = partial || o.resume;
  if (joining) join_run_folder(o.out_dir, run, /*create=*/false);  // before any work: a foreign folder is refused now
  auto frame_path = [&](int i) { return (fs::path(o.out_dir) / frame_file_name(i, run.exr)).string(); };

  std::unique_ptr<GlContext> gl;  // before the world: the world's GL objects die first
  auto world = make_world();
  load_scene_file(*world, o.run.scene);
  apply_assignment(*world, "timeofday.SequencePlayer/file=" + nlohmann::json(o.run.sequence).dump());
  apply_assignment(*world, "timeofday.SequencePlayer/playing=false");
  gl = create_headless_context();
  Renderer renderer(*world);
  auto render = [&](int i) {
    const double t = run.from + i / run.fps;
    // Every frame is a scrub to its time: the result never depends on the frames before it (or on
    // which shard renders it).
    apply_assignment(*world, "timeofday.SequencePlayer/time_s=" + nlohmann::json(t).dump());
    // Every frame alone (FrameInfo::alone): the same bytes whichever shard renders it, after
    // whichever frames.
    renderer.render_frame(FrameInfo{.time_s = t, .dt_s = 0.0, .index = uint64_t(i), .alone = true}, w, h);
  };
  // Up to 12 frames evenly spread over the run, first and last included.
  std::map<int, ImageU8> thumbs;
  if (!o.contact_sheet.empty())
    for (int k = 0, n = std::min(run.frames, kContactSheetFrames); k < n; ++k)
      thumbs[n == 1 ? 0 : int(std::lround(k * (run.frames - 1) / double(n - 1)))] = ImageU8{};
  int written = 0, already = 0;
  for (size_t k = 0; k < selected.size(); ++k) {
    const int i = selected[k];
    // A frame exists under its name only once written whole (the writer renames a finished file).
    if (o.resume && fs::is_regular_file(frame_path(i))) {
      ++already;
      continue;
    }
    render(i);
    // After the first frame: a bad scene or sequence (checked as it is applied) leaves the folder alone.
    if (written == 0 && joining) join_run_folder(o.out_dir, run, /*create=*/true);
    if (written == 0 && !joining) prepare_out_dir(o.out_dir, run, o.overwrite);
    ImageU8 ldr = renderer.read_output();
    if (run.exr) write_exr(frame_path(i), renderer.read_hdr());
    else write_png(frame_path(i), ldr);
    if (thumbs.count(i)) thumbs[i] = std::move(ldr);
    ++written;
    const int bar = int((k + 1) * 30 / selected.size());
    std::fprintf(stderr, "\r[%.*s%*s] frame %zu/%zu  t=%.2f s", bar, "==============================", 30 - bar, "", k + 1,
                 selected.size(), run.from + i / run.fps);
  }
  if (written) std::fprintf(stderr, "\n");
  if (!joining) std::printf("wrote %d frames to %s\n", written, o.out_dir.c_str());
  else
    std::printf("wrote %d frames to %s (%s%d of them already there)\n", written, o.out_dir.c_str(),
                shard ? ("shard " + o.shard + ", " + std::to_string(selected.size()) + " frames; ").c_str() : "", already);
  if (!o.contact_sheet.empty()) {
    std::vector<ImageU8> sheet;
    for (auto& [i, thumb] : thumbs) {
      // Frames an earlier run wrote: a PNG is the tone-mapped frame itself; an EXR is linear, so the
      // frame is rendered again for its tone-mapped image.
      if (thumb.rgba.empty() && !run.exr) thumb = read_png(frame_path(i));
      if (thumb.rgba.empty()) {
        render(i);
        thumb = renderer.read_output();
      }
      sheet.push_back(std::move(thumb));
    }
    write_png(o.contact_sheet, make_contact_sheet(sheet));
    std::printf("wrote contact sheet %s\n", o.contact_sheet.c_str());
  }
  if (!o.video.empty()) {
    const int status = run_program({"ffmpeg", "-loglevel", "error", "-y", "-framerate", std::to_string(run.fps), "-i",
                                    literal_file_argument(o.out_dir + "/frame_%05d.png"), "-pix_fmt", "yuv420p", "-vf",
                                    "scale=trunc(iw/2)*2:trunc(ih/2)*2", literal_file_argument(o.video)})
                           .status;
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

void check_assembly_options(const RunManifest& run, const std::string& video, const std::string& contact_sheet) {
  if (!video.empty() && run.exr) throw Error(ErrorInfo{.path = "--video", .message = "needs PNG frames (drop --exr)"});
  int w = 0, h = 0;
  parse_size(run.size, w, h);
  if (!contact_sheet.empty()) check_contact_sheet_size(run.frames, w, h);
}

void add_sequence_command(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<SequenceOptions>();
  CLI::App* cmd = app.add_subcommand("sequence", "Render a time-of-day sequence over a scene to numbered frames");
  cmd->add_option("scene", o->run.scene, "Scene file")->required()->check(CLI::ExistingFile);
  cmd->add_option("sequence", o->run.sequence, "Sequence file")->required()->check(CLI::ExistingFile);
  cmd->add_option("-o,--out", o->out_dir, "Folder for the frames")->required();
  add_run_options(*cmd, o->run);
  cmd->add_flag("--overwrite", o->overwrite, "Delete the frames of an earlier run in --out first (else a non-empty folder is refused)");
  cmd->add_option("--frames", o->frames, "Render only frames FIRST:LAST (inclusive, numbered from 0)");
  cmd->add_option("--shard", o->shard, "Render only shard I/N: every N-th frame from the I-th (I from 0), for N machines");
  cmd->add_flag("--resume", o->resume, "Skip frames already written to --out by this same run; render the rest");
  add_assembly_options(*cmd, o->video, o->contact_sheet);
  cmd->callback([o, &exit_code] { exit_code = run_sequence(*o); });
}

void add_run_options(CLI::App& cmd, RunSettings& run) {
  cmd.add_option("--fps", run.fps, "Frames per second of sequence time")->check(CLI::Range(0.001, 1000.0))->capture_default_str();
  cmd.add_option("-s,--size", run.size, "Frame size WxH")->capture_default_str();
  cmd.add_option("--from", run.from, "Start time, seconds")->check(CLI::Range(0.0, 1e7));
  cmd.add_option("--to", run.to, "End time, seconds (default: the sequence's duration)")->check(CLI::Range(0.0, 1e7));
  cmd.add_flag("--exr", run.exr, "Write linear HDR OpenEXR frames instead of PNG");
}

void add_assembly_options(CLI::App& cmd, std::string& video, std::string& contact_sheet) {
  cmd.add_option("--video", video, "Also encode an MP4 with ffmpeg, where installed");
  cmd.add_option("--contact-sheet", contact_sheet, "Also write a PNG of up to 12 thumbnails");
}

}  // namespace welkin::cli
