#pragma once
// The clouds as a term of the world's light environment (light_term.cpp).

namespace welkin {
class World;
}

namespace welkin::clouds {

// Declares the cloud shadows and sky occlusion as a term of the world's light environment.
void add_light_term(World& world);

}  // namespace welkin::clouds
