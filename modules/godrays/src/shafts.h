#pragma once
// The god-rays render system (src/shafts.cpp).
#include <glm/glm.hpp>
#include <optional>

#include "welkin/core/system.h"
#include "welkin/godrays/components.h"

namespace welkin::godrays {

void shafts_system(SystemContext& sc);

// The marched shafts look the air up at the ends of `segments` equal segments and sample the shadow
// `substeps` times in each: `steps` rounded up to a whole number of segments of (at most) four samples.
inline constexpr int kSubsteps = 4;
// The shafts' application skips tiles of this many texels square where they are zero (apply.vert).
inline constexpr int kApplyTileTexels = 8;
struct MarchSteps {
  int segments, substeps;
};
MarchSteps march_steps(int steps);

// Where the sun's image lies on the screen, in [0, 1]^2 texture coordinates (y up, as GL's), or
// nothing when the sun is behind the camera or off the screen: the screen-space shafts run only then.
std::optional<glm::vec2> sun_on_screen(const glm::mat4& view_projection, const glm::vec3& sun_direction);

}  // namespace welkin::godrays
