#include "model/autosave.h"

#include <nlohmann/json.hpp>

#include "welkin/core/error.h"
#include "welkin/core/files.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {
constexpr int kAutosaveVersion = 1;
constexpr uint64_t kMaxMetaBytes = 1 << 16;
constexpr const char* kMeta = "meta.json";
constexpr const char* kScene = "scene.json";
constexpr const char* kSequence = "sequence.json";
}  // namespace

fs::path Autosave::folder_beside(const fs::path& config_file) {
  return config_file.empty() ? fs::path() : config_file.parent_path() / "autosave";
}

Autosave::Written Autosave::state_of(const EditorDocument& doc) {
  return Written{doc.version(DocumentPart::scene), doc.version(DocumentPart::sequence), doc.scene_dirty(), doc.sequence_dirty()};
}

bool Autosave::behind(const EditorDocument& doc) const {
  if (!enabled()) return false;
  if (!doc.dirty()) return written_.has_value();  // a stale autosave of since-saved edits must go
  return !written_ || *written_ != state_of(doc);
}

void Autosave::write(EditorDocument& doc) {
  doc.end_preview();
  if (!enabled()) return;
  if (!doc.dirty()) {
    remove();
    return;
  }
  std::error_code ec;
  fs::create_directories(folder_, ec);
  if (ec) throw Error(ErrorInfo{.file = folder_.string(), .message = "cannot create the autosave folder: " + ec.message()});
  json meta{{"welkin_autosave", kAutosaveVersion}, {"scene", nullptr}, {"sequence", nullptr}};
  if (doc.scene_dirty()) {
    // The world as it is: painted maps' texels are not copied (they are written only with the scene).
    save_scene_file(doc.world(), (folder_ / kScene).string());
    meta["scene"] = {{"file", kScene}, {"original", doc.scene_path()}};
  }
  if (doc.sequence_dirty()) {
    save_sequence_file((folder_ / kSequence).string(), doc.sequence());
    meta["sequence"] = {{"file", kSequence}, {"original", doc.sequence_path()}};
  }
  write_file_atomically((folder_ / kMeta).string(), meta.dump(2) + "\n");
  written_ = state_of(doc);
}

std::optional<AutosaveContents> Autosave::find() const {
  std::error_code ec;
  if (!enabled() || !fs::exists(folder_ / kMeta, ec)) return std::nullopt;
  const std::string file = (folder_ / kMeta).string();
  json meta = json::parse(read_file_text(file, kMaxMetaBytes), nullptr, false);
  if (!meta.is_object() || meta.value("welkin_autosave", 0) != kAutosaveVersion)
    throw Error(ErrorInfo{.file = file, .expected = "an autosave meta file (welkin_autosave: 1)", .message = "unreadable autosave"});
  AutosaveContents c;
  auto part = [&](const char* key, const char* name, bool& present, std::string& original) {
    const json& p = meta.contains(key) ? meta[key] : json();
    if (p.is_null()) return;
    if (!p.is_object() || !p.contains("original") || !p["original"].is_string() || p.value("file", "") != name)
      throw Error(ErrorInfo{.file = file, .path = std::string("/") + key, .expected = std::string("{\"file\": \"") + name + "\", \"original\": PATH}",
                            .message = "unreadable autosave"});
    present = fs::exists(folder_ / name, ec);
    original = p["original"].get<std::string>();
  };
  part("scene", kScene, c.scene, c.scene_path);
  part("sequence", kSequence, c.sequence, c.sequence_path);
  if (!c.scene && !c.sequence) return std::nullopt;
  return c;
}

void Autosave::recover(EditorDocument& doc, const AutosaveContents& c) {
  if (c.scene) doc.recover_scene((folder_ / kScene).string(), c.scene_path);
  if (c.sequence) doc.recover_sequence((folder_ / kSequence).string(), c.sequence_path);
  // The files on disk now hold what the document holds: nothing to write until the next edit.
  written_ = state_of(doc);
}

void Autosave::remove() {
  written_.reset();
  if (!enabled()) return;
  std::error_code ec;
  for (const char* name : {kMeta, kScene, kSequence}) fs::remove(folder_ / name, ec);
}

}  // namespace welkin::editor
