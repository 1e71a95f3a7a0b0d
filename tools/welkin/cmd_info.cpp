// welkin info [--modules] [SCENE] [--gl] [--json]
#include <cstdio>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "session.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/scene/json_fields.h"
#include "welkin/scene/scene_file.h"

namespace welkin::cli {

namespace {

struct InfoOptions {
  std::string scene;
  bool modules = false;
  bool gl = false;
  bool json = false;
};

int run_info(const InfoOptions& o) {
  if (o.scene.ends_with(".glb") || o.scene.ends_with(".gltf")) {
    print_asset_info(o.scene, o.json);
    return kOk;
  }
  auto world = make_world();
  nlohmann::json j;
  j["version"] = "0.1.0";
  if (o.modules || o.scene.empty()) {
    nlohmann::json mods = nlohmann::json::array();
    for (const auto& m : world->modules().available())
      mods.push_back({{"name", m.name}, {"version", m.version}, {"description", m.description},
                      {"depends", m.depends}, {"uses", m.uses}, {"components", m.components},
                      {"origin", m.origin}, {"data_dir", m.data_dir.string()}});
    j["available_modules"] = mods;
    j["skipped_manifests"] = world->modules().manifest_problems();
    j["module_dirs"] = module_search_dirs();
  }
  if (!o.scene.empty()) {
    nlohmann::json doc = read_json_file(o.scene);
    j["scene"] = o.scene;
    load_scene(*world, doc, o.scene);  // first: a bad scene is refused at its first error, before any listing
    j["scene_components"] = scene_component_names(doc, o.scene);
    j["scene_modules"] = world->modules().loaded();
    j["entities"] = world->registry().alive_count();
  }
  if (o.gl) {
    auto ctx = create_headless_context();
    GlInfo gi = ctx->info();
    j["gl"] = {{"vendor", gi.vendor}, {"renderer", gi.renderer}, {"version", gi.version}};
  }
  if (o.json) {
    std::printf("%s\n", j.dump(2).c_str());
    return kOk;
  }
  std::printf("welkin %s\n", j["version"].get<std::string>().c_str());
  if (j.contains("available_modules")) {
    std::printf("\navailable modules:\n");
    for (const auto& m : j["available_modules"]) {
      std::printf("  %-12s %-8s %s\n", m["name"].get<std::string>().c_str(), m["version"].get<std::string>().c_str(),
                  m["description"].get<std::string>().c_str());
      std::string comps;
      for (const auto& c : m["components"]) comps += (comps.empty() ? "" : ", ") + c.get<std::string>();
      std::printf("  %-12s components: %s\n", "", comps.c_str());
      // Needed (loaded first), and read from when the scene has it (the shared state).
      for (const char* key : {"depends", "uses"}) {
        std::string names;
        for (const auto& d : m[key]) names += (names.empty() ? "" : ", ") + d.get<std::string>();
        const char* label = key == std::string_view("depends") ? "depends on" : "uses";
        if (!names.empty()) std::printf("  %-12s %s: %s\n", "", label, names.c_str());
      }
    }
  }
  if (j.contains("skipped_manifests") && !j["skipped_manifests"].empty()) {
    std::printf("\nskipped module manifests:\n");
    for (const auto& p : j["skipped_manifests"]) std::printf("  %s\n", p.get<std::string>().c_str());
  }
  if (j.contains("scene")) {
    std::printf("\nscene %s: %zu entities\n  components: ", o.scene.c_str(), j["entities"].get<size_t>());
    for (const auto& c : j["scene_components"]) std::printf("%s ", c.get<std::string>().c_str());
    std::printf("\n  loads modules: ");
    for (const auto& m : j["scene_modules"]) std::printf("%s ", m.get<std::string>().c_str());
    std::printf("\n");
  }
  if (j.contains("gl"))
    std::printf("\nOpenGL: %s | %s | %s\n", j["gl"]["vendor"].get<std::string>().c_str(),
                j["gl"]["renderer"].get<std::string>().c_str(), j["gl"]["version"].get<std::string>().c_str());
  return kOk;
}

}  // namespace

void add_info_command(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info", "Show available modules, what a scene loads, and the GL device");
  cmd->add_option("scene", opts->scene, "Scene file (lists the modules it loads) or a .glb/.gltf (lists its content)")->check(CLI::ExistingFile);
  cmd->add_flag("-m,--modules", opts->modules, "List available modules");
  cmd->add_flag("--gl", opts->gl, "Create a headless GL context and print its renderer");
  cmd->add_flag("--json", opts->json, "Machine-readable output");
  cmd->callback([opts, &exit_code] { exit_code = run_info(*opts); });
}

}  // namespace welkin::cli
