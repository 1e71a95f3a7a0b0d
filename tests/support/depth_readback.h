#pragma once
// Reads the frame's depth after the geometry (a render system at order 50), for tests of what the
// geometry systems report about the pixels they cover (FrameTargets::geometry).
#include <memory>
#include <vector>

#include "welkin/core/world.h"
#include "welkin/gfx/renderer.h"

namespace welkin::testing {

struct DepthReadback {
  int width = 0, height = 0;
  std::vector<float> depth;  // reversed Z: 0 where nothing was drawn
  // Pixels with depth outside `r`, and pixels with depth at all.
  int outside(const PixelRect& r) const {
    int n = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        n += depth[size_t(y) * size_t(width) + size_t(x)] > 0.0f && !(x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1);
    return n;
  }
  int covered() const {
    int n = 0;
    for (float d : depth) n += d > 0.0f;
    return n;
  }
};

// Add it after the scene is loaded: it runs after the geometry of the modules registered before it.
inline std::shared_ptr<DepthReadback> read_depth_after_geometry(World& world) {
  auto out = std::make_shared<DepthReadback>();
  world.scheduler().add(SystemDesc{
      .name = "test.read_depth", .stage = Stage::geometry, .run = [out](SystemContext& sc) {
        const FrameTargets t = *sc.targets;
        sc.graph->add_pass("test.read_depth", [&](PassBuilder& b) { b.read(t.depth); b.write(t.color); },
                           [t, out](PassContext& pc) {
                             const Texture& d = pc.texture(t.depth);
                             out->width = d.desc().width, out->height = d.desc().height;
                             out->depth.resize(size_t(out->width) * size_t(out->height));
                             glGetTextureImage(d.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                                               GLsizei(out->depth.size() * sizeof(float)), out->depth.data());
                           });
      }});
  return out;
}

}  // namespace welkin::testing
