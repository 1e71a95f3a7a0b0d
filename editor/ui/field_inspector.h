#pragma once
// The one inspector: every field of a component drawn from its reflection (sliders with ranges
// and units, colour pickers, enums as combos, nested structs, arrays of structs with add/remove,
// tooltips), no per-field code. Each change becomes a document edit: continuous while a widget is
// held, one undo step once it is released (IsItemDeactivatedAfterEdit). A field's context menu
// resets it, keys it on the timeline or copies its path.
#include "ui/editor_context.h"

namespace welkin::editor {

void draw_component_fields(EditorContext& ctx, EntityId entity, const TypeDesc& type);

}  // namespace welkin::editor
