// `ghostspace [INPUT...]`: the GLFW window, its Dear ImGui menu and panels, EXAMINE
// navigation. Rendering goes through the same render::SceneRenderer as --snapshot.
#include "app/commands.hpp"
#include "app/frame_log.hpp"
#include "app/single_instance.hpp"
#include "app/window_keys.hpp"
#include "app/window_script.hpp"
#include "app/window_state.hpp"
#include "render/context.hpp"
#include "scene/collision.hpp"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>

namespace gs::app {

namespace {

/// ImGui's lifetime, bound to one window.
struct ImGuiSession {
  explicit ImGuiSession(GLFWwindow* window) {
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini beside the user's files
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 330 core");
  }
  ~ImGuiSession() {
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  ImGuiSession(const ImGuiSession&) = delete;
  ImGuiSession& operator=(const ImGuiSession&) = delete;
};

/// Mouse and keys not taken by ImGui drive the active viewport's navigator (a click picks
/// it). EXAMINE: left drag orbits, right drag or shift + left drag pans, middle drag and
/// the wheel dolly. WALK and FLY: left drag looks around, the wheel and W/S/A/D, the
/// arrows and Q/E move at NavigationInfo.speed, stopped by walls (WALK: on the ground),
/// unless the world has an enabled KeySensor or StringSensor.
/// Alt+Left / Alt+Right: Back and Forward.
/// How far a walking avatar may drop at once (avatarSize[2]): going down a step follows
/// the terrain at once; deeper falls continue under gravity (applyGravity).
float avatarStep(const WindowState& state) {
  const auto& renderer = state.view().renderer();
  return renderer ? scene::Avatar::of(renderer->navigation()).stepHeight : 0.75f;
}

void navigate(WindowState& state, int menuHeight, int viewportHeight) {
  const ImGuiIO& io = ImGui::GetIO();
  // The pointing-device sensors see the mouse first (4.6.7, window_pointer.cpp): a press
  // on a sensor or an Anchor holds the pointer, and that drag does not navigate.
  const bool pointerChanged = io.MouseDelta.x != 0.0f || io.MouseDelta.y != 0.0f ||
                              io.MouseClicked[0] || io.MouseReleased[0];
  if (ImGui::IsMousePosValid() && pointerChanged && (!io.WantCaptureMouse || state.pointerHeld))
    state.pointerInput(io.MousePos.x, io.MousePos.y - static_cast<float>(menuHeight),
                       io.MouseDown[0], viewportHeight);
  if (io.WantCaptureMouse) return;
  if (state.pointerHint.clickable) {
    ImGui::SetMouseCursor(ImGuiMouseCursor_Hand);  // GLFW_HAND_CURSOR through the backend
    if (!state.pointerHint.description.empty())
      ImGui::SetTooltip("%s", state.pointerHint.description.c_str());
  }
  // A click picks the viewport the menus and the mouse act on.
  if (io.MouseClicked[0] || io.MouseClicked[1] || io.MouseClicked[2] || io.MouseWheel != 0.0f) {
    const std::size_t under =
        state.viewportAt(io.MousePos.x, io.MousePos.y - menuHeight, viewportHeight);
    if (under != Viewport::kNone) state.active = under;
  }
  scene::ExamineNavigator& navigator = state.view().navigator;
  viewportHeight = std::max(1, state.view().rect.height);
  const float dx = io.MouseDelta.x, dy = io.MouseDelta.y;
  const bool moved = dx != 0.0f || dy != 0.0f;
  const bool examine = navigator.mode() == scene::NavigationMode::examine;
  if (io.MouseDown[0] && moved && !state.pointerHeld) {
    if (io.KeyShift)
      navigator.pan(dx, dy, viewportHeight);
    else if (examine)
      navigator.orbit(dx, dy, viewportHeight);
    else
      navigator.look(dx, dy, viewportHeight);
  } else if (io.MouseDown[1] && moved) {
    navigator.pan(dx, dy, viewportHeight);
  } else if (io.MouseDown[2] && moved) {
    navigator.dolly(-dy / 20.0f);
  }
  const auto& renderer = state.view().renderer();
  // NavigationInfo.speed, times a bound GeoViewpoint's factor for its elevation.
  const float speed =
      renderer ? std::max(renderer->navigation().speed * renderer->navigation().speedFactor, 1e-3f)
               : 1.0f;
  if (io.MouseWheel != 0.0f) {
    if (examine)
      navigator.dolly(io.MouseWheel);
    else  // stopped by walls, on the ground (window_navigation.cpp)
      state.moveViewer(io.MouseWheel * speed * 0.5f, 0.0f, 0.0f, avatarStep(state));
  }
  // Alt+Left / Alt+Right: Back and Forward through the worlds links opened here.
  if (io.KeyAlt && !io.WantCaptureKeyboard) {
    if (ImGui::IsKeyPressed(GLFW_KEY_LEFT, false)) state.goBack();
    if (ImGui::IsKeyPressed(GLFW_KEY_RIGHT, false)) state.goForward();
  }
  // WALK and FLY: W/S or the arrows move forward and back, A/D sideways, Q/E down and up,
  // at NavigationInfo.speed metres per second; not while the world has an enabled
  // KeySensor or StringSensor (the keyboard is then the world's).
  if (!examine && !io.WantCaptureKeyboard && !io.KeyAlt && !state.worldWantsKeys()) {
    auto down = [](int key) { return ImGui::IsKeyDown(key); };
    const float step = speed * io.DeltaTime;
    const float f = (down('W') || down(GLFW_KEY_UP) ? 1.0f : 0.0f) -
                    (down('S') || down(GLFW_KEY_DOWN) ? 1.0f : 0.0f);
    const float r = (down('D') || down(GLFW_KEY_RIGHT) ? 1.0f : 0.0f) -
                    (down('A') || down(GLFW_KEY_LEFT) ? 1.0f : 0.0f);
    const float u = (down('E') ? 1.0f : 0.0f) - (down('Q') ? 1.0f : 0.0f);
    if (f != 0.0f || r != 0.0f || u != 0.0f) {
      state.moveViewer(f * step, r * step, u * step, avatarStep(state));
    }
  }
  state.applyGravity(io.DeltaTime);  // WALK: falls continue between moves
  if (moved && ((io.MouseDown[0] && !state.pointerHeld) || io.MouseDown[1] || io.MouseDown[2]))
    state.view().autoFrame = false;
  if (io.MouseWheel != 0.0f) state.view().autoFrame = false;
}

}  // namespace

namespace {

// A key held down (WALK and FLY move while it is): the window keeps drawing.
bool anyKeyDown() {
  const ImGuiIO& io = ImGui::GetIO();
  for (bool down : io.KeysDown)
    if (down) return true;
  return false;
}

}  // namespace

int runWindow(const Options& options) {
  // The web-browser helper's second launch: the running window opens the inputs.
  if (!options.newInstance && !options.inputs.empty() && options.script.empty() &&
      handToRunningInstance(options.inputs)) {
    std::printf("ghostspace: opened %zu input(s) in the running window\n", options.inputs.size());
    return 0;
  }
  std::unique_ptr<render::WindowContext> context;
  try {
    context = render::createWindowContext("GhostSpace", options.width, options.height,
                                          options.samples < 0 ? 4 : options.samples);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    return 1;
  }
  // The keyboard for the worlds' KeySensors and StringSensors: installed before ImGui's
  // callbacks, which call these first.
  KeyboardQueue keyboard;
  KeyboardQueue::install(context->glfwHandle(), keyboard);
  ImGuiSession imgui(context->glfwHandle());
  WindowState state;
  state.lastAspect = static_cast<float>(context->width()) / std::max(1, context->height());
  state.rendererOptions = rendererOptions(options);
  state.time = options.time;
  state.time.samples = render::drawFramebufferSamples();  // what the window got
  state.session = std::make_unique<session::StreamingSession>(loaderOptions(options));
  state.session->setTilesetOptions(tilesetOptions(options));
  state.setLayout(options.layout);
  state.openInputs(options.inputs, options.lods);
  WindowScript script;
  if (!options.script.empty()) {
    std::string error;
    if (!script.load(options.script, error)) {
      std::fprintf(stderr, "ghostspace: %s\n", error.c_str());
      return 2;
    }
  }

  std::unique_ptr<InstanceServer> instances;
  if (!options.newInstance) instances = std::make_unique<InstanceServer>();

  std::unique_ptr<FrameLog> frameLog;
  if (!options.frameLog.empty()) {
    frameLog = std::make_unique<FrameLog>(options.frameLog);
    if (!frameLog->ok()) {
      std::fprintf(stderr, "ghostspace: cannot write --frame-log %s\n", options.frameLog.c_str());
      return 2;
    }
  }

  int frame = 0;
  GLFWwindow* window = context->glfwHandle();
  // Frames are drawn only when something changes (issue 42, friction 4): input, a world
  // that moves by itself, streams arriving, a window script, a frame log or --frames N
  // (N frames asked for). At rest the
  // loop wakes four times a second to let the worlds' clocks run and to look for inputs
  // handed over by another launch, and draws nothing unless that changed something.
  // A few frames follow every input so that ImGui settles (hover, menus closing).
  constexpr int kSettleFrames = 3;
  int settle = kSettleFrames;
  std::vector<std::string> handedOver;
  while (!glfwWindowShouldClose(window) && !state.quitRequested) {
    const bool busy = state.restless() || !script.empty() || frameLog || options.frames > 0 ||
                      settle > 0 || ImGui::IsAnyMouseDown() || anyKeyDown();
    const double wait = busy ? 1.0 / 60.0 : 0.25;
    const auto waitStart = std::chrono::steady_clock::now();
    glfwWaitEventsTimeout(wait);
    const bool input =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - waitStart).count() <
        0.9 * wait;
    if (instances)
      for (std::string& in : instances->poll()) handedOver.push_back(std::move(in));
    if (input || !handedOver.empty()) settle = kSettleFrames;
    if (!busy && !input && handedOver.empty()) {
      // A quiet tick: the clocks run; draw only when that woke something.
      state.update();
      if (!state.restless()) continue;
    }
    if (settle > 0) --settle;
    if (frameLog) frameLog->beginFrame();
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();

    const int width = context->width(), height = context->height();
    const int menuHeight = drawMenuBar(state, static_cast<float>(width) / std::max(1, height));
    for (const std::string& in : handedOver) state.openInNewViewport(in);
    handedOver.clear();
    state.update();
    // Keys go to the active viewport's world, but not while a panel takes the typing
    // (releases always do: the world forgets keys it did not see go down).
    const bool panelsTyping = ImGui::GetIO().WantCaptureKeyboard;
    for (const KeyInput& k : keyboard.take())
      if (!k.press || !panelsTyping) state.keyInput(k.key, k.press);
    drawPanels(state);
    drawActiveViewportFrame(state, height);
    navigate(state, menuHeight, std::max(1, height - menuHeight));

    context->makeCurrent();
    state.drawScene(0, 0, width, std::max(1, height - menuHeight));
    state.saveScreenshot(width, std::max(1, height - menuHeight));
    if (!script.empty() && !script.step(state, width, std::max(1, height - menuHeight)))
      state.quitRequested = true;
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    context->swapBuffers();
    if (frameLog) frameLog->endFrame(state);
    if (options.frames > 0 && ++frame >= options.frames) break;
  }
  return 0;
}

}  // namespace gs::app
