// The sky pass shades the ground through the light environment only inside ground_pixel_rect: every
// pixel whose ray meets the ground must lie in it (checked against every pixel's own ray), and it must
// not be much larger than the ground's image (or the split would save nothing).
#include <algorithm>

#include "gpu_test_support.h"
#include "welkin/atmosphere/ground_region.h"

namespace welkin::atmosphere {
namespace {

struct Case {
  const char* name;
  glm::dvec3 position_m;
  float heading_deg, pitch_deg, fov_deg;
};

TEST(GroundRegion, HoldsEveryPixelWhoseRayMeetsTheGround) {
  const Atmosphere a;
  const Case cases[] = {{"peer view", {0, 0, 100}, 210, 8, 60},        {"level", {0, 0, 2000}, 0, 0, 60},
                        {"rolled down", {0, 0, 100}, 90, -30, 90},     {"looking up", {0, 0, 100}, 0, 60, 60},
                        {"straight down", {0, 0, 5000}, 0, -90, 60},   {"orbit", {0, 0, 1.0e6}, 0, -60, 60},
                        {"far planet, tiny", {0, 0, 4.0e8}, 0, -75, 60}, {"under the ground (lifted)", {0, 0, -50}, 0, 10, 60}};
  const int width = 160, height = 90;
  for (const Case& c : cases) {
    Camera cam;
    cam.position_m = c.position_m;
    cam.heading_deg = c.heading_deg, cam.pitch_deg = c.pitch_deg, cam.vertical_fov_deg = c.fov_deg;
    const FrameBlock u = make_uniforms(a, nullptr, nullptr, make_frame_view(cam, width, height));
    const PixelRect r = ground_pixel_rect(u, width, height);
    int x0 = width, y0 = height, x1 = -1, y1 = -1, inside = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        if (!ray_meets_ground(u, (x + 0.5) / width * 2.0 - 1.0, (y + 0.5) / height * 2.0 - 1.0)) continue;
        ++inside;
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
        EXPECT_TRUE(x >= r.x0 && x < r.x1 && y >= r.y0 && y < r.y1) << c.name << ": ground pixel " << x << "," << y << " outside";
      }
    if (inside == 0) {
      EXPECT_TRUE(r.empty()) << c.name;
      continue;
    }
    // At most the grid's margin (a cell and two pixels) beyond the ground's own box on each side.
    const int mx = width / 32 + 3, my = height / 32 + 3;
    EXPECT_GE(r.x0, x0 - mx) << c.name;
    EXPECT_GE(r.y0, y0 - my) << c.name;
    EXPECT_LE(r.x1, x1 + 1 + mx) << c.name;
    EXPECT_LE(r.y1, y1 + 1 + my) << c.name;
    std::printf("%-26s ground %5d px, rect %dx%d of %dx%d\n", c.name, inside, r.x1 - r.x0, r.y1 - r.y0, width, height);
  }
}

}  // namespace
}  // namespace welkin::atmosphere
