// `welkin accuracy clouds --image SCENE`: the scene's view marched at each quality beside the path
// tracer's image of the same rays (or, with --paths-per-pixel 0, beside the march at every pixel).
#pragma once
#include <map>
#include <string>
#include <vector>

#include "commands.h"
#include "welkin/clouds/components.h"

namespace welkin::cli {

int write_cloud_images(const CloudAccuracyOptions& o, const std::map<std::string, clouds::Quality>& names,
                       int width, int height);

}  // namespace welkin::cli
