// One view ray evaluated by any method, in the geometry of reference/probe.h: what `welkin probe`
// prints, what `welkin accuracy` sweeps and what the accuracy test checks. Radiance is for a sun of
// illuminance 1 (1/sr), atmosphere only: no sun disc, the ground lit as its albedo says where the
// ray meets it. "Single scattering" (orders 1) is every path with one scattering event, in the air
// or on the ground; for the GPU methods it switches the multiple-scattering LUT off.
#pragma once

#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "reference/probe.h"
#include "welkin/atmosphere/components.h"

namespace welkin {
class World;
class Renderer;
}  // namespace welkin

namespace welkin::atmosphere {

enum class ProbeMethod { reference, pathtrace, lut, raymarch };
std::optional<ProbeMethod> parse_probe_method(std::string_view name);
const char* probe_method_name(ProbeMethod method);

struct ProbeValue {
  glm::dvec3 transmittance{1.0};  // along the view ray to the ground or the top of the atmosphere
  glm::dvec3 radiance{0.0};       // 1/sr for sun illuminance 1
  glm::dvec3 radiance_ci95{0.0};  // path tracing: 95% half-width; quadrature: its error estimate
  std::uint64_t samples = 0;      // paths traced
  double ms = 0.0;                // CPU methods: wall time of this ray
};

// The double-precision quadrature: transmittance and single scattering, plus the directly lit
// ground where the ray meets it.
ProbeValue probe_reference(const reference::AtmosphereModel& model, const reference::ProbeGeometry& g);

struct PathTraceOptions {
  std::uint64_t samples = 1u << 16;
  std::uint64_t seed = 1;
  int threads = 2;
};
// Monte Carlo, all orders (or one with single_scattering), the ground lit where the ray meets it;
// transmittance by quadrature.
ProbeValue probe_pathtrace(const reference::AtmosphereModel& model, const reference::ProbeGeometry& g,
                           bool single_scattering, const PathTraceOptions& options = {});

// What one steady frame of a method costs (median over frames, forced to completion).
struct FrameCost {
  int width = 0, height = 0;
  double atmosphere_ms = 0;  // the atmosphere's passes
  double sky_ms = 0;         // the sky pass alone
  double frame_ms = 0;       // the whole frame
  double copy_ms = 0;        // a full-screen RGBA16F copy of the same size (the floor)
};

// The GPU path through the real renderer: a world with the atmosphere, a camera looking along the
// probe ray, a 1x1 frame whose pixel is the radiance. Transmittance comes from the same functions
// the method renders with (the transmittance LUT, or the raymarch's own march). One instance keeps
// its LUTs between rays, so sweeps pay for the medium once. Needs a current GL 4.5 context.
class GpuProbe {
 public:
  GpuProbe(const Atmosphere& atmosphere, SkyMethod method, bool single_scattering);
  ~GpuProbe();
  GpuProbe(const GpuProbe&) = delete;
  GpuProbe& operator=(const GpuProbe&) = delete;

  ProbeValue evaluate(const reference::ProbeGeometry& g);
  FrameCost frame_cost(const reference::ProbeGeometry& g, int width, int height, int frames = 9);
  // The atmosphere as loaded and validated (what the reference must be given).
  const Atmosphere& atmosphere() const;

 private:
  void aim(const reference::ProbeGeometry& g);
  std::unique_ptr<World> world_;
  std::unique_ptr<Renderer> renderer_;
  SkyMethod method_;
  std::uint64_t frame_ = 0;
};

}  // namespace welkin::atmosphere
