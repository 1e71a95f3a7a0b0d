#pragma once
#include <filesystem>

#include "welkin/core/system.h"

namespace welkin::weather {

// The update system: applies the first weather.Report when it changed since it was last applied.
// `station_table` is the module's data/stations.csv.
void apply_report_system(SystemContext& ctx, const std::filesystem::path& station_table);

}  // namespace welkin::weather
