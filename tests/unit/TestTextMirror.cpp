#include <catch2/catch.hpp>

#include <imgui.h>
#include <imgui_internal.h>  // ImGuiWindow: the inspection window's size and scroll

#include <cmath>

#include "HeadlessImGui.h"
#include "MiniCity.h"
#include "qv/scene/NullRenderDevice.h"
#include "qv/ui/ControlPanel.h"
#include "qv/ui/ImGuiBrowserBackend.h"
#include "qv/ui/TextMirror.h"

using namespace qv;

namespace {

struct RecordingHost final : UiHost {
  std::vector<std::string> urls;
  std::vector<std::pair<std::string, std::string>> downloads;  // file name, content
  void openUrl(const std::string& url) override { urls.push_back(url); }
  void download(const std::string& name, const std::string&, const std::string& content) override {
    downloads.emplace_back(name, content);
  }
  int imagesSaved = 0;
  void saveImage() override { ++imagesSaved; }
};

std::string drawPanel(Viewer& viewer, TextMirror& mirror, ControlPanel& panel, RecordingHost& host) {
  ImGui::NewFrame();
  mirror.beginFrame();
  ui::Widgets w(mirror);
  panel.draw(viewer, w, MemoryInfo{5u * 1024u * 1024u, 64u * 1024u * 1024u}, host);
  ImGui::Render();
  mirror.endFrame();
  return mirror.text();
}

std::string drawPanel(Viewer& viewer, TextMirror& mirror) {
  ControlPanel panel;
  RecordingHost host;
  return drawPanel(viewer, mirror, panel, host);
}

// The mini city opened in a viewer on a screen of the given height, settled, with a panel that
// draws it (the set-up of the tests that select buildings).
struct CityPanel {
  explicit CityPanel(int height, int width = 1280) {
    ImGui::GetIO().DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
    city.serve(fetcher);
    viewer.openCity("city/tileset.json", fetcher);
    viewer.setViewport(width, height, width, height);
    viewer.setCamera(CameraState{0.0, 0.0, 500.0, 0.0, 60.0, 45.0});
    for (int i = 0; i < 20; ++i) viewer.frame(1.0 / 60.0);
  }
  HeadlessImGui imgui;
  test::MiniCity city;
  test::FakeFetcher fetcher;
  NullRenderDevice device;
  Viewer viewer{device};
  TextMirror mirror;
  ControlPanel panel;
  RecordingHost host;
};

}  // namespace

TEST_CASE("The control panel's text mirror shows what the panel says", "[ui]") {
  HeadlessImGui imgui;
  NullRenderDevice device;
  Viewer viewer(device);
  viewer.showTestScene();
  viewer.frame(1.0 / 50.0);
  TextMirror mirror;
  const std::string text = drawPanel(viewer, mirror);
  CHECK(text.find("== QuakeView ==") != std::string::npos);
  CHECK(text.find("FPS: 50.0") != std::string::npos);
  CHECK(text.find("[Pause (Space)]") != std::string::npos);
  CHECK(text.find("> Animation") != std::string::npos);    // folded: play/pause and the time are above it
  CHECK(text.find("> Performance") != std::string::npos);  // collapsed until opened
  CHECK(text.find("== Map ==") != std::string::npos);
  CHECK(text.find("North arrow: view heading 30°") != std::string::npos);
  CHECK(text.find("Scale: ") != std::string::npos);
  CHECK(text.find("== Errors ==") == std::string::npos);

  viewer.pause();
  viewer.reportError("tile 0/0/0 failed: HTTP 404");
  const std::string after = drawPanel(viewer, mirror);
  CHECK(after.find("[Play (Space)]") != std::string::npos);
  CHECK(after.find("== Errors ==\ntile 0/0/0 failed: HTTP 404") != std::string::npos);
}

TEST_CASE("Labels mirror only their visible part", "[ui]") {
  CHECK(ui::visibleLabel("Play##transport") == "Play");
  CHECK(ui::visibleLabel("Speed") == "Speed");
  CHECK(ui::format("%d storeys, %.1f m", 102, 443.2) == "102 storeys, 443.2 m");
}

TEST_CASE("Names with control characters or bidirectional overrides cannot reorder or break a panel", "[ui]") {
  HeadlessImGui imgui;
  TextMirror mirror;
  ImGui::NewFrame();
  mirror.beginFrame();
  ui::Widgets w(mirror);
  // U+202E RIGHT-TO-LEFT OVERRIDE would show "exe.fdp" as "pdf.exe" and turn the rest around.
  const std::string name =
      "Clinic \xE2\x80\xAE"
      "exe.fdp\nEvil\x07";
  w.begin(("Building " + name + "##inspection").c_str());
  w.text("Name: " + name);
  w.field("Address",
          "1 Main St\r\n\xE2\x81\xA6"
          "Apt 2");
  w.selectable((name + "##row").c_str());
  w.textWrapped(name);
  w.end();
  ImGui::Render();
  mirror.endFrame();
  const std::string& text = mirror.text();
  CHECK(text.find("== Building Clinic exe.fdp Evil\xEF\xBF\xBD ==") != std::string::npos);
  CHECK(text.find("Name: Clinic exe.fdp Evil\xEF\xBF\xBD\n") != std::string::npos);
  CHECK(text.find("Address: 1 Main St  Apt 2\n") != std::string::npos);
  CHECK(text.find("> Clinic exe.fdp Evil\xEF\xBF\xBD\n") != std::string::npos);
  CHECK(text.find("\xE2\x80\xAE") == std::string::npos);
  CHECK(text.find("\xE2\x81\xA6") == std::string::npos);
  CHECK(text.find('\x07') == std::string::npos);
  CHECK(text.find('\r') == std::string::npos);
}

TEST_CASE("Selecting a building shows its inspection window and exports list the filtered buildings", "[ui][city]") {
  CityPanel setup(720);
  Viewer& viewer = setup.viewer;
  TextMirror& mirror = setup.mirror;
  ControlPanel& panel = setup.panel;
  RecordingHost& host = setup.host;
  REQUIRE(viewer.settled());

  CHECK_FALSE(viewer.select("no-such-building"));
  REQUIRE(viewer.select("s10"));
  for (int i = 0; i < 5; ++i) viewer.frame(1.0 / 60.0);
  // The motion series arrives with the history, which the inspection asks for (the building's sway
  // is under a pixel from here, so the animation does not): within a few frames.
  std::string text = drawPanel(viewer, mirror, panel, host);
  for (int i = 0; i < 10 && text.find("Roof displacement over time") == std::string::npos; ++i) {
    viewer.frame(1.0 / 60.0);
    text = drawPanel(viewer, mirror, panel, host);
  }
  CHECK(text.find("== Building s10 ==") != std::string::npos);
  CHECK(text.find("Use: office") != std::string::npos);
  CHECK(text.find("Height: 17.5 m (inferred from storeys and use)") != std::string::npos);
  CHECK(text.find("Storeys: 5 (inferred from height and use)") != std::string::npos);
  CHECK(text.find("Damage state: ") != std::string::npos);
  // One peak drift, the solver's, in its storey (MiniCity: the summary's peak of building (1, 1),
  // its largest storey drift in storey 5); the roof's 0.062 m in millimetres.
  const double peakDrift = test::MiniCity::responseOf(1, 1).peakDriftRatio;
  CHECK(text.find(ui::format("Peak inter-storey drift: %.2f %% in storey 5 (exact peak from the solver)",
                             peakDrift * 100.0)) != std::string::npos);
  CHECK(text.find("Peak inter-storey drift", text.find("Peak inter-storey drift") + 1) == std::string::npos);
  CHECK(text.find("Peak roof displacement: 62 mm") != std::string::npos);
  CHECK(text.find("Largest inter-storey drift over time (%), now ") != std::string::npos);
  CHECK(text.find("Roof displacement over time (mm), now ") != std::string::npos);
  CHECK(text.find("the peak above is the solver's exact value") != std::string::npos);
  CHECK(text.find("Plot axes: time 0 to 10.0 s, the current time") != std::string::npos);
  // Storey bars on the fixed scale of the building's type (C1 mid-rise for an unknown type).
  CHECK(text.find("Peak drift per storey (storey 1 = ground, left), fixed scale 0 to ") != std::string::npos);
  CHECK(text.find("Storeys by the state their drift reaches: ") != std::string::npos);
  CHECK(text.find("OpenStreetMap") == std::string::npos);  // a synthetic id has no OSM object
  // The site's own shaking (s10 is cell (1, 1): PGA 0.12 g), then the scaled record's PGA, named so.
  CHECK(text.find("Shaking at the site (ShakeMap): PGA 0.120 g, PGV 8.0 cm/s, PSA 0.3 s 0.240 g, PSA 1.0 s 0.060 g, "
                  "PSA 3.0 s 0.012 g, Vs30 400 m/s") != std::string::npos);
  CHECK(text.find("Record's PGA (scaled): ") != std::string::npos);

  // Feet on request.
  viewer.setShowFeet(true);
  text = drawPanel(viewer, mirror, panel, host);
  CHECK(text.find("Height: 57 ft (inferred from storeys and use)") != std::string::npos);
  CHECK(text.find("Peak roof displacement: 2.4 in") != std::string::npos);  // 0.062 m

  // The export writes the filtered list (every building when no filter is set) with lon/lat.
  BuildingFilters f;
  f.minDamage = 3;  // extensive or worse
  CHECK(drawPanel(viewer, mirror, panel, host).find("== Active filters ==") == std::string::npos);
  viewer.city()->setFilters(f);
  // The filter shows on the canvas (not only inside the panel's section).
  text = drawPanel(viewer, mirror, panel, host);
  CHECK(text.find("== Active filters ==\nFiltered (the rest is dimmed): damage at least extensive\n[Clear]") !=
        std::string::npos);
  const std::string csv = panel.exportList(viewer, "csv", host);
  REQUIRE(host.downloads.size() == 1);
  // The file says what it holds: a scenario's buildings under this filter.
  CHECK(host.downloads[0].first == "quakeview-scenario-buildings-damage-extensive.csv");
  std::size_t rows = 0;
  for (char c : csv) rows += c == '\n' ? 1u : 0u;
  std::size_t expected = 0;
  for (int i = 0; i < test::MiniCity::kSide; ++i) {
    for (int j = 0; j < test::MiniCity::kSide; ++j) expected += (i + j) % 5 >= 3 ? 1u : 0u;
  }
  CHECK(rows == expected + 2);  // the provenance comment and the header row
  CHECK(csv.rfind("\xEF\xBB\xBF# QuakeView building list | Shaking: SCENARIO", 0) == 0);
  CHECK(csv.find("| Filter: damage at least extensive\r\nid,name,address,use,importance,damage_state") !=
        std::string::npos);
  CHECK(csv.find(",-74.0") != std::string::npos);      // longitudes near the origin
  CHECK(csv.find(",shakemap,") != std::string::npos);  // the site's shaking travels with each row
  const std::string geojson = panel.exportList(viewer, "geojson", host);
  CHECK(geojson.find("\"type\":\"FeatureCollection\"") != std::string::npos);
}

TEST_CASE("The inspection window fits a short screen, scrolls with the wheel and starts at the top for each building",
          "[ui][city][inspection]") {
  CityPanel setup(400);
  Viewer& viewer = setup.viewer;
  TextMirror& mirror = setup.mirror;
  ControlPanel& panel = setup.panel;
  RecordingHost& host = setup.host;
  REQUIRE(viewer.settled());
  REQUIRE(viewer.select("s10"));
  for (int i = 0; i < 5; ++i) viewer.frame(1.0 / 60.0);
  for (int i = 0; i < 3; ++i) drawPanel(viewer, mirror, panel, host);
  ImGuiWindow* window = ImGui::FindWindowByName("###inspection");
  REQUIRE(window != nullptr);
  // Within the screen, the content taller than the window.
  CHECK(window->Pos.y >= 0.0f);
  CHECK(window->Pos.y + window->Size.y <= 400.0f);
  REQUIRE(window->ScrollMax.y > 0.0f);
  CHECK(window->Scroll.y == 0.0f);

  // The wheel over the window scrolls it: the browser backend hands the wheel to ImGui before
  // NewFrame (ImGuiBrowserBackend), where ImGui scrolls the hovered window.
  ImGui::GetIO().MousePos = ImVec2(window->Pos.x + 100.0f, window->Pos.y + 150.0f);
  drawPanel(viewer, mirror, panel, host);  // hovered from the next frame on
  ImGui::GetIO().MouseWheel = -2.0f;
  drawPanel(viewer, mirror, panel, host);
  drawPanel(viewer, mirror, panel, host);
  CHECK(window->Scroll.y > 0.0f);

  // The next building starts at the top.
  REQUIRE(viewer.select("s11"));
  for (int i = 0; i < 3; ++i) drawPanel(viewer, mirror, panel, host);
  CHECK(window->Scroll.y == 0.0f);
  CHECK(mirror.text().find("== Building s11 ==") != std::string::npos);
}

namespace {

// One frame of a panel, an inspection window and the map overlay, as the widgets write them.
void mirrorFrame(TextMirror& mirror, const std::string& fps, const std::string& damage, bool performanceOpen) {
  mirror.beginFrame();
  mirror.beginWindow("QuakeView");
  mirror.line(fps);
  mirror.line("Shaking: SCENARIO M6.8 (not a recorded event)");
  mirror.heading("v Consequences", "Consequences", true);
  mirror.line("Buildings (with a result) | 64 | 20");
  mirror.heading("v Damage and colours", "Damage and colours", true);
  mirror.line("Damage state: none, slight, moderate, extensive, complete");
  mirror.heading("> Find and filter", "Find and filter", false);
  mirror.heading(performanceOpen ? "v Performance" : "> Performance", "Performance", performanceOpen);
  if (performanceOpen) mirror.line("cull 0.20  lod 0.10  animate 0.30 ms");
  mirror.endWindow();
  mirror.beginWindow("Building s10");
  mirror.line("(no name)");
  mirror.line("Damage state: " + damage);
  mirror.endWindow();
  mirror.beginWindow("Map");
  mirror.line("Cursor: 40.74840° N, 73.98570° W");
  mirror.endWindow();
  mirror.endFrame();
}

}  // namespace

TEST_CASE("The accessible outline gives the panels as headings, without what changes every frame", "[ui][outline]") {
  TextMirror mirror;
  mirrorFrame(mirror, "FPS: 60.0", "moderate", false);
  // The plain text is unchanged: headers are lines there.
  CHECK(mirror.text().find("== QuakeView ==\nFPS: 60.0\nShaking: SCENARIO") == 0);
  CHECK(mirror.text().find("v Consequences\nBuildings (with a result) | 64 | 20\n") != std::string::npos);
  CHECK(mirror.text().find("> Find and filter\n") != std::string::npos);

  const std::vector<TextMirror::Section> outline = accessibleOutline(mirror.windows());
  REQUIRE(outline.size() == 6);
  CHECK(outline[0].heading == "Earthquake and data");
  CHECK(outline[0].lines == std::vector<std::string>{"Shaking: SCENARIO M6.8 (not a recorded event)"});
  CHECK(outline[1].heading == "Consequences");
  CHECK(outline[1].lines == std::vector<std::string>{"Buildings (with a result) | 64 | 20"});
  CHECK(outline[2].heading == "Damage and colours");
  CHECK(outline[3].heading == "Find and filter (collapsed in the panel)");
  CHECK(outline[3].lines.empty());
  CHECK(outline[4].heading == "Performance (collapsed in the panel)");
  CHECK(outline[5].heading == "Selected building: s10");  // no name: the id
  CHECK(outline[5].lines[1] == "Damage state: moderate");
  const std::string json = mirror.outlineJson();
  CHECK(json.find("\"heading\":\"Selected building: s10\"") != std::string::npos);
  CHECK(json.find("Cursor") == std::string::npos);  // the map overlay is left out
  CHECK(json.find("FPS") == std::string::npos);

  // The revision moves only when the outline does: not with the frame rate, but with the damage
  // shown, or a section opened (whose live measurements are not repeated).
  const std::uint64_t first = mirror.outlineRevision();
  CHECK(json.find("\"revision\":" + std::to_string(first)) != std::string::npos);
  mirrorFrame(mirror, "FPS: 58.3", "moderate", false);
  CHECK(mirror.outlineRevision() == first);
  mirrorFrame(mirror, "FPS: 58.3", "extensive", false);
  CHECK(mirror.outlineRevision() == first + 1);
  CHECK(mirror.outlineJson().find("Damage state: extensive") != std::string::npos);
  mirrorFrame(mirror, "FPS: 58.3", "extensive", true);
  CHECK(mirror.outlineRevision() == first + 2);
  CHECK(mirror.outlineJson().find("cull") == std::string::npos);
  CHECK(mirror.outlineJson().find("\"heading\":\"Performance\"") != std::string::npos);
}

TEST_CASE("Slash opens and focuses the search even in a collapsed panel, and Enter takes the first result",
          "[ui][city][keys]") {
  CityPanel setup(720);
  struct Backend {  // the browser backend on the fixture's context, for its keys
    Backend() : installed(ui::imguiBrowserInit()) {}
    ~Backend() { ui::imguiBrowserShutdown(); }
    Backend(const Backend&) = delete;
    Backend& operator=(const Backend&) = delete;
    bool installed;
  } backend;
  REQUIRE(backend.installed);
  Viewer& viewer = setup.viewer;
  REQUIRE(viewer.settled());
  for (int i = 0; i < 40 && !viewer.city()->searchIndexLoaded(); ++i) viewer.frame(1.0 / 60.0);
  REQUIRE(viewer.city()->searchIndexLoaded());
  auto frame = [&] { return drawPanel(viewer, setup.mirror, setup.panel, setup.host); };
  frame();
  ImGui::SetWindowCollapsed("QuakeView", true);
  std::string text = frame();
  CHECK(text.find("Find and filter") == std::string::npos);  // the whole panel is folded

  setup.panel.focusSearch();
  for (int i = 0; i < 3; ++i) text = frame();
  CHECK(text.find("v Find and filter\nSearch (/): []") != std::string::npos);
  REQUIRE(ui::imguiBrowserKeyboard() == ui::UiKeyboard::Typing);

  ImGui::GetIO().AddInputCharactersUTF8("Building 2-3");
  text = frame();
  CHECK(text.find("Search (/): [Building 2-3]") != std::string::npos);
  CHECK(viewer.selection().empty());
  const CameraState before = viewer.camera();
  ui::imguiBrowserKey("Enter", true, false, false, false);
  frame();
  ui::imguiBrowserKey("Enter", false, false, false, false);
  frame();
  CHECK(viewer.selection() == test::MiniCity::idOf(2, 3));
  for (int i = 0; i < 120; ++i) viewer.frame(1.0 / 60.0);  // the flight
  const CameraState after = viewer.camera();
  CHECK(std::hypot(after.x - before.x, after.y - before.y) > 1.0);
  CHECK(ui::imguiBrowserKeyboard() != ui::UiKeyboard::Typing);  // Enter ended the edit
}

TEST_CASE(
    "On a phone-wide screen the panel starts folded and fits the width, and the inspection window is a bottom sheet",
    "[ui][city][narrow]") {
  {
    CityPanel setup(844, 390);
    Viewer& viewer = setup.viewer;
    TextMirror& mirror = setup.mirror;
    ControlPanel& panel = setup.panel;
    RecordingHost& host = setup.host;
    REQUIRE(viewer.settled());
    REQUIRE(viewer.select("s10"));
    for (int i = 0; i < 5; ++i) viewer.frame(1.0 / 60.0);
    for (int i = 0; i < 3; ++i) drawPanel(viewer, mirror, panel, host);

    // The panel: only its title bar, on the screen.
    ImGuiWindow* main = ImGui::FindWindowByName("QuakeView");
    REQUIRE(main != nullptr);
    CHECK(main->Collapsed);
    CHECK(mirror.text().find("== QuakeView ==") != std::string::npos);
    CHECK(mirror.text().find("[Pause (Space)]") == std::string::npos);
    const std::string folded = mirror.layoutJson();
    const std::size_t entry = folded.find("{\"title\":\"QuakeView\",");
    REQUIRE(entry != std::string::npos);
    CHECK(folded.substr(entry, folded.find('}', entry) - entry).find("\"collapsed\":true") != std::string::npos);

    // The inspection window: across the bottom, at most 40 % of the height.
    ImGuiWindow* sheet = ImGui::FindWindowByName("###inspection");
    REQUIRE(sheet != nullptr);
    CHECK(sheet->Pos.x == 0.0f);
    CHECK(sheet->Size.x == 390.0f);
    CHECK(sheet->Pos.y + sheet->Size.y == Approx(844.0f));
    CHECK(sheet->Size.y <= 844.0f * 0.4f + 0.5f);
    CHECK(sheet->Size.y > 100.0f);
    CHECK(mirror.text().find("== Building s10 ==") != std::string::npos);

    // A tap on the panel's title bar opens it: its controls show, within the screen's width.
    CHECK(ui::imguiBrowserTapTitleBar(main->Pos.x + 80.0f, main->Pos.y + 6.0f));
    for (int i = 0; i < 3; ++i) drawPanel(viewer, mirror, panel, host);
    CHECK_FALSE(main->Collapsed);
    CHECK(mirror.text().find("[Pause (Space)]") != std::string::npos);
    CHECK(main->Pos.x >= 0.0f);
    CHECK(main->Pos.x + main->Size.x <= 390.0f);
    CHECK(main->Pos.y + main->Size.y <= 844.0f);
    // The layout says where the button is: inside the panel.
    const std::string layout = mirror.layoutJson();
    const std::size_t pause = layout.find("{\"window\":\"QuakeView\",\"label\":\"Pause (Space)\",\"x\":");
    CHECK(pause != std::string::npos);
  }

  // On a wide screen the same panel starts open, and the inspection window stays at the right.
  CityPanel wide(720);
  REQUIRE(wide.viewer.select("s10"));
  for (int i = 0; i < 5; ++i) wide.viewer.frame(1.0 / 60.0);
  for (int i = 0; i < 3; ++i) drawPanel(wide.viewer, wide.mirror, wide.panel, wide.host);
  CHECK_FALSE(ImGui::FindWindowByName("QuakeView")->Collapsed);
  CHECK(wide.mirror.text().find("[Pause (Space)]") != std::string::npos);
  CHECK(ImGui::FindWindowByName("###inspection")->Pos.x > 600.0f);
}

TEST_CASE("The Performance panel shows the frame's triangles and pixels, with the MSAA samples, in one line",
          "[ui][performance]") {
  HeadlessImGui imgui;
  NullRenderDevice device;
  Viewer viewer(device);
  viewer.showTestScene();
  viewer.frame(1.0 / 50.0);
  TextMirror mirror;
  ControlPanel panel;
  RecordingHost host;
  QualityState q;
  q.softwareRenderer = true;
  q.weakStart = true;  // the weak-device preset: one line says so, the Performance section why
  q.antialias = false;
  q.pixelWidth = 1280;
  q.pixelHeight = 720;
  q.msaaSamples = 0;
  panel.setQualityState(&q);
  const std::string triangles = ui::format("triangles %.0f · ", viewer.stats().triangles);
  std::string text = drawPanel(viewer, mirror, panel, host);
  CHECK(text.find("Software rendering: the weak-device preset is on (Performance).") != std::string::npos);
  CHECK(text.find("> Performance") != std::string::npos);  // folded: the panel opens compact
  panel.openSection("Performance");
  text = drawPanel(viewer, mirror, panel, host);
  CHECK(text.find("v Performance") != std::string::npos);
  CHECK(text.find(triangles + "pixels 1280×720 (no MSAA)\n") != std::string::npos);
  CHECK(q.pixels() == 1280u * 720u);
  CHECK(q.samples() == q.pixels());  // one sample a pixel without antialiasing

  // An antialiased context at a pixel ratio of 2 on a 640 x 360 canvas: four samples a pixel.
  q.antialias = true;
  q.pixelWidth = 1280;
  q.pixelHeight = 720;
  q.msaaSamples = 4;
  text = drawPanel(viewer, mirror, panel, host);
  CHECK(text.find(triangles + "pixels 1280×720 (×4 MSAA)\n") != std::string::npos);
  CHECK(q.samples() == 4u * 1280u * 720u);

  // Before the first frame has sized the canvas nothing is known: no made-up numbers.
  q.pixelWidth = 0;
  CHECK(q.pixels() == 0u);
  CHECK(q.samples() == 0u);
  text = drawPanel(viewer, mirror, panel, host);
  CHECK(text.find(triangles + "pixels unknown\n") != std::string::npos);
}

namespace {

// Cells of the tables drawn last frame whose text reaches beyond what is shown of their column
// (the column's clip rectangle, within the window): what the screen cuts off.
int cellsCutOff() {
  ImGuiContext& g = *GImGui;  // ImPool has no const accessors
  int cut = 0;
  for (int n = 0; n < g.Tables.GetBufSize(); ++n) {
    const ImGuiTable* table = g.Tables.GetByIndex(n);
    if (table == nullptr || table->LastFrameActive != g.FrameCount) continue;
    const float shown = table->OuterWindow->InnerClipRect.Max.x;
    for (int c = 0; c < table->ColumnsCount; ++c) {
      const ImGuiTableColumn& column = table->Columns[c];
      if (column.ContentMaxXUnfrozen > std::min(column.ClipRect.Max.x, shown) + 1.0f) ++cut;
    }
  }
  return cut;
}

}  // namespace

TEST_CASE("On a phone a table too wide is shown as pairs, each value wrapping within the panel, none cut off",
          "[ui][narrow]") {
  HeadlessImGui imgui;
  ImGui::GetIO().DisplaySize = ImVec2(390.0f, 844.0f);
  TextMirror mirror;
  const std::vector<std::string> headers{"", "City", "In view"};
  const std::vector<std::vector<std::string>> rows{
      {"Buildings (with a result)", "18008", "2691"},
      {"Repair cost", "$107.78 M (80.09-142.71)", "$17.21 M (12.00-30.07)"},
  };
  float right = 0.0f;
  for (int frame = 0; frame < 3; ++frame) {
    ImGui::NewFrame();
    mirror.beginFrame();
    ui::Widgets w(mirror);
    ImGui::SetNextWindowPos(ImVec2(10.0f, 10.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(370.0f, 600.0f), ImGuiCond_Always);
    if (w.begin("Phone panel")) {
      w.table("consequences", headers, rows);
      right = ImGui::GetWindowPos().x + ImGui::GetWindowSize().x;
    }
    w.end();
    ImGui::Render();
    mirror.endFrame();
  }
  REQUIRE(right == Approx(380.0f));
  // Every cell's text within its column and the window: nothing is cut off at the right.
  REQUIRE(GImGui->Tables.GetAliveCount() >= 2);  // stacked: City, then In view
  CHECK(cellsCutOff() == 0);
  // The mirror (the accessible text) has every row whole, in one line.
  CHECK(mirror.text().find("Repair cost | $107.78 M (80.09-142.71) | $17.21 M (12.00-30.07)") != std::string::npos);
}

TEST_CASE("On a tablet in portrait the panel's bottom stays clear of the map overlay in the corner", "[ui][narrow]") {
  // 640 px wide (not a phone: no bottom sheet, the panel open) so that the mini city's panel and
  // the overlay share columns; short enough for the panel to reach the bottom.
  CityPanel setup(760, 640);
  REQUIRE(setup.viewer.settled());
  // Its sections opened, so that its content is taller than the screen.
  for (const char* section : {"Animation", "Damage and colours", "Find and filter", "General", "Performance"}) {
    setup.panel.openSection(section);
  }
  for (int i = 0; i < 4; ++i) drawPanel(setup.viewer, setup.mirror, setup.panel, setup.host);
  ImGuiWindow* panel = ImGui::FindWindowByName("QuakeView");
  ImGuiWindow* overlay = ImGui::FindWindowByName("Map");
  REQUIRE(panel != nullptr);
  REQUIRE(overlay != nullptr);
  REQUIRE_FALSE(panel->Collapsed);
  // The panel is as tall as the screen allows (its content is taller): the case where it met the overlay.
  REQUIRE(panel->ContentSize.y > 760.0f);
  REQUIRE(panel->Pos.x + panel->Size.x > overlay->Pos.x);  // they share columns of the screen
  CHECK(panel->Pos.y + panel->Size.y <= overlay->Pos.y);
  CHECK(overlay->Pos.y + overlay->Size.y <= 760.0f);
}
