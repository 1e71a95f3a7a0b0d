#include "run_folder.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "commands.h"
#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/core/type_id.h"
#include "welkin/scene/json_fields.h"

namespace welkin::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* kPendingSuffix = ".pending-";  // create_file_exclusively's private copies

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
                          .expected = "at most " + std::to_string(kMaxSequenceFrames) + " frames",
                          .found = std::to_string(to - from) + " s at " + std::to_string(fps) + " fps"});
  return int(n);
}

std::string inputs_hash(const std::vector<std::string>& files) {
  uint64_t h = kFnv1aOffset;
  for (const std::string& f : files) {
    const auto bytes = read_file_bytes(f);
    h = fnv1a_64(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), h);
    // A separator, so moving bytes from one file to the other changes the hash.
    h = fnv1a_64("\xff", h);
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

// A non-negative decimal integer of at most kMaxSequenceFrames: no sign, no spaces, no overflow.
std::optional<int> parse_count(std::string_view text) {
  if (text.empty() || text.size() > 6 || !std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  int v = 0;
  std::from_chars(text.data(), text.data() + text.size(), v);
  return v <= kMaxSequenceFrames ? std::optional<int>(v) : std::nullopt;
}

}  // namespace

RunManifest describe_run(const RunSettings& s) {
  int w = 0, h = 0;
  parse_size(s.size, w, h);
  const double to = s.to < 0 ? sequence_duration(s.sequence) : s.to;
  if (!(to >= s.from))
    throw Error(ErrorInfo{.path = "--from/--to", .expected = "from <= to", .found = std::to_string(s.from) + " > " + std::to_string(to)});
  return RunManifest{.scene = fs::absolute(s.scene).lexically_normal().string(),
                     .sequence = fs::absolute(s.sequence).lexically_normal().string(),
                     .size = std::to_string(w) + "x" + std::to_string(h),
                     .fps = s.fps,
                     .from = s.from,
                     .to = to,
                     .exr = s.exr,
                     .frames = frame_count(s.from, to, s.fps),
                     .inputs_hash = inputs_hash({s.scene, s.sequence})};
}

bool same_run(const RunManifest& a, const RunManifest& b) {
  return a.size == b.size && a.fps == b.fps && a.from == b.from && a.to == b.to && a.exr == b.exr && a.frames == b.frames &&
         a.inputs_hash == b.inputs_hash;
}

std::string manifest_json(const RunManifest& m) {
  const nlohmann::json j = {{"welkin_run", 1},    {"scene", m.scene}, {"sequence", m.sequence}, {"size", m.size},
                            {"fps", m.fps},       {"from_s", m.from}, {"to_s", m.to},           {"exr", m.exr},
                            {"frames", m.frames}, {"inputs_hash", m.inputs_hash}};
  return j.dump(2) + "\n";
}

std::optional<RunManifest> read_run_manifest(const std::string& dir) {
  const fs::path path = fs::path(dir) / kRunManifestName;
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec))) return std::nullopt;
  const nlohmann::json j = read_json_file(path.string());
  try {
    if (j.at("welkin_run").get<int>() != 1) throw Error(ErrorInfo{.file = path.string(), .path = "/welkin_run", .expected = "1", .found = describe_json(j["welkin_run"])});
    RunManifest m{.scene = j.at("scene").get<std::string>(),
                  .sequence = j.at("sequence").get<std::string>(),
                  .size = j.at("size").get<std::string>(),
                  .fps = j.at("fps").get<double>(),
                  .from = j.at("from_s").get<double>(),
                  .to = j.at("to_s").get<double>(),
                  .exr = j.at("exr").get<bool>(),
                  .frames = j.at("frames").get<int>(),
                  .inputs_hash = j.at("inputs_hash").get<std::string>()};
    if (m.frames < 1 || m.frames > kMaxSequenceFrames)
      throw Error(ErrorInfo{.file = path.string(), .path = "/frames", .expected = "1 to " + std::to_string(kMaxSequenceFrames), .found = std::to_string(m.frames)});
    return m;
  } catch (const nlohmann::json::exception& e) {
    throw Error(ErrorInfo{.file = path.string(), .message = std::string("not a run manifest: ") + e.what()});
  }
}

std::string frame_file_name(int index, bool exr) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05d.%s", index, exr ? "exr" : "png");
  return name;
}

bool is_frame_file(const std::string& name) {
  static const std::regex re(R"(frame_\d{5,}\.(png|exr))");
  return std::regex_match(name, re);
}

int frame_of_temporary_file(const std::string& name, bool exr) {
  // The atomic writer's temporary names: "." + target name + ".tmp-" + pid, counter and clock.
  static const std::regex png(R"(\.frame_(\d{5})\.png\.tmp-.*)"), exr_re(R"(\.frame_(\d{5})\.exr\.tmp-.*)");
  std::smatch m;
  return std::regex_match(name, m, exr ? exr_re : png) ? std::stoi(m[1]) : -1;
}

bool create_file_exclusively(const std::string& path, const std::string& bytes) {
  // Written whole under a name of this process's own, then linked to the shared name: link(2) never
  // replaces a file, so of many shards starting at once exactly one creates it, and nobody reads a
  // half-written one. (Atomic on NFS too.)
  static std::atomic<uint64_t> counter{0};  // threads of one process share its pid
  const std::string mine = path + kPendingSuffix + std::to_string(::getpid()) + "-" + std::to_string(counter++);
  write_file_atomically(mine, bytes);
  const int linked = ::link(mine.c_str(), path.c_str());
  const int err = errno;
  ::unlink(mine.c_str());
  if (linked == 0) return true;
  if (err == EEXIST) return false;
  throw Error(ErrorInfo{.file = path, .message = std::string("cannot create: ") + std::strerror(err)});
}

void join_run_folder(const std::string& dir, const RunManifest& run, bool create) {
  std::error_code ec;
  if (!fs::exists(dir, ec) && !create) return;
  if (create) fs::create_directories(dir, ec);
  if (!fs::is_directory(dir, ec))
    throw Error(ErrorInfo{.file = dir, .message = "cannot create the output folder" + (ec ? ": " + ec.message() : "")});
  std::optional<RunManifest> found = read_run_manifest(dir);
  if (!found) {
    // Nothing else may be there but another shard's manifest on its way in (its private copy), or
    // already in since it was read above (the exclusive creation below then reads it).
    const std::string pending = std::string(kRunManifestName) + kPendingSuffix;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
      const std::string name = e.path().filename().string();
      if (name != kRunManifestName && !name.starts_with(pending) && !name.starts_with("." + pending))
        throw Error(ErrorInfo{.file = dir,
                              .message = "the output folder is not empty and holds no " + std::string(kRunManifestName) +
                                         "; shards and resumed runs share only a folder of their own run"});
    }
    if (!create) return;
    const std::string manifest = (fs::path(dir) / kRunManifestName).string();
    if (create_file_exclusively(manifest, manifest_json(run))) return;
    found = read_run_manifest(dir);  // another shard was first
  }
  if (!same_run(*found, run))
    throw Error(ErrorInfo{.file = (fs::path(dir) / kRunManifestName).string(),
                          .message = "the folder holds frames of another run (" + found->size + ", " + std::to_string(found->frames) +
                                     " frames, inputs " + found->inputs_hash + "; this run: " + run.size + ", " +
                                     std::to_string(run.frames) + " frames, inputs " + run.inputs_hash +
                                     "); choose another folder, or --overwrite it with a whole run"});
}

FrameRange parse_frame_range(const std::string& text) {
  const Error bad(ErrorInfo{.path = "--frames",
                            .expected = "FIRST:LAST, frame numbers from 0 to " + std::to_string(kMaxSequenceFrames - 1) + " with FIRST <= LAST, e.g. 0:99",
                            .found = "'" + text + "'"});
  const size_t colon = text.find(':');
  if (colon == std::string::npos) throw bad;
  const std::optional<int> first = parse_count(std::string_view(text).substr(0, colon)),
                           last = parse_count(std::string_view(text).substr(colon + 1));
  if (!first || !last || *first > *last || *last >= kMaxSequenceFrames) throw bad;
  return {*first, *last};
}

Shard parse_shard(const std::string& text) {
  const Error bad(ErrorInfo{.path = "--shard",
                            .expected = "I/N, the I-th of N shards with 0 <= I < N <= " + std::to_string(kMaxSequenceFrames) + ", e.g. 0/4",
                            .found = "'" + text + "'"});
  const size_t slash = text.find('/');
  if (slash == std::string::npos) throw bad;
  const std::optional<int> index = parse_count(std::string_view(text).substr(0, slash)),
                           count = parse_count(std::string_view(text).substr(slash + 1));
  if (!index || !count || *count < 1 || *index >= *count) throw bad;
  return {*index, *count};
}

std::vector<int> select_frames(int frames, const std::optional<FrameRange>& range, const std::optional<Shard>& shard) {
  const FrameRange r = range.value_or(FrameRange{0, frames - 1});
  if (r.last >= frames)
    throw Error(ErrorInfo{.path = "--frames", .expected = "frames within the run's 0 to " + std::to_string(frames - 1),
                          .found = std::to_string(r.first) + ":" + std::to_string(r.last)});
  const Shard s = shard.value_or(Shard{});
  // Every count-th frame rather than a block each: a shard's frames spread over the whole sequence,
  // so shards cost about the same when night frames are cheap and cloudy noon ones are not.
  std::vector<int> out;
  for (int i = r.first + s.index; i <= r.last; i += s.count) out.push_back(i);
  return out;
}

}  // namespace welkin::cli
