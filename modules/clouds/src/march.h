#pragma once
// The march and its composite after the geometry (march.cpp).

namespace welkin {
struct SystemContext;
}

namespace welkin::clouds {

// Render phase, after the atmosphere's aerial perspective (order 150): the march at the quality's
// resolution and the composite over the frame.
void clouds_system(SystemContext& sc);

}  // namespace welkin::clouds
