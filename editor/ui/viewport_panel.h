#pragma once
// The viewport's camera, shared by the panel (mouse and keys) and scripts (`fly`).
#include "ui/editor_context.h"

namespace welkin::editor {

// Where the viewport looks from now: the editor's own pose, or the scene camera's when looking
// through it.
ViewPose current_view_pose(EditorContext& ctx);
// One step of flight. Moves the editor's pose, or, when looking through the scene camera, the
// scene's core.Camera as a continuous (undoable) edit. Returns the new pose.
ViewPose fly_view(EditorContext& ctx, const FlyInput& input);

}  // namespace welkin::editor
