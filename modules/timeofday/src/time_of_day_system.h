#pragma once
#include "welkin/core/system.h"
#include "welkin/timeofday/components.h"
#include "welkin/timeofday/sky.h"
#include "welkin/timeofday/time.h"

namespace welkin::timeofday {
// The instant a TimeOfDay describes (throws Error for an impossible date such as 30 February).
UtcTime utc_of(const TimeOfDay& tod);
// Rewrites date and local time from an instant, keeping the UTC offset.
void set_local_time(TimeOfDay& tod, const UtcTime& utc);
SkyState sky_of(const TimeOfDay& tod);
void time_of_day_system(SystemContext& sc);
void sequence_player_system(SystemContext& sc);
}  // namespace welkin::timeofday
