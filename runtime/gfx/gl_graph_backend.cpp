#include "welkin/gfx/gl_graph_backend.h"

#include <cstdlib>
#include <cstring>

namespace welkin {

Texture* GlGraphBackend::acquire(const TextureDesc& desc) {
  for (auto& s : pool_)
    if (!s.in_use && s.texture->desc() == desc) {
      s.in_use = true;
      return s.texture.get();
    }
  pool_.push_back({std::make_unique<Texture>(desc), true});
  return pool_.back().texture.get();
}

void GlGraphBackend::release(Texture* t) {
  for (auto& s : pool_)
    if (s.texture.get() == t) s.in_use = false;
}

void GlGraphBackend::begin_frame() {
  // The previous frame's presented targets were read by now; everything is free again.
  for (auto& s : pool_) s.in_use = false;
  next_query_ = 0;
  serial_ms_.clear();
  waited_ms_ = 0.0;
  if (!mode_decided_) {
    // A software rasteriser bins draws and runs them at the next flush, so GPU timestamps land at
    // submission and credit one pass with another's work. There, each pass is finished on its own.
    const char* r = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const char* env = std::getenv("WELKIN_SERIAL_TIMINGS");
    serial_ = (env && std::strcmp(env, "1") == 0) ||
              (r && (std::strstr(r, "llvmpipe") || std::strstr(r, "softpipe")));
    mode_decided_ = true;
  }
}

// Timestamps before and after every pass (GL_TIMESTAMP): unlike TIME_ELAPSED they need no
// begin/end nesting, and llvmpipe reports them reliably.
void GlGraphBackend::record_timestamp() {
  if (next_query_ == queries_.size()) {
    GLuint q = 0;
    glCreateQueries(GL_TIMESTAMP, 1, &q);
    queries_.emplace_back(q);
  }
  glQueryCounter(queries_[next_query_++].id(), GL_TIMESTAMP);
}

void GlGraphBackend::begin_pass(const std::string& name) {
  glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name.c_str());
  if (serial_) {
    const auto t0 = std::chrono::steady_clock::now();
    glFinish();
    pass_start_ = std::chrono::steady_clock::now();
    waited_ms_ += std::chrono::duration<double, std::milli>(pass_start_ - t0).count();
  } else {
    record_timestamp();
  }
}

void GlGraphBackend::end_pass() {
  if (serial_) {
    glFinish();
    serial_ms_.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - pass_start_).count());
    waited_ms_ += serial_ms_.back();
  } else {
    record_timestamp();
  }
  glPopDebugGroup();
}

std::vector<double> GlGraphBackend::resolve_gpu_times() {
  if (serial_) return serial_ms_;
  const auto waiting_since = std::chrono::steady_clock::now();
  std::vector<double> ms;
  for (size_t i = 0; i + 1 < next_query_; i += 2) {
    GLuint64 t0 = 0, t1 = 0;
    glGetQueryObjectui64v(queries_[i].id(), GL_QUERY_RESULT, &t0);
    glGetQueryObjectui64v(queries_[i + 1].id(), GL_QUERY_RESULT, &t1);
    ms.push_back(t1 > t0 ? double(t1 - t0) * 1e-6 : 0.0);
  }
  waited_ms_ +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - waiting_since).count();
  return ms;
}

}  // namespace welkin
