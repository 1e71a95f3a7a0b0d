#pragma once
// What every panel works with: the document and presets (the model), the viewport's camera and
// frame statistics, the timeline's playhead, the message log, the session guard (prompts before
// work is lost) and requests for the application (screenshots) that it carries out between frames.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "model/editor_document.h"
#include "model/fly_camera.h"
#include "model/map_painting.h"
#include "model/viewport_cost.h"
#include "model/preset_library.h"
#include "model/session_guard.h"
#include "ui/message_log.h"
#include "welkin/gfx/renderer.h"

namespace welkin::editor {

struct ViewportState {
  ViewPose pose;                          // the editor's own camera, apart from the scene's
  bool look_through_scene_camera = false;  // fly the scene camera itself (undoable edits)
  double speed_multiplier = 1;            // mouse wheel over the viewport
  FlySettings fly;
  int render_width = 960, render_height = 540;  // asked for by the panel's size
  unsigned texture = 0;                   // the last frame's tone-mapped output (GL name)
  int texture_width = 0, texture_height = 0;
  std::string render_error;               // why the last frame failed, shown in the viewport
  bool flying = false;                    // right mouse button held over the image
  // The scene's clock (the world's frame time: the clouds' wind drift, a time of day's time_scale).
  // Paused, a still view stops changing, so the modules keep what they drew and it costs little.
  bool clock_running = false;
  MovingScale moving_scale;               // how much of the viewport a moving frame renders
  SettledView settled;                    // a still view's last frame shown instead of rendering
};

struct FrameStats {
  FrameResult last;
  double cpu_frame_ms = 0;                 // whole editor frame, main loop to main loop
  double gpu_total_ms = 0;
  bool kept = false;                       // the last frame was shown again, not rendered (settled)
  std::array<float, 240> frame_ms_history{};  // a ring for the HUD and profiler plots
  size_t history_cursor = 0;
  void push(double frame_ms) {
    cpu_frame_ms = frame_ms;
    frame_ms_history[history_cursor] = float(frame_ms);
    history_cursor = (history_cursor + 1) % frame_ms_history.size();
  }
};

struct TimelineState {
  double playhead_s = 0;
  bool playing = false;
  bool loop = true;
  bool preview = true;  // write the sequence's values into the scene as the playhead moves
  std::vector<std::string> problems;  // tracks the last preview could not apply
  // What was last previewed: the scene is written only when the playhead or the sequence changes,
  // so an inspector edit of a keyed field holds until the playhead moves.
  double previewed_at_s = -1;
  Sequence previewed;
};

// What the preset browser shows; here rather than inside the panel so a script can point it.
struct PresetBrowserState {
  std::string selected_module, selected_name;  // the preset whose details are shown
};

// The brush a map panel paints with (model/map_painting.h), in the panel's image or the viewport.
struct MapBrushState {
  MapBrush brush;
  std::optional<MapFieldSpec> viewport_target;  // left-dragging in the viewport paints this map
  double altitude_m = 1500.0;                   // where viewport rays meet the map (e.g. cloud level)
  int new_map_side = 512;
  bool stroking = false;                        // a stroke is open (one undo step until release)
  // The panel's image of the map, uploaded again when a stroke changed it.
  unsigned texture = 0;
  std::string texture_file;
  uint64_t texture_revision = 0;
};

struct EditorContext {
  EditorDocument& doc;
  PresetLibrary& presets;
  SessionGuard& session;  // quit, open and new go through it: it asks before unsaved work is lost
  ViewportState viewport;
  FrameStats stats;
  TimelineState timeline;
  PresetBrowserState preset_browser;
  MapBrushState map_brush;
  MessageLog log;
  std::vector<std::string> screenshot_requests;  // viewport images to write after this frame

  // Runs an edit, turning a rejected value into a message instead of an exception.
  template <class Fn> bool attempt(Fn&& fn) {
    try {
      fn();
      return true;
    } catch (const std::exception& e) {
      log.error(e.what());
      return false;
    }
  }
};

}  // namespace welkin::editor
