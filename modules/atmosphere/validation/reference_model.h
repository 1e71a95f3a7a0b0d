// The atmosphere component in the CPU reference's terms, so `welkin probe`, `welkin accuracy` and the
// tests compare the GPU path and the reference on exactly the same planet.
#pragma once

#include "reference/atmosphere_model.h"
#include "welkin/atmosphere/components.h"

namespace welkin::atmosphere {

// Profiles of 0, 1 or 2 layers become the reference's two-layer form (one layer goes in the second
// slot with a zero-width first layer, as on the GPU).
reference::DensityProfile to_reference(const DensityProfile& profile);
reference::AtmosphereModel to_reference(const Atmosphere& atmosphere);

}  // namespace welkin::atmosphere
