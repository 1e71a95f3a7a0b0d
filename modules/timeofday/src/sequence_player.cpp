#include <filesystem>
#include <map>

#include "time_of_day_system.h"
#include "welkin/core/world.h"
#include "welkin/scene/sequence.h"

namespace welkin::timeofday {

namespace {
// Parsed sequences by path, reloaded when the file changes on disk (the editor saves while playing).
struct SequenceCache {
  static constexpr std::string_view kTypeName = "timeofday.SequenceCache";
  struct Entry {
    std::filesystem::file_time_type stamp;
    Sequence sequence;
  };
  std::map<std::string, Entry> entries;
  const Sequence& get(const std::string& path) {
    std::error_code ec;
    auto stamp = std::filesystem::last_write_time(path, ec);
    auto it = entries.find(path);
    if (it == entries.end() || it->second.stamp != stamp)
      it = entries.insert_or_assign(path, Entry{stamp, load_sequence_file(path)}).first;
    return it->second.sequence;
  }
};
}  // namespace

void sequence_player_system(SystemContext& sc) {
  auto& cache = sc.world.resource<SequenceCache>();
  sc.world.registry().each<SequencePlayer>([&](Entity, SequencePlayer& p) {
    if (p.file.empty()) return;
    const Sequence& seq = cache.get(p.file);
    if (p.playing && sc.frame.dt_s > 0) p.time_s += sc.frame.dt_s * p.speed;
    if (p.loop && seq.duration_s > 0)
      p.time_s = std::fmod(std::fmod(p.time_s, seq.duration_s) + seq.duration_s, seq.duration_s);
    apply_sequence(seq, sc.world, p.time_s);
  });
}

}  // namespace welkin::timeofday
