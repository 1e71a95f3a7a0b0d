#pragma once
// One recorded change: where it happened and the JSON value before and after. Every edit the
// editor makes (inspector, presets, outliner, timeline) is one of these, so one history undoes all.
#include <nlohmann/json.hpp>
#include <string>

#include "model/entity_ids.h"

namespace welkin::editor {

enum class EditTarget {
  field,      // one field of a component: component + path
  component,  // a whole component; null = the entity does not have it (add / remove)
  entity,     // a whole entity {"name", "components"}; null = it does not exist
  sequence,   // the timeline's sequence document
  map,        // texels of a painted map: path = its file; {"x", "y", "width", "height", "texels"}
};

struct Edit {
  EditTarget target = EditTarget::field;
  EntityId entity = kNoEntity;
  std::string component;  // full name, e.g. "core.Camera"
  std::string path;       // field path inside the component, e.g. "position_m/2"
  nlohmann::json before, after;

  // Same place: consecutive edits of one slot merge into one step (a slider drag).
  bool same_slot(const Edit& other) const {
    return target == other.target && entity == other.entity && component == other.component && path == other.path;
  }
};

}  // namespace welkin::editor
