#include "welkin/core/module.h"

namespace testorphan {
struct Thing {
  static constexpr std::string_view kTypeName = "testorphan.Thing";
  float x = 0;
};
void describe(welkin::TypeBuilder<Thing>& t) { t.field("x", &Thing::x); }
}  // namespace testorphan

namespace welkin::modules {
void register_testorphan(ModuleContext& ctx) { ctx.component<testorphan::Thing>(); }
}  // namespace welkin::modules
