// The "core" module: components every scene may use without loading a plugin.
#include "welkin/core/module.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/debug_content.h"
#include "welkin/scene/scene_file.h"

namespace welkin {

namespace {
void register_core(ModuleContext& ctx) {
  ctx.component<Name>();
  ctx.component<Camera>();
  register_debug_content(ctx);
}
}  // namespace

const ModuleDefinition& builtin_module_definition() {
  static const ModuleDefinition def{
      R"({"name": "core", "version": "0.1.0",
          "description": "Built-in components: names, camera, debug content",
          "components": ["core.Name", "core.Camera", "core.Backdrop", "core.DirectionalLight",
                         "core.DebugShape"]})",
      nullptr, register_core};
  return def;
}

}  // namespace welkin
