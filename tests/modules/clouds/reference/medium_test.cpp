#include "reference/medium.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

namespace welkin::clouds::reference {
namespace {

TEST(HomogeneousSlab, SegmentIsTheStretchBetweenThePlanes) {
  const HomogeneousSlab slab(100.0, 300.0, 0.02);
  const double c = std::cos(kPi / 3.0), s = std::sin(kPi / 3.0);  // 60 degrees from the zenith.
  const MajorantSegments up = slab.segments({{0, 0, 0}, {s, 0, c}});
  ASSERT_EQ(up.size(), 1u);
  EXPECT_NEAR(up[0].t0, 200.0, 1e-9);
  EXPECT_NEAR(up[0].t1, 600.0, 1e-9);
  EXPECT_EQ(up[0].majorant, 0.02);
  EXPECT_TRUE(slab.segments({{0, 0, 0}, {0, 0, -1}}).empty());  // Looking away.
  EXPECT_TRUE(slab.segments({{0, 0, 0}, {1, 0, 0}}).empty());   // Horizontal, below it.
  const MajorantSegments inside = slab.segments({{0, 0, 200}, {1, 0, 0}});
  ASSERT_EQ(inside.size(), 1u);
  EXPECT_EQ(inside[0].t0, 0.0);
  EXPECT_TRUE(std::isinf(inside[0].t1));
  const MajorantSegments from_inside = slab.segments({{0, 0, 200}, {0, 0, -1}});
  ASSERT_EQ(from_inside.size(), 1u);
  EXPECT_NEAR(from_inside[0].t1, 100.0, 1e-12);
  EXPECT_EQ(slab.extinction({5, 5, 150}), 0.02);
  EXPECT_EQ(slab.extinction({5, 5, 301}), 0.0);
}

TEST(HomogeneousSphere, SegmentIsTheChord) {
  const HomogeneousSphere sphere({0, 0, 1000}, 100.0, 0.5);
  const MajorantSegments centre = sphere.segments({{0, 0, 0}, {0, 0, 1}});
  ASSERT_EQ(centre.size(), 1u);
  EXPECT_NEAR(centre[0].t0, 900.0, 1e-9);
  EXPECT_NEAR(centre[0].t1, 1100.0, 1e-9);
  const MajorantSegments offset = sphere.segments({{60, 0, 0}, {0, 0, 1}});  // Chord 2 * 80.
  ASSERT_EQ(offset.size(), 1u);
  EXPECT_NEAR(offset[0].t1 - offset[0].t0, 160.0, 1e-9);
  EXPECT_TRUE(sphere.segments({{101, 0, 0}, {0, 0, 1}}).empty());
  EXPECT_TRUE(sphere.segments({{0, 0, 0}, {0, 0, -1}}).empty());
  const MajorantSegments inside = sphere.segments({{0, 0, 1000}, {1, 0, 0}});
  ASSERT_EQ(inside.size(), 1u);
  EXPECT_EQ(inside[0].t0, 0.0);
  EXPECT_NEAR(inside[0].t1, 100.0, 1e-12);
}

// A planet-sized shell seen from its surface and from space: the hollow splits a chord in two.
TEST(SphericalShell, SegmentsAroundTheHollow) {
  const double r = 6'360'000.0, base = r + 1500.0, top = r + 4000.0;
  const glm::dvec3 centre(0.0);
  // From the ground straight up: one stretch, base to top.
  const MajorantSegments up = spherical_shell_segments({{0, 0, r}, {0, 0, 1}}, centre, base, top, 0.1);
  ASSERT_EQ(up.size(), 1u);
  EXPECT_NEAR(up[0].t0, 1500.0, 1e-6);
  EXPECT_NEAR(up[0].t1, 4000.0, 1e-6);
  // From space through the centre: in, across the hollow, out.
  const MajorantSegments through =
      spherical_shell_segments({{0, 0, 2 * r}, {0, 0, -1}}, centre, base, top, 0.1);
  ASSERT_EQ(through.size(), 2u);
  EXPECT_NEAR(through[0].t0, 2 * r - top, 1e-6);
  EXPECT_NEAR(through[0].t1, 2 * r - base, 1e-6);
  EXPECT_NEAR(through[1].t0, 2 * r + base, 1e-6);
  EXPECT_NEAR(through[1].t1, 2 * r + top, 1e-6);
  // Inside the shell looking down through the hollow: from 0 to the base, then the far side.
  const MajorantSegments inside =
      spherical_shell_segments({{0, 0, r + 2000.0}, {0, 0, -1}}, centre, base, top, 0.1);
  ASSERT_EQ(inside.size(), 2u);
  EXPECT_EQ(inside[0].t0, 0.0);
  EXPECT_NEAR(inside[0].t1, 500.0, 1e-6);
  // A horizontal ray at the shell's middle height stays in the shell for a long chord.
  const MajorantSegments horizontal =
      spherical_shell_segments({{0, 0, r + 2000.0}, {1, 0, 0}}, centre, base, top, 0.1);
  ASSERT_EQ(horizontal.size(), 1u);
  const double expected = std::sqrt(top * top - (r + 2000.0) * (r + 2000.0));
  EXPECT_NEAR(horizontal[0].t1, expected, 1e-3);
}

TEST(FunctionMedium, ForwardsBothFunctions) {
  const FunctionMedium medium([](const glm::dvec3& p) { return p.x; },
                              [](const Ray&) { return MajorantSegments{{1.0, 2.0, 3.0}}; }, 0.8);
  EXPECT_EQ(medium.extinction({2.5, 0, 0}), 2.5);
  EXPECT_EQ(medium.segments({}).at(0).majorant, 3.0);
  EXPECT_EQ(medium.single_scattering_albedo, 0.8);
}

}  // namespace
}  // namespace welkin::clouds::reference
