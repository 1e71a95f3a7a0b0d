#pragma once
// Crash recovery. Every so often the unsaved parts of the document (scene, sequence) are written
// beside the editor state, in <config folder>/autosave/ ($XDG_CONFIG_HOME/welkin/autosave/), with a
// small meta.json naming the files they came from. A save that leaves nothing unsaved, or a quit
// whose prompt was answered, removes them; a crash leaves them for the next start to offer back.
#include <filesystem>
#include <optional>
#include <string>

#include "model/editor_document.h"

namespace welkin::editor {

// What an autosave holds: each part it wrote and the file that part came from ("" if never saved).
struct AutosaveContents {
  bool scene = false, sequence = false;
  std::string scene_path, sequence_path;
};

class Autosave {
 public:
  Autosave() = default;  // disabled: writes and finds nothing (--no-config)
  explicit Autosave(std::filesystem::path folder) : folder_(std::move(folder)) {}
  // The autosave folder for an editor state file: "autosave" beside it.
  static std::filesystem::path folder_beside(const std::filesystem::path& config_file);

  bool enabled() const { return !folder_.empty(); }
  const std::filesystem::path& folder() const { return folder_; }

  // True when the document holds unsaved edits that the autosave on disk does not (yet) hold.
  bool behind(const EditorDocument& doc) const;
  // Writes the document's unsaved parts through the atomic writer, the meta file last so it never
  // names a file not yet written; removes the autosave when nothing is unsaved. Throws Error.
  void write(EditorDocument& doc);  // ends the timeline's preview first: it writes the document
  // The autosave left on disk, if any. A meta file that does not read is reported as an Error.
  std::optional<AutosaveContents> find() const;
  // Puts the autosaved parts into the document, named by their original files and dirty.
  void recover(EditorDocument& doc, const AutosaveContents& contents);
  // Deletes the autosave (meta file first, so a half-removed one is never offered). Never throws.
  void remove();

 private:
  // What the last write() held: the parts' versions and which were unsaved (a save changes that).
  struct Written {
    PartVersion scene = 0, sequence = 0;
    bool scene_dirty = false, sequence_dirty = false;
    friend bool operator==(const Written&, const Written&) = default;
  };
  static Written state_of(const EditorDocument& doc);

  std::filesystem::path folder_;
  std::optional<Written> written_;  // empty: nothing of this session is on disk
};

}  // namespace welkin::editor
