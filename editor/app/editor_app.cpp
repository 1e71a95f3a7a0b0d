#include "app/editor_app.h"

#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>
#include <imgui_stdlib.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "app/module_dirs.h"
#include "app/script_player.h"
#include "model/editor_config.h"
#include "model/frame_measure.h"
#include "model/panel_layout.h"
#include "ui/panel_registry.h"
#include "ui/viewport_panel.h"
#include "welkin/core/error.h"
#include "welkin/core/log.h"
#include "welkin/gfx/camera.h"
#include "welkin/gfx/gl_context.h"
#include "welkin/gfx/image.h"
#include "welkin/gfx/renderer.h"
#include "welkin/scene/scene_file.h"

namespace welkin::editor {

namespace fs = std::filesystem;

namespace {

enum ExitCode { kOk = 0, kFailure = 1, kUsage = 2, kBadInput = 3, kCrashed = 70 };

// Dear ImGui's context and backends, shut down before the window goes.
class ImGuiSession {
 public:
  ImGuiSession(GLFWwindow* window, const std::string& layout) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;  // the layout lives in the editor config, written atomically
    if (!layout.empty()) ImGui::LoadIniSettingsFromMemory(layout.c_str(), layout.size());
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");
  }
  ~ImGuiSession() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiSession(const ImGuiSession&) = delete;
  ImGuiSession& operator=(const ImGuiSession&) = delete;
};

ViewPose pose_of(const Camera& c) { return ViewPose{c.position_m, c.heading_deg, c.pitch_deg}; }

// The editor's view: the scene camera's lens and exposure at the fly camera's pose, passed to
// Renderer::render_frame as the frame's camera (the scene's own camera is left untouched).
Camera view_camera(const Camera& scene_camera, const ViewPose& pose) {
  Camera view = scene_camera;
  view.position_m = pose.position_m;
  view.heading_deg = float(pose.heading_deg);
  view.pitch_deg = float(pose.pitch_deg);
  view.roll_deg = 0.0f;
  return view;
}

void write_viewport_image(Renderer& renderer, const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  if (ext != ".png" && ext != ".exr")
    throw Error(ErrorInfo{.file = path, .expected = "a .png or .exr file name", .found = "'" + ext + "'"});
  if (fs::path parent = fs::path(path).parent_path(); !parent.empty()) fs::create_directories(parent);
  if (ext == ".exr") write_exr(path, renderer.read_hdr());
  else write_png(path, renderer.read_output());
}

// The whole window as the user sees it (the back buffer, before the swap).
void write_window_image(int width, int height, const std::string& path) {
  ImageU8 image{width, height, std::vector<uint8_t>(size_t(width) * height * 4)};
  std::vector<uint8_t> rows(image.rgba.size());
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  size_t stride = size_t(width) * 4;
  for (int y = 0; y < height; ++y)  // GL is bottom-up, files top-down
    std::copy_n(&rows[size_t(height - 1 - y) * stride], stride, &image.rgba[size_t(y) * stride]);
  for (size_t i = 3; i < image.rgba.size(); i += 4) image.rgba[i] = 255;
  if (fs::path parent = fs::path(path).parent_path(); !parent.empty()) fs::create_directories(parent);
  write_png(path, image);
}

// Puts the next window at a rectangle of the default layout (model/panel_layout.h).
void place_panel(const PanelRect& r, ImGuiCond cond) {
  ImGui::SetNextWindowPos(ImVec2(r.x, r.y), cond);
  ImGui::SetNextWindowSize(ImVec2(r.w, r.h), cond);
}

// Whether a window is where the layout put it (to a pixel): then it is docked and follows the layout.
bool at_rect(ImVec2 pos, ImVec2 size, const PanelRect& r) {
  return std::abs(pos.x - r.x) < 1 && std::abs(pos.y - r.y) < 1 && std::abs(size.x - r.w) < 1 && std::abs(size.y - r.h) < 1;
}

std::vector<std::string> scene_files() {
  std::vector<std::string> files;
  std::error_code ec;
  for (const char* dir : {"assets/scenes", WELKIN_SOURCE_PRESET_DIR "/../scenes"})
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (e.path().extension() == ".json") files.push_back(e.path().lexically_normal().string());
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

class EditorApp {
 public:
  explicit EditorApp(const EditorOptions& o) : options_(o) {}
  int run();

 private:
  void load_config();
  void save_config();
  bool open_scene(const std::string& path);
  void reset_view_to_scene_camera();
  // After the document's world is replaced (a scene opened): the view starts at its camera.
  void follow_world();
  void render_scene(const FrameInfo& frame);
  // What a frame is made from (SettledView): the scene's components, the view and its size, the
  // clock, the document's versions (painted maps change them) and an open brush stroke.
  uint64_t frame_digest(const FrameInfo& frame) const;
  void draw_ui();
  void draw_main_menu();
  // The session guard's prompt (unsaved changes, overwrite, recover) as a modal.
  void draw_prompt();
  void handle_shortcuts();
  bool run_app_verb(const ScriptLine& line);
  void finish_frame_requests();
  // The timeline's playhead (while playing) and its preview written into the scene.
  void advance_timeline(double dt_s);
  // What the last frame took (dt_s, main loop to main loop): the HUD's figures, the measurement, the
  // moving frames' scale; and the scene's clock advanced by it while it runs.
  void account_last_frame(double dt_s);
  // measure-frames: the last frame's figures into the measurement (printed once it has them all),
  // and the view flown for the frame about to be rendered.
  void measure_last_frame(double frame_ms);
  void fly_measured_view(double dt_s);
  // Whether the last frame was rendered smaller than the viewport (a moving view).
  bool last_frame_reduced() const;

  EditorOptions options_;
  EditorConfig config_;
  fs::path config_path_;
  std::unique_ptr<WindowContext> window_;
  std::unique_ptr<ImGuiSession> imgui_;
  std::unique_ptr<EditorDocument> doc_;
  std::unique_ptr<PresetLibrary> presets_;
  std::unique_ptr<SessionGuard> session_;
  std::unique_ptr<EditorContext> ctx_;
  std::unique_ptr<Renderer> renderer_;
  uint64_t renderer_generation_ = 0;
  uint64_t view_generation_ = 0;
  bool rendered_once_ = false;
  PanelRegistry panels_;
  ScriptPlayer script_;
  std::string window_shot_;  // screenshot-window target, taken after this frame's UI
  bool script_failed_ = false;
  std::string open_path_, save_path_;
  std::optional<FrameMeasurement> measure_;  // a measure-frames line in progress (the script waits)
  int measure_rendered_ = 0;                  // frames rendered since it began
  uint64_t frame_index_ = 0;
  double clock_s_ = 0;  // the scene's clock: advances only while the viewport's clock runs
  int laid_out_w_ = 0, laid_out_h_ = 0;  // the window size the panels were placed for
  // Each panel's last rectangle from the layout, and whether it is still there (docked): a docked
  // panel moves with the layout as other panels open and close; one the user moved stays put.
  struct Placement {
    PanelRect rect;
    bool docked = false;
  };
  std::map<std::string, Placement> placed_;
  std::set<std::string> available_panels_;  // panels whose module was loaded last frame
  std::set<std::string> focus_pending_;     // panels to bring to the front next frame
};

void EditorApp::load_config() {
  if (options_.no_config) return;
  config_path_ = options_.config.empty() ? editor_config_path() : fs::path(options_.config);
  std::vector<std::string> warnings;
  config_ = load_editor_config(config_path_, warnings);
  for (const auto& w : warnings) log::warn(w);
}

void EditorApp::save_config() {
  if (options_.no_config || config_path_.empty()) return;
  int w = 0, h = 0;
  glfwGetWindowSize(window_->handle(), &w, &h);
  if (w > 0 && h > 0) config_.window_width = w, config_.window_height = h;
  size_t n = 0;
  const char* ini = ImGui::SaveIniSettingsToMemory(&n);
  config_.imgui_layout.assign(ini, n);
  config_.panels.clear();
  for (const EditorPanel& p : panels_.panels()) config_.panels[p.title] = p.open;
  config_.last_scene = doc_->scene_path().empty() ? config_.last_scene : fs::absolute(doc_->scene_path()).string();
  config_.view = ctx_->viewport.pose;
  config_.view_scene = config_.last_scene;
  config_.fly_speed_multiplier = ctx_->viewport.speed_multiplier;
  config_.look_through_scene_camera = ctx_->viewport.look_through_scene_camera;
  try {
    save_editor_config(config_path_, config_);
  } catch (const Error& e) {
    log::warn(format_error(e.info()));
  }
}

bool EditorApp::open_scene(const std::string& path) {
  try {
    doc_->load_scene(path);
  } catch (const Error& e) {
    ctx_->log.error(format_error(e.info()));
    return false;
  }
  ctx_->log.info("opened " + path);
  return true;
}

void EditorApp::reset_view_to_scene_camera() {
  Registry& reg = doc_->world().registry();
  Entity cam = reg.first<Camera>();
  std::string scene = doc_->scene_path().empty() ? "" : fs::absolute(doc_->scene_path()).string();
  if (config_.view && !scene.empty() && config_.view_scene == scene) ctx_->viewport.pose = *config_.view;  // as left last time
  else if (!cam.is_null()) ctx_->viewport.pose = pose_of(*reg.get<Camera>(cam));
  config_.view.reset();  // only the first scene of a run resumes the remembered view
}

void EditorApp::follow_world() {
  if (view_generation_ == doc_->world_generation()) return;
  view_generation_ = doc_->world_generation();
  reset_view_to_scene_camera();
}

void EditorApp::render_scene(const FrameInfo& frame) {
  ViewportState& vp = ctx_->viewport;
  if (!renderer_ || renderer_generation_ != doc_->world_generation()) {
    // A new world (scene opened): its renderer and GL resources start afresh.
    renderer_.reset();
    renderer_ = std::make_unique<Renderer>(doc_->world());
    renderer_generation_ = doc_->world_generation();
  }
  Registry& reg = doc_->world().registry();
  Entity cam = reg.first<Camera>();
  if (cam.is_null()) {
    vp.render_error.clear();
    return;
  }
  ctx_->stats.kept = false;
  try {
    // Settled: nothing the frame is made from changed for a while, so it would be the last one again.
    if (rendered_once_ && vp.render_error.empty() && vp.settled.keep(frame_digest(frame))) {
      ctx_->stats.kept = true;
      ctx_->stats.last.timings.clear();
      ctx_->stats.gpu_total_ms = 0;
      return;
    }
    // The scene's camera, or the editor's view from its lens; moving frames at the viewport's scale.
    const Camera& scene_camera = *reg.get<Camera>(cam);
    Camera view = vp.look_through_scene_camera ? scene_camera : view_camera(scene_camera, vp.pose);
    view.moving_render_scale = vp.moving_scale.for_camera(scene_camera.moving_render_scale);
    ctx_->stats.last = renderer_->render_frame(frame, vp.render_width, vp.render_height, &view);
    vp.render_error.clear();
    rendered_once_ = true;
  } catch (const Error& e) {
    vp.render_error = format_error(e.info());
  } catch (const std::exception& e) {  // a module's bug must not take the artist's session down
    vp.render_error = e.what();
  }
  double gpu = 0;
  for (const auto& t : ctx_->stats.last.timings) gpu += t.gpu_ms;
  ctx_->stats.gpu_total_ms = gpu;
  if (rendered_once_) {
    vp.texture = renderer_->output_texture().id();
    vp.texture_width = renderer_->output_texture().desc().width;
    vp.texture_height = renderer_->output_texture().desc().height;
  }
}

uint64_t EditorApp::frame_digest(const FrameInfo& frame) const {
  const ViewportState& vp = ctx_->viewport;
  uint64_t h = fnv1a_64(save_scene(doc_->world()).dump());  // every component, as the scene file has it
  const double view[6] = {vp.pose.position_m.x, vp.pose.position_m.y, vp.pose.position_m.z, vp.pose.heading_deg,
                          vp.pose.pitch_deg, frame.time_s};
  const uint64_t state[8] = {uint64_t(vp.render_width), uint64_t(vp.render_height), uint64_t(vp.look_through_scene_camera),
                             uint64_t(vp.clock_running), doc_->world_generation(), doc_->version(DocumentPart::scene),
                             doc_->version(DocumentPart::sequence), uint64_t(ctx_->map_brush.stroking)};
  return fnv1a_64_of(state, fnv1a_64_of(view, h));
}

void EditorApp::draw_main_menu() {
  bool open_popup = false, save_popup = false;
  if (ImGui::BeginMainMenuBar()) {
    if (ImGui::BeginMenu("File")) {
      if (ImGui::MenuItem("New scene")) ctx_->attempt([&] { session_->request(GuardedAction::new_scene); });
      if (ImGui::MenuItem("Open scene...")) open_popup = true;
      if (ImGui::MenuItem("Save scene", "Ctrl+S", false, !doc_->scene_path().empty()))
        if (ctx_->attempt([&] { doc_->save_scene(doc_->scene_path()); })) ctx_->log.info("saved " + doc_->scene_path());
      if (ImGui::MenuItem("Save scene as...")) save_popup = true;
      ImGui::Separator();
      std::string stem = "screenshots/welkin-" + std::to_string(std::time(nullptr));
      if (ImGui::MenuItem("Screenshot viewport (PNG)", "F12")) ctx_->screenshot_requests.push_back(stem + ".png");
      if (ImGui::MenuItem("Screenshot viewport (EXR, linear HDR)")) ctx_->screenshot_requests.push_back(stem + ".exr");
      ImGui::Separator();
      if (ImGui::MenuItem("Quit")) ctx_->attempt([&] { session_->request(GuardedAction::quit); });
      ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Edit")) {
      const HistoryStep* u = doc_->history().next_undo();
      const HistoryStep* r = doc_->history().next_redo();
      if (ImGui::MenuItem(u ? ("Undo " + u->label).c_str() : "Undo", "Ctrl+Z", false, u != nullptr)) ctx_->attempt([&] { doc_->undo(); });
      if (ImGui::MenuItem(r ? ("Redo " + r->label).c_str() : "Redo", "Ctrl+Y", false, r != nullptr)) ctx_->attempt([&] { doc_->redo(); });
      ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Panels")) {
      for (EditorPanel& p : panels_.panels()) {
        bool available = panels_.available(p, *ctx_);
        ImGui::MenuItem(p.title.c_str(), nullptr, &p.open, available);
        if (!available && ImGui::IsItemHovered()) ImGui::SetTooltip("needs module '%s' in the scene", p.requires_module.c_str());
      }
      ImGui::EndMenu();
    }
    // Title and the latest message, right of the menus.
    std::string title = (doc_->scene_path().empty() ? std::string("(new scene)") : doc_->scene_path()) + (doc_->dirty() ? " *" : "");
    ImGui::TextDisabled("  %s", title.c_str());
    if (!ctx_->log.messages().empty()) {
      const Message& m = ctx_->log.messages().back();
      ImGui::SameLine();
      ImGui::TextColored(m.level == Message::Level::error ? ImVec4(1.0f, 0.45f, 0.4f, 1.0f) : ImVec4(0.6f, 0.85f, 0.6f, 1.0f), "  %s",
                         m.text.c_str());
    }
    ImGui::EndMainMenuBar();
  }
  if (open_popup) {
    open_path_ = doc_->scene_path();
    ImGui::OpenPopup("Open scene");
  }
  if (save_popup) {
    save_path_ = doc_->scene_path();
    ImGui::OpenPopup("Save scene as");
  }
  if (ImGui::BeginPopupModal("Open scene", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    for (const std::string& f : scene_files())
      if (ImGui::Selectable(f.c_str(), f == open_path_)) open_path_ = f;
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 30);
    ImGui::InputText("path", &open_path_);
    // Through the guard: unsaved edits are asked about (in its own prompt) before they go.
    if (ImGui::Button("open") && ctx_->attempt([&] { session_->request(GuardedAction::open_scene, open_path_); }))
      ImGui::CloseCurrentPopup();
    ImGui::SameLine();
    if (ImGui::Button("cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
  if (ImGui::BeginPopupModal("Save scene as", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) {
    ImGui::SetNextItemWidth(ImGui::GetFontSize() * 30);
    ImGui::InputText("path", &save_path_);
    // Another file that exists is replaced only after the overwrite prompt.
    if (ImGui::Button("save") && ctx_->attempt([&] { session_->request(GuardedAction::save_scene_as, save_path_); }))
      ImGui::CloseCurrentPopup();
    ImGui::SameLine();
    if (ImGui::Button("cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
  }
}

void EditorApp::draw_prompt() {
  static constexpr const char* kPromptId = "###session-prompt";  // one modal whatever its title
  if (!session_->prompt()) {
    // Answered elsewhere (a script line): close the modal still open from the last frame.
    if (ImGui::IsPopupOpen(kPromptId) && ImGui::BeginPopupModal(kPromptId)) {
      ImGui::CloseCurrentPopup();
      ImGui::EndPopup();
    }
    return;
  }
  const Prompt prompt = *session_->prompt();
  const char* title = prompt.kind == PromptKind::unsaved     ? "Unsaved changes"
                      : prompt.kind == PromptKind::overwrite ? "Replace file?"
                                                             : "Recover unsaved work?";
  const std::string id = std::string(title) + kPromptId;
  if (!ImGui::IsPopupOpen(kPromptId)) ImGui::OpenPopup(id.c_str());
  if (!ImGui::BeginPopupModal(id.c_str(), nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::TextUnformatted(prompt_text(prompt).c_str());
  if (prompt.kind == PromptKind::unsaved && prompt.scene && !doc_->scene_path().empty())
    ImGui::TextDisabled("scene: %s", doc_->scene_path().c_str());
  if (prompt.kind == PromptKind::unsaved && prompt.sequence && !doc_->sequence_path().empty())
    ImGui::TextDisabled("sequence: %s", doc_->sequence_path().c_str());
  if (!prompt.error.empty()) ImGui::TextColored(ImVec4(1.0f, 0.45f, 0.4f, 1.0f), "%s", prompt.error.c_str());
  std::optional<Answer> chosen;
  auto button = [&](const char* label, Answer answer) {
    if (ImGui::Button(label)) chosen = answer;
    ImGui::SameLine();
  };
  switch (prompt.kind) {
    case PromptKind::unsaved:
      button("Save", Answer::save);
      button("Discard", Answer::discard);
      button("Cancel", Answer::cancel);
      break;
    case PromptKind::overwrite:
      button("Overwrite", Answer::overwrite);
      button("Cancel", Answer::cancel);
      break;
    case PromptKind::recover:
      button("Recover", Answer::recover);
      button("Discard", Answer::discard);
      break;
  }
  ImGui::NewLine();
  if (chosen) ctx_->attempt([&] { session_->answer(*chosen); });
  if (!session_->prompt()) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

void EditorApp::handle_shortcuts() {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantTextInput || session_->prompt()) return;  // a prompt waits: nothing else changes
  if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Z)) ctx_->attempt([&] { io.KeyShift ? doc_->redo() : doc_->undo(); });
  if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_Y)) ctx_->attempt([&] { doc_->redo(); });
  if (io.KeyCtrl && ImGui::IsKeyPressed(GLFW_KEY_S) && !doc_->scene_path().empty())
    if (ctx_->attempt([&] { doc_->save_scene(doc_->scene_path()); })) ctx_->log.info("saved " + doc_->scene_path());
  if (ImGui::IsKeyPressed(GLFW_KEY_F12, false))
    ctx_->screenshot_requests.push_back("screenshots/welkin-" + std::to_string(std::time(nullptr)) + ".png");
}

void EditorApp::draw_ui() {
  draw_main_menu();
  int w = 0, h = 0;
  glfwGetWindowSize(window_->handle(), &w, &h);
  bool resized = laid_out_w_ && (w != laid_out_w_ || h != laid_out_h_);
  laid_out_w_ = w, laid_out_h_ = h;
  std::vector<std::string> shown;  // in the Panels menu's order, which the columns stack in
  for (EditorPanel& p : panels_.panels())
    if (p.open && panels_.available(p, *ctx_)) shown.push_back(p.title);
  const std::map<std::string, PanelRect> layout = layout_panels(shown, float(w), float(h), ImGui::GetFrameHeight());
  for (EditorPanel& p : panels_.panels()) {
    bool available = panels_.available(p, *ctx_);
    bool appeared = available && !available_panels_.count(p.title);
    if (available) available_panels_.insert(p.title);
    else available_panels_.erase(p.title);
    if (!p.open || !available) continue;
    // First use: the layout, unless the remembered one (ImGui's .ini) places the panel. Afterwards
    // docked panels follow the layout; a change of window size lays every panel out again.
    const PanelRect& rect = layout.at(p.title);
    auto placement = placed_.find(p.title);
    if (resized) place_panel(rect, ImGuiCond_Always);
    else if (placement == placed_.end()) place_panel(rect, ImGuiCond_FirstUseEver);
    else if (placement->second.docked && !(placement->second.rect == rect)) place_panel(rect, ImGuiCond_Always);
    // A module's panel that just arrived comes to the front, a frame later so that panels created in
    // the same first frame cannot cover it.
    if (focus_pending_.erase(p.title)) ImGui::SetNextWindowFocus();
    if (appeared && !p.requires_module.empty()) focus_pending_.insert(p.title);
    ImGuiWindowFlags flags = p.title == "Viewport" ? ImGuiWindowFlags_NoScrollbar | ImGuiWindowFlags_NoScrollWithMouse : 0;
    if (p.title == "Viewport") ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(2, 2));
    bool visible = ImGui::Begin(p.title.c_str(), &p.open, flags);
    placed_[p.title] = Placement{rect, at_rect(ImGui::GetWindowPos(), ImGui::GetWindowSize(), rect)};
    if (p.title == "Viewport") ImGui::PopStyleVar();
    if (visible) p.draw(*ctx_);
    ImGui::End();
  }
  // Last: Dear ImGui 1.86 asserts when a window first appears after a modal opened in the same
  // frame (ocornut/imgui#4920), as the panels do in the first frame of a recovery prompt.
  draw_prompt();
  handle_shortcuts();
  // A continuous edit ends when nothing is held any more, whichever widget (or popup) made it.
  if (!ImGui::IsAnyItemActive()) doc_->end_continuous_edit();
}

bool EditorApp::run_app_verb(const ScriptLine& line) {
  const std::string& v = line.verb;
  const auto& a = line.args;
  auto usage = [&](size_t n, const char* text) {
    if (a.size() != n) throw Error(ErrorInfo{.message = std::string("usage: ") + text});
  };
  auto number = [&](size_t i) {
    char* end = nullptr;
    double x = std::strtod(a[i].c_str(), &end);
    if (*end != '\0' || !std::isfinite(x)) throw Error(ErrorInfo{.expected = "a number", .found = "'" + a[i] + "'"});
    return x;
  };
  if (v == "screenshot") {
    usage(1, "screenshot PATH.png|PATH.exr");
    ctx_->screenshot_requests.push_back(a[0]);
  } else if (v == "screenshot-window") {
    usage(1, "screenshot-window PATH.png");
    window_shot_ = a[0];
  } else if (v == "view") {
    usage(5, "view X Y Z HEADING PITCH");
    ctx_->viewport.pose = ViewPose{{number(0), number(1), number(2)}, number(3), std::clamp(number(4), -89.5, 89.5)};
  } else if (v == "look-through-scene-camera") {
    usage(1, "look-through-scene-camera on|off");
    ctx_->viewport.look_through_scene_camera = a[0] == "on";
  } else if (v == "resize") {
    usage(2, "resize WIDTH HEIGHT");
    glfwSetWindowSize(window_->handle(), int(number(0)), int(number(1)));
  } else if (v == "fly") {
    // The viewport's own flight path, driven from a script: FORWARD RIGHT UP in [-1, 1], mouse
    // motion in pixels, for SECONDS (one step; a flight looking through the scene camera is undoable).
    usage(6, "fly FORWARD RIGHT UP LOOK_DX LOOK_DY SECONDS");
    fly_view(*ctx_, FlyInput{.forward = number(0), .right = number(1), .up = number(2), .look_dx_px = number(3),
                             .look_dy_px = number(4), .speed_multiplier = ctx_->viewport.speed_multiplier, .dt_s = number(5)});
    doc_->end_continuous_edit();
  } else if (v == "map-brush") {
    usage(5, "map-brush COMPONENT/FIELD RADIUS_M STRENGTH add|clear|reset ALTITUDE_M");
    MapBrushState& st = ctx_->map_brush;
    st.viewport_target = declared_map(*doc_, a[0]);
    st.brush = MapBrush{.radius_m = std::clamp(number(1), 1.0, 1e7), .strength = std::clamp(number(2), 0.0, 1.0), .mode = brush_mode_named(a[3])};
    st.altitude_m = number(4);
  } else if (v == "paint-viewport") {
    // One stamp where the last frame looks at a place given as fractions of its width and height
    // from the top-left, as a left click there does while a map panel's brush paints in the viewport.
    usage(2, "paint-viewport FX FY");
    const RenderContext* rc = doc_->world().find_resource<RenderContext>();
    if (!ctx_->map_brush.viewport_target || !rc) throw Error(ErrorInfo{.message = "no map brush (use: map-brush) or no frame yet"});
    const size_t steps = doc_->history().steps().size();
    paint_in_viewport(*ctx_, glm::dvec2(number(0) * ctx_->viewport.texture_width, number(1) * ctx_->viewport.texture_height));
    doc_->end_continuous_edit();
    ctx_->map_brush.stroking = false;
    if (doc_->history().steps().size() == steps) throw Error(ErrorInfo{.message = "the brush painted nothing there (off the map or the sky)"});
  } else if (v == "show-preset") {
    usage(2, "show-preset MODULE NAME");
    ctx_->preset_browser = PresetBrowserState{a[0], a[1]};
  } else if (v == "clock") {
    usage(1, "clock run|pause");
    if (a[0] != "run" && a[0] != "pause") throw Error(ErrorInfo{.expected = "run or pause", .found = "'" + a[0] + "'"});
    ctx_->viewport.clock_running = a[0] == "run";
  } else if (v == "moving-budget") {
    usage(1, "moving-budget MS|off");
    const double ms = a[0] == "off" ? 0.0 : number(0);
    if (ms < 0.0 || ms > 1e5) throw Error(ErrorInfo{.expected = "a budget from 0 to 100000 ms, or off", .found = "'" + a[0] + "'"});
    ctx_->viewport.moving_scale = MovingScale{.budget_ms = ms};
  } else if (v == "keep-settled") {
    usage(1, "keep-settled FRAMES|off");
    const double frames = a[0] == "off" ? 0.0 : number(0);
    if ((frames < 1 && a[0] != "off") || frames > 100000 || frames != std::floor(frames))
      throw Error(ErrorInfo{.expected = "a whole number of frames from 1 to 100000, or off", .found = "'" + a[0] + "'"});
    ctx_->viewport.settled = SettledView{.frames = int(frames)};
  } else if (v == "measure-frames") {
    MeasureRequest request = parse_measure_request(a);
    if (request.fly && ctx_->viewport.look_through_scene_camera)
      throw Error(ErrorInfo{.message = "measure-frames flies the editor's own view: use look-through-scene-camera off first"});
    measure_.emplace(request);
    measure_rendered_ = 0;
  } else if (v == "close-window") {
    // What the window's close button does (GLFW's close flag): the next frame asks like quit.
    usage(0, "close-window");
    glfwSetWindowShouldClose(window_->handle(), GLFW_TRUE);
  } else if (v == "crash") {
    // What a crash leaves: no prompt, no saved config, the autosave in place (scripts test recovery).
    usage(0, "crash");
    std::fprintf(stderr, "welkin-editor: %s: crash (simulated), exit status %d\n", line.where().c_str(), kCrashed);
    std::_Exit(kCrashed);
  } else {
    return false;
  }
  return true;
}

void EditorApp::measure_last_frame(double frame_ms) {
  if (!measure_ || measure_rendered_ == 0) return;
  const FrameResult& last = ctx_->stats.last;
  const ViewportState& vp = ctx_->viewport;
  MeasuredFrame frame{.frame_ms = frame_ms, .reduced = last_frame_reduced(), .kept = ctx_->stats.kept};
  for (const PassTiming& t : last.timings) frame.passes.push_back(MeasuredPass{t.name, t.gpu_ms});
  measure_->add(frame);
  if (!measure_->done()) return;
  const std::string load = load_average();
  const std::string report = measure_->report("viewport " + std::to_string(vp.texture_width) + "x" + std::to_string(vp.texture_height) +
                                              (load.empty() ? "" : ", load " + load));
  std::fputs(report.c_str(), stdout);  // like `print`: scripts read it
  std::fflush(stdout);
  ctx_->log.info(report.substr(0, report.find('\n')));
  measure_.reset();
}

void EditorApp::account_last_frame(double dt_s) {
  ctx_->stats.push(dt_s * 1000.0);
  measure_last_frame(dt_s * 1000.0);
  if (last_frame_reduced()) ctx_->viewport.moving_scale.after_moving_frame(dt_s * 1000.0);
  if (ctx_->viewport.clock_running) clock_s_ += dt_s;
}

bool EditorApp::last_frame_reduced() const {
  const FrameResult& last = ctx_->stats.last;
  const ViewportState& vp = ctx_->viewport;
  return int64_t(last.rendered_width) * last.rendered_height < int64_t(vp.texture_width) * vp.texture_height;
}

void EditorApp::fly_measured_view(double dt_s) {
  if (!measure_) return;
  const MeasureRequest& r = measure_->request();
  if (r.fly) ctx_->viewport.pose = glide(ctx_->viewport.pose, r.speed_mps, r.turn_deg_s, dt_s);
  ++measure_rendered_;
}

void EditorApp::advance_timeline(double dt_s) {
  TimelineState& tl = ctx_->timeline;
  double duration = doc_->sequence().duration_s;
  if (tl.playing) {
    tl.playhead_s += dt_s;
    if (tl.playhead_s > duration) {
      tl.playhead_s = tl.loop ? std::fmod(tl.playhead_s, duration) : duration;
      tl.playing = tl.loop;
    }
  }
  if (!tl.preview || doc_->sequence().tracks.empty()) {
    tl.problems.clear();
    tl.previewed_at_s = -1;
  } else if (!doc_->previewing() || tl.playhead_s != tl.previewed_at_s || !(doc_->sequence() == tl.previewed)) {
    tl.problems = doc_->preview_sequence(tl.playhead_s);
    tl.previewed_at_s = tl.playhead_s;
    tl.previewed = doc_->sequence();
  }
}

void EditorApp::finish_frame_requests() {
  for (const std::string& path : ctx_->screenshot_requests) {
    bool ok = ctx_->attempt([&] {
      if (!rendered_once_) throw Error(ErrorInfo{.file = path, .message = "no frame has been rendered yet"});
      write_viewport_image(*renderer_, path);
    });
    if (ok) ctx_->log.info("wrote " + path);
    else if (script_.loaded()) script_failed_ = true;  // a scripted run must not pass without its image
  }
  ctx_->screenshot_requests.clear();
}

int EditorApp::run() {
  if (!display_available()) {
    std::fprintf(stderr,
                 "welkin-editor: no display (DISPLAY / WAYLAND_DISPLAY unset). On a headless machine run it under Xvfb:\n"
                 "  Xvfb :99 -screen 0 1920x1080x24 & DISPLAY=:99 welkin-editor assets/scenes/default.json\n");
    return kUsage;
  }
  if (!options_.script.empty()) {
    try {
      script_ = ScriptPlayer(load_script(options_.script));
    } catch (const Error& e) {
      std::fprintf(stderr, "welkin-editor: %s\n", format_error(e.info()).c_str());
      return kBadInput;
    }
  }
  load_config();
  int width = options_.width ? options_.width : config_.window_width;
  int height = options_.height ? options_.height : config_.window_height;
  try {
    window_ = std::make_unique<WindowContext>(width, height, "Welkin editor");
  } catch (const Error& e) {
    std::fprintf(stderr, "welkin-editor: %s\n", format_error(e.info()).c_str());
    return kUsage;
  }
  imgui_ = std::make_unique<ImGuiSession>(window_->handle(), config_.imgui_layout);

  doc_ = std::make_unique<EditorDocument>(make_world_with_plugins);
  presets_ = std::make_unique<PresetLibrary>(make_world_with_plugins());
  for (const PresetFolder& f : extra_preset_folders()) presets_->add_folder(f);
  presets_->rescan();
  // --no-config keeps the editor off its state folder, autosave included.
  session_ = std::make_unique<SessionGuard>(*doc_, options_.no_config ? Autosave() : Autosave(Autosave::folder_beside(config_path_)));
  ctx_ = std::make_unique<EditorContext>(EditorContext{.doc = *doc_, .presets = *presets_, .session = *session_});
  ctx_->viewport.speed_multiplier = config_.fly_speed_multiplier;
  ctx_->viewport.look_through_scene_camera = config_.look_through_scene_camera;
  register_builtin_panels(panels_);
  std::vector<std::string> panel_errors;
  register_module_panels(panels_, read_module_panels(doc_->world().modules(), panel_errors));
  for (const auto& e : panel_errors) ctx_->log.error(e);
  for (EditorPanel& p : panels_.panels())
    if (auto it = config_.panels.find(p.title); it != config_.panels.end()) p.open = it->second;
    else if (p.title == "History") p.open = false;

  std::error_code ec;
  if (!options_.scene.empty()) {
    if (!open_scene(options_.scene)) return kBadInput;  // the log has printed why
  } else if (!config_.last_scene.empty() && fs::exists(config_.last_scene, ec)) {
    open_scene(config_.last_scene);  // a last scene that no longer loads is only a message
  }
  session_->offer_recovery();  // after the scene opened: recovering replaces it

  auto start = std::chrono::steady_clock::now();
  auto last = start;
  while (!session_->quit_approved()) {
    glfwPollEvents();
    if (window_->should_close()) {
      // The window's close button is a quit like any other: it asks first when work is unsaved.
      glfwSetWindowShouldClose(window_->handle(), GLFW_FALSE);
      if (!session_->prompt()) ctx_->attempt([&] { session_->request(GuardedAction::quit); });
    }
    auto now = std::chrono::steady_clock::now();
    double dt = std::chrono::duration<double>(now - last).count();
    last = now;
    account_last_frame(dt);

    follow_world();
    if (script_.active() && !measure_) {
      try {
        script_.step(*ctx_, [this](const ScriptLine& line) { return run_app_verb(line); });
      } catch (const Error& e) {
        ctx_->log.error("script: " + format_error(e.info()));
        script_failed_ = true;
      }
    }
    if (script_failed_ || session_->quit_approved()) break;
    follow_world();  // a script line may have opened another scene
    session_->tick(std::chrono::duration<double>(now - start).count());
    for (const GuardMessage& m : session_->take_messages()) m.error ? ctx_->log.error(m.text) : ctx_->log.info(m.text);

    advance_timeline(dt);

    fly_measured_view(dt);
    // The scene's clock: paused, no step and no drift.
    FrameInfo frame{.time_s = clock_s_, .dt_s = ctx_->viewport.clock_running && frame_index_ ? dt : 0.0, .index = frame_index_};
    render_scene(frame);

    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    draw_ui();
    ImGui::Render();
    int fw = 0, fh = 0;
    window_->framebuffer_size(fw, fh);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, fw, fh);
    glClearColor(0.08f, 0.08f, 0.09f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    if (!window_shot_.empty()) {
      std::string path = std::exchange(window_shot_, {});
      if (ctx_->attempt([&] { write_window_image(fw, fh, path); })) ctx_->log.info("wrote " + path);
      else script_failed_ = true;
    }
    finish_frame_requests();
    glfwSwapBuffers(window_->handle());
    ++frame_index_;
    if (script_failed_) break;
  }
  for (const GuardMessage& m : session_->take_messages()) m.error ? ctx_->log.error(m.text) : ctx_->log.info(m.text);
  save_config();
  // GL objects go while the context is current: renderer, worlds, then ImGui, then the window.
  renderer_.reset();
  ctx_.reset();
  session_.reset();
  presets_.reset();
  doc_.reset();
  imgui_.reset();
  window_.reset();
  return script_failed_ ? kFailure : kOk;
}

}  // namespace

int run_editor(const EditorOptions& options) { return EditorApp(options).run(); }

}  // namespace welkin::editor
