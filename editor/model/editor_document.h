#pragma once
// The document an editor session works on: the scene's world, the timeline's sequence, the
// selection and the one undo history. Every change goes through here as an Edit, so inspector,
// outliner, preset and timeline changes undo and redo alike. No GL, no ImGui: tests drive it directly.
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "model/command_history.h"
#include "model/entity_ids.h"
#include "model/sequence.h"
#include "welkin/core/world.h"
#include "welkin/scene/painted_map.h"

namespace welkin::editor {

// Makes an empty world that knows where the plugin modules are.
using WorldFactory = std::function<std::unique_ptr<World>()>;

struct EntityRow {
  EntityId id = kNoEntity;
  std::string name;  // display name: core.Name, else "#<index>"
};

class EditorDocument {
 public:
  explicit EditorDocument(WorldFactory make_world);
  ~EditorDocument();

  // --- Scene ---------------------------------------------------------------------------------
  void new_scene();
  // Replaces the world; on any error the current scene stays as it was. Clears the history.
  void load_scene(const std::string& path);
  void save_scene(const std::string& path);
  const std::string& scene_path() const { return scene_path_; }
  World& world() { return *world_; }
  const World& world() const { return *world_; }
  // Bumped whenever the world object is replaced (renderers built over the old one must go).
  uint64_t world_generation() const { return world_generation_; }
  // The scene (with its painted maps) or the sequence differs from what was last loaded or saved.
  // Each follows the undo position: undoing back to the saved point makes it clean again.
  bool scene_dirty() const { return history_.version(DocumentPart::scene) != saved_[size_t(DocumentPart::scene)]; }
  bool sequence_dirty() const { return history_.version(DocumentPart::sequence) != saved_[size_t(DocumentPart::sequence)]; }
  bool dirty() const { return scene_dirty() || sequence_dirty(); }
  // What each part holds now (CommandHistory::version): an autosave notes it to skip writing twice.
  PartVersion version(DocumentPart part) const { return history_.version(part); }

  // Crash recovery (model/autosave.h): the scene read from `file`, but named `original_path` (empty
  // for a scene never saved) and dirty, since it holds edits that file does not. History cleared.
  void recover_scene(const std::string& file, const std::string& original_path);
  // The sequence read from `file`, named `original_path` and dirty; one undo step.
  void recover_sequence(const std::string& file, const std::string& original_path);

  // --- Entities and selection ------------------------------------------------------------------
  std::vector<EntityRow> entities();
  Entity entity(EntityId id) const { return ids_.entity_of(id); }
  EntityId id_of(Entity e) { return ids_.id_of(e); }
  std::string display_name(EntityId id) const;
  // First entity with this core.Name value, or kNoEntity.
  EntityId find_by_name(std::string_view name);
  EntityId selected() const;
  void select(EntityId id) { selected_ = id; }
  // Like `welkin --set`: the selected entity when it has the component, else the first that has it.
  EntityId entity_with(const std::string& component);
  std::vector<const TypeDesc*> components_of(EntityId id) const;
  // The component's type, loading its module into the scene's world when needed; throws Error.
  const TypeDesc& require_component(const std::string& component);
  // Every component name the installed modules declare (loaded or not), sorted.
  std::vector<std::string> known_components() const;

  // --- Reading values ------------------------------------------------------------------------
  // Null when the entity does not have the component.
  nlohmann::json get_component(EntityId id, const std::string& component) const;
  nlohmann::json get_field(EntityId id, const std::string& component, const std::string& path) const;
  // Live storage of a component (the inspector reads through reflection); nullptr when absent.
  const void* component_data(EntityId id, const TypeDesc& type) const;

  // --- Edits: each applies at once and becomes one undo step. A rejected value throws Error and
  // changes nothing. `continuous` edits of one slot merge until end_continuous_edit() (a drag).
  EntityId add_entity(const std::string& name, const nlohmann::json& components = nlohmann::json::object());
  void remove_entity(EntityId id);
  void rename_entity(EntityId id, const std::string& name);
  void add_component(EntityId id, const std::string& component);
  void remove_component(EntityId id, const std::string& component);
  void set_field(EntityId id, const std::string& component, const std::string& path, const nlohmann::json& value,
                 bool continuous = false);
  // Replaces every field of a component (preset apply, blend, revert); adds it when absent.
  void set_component(EntityId id, const std::string& component, const nlohmann::json& value, const std::string& label,
                     bool continuous = false);
  void end_continuous_edit() { history_.seal(); }

  bool undo();
  bool redo();
  const CommandHistory& history() const { return history_; }

  // --- Painted maps (welkin/scene/painted_map.h), kept in the world's PaintedMaps ---------------
  // One stamp of a brush on the map in `file` (read on first use): one undo step, or with
  // `continuous` part of a stroke that stays one step until end_continuous_edit(). False when the
  // stamp misses the map. save_scene also writes every map changed since it was read.
  bool paint_map(const std::string& file, const BrushStamp& stamp, bool continuous = false);

  // --- Timeline ------------------------------------------------------------------------------
  const Sequence& sequence() const { return sequence_; }
  const std::string& sequence_path() const { return sequence_path_; }
  void set_sequence(Sequence sequence, const std::string& label, bool continuous = false);
  void load_sequence(const std::string& path);  // undoable, like any other change of the sequence
  void save_sequence(const std::string& path);
  // Writes every track's value at `time_s` into the world (welkin::apply_sequence). A preview, not an edit: nothing is
  // recorded, and the components it writes over are kept as they were. Returns one message per track that could not be
  // applied.
  std::vector<std::string> preview_sequence(double time_s);
  // Puts back what the preview wrote over. Every edit, undo, redo, save and autosave does this first, so the history
  // and the files never hold previewed values and the dirty flags do not move; the view previews again next frame.
  void end_preview();
  bool previewing() const { return previewing_; }

 private:
  struct PreviewOriginal {
    EntityId entity;
    std::string component;
    nlohmann::json value;  // the component as the document holds it
  };
  void keep_preview_originals(const std::string& component);
  void execute(Edit edit, const std::string& label, bool continuous);
  // Replaces the world and forgets the history; a clean sequence stays clean.
  void replace_world(std::unique_ptr<World> world, const std::string& path);
  void mark_saved(DocumentPart part) { saved_[size_t(part)] = history_.version(part); }
  void mark_unsaved(DocumentPart part) { saved_[size_t(part)] = kNeverSaved; }
  static constexpr PartVersion kNeverSaved = ~PartVersion(0);  // no history version equals it
  void apply(const Edit& edit, const nlohmann::json& value);
  nlohmann::json entity_snapshot(EntityId id) const;
  Entity require_entity(EntityId id) const;

  WorldFactory make_world_;
  std::unique_ptr<World> world_;
  uint64_t world_generation_ = 0;
  std::string scene_path_;
  EntityIds ids_;
  EntityId selected_ = kNoEntity;
  CommandHistory history_;
  Sequence sequence_;
  std::vector<PreviewOriginal> preview_originals_;
  bool previewing_ = false;
  std::string sequence_path_;
  std::array<PartVersion, kDocumentParts> saved_{};  // each part's version when last loaded or saved
};

}  // namespace welkin::editor
