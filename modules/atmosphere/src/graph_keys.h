#pragma once
// The atmosphere's tables as lut_system (passes.cpp) publishes them on the render graph for the
// module's later systems (frame_passes.cpp).
#include "welkin/gfx/render_graph.h"

namespace welkin::atmosphere {

inline constexpr GraphKey kTransmittanceLut{"atmosphere.transmittance"};
inline constexpr GraphKey kMultiscatteringLut{"atmosphere.multiscattering"};
inline constexpr GraphKey kSkyViewLut{"atmosphere.sky_view"};
inline constexpr GraphKey kAerialInscattering{"atmosphere.aerial_inscattering"};
inline constexpr GraphKey kAerialTransmittance{"atmosphere.aerial_transmittance"};
inline constexpr GraphKey kSkyIrradiance{"atmosphere.sky_irradiance"};

}  // namespace welkin::atmosphere
