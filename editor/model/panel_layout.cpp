#include "model/panel_layout.h"

#include <algorithm>
#include <cmath>

namespace welkin::editor {

namespace {

// A panel's share of its column: the inspector and the presets hold the most rows, a map wants to be
// about as tall as the column is wide.
float weight_of(const std::string& title) {
  if (title == "Inspector") return 2.0f;
  if (title == "Presets") return 1.4f;
  if (title == "History") return 0.7f;
  if (title == "Profiler") return 0.8f;
  return 1.0f;
}

// Stacks the panels of one column from `top` down, each as tall as its share of `height`.
void stack(const std::vector<std::string>& titles, float x, float width, float top, float height,
           std::map<std::string, PanelRect>& out) {
  float total = 0;
  for (const std::string& t : titles) total += weight_of(t);
  float y = top;
  for (size_t i = 0; i < titles.size(); ++i) {
    // The last one takes what rounding left, so the column ends exactly at the bottom.
    float h = i + 1 == titles.size() ? top + height - y : std::floor(height * weight_of(titles[i]) / total);
    out[titles[i]] = PanelRect{x, y, width, h};
    y += h;
  }
}

}  // namespace

PanelColumn column_of_panel(const std::string& title) {
  if (title == "Viewport") return PanelColumn::centre;
  if (title == "Timeline") return PanelColumn::bottom;
  if (title == "Outliner" || title == "Inspector" || title == "History") return PanelColumn::left;
  return PanelColumn::right;  // presets, profiler, time of day and whatever modules add
}

std::map<std::string, PanelRect> layout_panels(const std::vector<std::string>& shown, float w, float h,
                                               float top) {
  // Side columns and the timeline strip scale with the window, within readable limits.
  const float left = std::floor(std::clamp(w * 0.23f, 240.0f, 420.0f));
  const float right = std::floor(std::clamp(w * 0.27f, 280.0f, 470.0f));
  const float bottom = std::floor(std::clamp(h * 0.28f, 150.0f, 320.0f));
  const float body = std::max(h - top, 1.0f), middle = std::max(w - left - right, 1.0f);
  // Without a timeline the viewport reaches down to the bottom of the window.
  const bool timeline = std::find_if(shown.begin(), shown.end(), [](const std::string& t) {
                          return column_of_panel(t) == PanelColumn::bottom;
                        }) != shown.end();
  const float strip = timeline ? std::min(bottom, body - 1.0f) : 0.0f;
  std::vector<std::string> left_titles, right_titles;
  std::map<std::string, PanelRect> out;
  for (const std::string& t : shown) {
    switch (column_of_panel(t)) {
      case PanelColumn::left:
        left_titles.push_back(t);
        break;
      case PanelColumn::right:
        right_titles.push_back(t);
        break;
      case PanelColumn::centre:
        out[t] = PanelRect{left, top, middle, body - strip};
        break;
      case PanelColumn::bottom:
        out[t] = PanelRect{left, top + body - strip, middle, strip};
        break;
    }
  }
  stack(left_titles, 0, left, top, body, out);
  stack(right_titles, w - right, right, top, body, out);
  return out;
}

}  // namespace welkin::editor
