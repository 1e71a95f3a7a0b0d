// The default panel layout: the viewport in the middle, the timeline under it, the other panels
// stacked in the side columns; no panel covers another, and none leaves the window.
#include "model/panel_layout.h"

#include <gtest/gtest.h>

namespace {

using namespace welkin::editor;

const std::vector<std::string> kAllPanels = {"Viewport",    "Outliner", "Inspector", "Presets",    "Timeline",
                                             "Time of day", "Profiler", "History",   "Weather map"};

void expect_tiled(const std::map<std::string, PanelRect>& layout, float w, float h, float top) {
  for (const auto& [title, r] : layout) {
    EXPECT_GE(r.x, 0) << title;
    EXPECT_GE(r.y, top) << title;
    EXPECT_LE(r.x + r.w, w) << title;
    EXPECT_LE(r.y + r.h, h) << title;
    EXPECT_GT(r.w, 0) << title;
    EXPECT_GT(r.h, 0) << title;
    for (const auto& [other, o] : layout)
      if (other != title) {
        EXPECT_FALSE(r.overlaps(o)) << title << " covers " << other;
      }
  }
}

TEST(PanelLayout, EveryPanelHasItsOwnPlaceAroundTheViewport) {
  for (auto [w, h] : {std::pair{1600.0f, 900.0f}, {1280.0f, 720.0f}, {800.0f, 600.0f}, {3840.0f, 2160.0f}}) {
    auto layout = layout_panels(kAllPanels, w, h, 19);
    ASSERT_EQ(layout.size(), kAllPanels.size());
    expect_tiled(layout, w, h, 19);
    // The side columns are filled to the bottom, and the viewport and timeline fill the middle.
    const PanelRect& view = layout.at("Viewport");
    const PanelRect& timeline = layout.at("Timeline");
    EXPECT_EQ(view.x, layout.at("Outliner").w);
    EXPECT_EQ(view.x + view.w, layout.at("Presets").x);
    EXPECT_EQ(timeline.y, view.y + view.h);
    EXPECT_EQ(timeline.y + timeline.h, h);
    EXPECT_EQ(layout.at("History").y + layout.at("History").h, h);
    EXPECT_EQ(layout.at("Weather map").y + layout.at("Weather map").h, h);
  }
  // 1600 x 900: the columns are 368 and 432 pixels wide, the timeline 252 tall.
  auto layout = layout_panels(kAllPanels, 1600, 900, 19);
  EXPECT_EQ(layout.at("Viewport"), (PanelRect{368, 19, 800, 881 - 252}));
}

TEST(PanelLayout, AModulePanelJoinsTheRightColumnAndTheOthersMakeRoom) {
  auto before = layout_panels({"Viewport", "Presets", "Profiler"}, 1600, 900, 19);
  auto after = layout_panels({"Viewport", "Presets", "Profiler", "Weather map"}, 1600, 900, 19);
  expect_tiled(after, 1600, 900, 19);
  EXPECT_EQ(after.at("Weather map").x, after.at("Presets").x);
  EXPECT_LT(after.at("Presets").h, before.at("Presets").h);
  EXPECT_EQ(after.at("Viewport"), before.at("Viewport"));  // the viewport never moves for a side panel
  // Without a timeline the viewport reaches the bottom.
  EXPECT_EQ(after.at("Viewport").y + after.at("Viewport").h, 900);
  EXPECT_EQ(column_of_panel("Some module panel"), PanelColumn::right);
}

}  // namespace
