#include "welkin/core/registry.h"

#include <gtest/gtest.h>

#include "welkin/core/world.h"

namespace {

struct Position {
  static constexpr std::string_view kTypeName = "test.Position";
  glm::vec3 value{0.0f};
};
void describe(welkin::TypeBuilder<Position>& t) { t.field("value", &Position::value); }

struct Velocity {
  static constexpr std::string_view kTypeName = "test.Velocity";
  glm::vec3 value{0.0f};
};
void describe(welkin::TypeBuilder<Velocity>& t) { t.field("value", &Velocity::value); }

// Counts live instances so the pool's construct/move/destroy bookkeeping is checked.
struct Tracked {
  static constexpr std::string_view kTypeName = "test.Tracked";
  static inline int alive = 0;
  std::string payload = "x";
  Tracked() { ++alive; }
  Tracked(const Tracked& o) : payload(o.payload) { ++alive; }
  Tracked(Tracked&& o) noexcept : payload(std::move(o.payload)) { ++alive; }
  Tracked& operator=(const Tracked&) = default;
  Tracked& operator=(Tracked&&) = default;
  ~Tracked() { --alive; }
};
void describe(welkin::TypeBuilder<Tracked>& t) { t.field("payload", &Tracked::payload); }

using welkin::Entity;
using welkin::Registry;

TEST(Registry, CreateDestroyAndVersionReuse) {
  Registry r;
  Entity a = r.create(), b = r.create();
  EXPECT_NE(a, b);
  EXPECT_TRUE(r.valid(a));
  r.destroy(a);
  EXPECT_FALSE(r.valid(a));
  Entity c = r.create();
  EXPECT_EQ(c.index, a.index) << "indices are recycled";
  EXPECT_EQ(c.version, a.version + 1) << "a recycled index gets a new version";
  EXPECT_FALSE(r.valid(a)) << "the stale handle stays invalid";
  EXPECT_EQ(r.alive_count(), 2u);
  r.destroy(a);  // destroying a stale handle must not touch the new entity
  EXPECT_TRUE(r.valid(c));
}

TEST(Registry, ComponentsAddGetRemove) {
  Registry r;
  Entity e = r.create();
  r.emplace<Position>(e).value = {1, 2, 3};
  ASSERT_NE(r.get<Position>(e), nullptr);
  EXPECT_EQ(r.get<Position>(e)->value, glm::vec3(1, 2, 3));
  EXPECT_EQ(r.get<Velocity>(e), nullptr);
  r.remove<Position>(e);
  EXPECT_EQ(r.get<Position>(e), nullptr);
  r.emplace<Position>(e);
  r.destroy(e);
  Entity f = r.create();
  EXPECT_EQ(r.get<Position>(f), nullptr) << "a recycled index does not inherit components";
}

TEST(Registry, ViewsVisitOnlyEntitiesWithAllComponents) {
  Registry r;
  std::vector<Entity> both;
  for (int i = 0; i < 100; ++i) {
    Entity e = r.create();
    r.emplace<Position>(e).value.x = float(i);
    if (i % 3 == 0) {
      r.emplace<Velocity>(e).value.x = 1.0f;
      both.push_back(e);
    }
  }
  std::vector<Entity> seen;
  r.each<Position, Velocity>([&](Entity e, Position& p, Velocity& v) {
    p.value += v.value;
    seen.push_back(e);
  });
  std::sort(seen.begin(), seen.end(), [](Entity a, Entity b) { return a.index < b.index; });
  EXPECT_EQ(seen, both);
  EXPECT_EQ(r.get<Position>(both[1])->value.x, 4.0f);  // entity 3 moved by 1
  EXPECT_EQ(r.get<Position>(Entity{1, 0})->value.x, 1.0f);  // untouched
}

TEST(Registry, SwapRemoveKeepsOtherComponentsIntact) {
  const int baseline = (welkin::type_desc<Tracked>(), Tracked::alive);  // the declared-defaults instance
  {
  Registry r;
  std::vector<Entity> es;
  for (int i = 0; i < 10; ++i) {
    es.push_back(r.create());
    r.emplace<Tracked>(es.back()).payload = "p" + std::to_string(i);
  }
  EXPECT_EQ(Tracked::alive, baseline + 10);
  r.remove<Tracked>(es[2]);
  r.destroy(es[5]);
  EXPECT_EQ(Tracked::alive, baseline + 8);
  for (int i : {0, 1, 3, 4, 6, 7, 8, 9}) EXPECT_EQ(r.get<Tracked>(es[i])->payload, "p" + std::to_string(i));
  }
  EXPECT_EQ(Tracked::alive, baseline) << "the registry destroys every component it holds";
}


TEST(TypeIds, StableAcrossLibrariesBecauseDerivedFromNames) {
  static_assert(welkin::type_id<Position>() == welkin::type_id_of_name("test.Position"));
  // FNV-1a 64 of "a" is a published test vector.
  EXPECT_EQ(welkin::type_id_of_name("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_NE(welkin::type_id<Position>(), welkin::type_id<Velocity>());
}

TEST(Scheduler, SkipsSystemsWhoseQueryMatchesNothing) {
  welkin::World world;
  int moved = 0, lonely = 0;
  world.scheduler().add({.name = "move", .stage = welkin::Stage::simulate,
                         .reads = {welkin::type_id<Velocity>()}, .writes = {welkin::type_id<Position>()},
                         .run = [&](welkin::SystemContext&) { ++moved; }});
  world.scheduler().add({.name = "lonely", .stage = welkin::Stage::simulate, .reads = {welkin::type_id<Velocity>()},
                         .run = [&](welkin::SystemContext&) { ++lonely; }});
  Registry& r = world.registry();
  Entity a = r.create();
  r.emplace<Position>(a);
  Entity b = r.create();
  r.emplace<Velocity>(b);
  auto ran = world.update({});
  EXPECT_EQ(moved, 0) << "no entity has both Position and Velocity";
  EXPECT_EQ(lonely, 1);
  r.emplace<Velocity>(a);
  ran = world.update({});
  EXPECT_EQ(moved, 1);
  EXPECT_EQ(ran, (std::vector<std::string>{"move", "lonely"}));
}

}  // namespace
