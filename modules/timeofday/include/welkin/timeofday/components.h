#pragma once
// Time-of-day components. TimeOfDay places the scene origin on Earth at a date and local time; its
// system computes the sun and moon and writes them, the clock and the origin's place into the
// world's shared state (welkin/scene/shared_state.h), which the lights of the scene follow (the
// atmosphere's, or the built-in core.DirectionalLight), so this module needs no other module.
// SequencePlayer plays a keyframed sequence file.
#include <string>
#include <string_view>

#include "welkin/core/reflection.h"

namespace welkin::timeofday {

enum class DeltaTMode : int { automatic = 0, manual = 1 };

struct TimeOfDay {
  static constexpr std::string_view kTypeName = "timeofday.TimeOfDay";
  int year = 2026;
  int month = 6;
  int day = 21;
  double local_time_h = 17.0;  // local clock time, hours in [0, 24)
  double utc_offset_h = 0.0;   // local time minus UTC
  double latitude_deg = 46.5;
  double longitude_deg = 7.9;
  double elevation_m = 500.0;
  float time_scale = 0.0f;  // simulated seconds per real second; 0 pauses
  float pressure_mbar = 1013.25f;
  float temperature_c = 15.0f;
  bool refraction = true;
  DeltaTMode delta_t_mode = DeltaTMode::automatic;
  float delta_t_s = 69.0f;  // TT - UT, used when delta_t_mode is manual
};
void describe(TypeBuilder<TimeOfDay>& t);

struct SequencePlayer {
  static constexpr std::string_view kTypeName = "timeofday.SequencePlayer";
  std::string file;      // sequence JSON, relative paths resolved against the working directory
  double time_s = 0.0;   // sequence time; scrubbing sets it, playing advances it
  bool playing = true;
  bool loop = false;
  float speed = 1.0f;
};
void describe(TypeBuilder<SequencePlayer>& t);

}  // namespace welkin::timeofday
