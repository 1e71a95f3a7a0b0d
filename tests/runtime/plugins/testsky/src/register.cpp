#include "welkin/core/module.h"
#include "welkin/core/world.h"

namespace testsky {
struct Layer {
  static constexpr std::string_view kTypeName = "testsky.Layer";
  float coverage = 0.5f;
  float altitude_km = 2.0f;
};
void describe(welkin::TypeBuilder<Layer>& t) {
  t.field("coverage", &Layer::coverage).range(0, 1);
  t.field("altitude_km", &Layer::altitude_km).unit("km").range(0, 100);
}
enum class Mode : int { soft = 0, hard = 1 };
struct Glow {
  static constexpr std::string_view kTypeName = "testsky.Glow";
  glm::vec3 tint{1.0f, 0.5f, 0.25f};
  Mode mode = Mode::soft;
  std::vector<Layer> layers{Layer{}};
  std::string label = "glow";
};
void describe(welkin::TypeBuilder<Glow>& t) {
  t.field("tint", &Glow::tint).color().range(0, 1);
  t.field("mode", &Glow::mode).values({{"soft", 0}, {"hard", 1}});
  t.field("layers", &Glow::layers).max_count(4);
  t.field("label", &Glow::label);
}
}  // namespace testsky

namespace welkin::modules {
void register_testsky(ModuleContext& ctx) { ctx.component<testsky::Glow>(); }
}  // namespace welkin::modules
