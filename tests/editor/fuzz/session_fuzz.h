#pragma once
// The session fuzzer: random editor sessions made of script verbs (the lines `welkin-editor --script`
// runs), driven through the same model functions the script player calls, with the editor's promises
// checked after every line:
//  - no crash and no sanitizer report (the CI run is built with ASan and UBSan);
//  - a line that fails changes nothing;
//  - undoing everything gives back the scene, painted maps and sequence as they were when the
//    history began (loaded, new or recovered), byte for byte, and redoing everything gives back the
//    state before the undos, dirty flags included;
//  - a part that is not dirty holds what its file holds (editor/README.md: dirtiness follows the
//    undo position), and a save leaves it clean;
//  - `crash` then `answer recover` gives the state of the last autosave, and no saved file changes.
// A failing session is shrunk to a short script, which can be committed and replayed as a test.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace welkin::editor::fuzz {

// The scratch folder a session runs in: a scene, a sequence, presets and a module panel declaring
// the test module's map, rewritten before every session. Scripts name it ${FUZZ}.
class FuzzFolder {
 public:
  explicit FuzzFolder(std::filesystem::path root);
  void reset() const;  // fresh files, no autosave
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
};

struct Failure {
  size_t line = 0;   // index of the line after which an invariant broke
  std::string what;  // which invariant, and how
};

// Runs `lines` (script text, one verb per line, ${FUZZ} for the folder) from a fresh folder and
// checks every invariant after each; the first broken one, or nothing.
std::optional<Failure> run_session(const FuzzFolder& folder, const std::vector<std::string>& lines);

// A random session of `steps` lines from `seed`, generated against the live document so most lines
// are meaningful (existing entity names, fields of present components), with invalid values mixed in.
// When the session fails, `failure` is set and the lines stop at the failing one.
std::vector<std::string> random_session(const FuzzFolder& folder, uint64_t seed, size_t steps,
                                        std::optional<Failure>& failure);

// The shortest session found that still fails with the same invariant (first word of `what`).
std::vector<std::string> shrink(const FuzzFolder& folder, std::vector<std::string> lines,
                                const Failure& failure);

}  // namespace welkin::editor::fuzz
