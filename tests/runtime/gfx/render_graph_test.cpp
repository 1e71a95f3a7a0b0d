// Render-graph logic on a fake backend: no GL, so culling and pooling are checked exactly.
#include "welkin/gfx/render_graph.h"

#include <gtest/gtest.h>

#include <deque>

namespace {

using namespace welkin;

class FakeBackend : public GraphBackend {
 public:
  Texture* acquire(const TextureDesc& d) override {
    for (auto& s : slots)
      if (!s.used && s.desc == d) {
        s.used = true;
        return &s.tex;
      }
    slots.push_back({d, true, Texture()});
    ++allocations;
    return &slots.back().tex;
  }
  void release(Texture* t) override {
    for (auto& s : slots)
      if (&s.tex == t) s.used = false;
  }
  void begin_pass(const std::string& n) override { begun.push_back(n); }
  void end_pass() override {}
  std::vector<double> resolve_gpu_times() override { return std::vector<double>(begun.size(), 1.5); }
  void begin_frame() override {
    begun.clear();
    for (auto& s : slots) s.used = false;
  }
  struct Slot {
    TextureDesc desc;
    bool used;
    Texture tex;
  };
  std::deque<Slot> slots;
  int allocations = 0;
  std::vector<std::string> begun;
};

const TextureDesc kSmall{.width = 8, .height = 8};

TEST(RenderGraph, CullsPassesWhoseOutputsReachNoTarget) {
  RenderGraph g;
  Texture out_tex;
  ResourceHandle out = g.import("out", out_tex);
  ResourceHandle lut, unused;
  bool culled_ran = false, used_ran = false, final_ran = false;
  g.add_pass("make_lut", [&](PassBuilder& b) { lut = b.create("lut", kSmall); }, [&](PassContext&) { used_ran = true; });
  g.add_pass("make_unused", [&](PassBuilder& b) { unused = b.create("unused", kSmall); },
             [&](PassContext&) { culled_ran = true; });
  g.add_pass("consume_unused", [&](PassBuilder& b) { b.read(unused); b.create("dead_end", kSmall); },
             [&](PassContext&) { culled_ran = true; });
  g.add_pass("final", [&](PassBuilder& b) { b.read(lut); b.write(out); }, [&](PassContext&) { final_ran = true; });
  g.present(out);
  EXPECT_EQ(g.compile(), (std::vector<std::string>{"make_lut", "final"}));
  FakeBackend be;
  g.execute(be);
  EXPECT_FALSE(culled_ran);
  EXPECT_TRUE(used_ran && final_ran);
  EXPECT_EQ(g.culled_passes(), (std::vector<std::string>{"make_unused", "consume_unused"}));
  ASSERT_EQ(g.timings().size(), 2u);
  EXPECT_EQ(g.timings()[1].name, "final");
  EXPECT_EQ(g.timings()[1].gpu_ms, 1.5);
}

TEST(RenderGraph, SideEffectPassesSurviveAndOrderIsDeclarationOrder) {
  RenderGraph g;
  std::vector<std::string> order;
  Texture t;
  ResourceHandle persistent = g.import("persistent", t);
  g.add_pass("update_lut", [&](PassBuilder& b) { b.write(persistent); b.side_effect(); },
             [&](PassContext&) { order.push_back("update_lut"); });
  g.add_pass("nothing_reads_me", [&](PassBuilder& b) { b.write(persistent); }, [&](PassContext&) { order.push_back("x"); });
  FakeBackend be;
  g.execute(be);
  EXPECT_EQ(order, std::vector<std::string>{"update_lut"});
}

TEST(RenderGraph, ReadModifyWriteChainsStayAlive) {
  RenderGraph g;
  Texture out_tex;
  ResourceHandle out = g.import("out", out_tex);
  ResourceHandle color;
  std::vector<std::string> order;
  g.add_pass("clear", [&](PassBuilder& b) { color = b.create("color", kSmall); }, [&](PassContext&) { order.push_back("clear"); });
  g.add_pass("sky", [&](PassBuilder& b) { b.read(color); b.write(color); }, [&](PassContext&) { order.push_back("sky"); });
  g.add_pass("terrain", [&](PassBuilder& b) { b.read(color); b.write(color); }, [&](PassContext&) { order.push_back("terrain"); });
  g.add_pass("tonemap", [&](PassBuilder& b) { b.read(color); b.write(out); }, [&](PassContext&) { order.push_back("tonemap"); });
  g.present(out);
  FakeBackend be;
  g.execute(be);
  EXPECT_EQ(order, (std::vector<std::string>{"clear", "sky", "terrain", "tonemap"}));
}

TEST(RenderGraph, TransientsAreReusedAfterTheirLastUse) {
  RenderGraph g;
  Texture out_tex;
  ResourceHandle out = g.import("out", out_tex);
  ResourceHandle a, b2, c;
  Texture *ta = nullptr, *tc = nullptr;
  g.add_pass("a", [&](PassBuilder& b) { a = b.create("a", kSmall); }, [&](PassContext& pc) { ta = &pc.texture(a); });
  g.add_pass("b", [&](PassBuilder& b) { b.read(a); b2 = b.create("b", kSmall); }, [&](PassContext&) {});
  g.add_pass("c", [&](PassBuilder& b) { b.read(b2); c = b.create("c", kSmall); }, [&](PassContext& pc) { tc = &pc.texture(c); });
  g.add_pass("d", [&](PassBuilder& b) { b.read(c); b.write(out); }, [&](PassContext&) {});
  g.present(out);
  FakeBackend be;
  g.execute(be);
  EXPECT_EQ(be.allocations, 2) << "'a' dies after pass b, so 'c' takes its texture";
  EXPECT_EQ(ta, tc);
  // A second frame reuses the pool entirely.
  RenderGraph g2;
  ResourceHandle out2 = g2.import("out", out_tex), x;
  g2.add_pass("x", [&](PassBuilder& b) { x = b.create("x", kSmall); }, [](PassContext&) {});
  g2.add_pass("y", [&](PassBuilder& b) { b.read(x); b.write(out2); }, [](PassContext&) {});
  g2.present(out2);
  g2.execute(be);
  EXPECT_EQ(be.allocations, 2);
}

TEST(RenderGraph, UndeclaredAccessIsAnError) {
  RenderGraph g;
  Texture out_tex;
  ResourceHandle out = g.import("out", out_tex), hidden;
  g.add_pass("maker", [&](PassBuilder& b) { hidden = b.create("hidden", kSmall); b.side_effect(); }, [](PassContext&) {});
  g.add_pass("sneaky", [&](PassBuilder& b) { b.write(out); }, [&](PassContext& pc) { pc.texture(hidden); });
  g.present(out);
  FakeBackend be;
  EXPECT_THROW(g.execute(be), std::exception);
}

// A transient made on the graph before its passes: each pass takes its handle by value. It is
// allocated for its first user and returned after its last, like one a pass creates; one that only
// culled passes touch is never allocated.
TEST(RenderGraph, TransientsMadeBeforeTheirPassesAreAllocatedForTheirUsers) {
  RenderGraph g;
  Texture out_tex;
  const ResourceHandle out = g.import("out", out_tex);
  const ResourceHandle made = g.create("made", kSmall), unused = g.create("unused", kSmall);
  const Texture *written = nullptr, *read = nullptr;
  g.add_pass("culled", [unused](PassBuilder& b) { b.write(unused); }, [](PassContext&) {});
  g.add_pass("write", [made](PassBuilder& b) { b.write(made); },
             [made, &written](PassContext& pc) { written = &pc.texture(made); });
  g.add_pass("read", [made, out](PassBuilder& b) { b.read(made); b.write(out); },
             [made, &read](PassContext& pc) { read = &pc.texture(made); });
  g.present(out);
  FakeBackend be;
  g.execute(be);
  EXPECT_EQ(g.culled_passes(), std::vector<std::string>{"culled"});
  EXPECT_EQ(be.allocations, 1);
  ASSERT_NE(written, nullptr);
  EXPECT_EQ(written, read);
  EXPECT_FALSE(be.slots.front().used) << "returned after its last use";
}

TEST(RenderGraph, ResourcesArePublishedUnderTypedKeys) {
  static constexpr GraphKey kFront{"test.front"}, kOther{"test.other"};
  RenderGraph g;
  Texture t;
  EXPECT_FALSE(g.published(kFront).valid()) << "nothing published yet";
  const ResourceHandle a = g.import("a", t), b = g.create("b", kSmall);
  g.publish(kFront, a);
  EXPECT_EQ(g.published(kFront), a);
  EXPECT_FALSE(g.published(kOther).valid());
  g.publish(kFront, b);
  EXPECT_EQ(g.published(kFront), b) << "a second publication replaces the first";
  EXPECT_THROW(g.publish(kOther, ResourceHandle{}), std::exception);
}

}  // namespace
