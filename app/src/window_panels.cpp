// The Dear ImGui menu bar, open-file dialog and log panel of the window.
#include "app/window_state.hpp"
#include "formats/input_kind.hpp"
#include "session/animations.hpp"
#include "session/splat_inputs.hpp"

#include <imgui.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <ctime>
#include <filesystem>

namespace gs::app {

namespace {

// A folder that opens as one input: a DICOM series or TIFF slices (formats::classifyFile
// says a volume kind) or a QNV tileset (it holds index.qnvt).
bool folderOpensAsInput(const std::string& path) {
  return formats::isVolume(formats::classifyFile(path)) || !session::tilesetIndexOf(path).empty();
}

void drawOpenDialog(WindowState& state) {
  if (!state.showOpenDialog) return;
  ImGui::SetNextWindowSize(ImVec2(520, 380), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Open world", &state.showOpenDialog)) {
    ImGui::End();
    return;
  }
  ImGui::TextUnformatted("Path or http(s):// URL of a world, stream, mesh, volume or splat scene");
  ImGui::TextUnformatted("(a DICOM series, TIFF slices or tileset folder: type it, then Open):");
  const bool entered = ImGui::InputText("##path", state.openPath, sizeof state.openPath,
                                        ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if (ImGui::Button("Open") || entered) {
    std::error_code ec;
    const std::filesystem::path p(state.openPath);
    if (std::filesystem::is_directory(p, ec) && !folderOpensAsInput(state.openPath)) {
      // A folder: list it below.
    } else {
      state.open(state.openPath);
      state.showOpenDialog = false;
    }
  }
  // A plain browser of the folder typed (or the current folder).
  std::error_code ec;
  std::filesystem::path dir(state.openPath);
  if (!std::filesystem::is_directory(dir, ec)) dir = dir.parent_path();
  if (dir.empty()) dir = std::filesystem::current_path(ec);
  ImGui::Separator();
  ImGui::Text("%s", dir.string().c_str());
  ImGui::BeginChild("files");
  if (ImGui::Selectable("..")) {
    std::snprintf(state.openPath, sizeof state.openPath, "%s/", dir.parent_path().string().c_str());
  }
  std::vector<std::filesystem::directory_entry> entries;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    entries.push_back(*it);
  std::sort(entries.begin(), entries.end());
  for (const auto& e : entries) {
    const bool folder = e.is_directory(ec);
    if (!folder && !formats::isOpenableName(e.path().filename().string())) continue;
    const std::string label = e.path().filename().string() + (folder ? "/" : "");
    if (ImGui::Selectable(label.c_str())) {
      std::snprintf(state.openPath, sizeof state.openPath, "%s%s", e.path().string().c_str(),
                    folder ? "/" : "");
      if (!folder) {
        state.open(e.path().string());
        state.showOpenDialog = false;
      }
    }
  }
  ImGui::EndChild();
  ImGui::End();
}

void drawLog(WindowState& state) {
  if (!state.showLog) return;
  ImGui::SetNextWindowSize(ImVec2(640, 200), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Log", &state.showLog)) {
    ImGui::End();
    return;
  }
  if (ImGui::Button("Clear")) state.log.clear();
  ImGui::Separator();
  ImGui::BeginChild("lines");
  for (const LogLine& line : state.log) {
    if (line.error) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextUnformatted(line.text.c_str());
    if (line.error) ImGui::PopStyleColor();
  }
  if (ImGui::GetScrollY() >= ImGui::GetScrollMaxY()) ImGui::SetScrollHereY(1.0f);
  ImGui::EndChild();
  ImGui::End();
}

// Animations: the world's named TimeSensors (a glTF asset's animations, docs/gltf.md). The
// list is made only while the menu is open (a walk over the world).
void drawAnimationsMenu(WindowState& state) {
  if (!state.runtimes || state.view().world >= state.worlds.size()) return;
  if (!ImGui::BeginMenu("Animations")) return;
  const auto& scene = state.worlds[state.view().world].scene;
  const std::vector<vrml::Node*> sensors = session::namedTimeSensors(*scene);
  if (sensors.empty()) ImGui::MenuItem("(no named TimeSensor)", nullptr, false, false);
  runtime::ExecutionModel& model = state.runtimes->of(scene, state.worldTime());
  const bool exclusive = scene->x3d.encoding == "glTF";  // one glTF animation at a time
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    ImGui::PushID(static_cast<int>(i));
    const bool active = session::animationActive(*sensors[i]);
    if (ImGui::MenuItem(sensors[i]->defName.c_str(), nullptr, active)) {
      if (active)
        session::stopAnimation(model, *sensors[i]);
      else
        session::startAnimation(model, *sensors[i], sensors, exclusive);
    }
    ImGui::PopID();
  }
  ImGui::EndMenu();
}

}  // namespace

/// Every stream of the session: state, bytes, vectors, packets lost, rate, error.
static void drawStreams(WindowState& state) {
  if (!state.showStreams) return;
  ImGui::SetNextWindowSize(ImVec2(900, 240), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Streams", &state.showStreams)) {
    ImGui::End();
    return;
  }
  const auto streams = state.session->progress();
  // The numbers keep their width; the URL column takes what is left and shows the file
  // name, the whole URL (and any error) in its tooltip (issue 42, friction 8: at the
  // default size the columns were cut off).
  if (ImGui::BeginTable(
          "streams", 6,
          ImGuiTableFlags_Borders | ImGuiTableFlags_Resizable | ImGuiTableFlags_SizingFixedFit)) {
    ImGui::TableSetupColumn("URL", ImGuiTableColumnFlags_WidthStretch);
    for (const char* h : {"state", "bytes", "kB/s", "vectors", "lost"})
      ImGui::TableSetupColumn(h, ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableHeadersRow();
    for (const net::StreamProgress& p : streams) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const std::size_t slash = p.url.find_last_of('/', p.url.size() > 1 ? p.url.size() - 2 : 0);
      const std::string name = slash == std::string::npos ? p.url : p.url.substr(slash + 1);
      ImGui::TextUnformatted(name.c_str());
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("%s%s%s", p.url.c_str(), p.error.empty() ? "" : "\n", p.error.c_str());
      ImGui::TableNextColumn();
      if (p.stage.empty())
        ImGui::Text("%s %.0f%%", net::toString(p.state), p.fraction() * 100.0);
      else
        ImGui::TextUnformatted(p.stage.c_str());
      ImGui::TableNextColumn();
      if (p.kind == net::StreamKind::splats && p.bytes == 0 && p.expectedBytes < 0)
        ImGui::TextUnformatted("local file");
      else if (p.expectedBytes >= 0)
        ImGui::Text("%llu / %lld", static_cast<unsigned long long>(p.bytes),
                    static_cast<long long>(p.expectedBytes));
      else
        ImGui::Text("%llu", static_cast<unsigned long long>(p.bytes));
      ImGui::TableNextColumn();
      ImGui::Text("%.0f", p.bytesPerSecond / 1e3);
      ImGui::TableNextColumn();
      if (p.kind == net::StreamKind::qnv)
        ImGui::Text("%llu / %llu", static_cast<unsigned long long>(p.vectors),
                    static_cast<unsigned long long>(p.expectedVectors));
      else if (p.kind == net::StreamKind::splats)
        ImGui::Text("%llu / %llu splats", static_cast<unsigned long long>(p.vectors),
                    static_cast<unsigned long long>(p.expectedVectors));
      else
        ImGui::Text("%llu nodes", static_cast<unsigned long long>(p.rootNodes));
      ImGui::TableNextColumn();
      ImGui::Text("%llu", static_cast<unsigned long long>(p.packetsLost));
    }
    ImGui::EndTable();
  }
  const net::FetchBudget& budget = state.session->loader().budget();
  ImGui::Text("%u requests, %.1f MB in all", budget.requests(),
              static_cast<double>(budget.totalBytes()) / 1e6);
  ImGui::End();
}

void drawActiveViewportFrame(const WindowState& state, int windowHeight) {
  // With several viewports, the one the menus and keys act on has a frame (issue 42,
  // friction 8). Its rectangle has a lower-left origin; ImGui's an upper-left one.
  if (state.viewports.size() < 2 || state.active >= state.viewports.size()) return;
  const ViewportRect& r = state.viewports[state.active].rect;
  if (r.width <= 0 || r.height <= 0) return;
  const float top = static_cast<float>(windowHeight - (r.y + r.height));
  ImGui::GetBackgroundDrawList()->AddRect(
      ImVec2(static_cast<float>(r.x) + 1.0f, top + 1.0f),
      ImVec2(static_cast<float>(r.x + r.width) - 1.0f, top + static_cast<float>(r.height) - 1.0f),
      IM_COL32(255, 200, 60, 255), 0.0f, 0, 2.0f);
}

int drawMenuBar(WindowState& state, float aspect) {
  (void)aspect;  // the active viewport's aspect is kept by drawScene()
  int height = 0;
  if (!ImGui::BeginMainMenuBar()) return 0;
  if (ImGui::BeginMenu("File")) {
    if (ImGui::MenuItem("Open...", "Ctrl+O")) state.showOpenDialog = true;
    if (ImGui::BeginMenu("Recent", !state.recent.empty())) {
      for (const std::string& path : std::vector<std::string>(state.recent))
        if (ImGui::MenuItem(path.c_str())) state.open(path);
      ImGui::EndMenu();
    }
    if (ImGui::BeginMenu("Worlds", state.worlds.size() > 1)) {
      for (std::size_t i = 0; i < state.worlds.size(); ++i)
        if (ImGui::MenuItem(state.worlds[i].scene->url.c_str(), nullptr, i == state.view().world))
          state.show(i, state.active);
      ImGui::EndMenu();
    }
    // Back and Forward through the worlds Anchor links opened in this viewport.
    if (ImGui::MenuItem("Back", "Alt+Left", false, !state.view().back.empty())) state.goBack();
    if (ImGui::MenuItem("Forward", "Alt+Right", false, !state.view().forward.empty()))
      state.goForward();
    ImGui::Separator();
    // Screenshots go to the current folder, named by the time.
    auto stamp = [] {
      char name[64];
      const std::time_t t = std::time(nullptr);
      std::strftime(name, sizeof name, "ghostspace-%Y%m%d-%H%M%S.png", std::localtime(&t));
      return std::string(name);
    };
    if (ImGui::MenuItem("Save screenshot of the window")) {
      state.screenshotPath = stamp();
      state.screenshotViewportOnly = false;
    }
    if (ImGui::MenuItem("Save screenshot of this viewport")) {
      state.screenshotPath = stamp();
      state.screenshotViewportOnly = true;
    }
    ImGui::Separator();
    if (ImGui::MenuItem("Quit", "Ctrl+Q")) state.quitRequested = true;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("Reset view", "R", false, state.view().renderer() != nullptr))
      state.resetView();
    if (ImGui::MenuItem("Fit to scene", "F", false, state.view().renderer() != nullptr))
      state.fitToScene();
    if (state.view().renderer()) {
      bool headlight = state.view().renderer()->headlight();
      if (ImGui::MenuItem("Headlight", nullptr, &headlight))
        state.view().renderer()->setHeadlight(headlight);
    }
    ImGui::Separator();
    const scene::RenderMode mode = state.view().options.traversal.mode;
    if (ImGui::MenuItem("Polygons", nullptr, mode == scene::RenderMode::polygons))
      state.setMode(scene::RenderMode::polygons);
    if (ImGui::MenuItem("Splats (QNV)", nullptr, mode == scene::RenderMode::splats))
      state.setMode(scene::RenderMode::splats);
    if (ImGui::MenuItem("Outlines only", nullptr, mode == scene::RenderMode::outlines))
      state.setMode(scene::RenderMode::outlines);
    // The browser option Shading of this viewport's world, as X_ITE's context menu sets it
    // (and as the world's Scripts may: render/browser_options.hpp).
    if (ImGui::BeginMenu("Shading", state.view().renderer() != nullptr)) {
      const render::ShadingOption current = state.shading();
      for (const render::ShadingOption s :
           {render::ShadingOption::phong, render::ShadingOption::gouraud,
            render::ShadingOption::flat, render::ShadingOption::wireframe,
            render::ShadingOption::point}) {
        std::string label(render::shadingName(s));
        for (std::size_t i = 1; i < label.size(); ++i)
          label[i] = static_cast<char>(std::tolower(static_cast<unsigned char>(label[i])));
        if (ImGui::MenuItem(label.c_str(), nullptr, s == current)) state.setShading(s);
      }
      ImGui::EndMenu();
    }
    float lod = static_cast<float>(state.view().options.lod);
    if (ImGui::SliderFloat("Level of detail", &lod, 0.001f, 1.0f, "%.3f",
                           ImGuiSliderFlags_Logarithmic))
      state.setLod(lod);
    ImGui::MenuItem("Automatic level of detail (30 frames/s)", nullptr, &state.view().autoLod);
    int budget = static_cast<int>(std::min<std::uint64_t>(state.view().vectorBudget, 1u << 30));
    if (ImGui::InputInt("Vector budget (0: none)", &budget, 10000, 100000,
                        ImGuiInputTextFlags_EnterReturnsTrue))
      state.setVectorBudget(static_cast<std::uint64_t>(std::max(budget, 0)));
    ImGui::Separator();
    ImGui::Separator();
    const scene::NavigationMode nav = state.view().navigator.mode();
    if (ImGui::MenuItem("Examine", nullptr, nav == scene::NavigationMode::examine))
      state.setNavigation(scene::NavigationMode::examine);
    if (ImGui::MenuItem("Walk", nullptr, nav == scene::NavigationMode::walk))
      state.setNavigation(scene::NavigationMode::walk);
    if (ImGui::MenuItem("Fly", nullptr, nav == scene::NavigationMode::fly))
      state.setNavigation(scene::NavigationMode::fly);
    ImGui::MenuItem("Link this viewport's camera", nullptr, &state.view().linked);
    ImGui::Separator();
    for (const LayoutInfo& l : kLayouts) {
      const std::string label = "Layout " + std::string(l.name);
      if (ImGui::MenuItem(label.c_str(), nullptr, state.layout == l.layout))
        state.setLayout(l.layout);
    }
    ImGui::Separator();
    ImGui::MenuItem("Streams", nullptr, &state.showStreams);
    ImGui::MenuItem("Log", nullptr, &state.showLog);
    ImGui::EndMenu();
  }
  const auto& renderer = state.view().renderer();
  const bool haveViewpoints = renderer && !renderer->viewpoints().empty();
  if (ImGui::BeginMenu("Viewpoints", haveViewpoints)) {
    const auto& vps = renderer->viewpoints();
    // X3D ViewpointGroups (clause 23.4.6): a group not displayed, or whose box does not
    // hold the viewer, hides its viewpoints; the groups' descriptions lead the label.
    const glm::vec3 viewer = state.view().navigator.camera().position;
    for (std::size_t i = 0; i < vps.size(); ++i) {
      if (!vps[i].listedAt(viewer)) continue;
      std::string label;
      for (const std::string& g : vps[i].groups) label += g + " / ";
      label += vps[i].description;
      ImGui::PushID(static_cast<int>(i));
      if (ImGui::MenuItem(label.c_str())) state.jumpToViewpoint(i);
      ImGui::PopID();
    }
    ImGui::EndMenu();
  }
  drawAnimationsMenu(state);
  if (renderer) {
    const auto& st = renderer->statistics();
    ImGui::Separator();
    ImGui::Text("%zu shapes, %zu triangles, %zu splats, %.1f ms", st.shapes, st.triangles,
                st.splats, 1000.0f / std::max(1.0f, ImGui::GetIO().Framerate));
  }
  // While anything streams: how far, in one line (the Streams panel has the details).
  if (!state.session->settled()) {
    std::uint64_t bytes = 0;
    double fraction = 0.0, rate = 0.0;
    const auto streams = state.session->progress();
    for (const net::StreamProgress& p : streams) {
      bytes += p.bytes;
      fraction += p.fraction() / static_cast<double>(streams.size());
      rate += p.bytesPerSecond;
    }
    ImGui::Separator();
    ImGui::Text("loading %.0f%%, %.1f MB at %.0f kB/s", fraction * 100.0,
                static_cast<double>(bytes) / 1e6, rate / 1e3);
  }
  height = static_cast<int>(ImGui::GetWindowSize().y);
  ImGui::EndMainMenuBar();

  // Keyboard shortcuts when ImGui is not typing (ImGui 1.86 indexes keys by GLFW key code,
  // which for letters is the upper-case ASCII code).
  const ImGuiIO& io = ImGui::GetIO();
  if (!io.WantCaptureKeyboard) {
    if (io.KeyCtrl && ImGui::IsKeyPressed('O')) state.showOpenDialog = true;
    if (io.KeyCtrl && ImGui::IsKeyPressed('Q')) state.quitRequested = true;
    if (!io.KeyCtrl && ImGui::IsKeyPressed('R')) state.resetView();
    if (!io.KeyCtrl && ImGui::IsKeyPressed('F')) state.fitToScene();
  }
  return height;
}

void drawPanels(WindowState& state) {
  drawOpenDialog(state);
  drawStreams(state);
  drawLog(state);
}

}  // namespace gs::app
