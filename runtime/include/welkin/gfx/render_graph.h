#pragma once
// The frame graph. Each frame, systems add passes that declare the textures they read and write;
// compile() walks backwards from the presented targets and drops every pass whose outputs reach
// none of them (Granite/Filament style), computes transient lifetimes, and execute() allocates
// transient textures from a pool, runs the surviving passes in declaration order and times each.
// The graph itself makes no GL calls: a backend allocates textures and times passes, so culling
// and pooling are tested without a GPU.
#include <chrono>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "welkin/gfx/gl_objects.h"

namespace welkin {

struct ResourceHandle {
  uint32_t index = 0xffffffffu;
  bool valid() const { return index != 0xffffffffu; }
  friend bool operator==(ResourceHandle, ResourceHandle) = default;
};

// The name under which one system's passes publish a resource for the passes of later systems
// (Filament's blackboard), declared once as a constant that the publisher and its readers share:
//   inline constexpr GraphKey kSceneDepth{"scene_depth"};
struct GraphKey {
  std::string_view name;
};

class RenderGraph;

class PassBuilder {
 public:
  ResourceHandle create(const std::string& name, const TextureDesc& desc);
  ResourceHandle read(ResourceHandle h);
  ResourceHandle write(ResourceHandle h);
  // Keeps the pass even if nothing reads its outputs (readbacks, persistent LUT updates).
  void side_effect();

 private:
  friend class RenderGraph;
  PassBuilder(RenderGraph& g, uint32_t pass) : graph_(g), pass_(pass) {}
  RenderGraph& graph_;
  uint32_t pass_;
};

class PassContext {
 public:
  Texture& texture(ResourceHandle h) const;
  const std::string& pass_name() const { return name_; }

 private:
  friend class RenderGraph;
  PassContext(RenderGraph& g, std::string name) : graph_(g), name_(std::move(name)) {}
  RenderGraph& graph_;
  std::string name_;
};

// Allocates transient textures and times passes; the GL backend and test fakes implement it.
class GraphBackend {
 public:
  virtual ~GraphBackend() = default;
  virtual Texture* acquire(const TextureDesc& desc) = 0;
  virtual void release(Texture* texture) = 0;
  virtual void begin_pass(const std::string& name) = 0;
  virtual void end_pass() = 0;
  // GPU milliseconds of each pass since the last frame began (in begin order); may block.
  virtual std::vector<double> resolve_gpu_times() = 0;
  virtual void begin_frame() = 0;
};

struct PassTiming {
  std::string name;
  std::string system;  // the system that added the pass ("" for the renderer's own)
  double gpu_ms = 0;  // from GL timer queries (0 where unsupported)
  double cpu_ms = 0;  // wall time of the execute callback
};

class RenderGraph {
 public:
  using SetupFn = std::function<void(PassBuilder&)>;
  using ExecuteFn = std::function<void(PassContext&)>;

  ResourceHandle import(const std::string& name, Texture& texture);
  // A transient texture of this frame, made before the passes that use it: its handle goes into each
  // pass's setup (which reads or writes it) and execute by value. Allocated before the first pass that
  // uses it runs, returned after the last.
  ResourceHandle create(const std::string& name, const TextureDesc& desc);
  void add_pass(const std::string& name, const SetupFn& setup, ExecuteFn execute);
  // The system whose passes follow (timings name it: the cost of each path); "" for the renderer's.
  void set_system(std::string name) { system_ = std::move(name); }
  void present(ResourceHandle h);

  // Culling and lifetimes. Returns the names of the passes that will run.
  std::vector<std::string> compile();
  void execute(GraphBackend& backend);

  const std::vector<PassTiming>& timings() const { return timings_; }
  std::vector<std::string> culled_passes() const;
  std::string resource_name(ResourceHandle h) const { return resources_.at(h.index).name; }
  const TextureDesc& resource_desc(ResourceHandle h) const { return resources_.at(h.index).desc; }

  // Resources shared between the systems of one frame: `publish` replaces what the key held;
  // `published` is invalid when nothing was published under it this frame.
  void publish(GraphKey key, ResourceHandle h);
  ResourceHandle published(GraphKey key) const;

 private:
  friend class PassBuilder;
  friend class PassContext;
  struct Resource {
    std::string name;
    TextureDesc desc;
    Texture* texture = nullptr;  // imported, or acquired during execute
    bool imported = false;
    int first_use = -1, last_use = -1;  // pass indices (alive passes only)
  };
  struct Pass {
    std::string name, system;
    std::vector<uint32_t> reads, writes;
    ExecuteFn execute;
    bool side_effect = false;
    bool alive = false;
  };
  std::vector<Resource> resources_;
  std::vector<Pass> passes_;
  std::vector<uint32_t> presented_;
  std::map<std::string, ResourceHandle, std::less<>> blackboard_;
  std::vector<PassTiming> timings_;
  std::string system_;
  bool compiled_ = false;
};

}  // namespace welkin
