#pragma once
// Render-graph backend on OpenGL: a texture pool that persists across frames (transients are
// reused, not reallocated) and a GPU timing of every pass.
#include <chrono>
#include <memory>
#include <vector>

#include "welkin/gfx/render_graph.h"

namespace welkin {

class GlGraphBackend : public GraphBackend {
 public:
  Texture* acquire(const TextureDesc& desc) override;
  void release(Texture* texture) override;
  void begin_pass(const std::string& name) override;
  void end_pass() override;
  std::vector<double> resolve_gpu_times() override;
  void begin_frame() override;
  size_t pooled_textures() const { return pool_.size(); }
  // True when passes are timed by finishing each one (software rasterisers), not by GPU timestamps.
  bool serial_timing() const { return serial_; }
  // Milliseconds the CPU waited for the GPU since the frame began (finishing passes to time them,
  // reading timestamps back): what a frame's CPU time leaves out.
  double waited_ms() const { return waited_ms_; }

 private:
  void record_timestamp();
  struct Slot {
    std::unique_ptr<Texture> texture;
    bool in_use = false;
  };
  std::vector<Slot> pool_;
  std::vector<GlQueryName> queries_;
  size_t next_query_ = 0;
  bool serial_ = false, mode_decided_ = false;
  std::chrono::steady_clock::time_point pass_start_;
  std::vector<double> serial_ms_;
  double waited_ms_ = 0.0;
};

}  // namespace welkin
