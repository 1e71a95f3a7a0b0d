#include "welkin/assets/asset_cache.h"

#include <gtest/gtest.h>

#include "test_util.h"

namespace welkin::assets::test {
namespace {

GlbWriter small_grid(int n) {
  GlbWriter w;
  w.add_node("g", w.add_mesh(grid_mesh(n)).mesh);
  return w;
}

TEST(AssetCache, SameFileLoadsOnceWhateverThePathSpelling) {
  const fs::path dir = temp_dir("cache");
  small_grid(2).write((dir / "a.glb").string());
  AssetCache cache;
  const auto m1 = cache.load((dir / "a.glb").string());
  const auto m2 = cache.load((dir / "." / "a.glb").string());
  fs::remove(dir / "link.glb");
  fs::create_symlink(dir / "a.glb", dir / "link.glb");
  const auto m3 = cache.load((dir / "link.glb").string());
  EXPECT_EQ(m1.get(), m2.get());
  EXPECT_EQ(m1.get(), m3.get());
  EXPECT_EQ(cache.load_count(), 1u);
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_EQ(m1->vertex_count(), 9u);
}

TEST(AssetCache, ChangedFileIsReloaded) {
  const fs::path dir = temp_dir("cache2");
  const fs::path f = dir / "b.glb";
  small_grid(2).write(f.string());
  AssetCache cache;
  const auto m1 = cache.load(f.string());
  small_grid(3).write(f.string());
  fs::last_write_time(f, fs::last_write_time(f) + std::chrono::seconds(2));  // coarse clocks
  const auto m2 = cache.load(f.string());
  EXPECT_NE(m1.get(), m2.get());
  EXPECT_EQ(m2->vertex_count(), 16u);
  EXPECT_EQ(m1->vertex_count(), 9u);  // holders of the old model keep it
  EXPECT_EQ(cache.load_count(), 2u);
}

TEST(AssetCache, EvictsOnlyUnusedAndReportsErrors) {
  const fs::path dir = temp_dir("cache3");
  small_grid(1).write((dir / "c.glb").string());
  small_grid(2).write((dir / "d.glb").string());
  AssetCache cache;
  auto keep = cache.load((dir / "c.glb").string());
  cache.load((dir / "d.glb").string());
  EXPECT_EQ(cache.evict_unused(), 1u);
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_THROW(cache.load((dir / "missing.glb").string()), Error);
  write_bytes(dir / "bad.glb", "glTF");
  EXPECT_THROW(cache.load((dir / "bad.glb").string()), Error);
  EXPECT_EQ(cache.size(), 1u);
}

}  // namespace
}  // namespace welkin::assets::test
