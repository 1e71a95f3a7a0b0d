#pragma once
// The march and its composite after the geometry (march.cpp).
#include "clouds_gpu.h"
#include "welkin/gfx/render_graph.h"
#include "welkin/gfx/renderer.h"

namespace welkin {
struct SystemContext;
class World;
}  // namespace welkin

namespace welkin::clouds {

// What every march reads (clouds/march_pixel.glsl), bound in its pass: the light environment, the
// field, the scene's depth, the blue noise and, when drawn, where the mesh clusters turn opaque
// (`front`, at `front_unit`).
void bind_march_inputs(PassContext& pc, World& world, const CloudsGpu& gpu, const FrameTargets& t,
                       ResourceHandle front, GLuint front_unit);

// Render phase, after the atmosphere's aerial perspective (order 150): the march at the quality's
// resolution and the composite over the frame.
void clouds_system(SystemContext& sc);

}  // namespace welkin::clouds
