#pragma once
// Where panels sit by default. Dear ImGui 1.86 as Debian ships it has no docking, so the editor lays
// its panels out itself: the viewport in the middle, the timeline under it, and every other panel
// stacked in the left or right column, so nothing covers the viewport unless the user moves it there.
// A module's panel (the Weather map, say) joins the right column. Pure arithmetic: no ImGui.
#include <map>
#include <string>
#include <vector>

namespace welkin::editor {

struct PanelRect {
  float x = 0, y = 0, w = 0, h = 0;
  bool overlaps(const PanelRect& o) const {
    return x < o.x + o.w && o.x < x + w && y < o.y + o.h && o.y < y + h;
  }
  friend bool operator==(const PanelRect&, const PanelRect&) = default;
};

enum class PanelColumn { left, centre, bottom, right };
PanelColumn column_of_panel(const std::string& title);

// The rectangle of each shown panel (titles in the Panels menu's order) in a window of w x h pixels
// whose menu bar is `top` pixels tall. Panels of one column share its height in proportion to their
// weights; no two rectangles overlap and all lie inside the window.
std::map<std::string, PanelRect> layout_panels(const std::vector<std::string>& shown, float w, float h,
                                               float top);

}  // namespace welkin::editor
