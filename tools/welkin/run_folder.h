#pragma once
// A sequence run and the folder its frames go to. One run is a scene, a sequence and the settings that
// decide its frames (fps, size, from, to, PNG or EXR); a run manifest (welkin-run.json) in the folder
// says which run the frames belong to, so shards started on many machines, a resumed run and
// `welkin farm status` agree on it, and frames of two runs never mix.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace welkin::cli {

// Frames per run: frame_%05d names stay five digits, and a run stays under about 70 minutes of
// 24 fps video however large --to or the sequence's duration is.
inline constexpr int kMaxSequenceFrames = 100000;
inline constexpr const char* kRunManifestName = "welkin-run.json";

// What a user asks for on the command line (`welkin sequence`, `welkin farm slurm`).
struct RunSettings {
  std::string scene, sequence, size = "320x180";
  double fps = 24.0, from = 0.0, to = -1.0;  // to < 0: the sequence's duration
  bool exr = false;
};

// The run those settings resolve to: its frame count, its end time and a hash of its input files.
struct RunManifest {
  std::string scene, sequence;  // absolute paths, for people; not part of the run's identity
  std::string size;
  double fps = 0, from = 0, to = 0;
  bool exr = false;
  int frames = 0;
  std::string inputs_hash;  // FNV-1a 64 of the scene's and the sequence's bytes
};

// Reads the sequence's duration and the input files; throws Error naming the file or the option.
RunManifest describe_run(const RunSettings& settings);
// Same frames from the same inputs (paths may differ: a cluster mounts files elsewhere).
bool same_run(const RunManifest& a, const RunManifest& b);
std::string manifest_json(const RunManifest& m);
// The manifest in `dir`, or nothing where there is none; throws Error if it is unreadable or malformed.
std::optional<RunManifest> read_run_manifest(const std::string& dir);

std::string frame_file_name(int index, bool exr);
// frame_NNNNN.png|exr: the files a run writes (and --overwrite removes).
bool is_frame_file(const std::string& name);
// The frame a temporary file of the atomic writer was going to become (.frame_00003.png.tmp-...), or -1.
int frame_of_temporary_file(const std::string& name, bool exr);

// Creates `path` holding `bytes` only if nothing has that name yet, and atomically: a reader sees no
// file or the whole file. Returns false where the name was taken (by another shard, say).
bool create_file_exclusively(const std::string& path, const std::string& bytes);

// For shards and resumed runs, which share a folder: the folder must be empty or hold this run's
// manifest. With `create`, makes the folder and the manifest (race-free when many shards start at
// once); without, only checks what is there. Throws Error naming the folder.
void join_run_folder(const std::string& dir, const RunManifest& run, bool create);

// --frames A:B (first and last frame, inclusive) and --shard I/N (the I-th of N, I from 0).
struct FrameRange {
  int first = 0, last = 0;
};
struct Shard {
  int index = 0, count = 1;
};
// Strict: digits only, in range; throws Error naming the option.
FrameRange parse_frame_range(const std::string& text);
Shard parse_shard(const std::string& text);
// The frames of a run of `frames` frames to render: those in `range` (all by default), of which a
// shard takes every count-th, starting at its index. Deterministic, so shards never overlap and
// together cover the range. Throws Error if the range ends past the run's last frame.
std::vector<int> select_frames(int frames, const std::optional<FrameRange>& range, const std::optional<Shard>& shard);

}  // namespace welkin::cli
