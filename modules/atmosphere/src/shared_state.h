#pragma once
// The atmosphere's part of the world's shared state (welkin/scene/shared_state.h).

namespace welkin {
struct SystemContext;
}

namespace welkin::atmosphere {

// Runs in the update phase after the time of day: its sun, moon and stars follow the ephemeris and
// the clock when the scene has them; then it completes the shared state with the lights it draws
// and its planet.
void shared_state_system(SystemContext& sc);

}  // namespace welkin::atmosphere
