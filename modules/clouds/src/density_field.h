#pragma once
// The density field as shaders include it (shaders/clouds/density.glsl): its bindings, and the
// compile-time description of this frame's layers and light model (density_field.cpp).
#include "clouds_gpu.h"
#include "welkin/gfx/shader.h"

namespace welkin::clouds {

// Binds the density field's block, layers and noise (shaders/clouds/density.glsl's bindings).
void bind_field(const CloudsGpu& gpu);
// The field's compile-time description for a shader that includes density.glsl.
ShaderDefines field_defines(const CloudsGpu& gpu);
// The march's altitude bands for clouds/march_pixel.glsl: CLOUDS_BANDS and, per band, the compiled
// layers (CLOUDS_BAND_LAYERS_i, a mask) that its samples and their light steps can reach this frame
// (none when the layers are not compiled in: every band then marches every layer).
ShaderDefines band_defines(const CloudsGpu& gpu);
// The light model's choices (multiple scattering, powder, phase function) for a shader that includes
// clouds/light_model.glsl: compiled in, since llvmpipe evaluates both sides of a uniform branch.
ShaderDefines light_model_defines(const CloudsGpu& gpu);

}  // namespace welkin::clouds
