#include "time_of_day_system.h"
#include "welkin/core/module.h"
#include "welkin/timeofday/components.h"

namespace welkin::timeofday {

void describe(TypeBuilder<TimeOfDay>& t) {
  t.tooltip("Date, local time and place of the scene origin; drives the sun and moon");
  t.field("year", &TimeOfDay::year).range(1900, 2100).tooltip("Years covered to SPA accuracy");
  t.field("month", &TimeOfDay::month).range(1, 12);
  t.field("day", &TimeOfDay::day).range(1, 31);
  t.field("local_time_h", &TimeOfDay::local_time_h)
      .unit("h")
      .range(0, 24)
      .tooltip("Local clock time (UTC + offset)");
  t.field("utc_offset_h", &TimeOfDay::utc_offset_h).unit("h").range(-14, 14);
  t.field("latitude_deg", &TimeOfDay::latitude_deg).unit("deg").range(-90, 90);
  t.field("longitude_deg", &TimeOfDay::longitude_deg).unit("deg").range(-180, 180).tooltip("East positive");
  t.field("elevation_m", &TimeOfDay::elevation_m).unit("m").range(-11000, 1e8);
  t.field("time_scale", &TimeOfDay::time_scale)
      .range(-1e6, 1e6)
      .tooltip("Simulated seconds per second; 0 pauses");
  t.field("pressure_mbar", &TimeOfDay::pressure_mbar).unit("mbar").range(0, 5000).tooltip("For refraction");
  t.field("temperature_c", &TimeOfDay::temperature_c).unit("C").range(-273, 1000).tooltip("For refraction");
  t.field("refraction", &TimeOfDay::refraction).tooltip("Raise the sun and moon by atmospheric refraction");
  t.field("delta_t_mode", &TimeOfDay::delta_t_mode).values({{"automatic", 0}, {"manual", 1}});
  t.field("delta_t_s", &TimeOfDay::delta_t_s).unit("s").range(-1e5, 1e5).tooltip("TT - UT when manual");
  // An impossible date (30 February) is an error where it is written, not a silently shifted day.
  t.validate([](const TimeOfDay& tod) { utc_of(tod); });
}

void describe(TypeBuilder<SequencePlayer>& t) {
  t.tooltip("Plays a keyframed sequence file over the scene");
  t.field("file", &SequencePlayer::file).tooltip("Sequence JSON file");
  t.field("time_s", &SequencePlayer::time_s).unit("s").range(0, 1e7);
  t.field("playing", &SequencePlayer::playing);
  t.field("loop", &SequencePlayer::loop);
  t.field("speed", &SequencePlayer::speed).range(-100, 100);
}

}  // namespace welkin::timeofday

namespace welkin::modules {
void register_timeofday(ModuleContext& ctx) {
  using namespace welkin::timeofday;
  ctx.component<TimeOfDay>();
  ctx.component<SequencePlayer>();
  // The sequence runs first so the clock it sets is what the sun is computed from.
  ctx.system({.name = "timeofday.sequence",
              .stage = Stage::simulate,
              .writes = {type_id<SequencePlayer>()},
              .run = sequence_player_system});
  ctx.system({.name = "timeofday.sun_and_moon",
              .stage = Stage::simulate,
              .after = {"timeofday.sequence"},
              .writes = {type_id<TimeOfDay>()},
              .run = time_of_day_system});
}
}  // namespace welkin::modules
