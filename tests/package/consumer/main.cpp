// Builds a scene in code through the ECS, renders one frame headless and checks the pixels.
#include <cstdio>

#include "welkin/core/world.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/renderer.h"

int main(int argc, char** argv) {
  auto gl = welkin::create_headless_context();
  {
    welkin::World world;
    world.modules().add_search_dir(WELKIN_MODULE_DIR);
    auto& reg = world.registry();
    welkin::Entity cam = reg.create();
    reg.emplace<welkin::Camera>(cam).pitch_deg = 10.0f;
    reg.emplace<welkin::Backdrop>(reg.create());
    welkin::Renderer renderer(world);
    renderer.render_frame({}, 64, 32);
    welkin::ImageU8 img = renderer.read_output();
    if (argc > 1) welkin::write_png(argv[1], img);
    const uint8_t* top = img.pixel(32, 1);
    std::printf("consumer: top pixel %d %d %d\n", top[0], top[1], top[2]);
    if (!(top[2] > top[0] && top[2] > 60)) return 1;  // a blue backdrop sky
  }
  return 0;
}
