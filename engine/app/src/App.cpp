#include "App.h"

#include <imgui.h>

#include <algorithm>
#include <iterator>
#include <vector>

#include "qv/core/JsonWriter.h"
#include "qv/quality/SoftwareRenderer.h"
#include "qv/ui/ImGuiBrowserBackend.h"
#include "qv/ui/PanelPicture.h"

namespace qv {
namespace {

constexpr const char* kCanvas = "#canvas";

}  // namespace

namespace {

QualityPreset presetOf(QualityChoice choice) {
  switch (choice) {
    case QualityChoice::Balanced:
      return QualityPreset::Balanced;
    case QualityChoice::Low:
      return QualityPreset::Low;
    default:
      return QualityPreset::High;
  }
}

}  // namespace

bool App::start(const AppOptions& options, const std::vector<std::string>& startupErrors) {
  // On a software renderer the frame time is the triangles and the antialiased pixels: start in
  // the weak-device preset, without antialiasing, at a pixel ratio of at most 1, unless the link
  // asks for antialiasing (?aa=1) or a preset (?quality=). The context's antialiasing is fixed for
  // its life, so this is decided before it exists, from the shell's probe of the renderer.
  quality_.renderer = options.webGlRenderer;
  quality_.softwareRenderer = isSoftwareRenderer(options.webGlRenderer);
  quality_.weakStart = quality_.softwareRenderer && !options.antialiasForced && options.quality == QualityChoice::Auto;
  quality_.antialias = options.antialias && !quality_.weakStart;
  quality_.maxPixelRatio = quality_.weakStart ? 1.0 : 0.0;
  quality_.governorOn = options.quality == QualityChoice::Auto;
  quality_.governorMaxStep = governor_.options().maxStep;
  quality_.slowFrameMs = governor_.options().slowFrameMs;
  quality_.fastFrameMs = governor_.options().fastFrameMs;

  map2d_ = options.map2d;
  if (map2d_) {
    // No WebGL2: the scene chooses, loads and culls tiles as for the 3D view, draws nothing; the
    // page draws the 2D city (map2d()) and the panels as HTML.
    device_ = std::make_unique<NullRenderDevice>();
  } else {
    std::string error;
    if (!browser::createWebGl2Context(kCanvas, browser::GlContextOptions{quality_.antialias}, error)) {
      browser::notifyFatal(error);
      return false;
    }
    quality_.msaaSamples = browser::drawingBufferSamples();
    auto gl = std::make_unique<GlRenderDevice>();
    if (!gl->ok()) {
      browser::notifyFatal("The graphics shaders could not be built on this device: " + gl->error());
      return false;
    }
    device_ = std::move(gl);
  }

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini in a browser
  io.ConfigFlags |= ImGuiConfigFlags_NavEnableKeyboard | ImGuiConfigFlags_NavNoCaptureKeyboard;
  ImGui::StyleColorsLight();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 4.0f;
  style.FrameRounding = 3.0f;
  // The keyboard focus (ImGui's navigation highlight, a 2 px frame): a dark blue with a contrast
  // of about 7:1 to the light panel, where the light theme's own pale blue has about 2.5:1.
  style.Colors[ImGuiCol_NavHighlight] = ImVec4(0.0f, 0.25f, 0.70f, 1.0f);
  ui::imguiBrowserInit();
  if (map2d_) {
    // The panels still run (the accessible copy, uiText(), the exports) but are not drawn.
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsAlpha8(&pixels, &w, &h);
  } else {
    uiRenderer_ = std::make_unique<GlImGuiRenderer>();
    if (!uiRenderer_->ok()) {
      browser::notifyFatal("The panels' shaders could not be built on this device: " + uiRenderer_->error());
      return false;
    }
  }

  viewer_ = std::make_unique<Viewer>(*device_);
  for (const std::string& e : startupErrors) viewer_->reportError(e);
  if (!options.dataUrl.empty()) {
    viewer_->openCity(options.dataUrl, fetcher_, options.city);
  } else {
    viewer_->showTestScene();
  }
  panel_.setQualityState(&quality_);
  panel_.setQuality(quality_.weakStart ? QualityPreset::Low : presetOf(options.quality));
  if (panel_.quality() != QualityPreset::High) ControlPanel::applyQuality(*viewer_, panel_.quality());
  if (options.benchSeconds > 0.0) viewer_->startBench(options.benchSeconds);
  if (options.camera) viewer_->setCamera(*options.camera);
  pendingTime_ = options.timeSeconds;
  if (!options.playing) viewer_->pause();
  pendingSelect_ = options.select;
  if (options.filters && viewer_->city() != nullptr) viewer_->city()->setFilters(*options.filters);
  if (!map2d_) input_ = std::make_unique<BrowserInput>(kCanvas);
  PixelRatioRules pixelRules;
  pixelRules.narrowWidthCss = static_cast<double>(ControlPanel::kNarrowWidthCss);
  pixelRatio_ = PixelRatioGovernor(pixelRules);
  lastFrameSeconds_ = browser::nowSeconds();
  startSeconds_ = lastFrameSeconds_;
  return true;
}

void App::dispatchInput() {
  std::vector<InputEvent> events = std::move(deferred_);
  deferred_.clear();
  if (input_) {
    for (InputEvent& e : input_->drain()) events.push_back(std::move(e));
  }

  // A release of something pressed in this frame waits for the next one (ImGui samples input once
  // a frame), and so do the events after it, to keep their order.
  // After '/', the keys typed next are the search's: they wait until its field is being edited
  // (two frames: the panel opens and focuses it, then ImGui starts the edit), so that neither a
  // letter turns the camera nor a character is lost.
  if (searchPendingFrames_ > 0) --searchPendingFrames_;
  if (ui::imguiBrowserKeyboard() == ui::UiKeyboard::Typing) searchPendingFrames_ = 0;
  // Escape or Tab among them means the user has left the search before its edit began: no more
  // waiting (which would hold every later key for up to kSearchPendingFrames frames).
  for (const InputEvent& e : events) {
    if (searchPendingFrames_ > 0 && e.type == InputEvent::Type::KeyDown && (e.code == "Escape" || e.code == "Tab")) {
      searchPendingFrames_ = 0;
      if (e.code == "Escape") panel_.cancelFocusSearch();
    }
  }
  std::size_t i = 0;
  for (bool stop = false; i < events.size() && !stop; i += stop ? 0 : 1) {
    InputEvent& e = events[i];
    if (searchPendingFrames_ > 0) break;
    if (e.type == InputEvent::Type::PointerUp && ui::imguiBrowserMustDeferButtonUp(e.button)) break;
    if (e.type == InputEvent::Type::KeyUp && ui::imguiBrowserMustDeferKeyUp(e.code)) break;
    if (e.type != InputEvent::Type::PointerMove) uiInput_ = true;
    switch (e.type) {
      case InputEvent::Type::PointerDown:
        ui::imguiBrowserPointerDown(e.button, e.x, e.y);
        if (!ui::imguiBrowserCovers(e.x, e.y)) {
          viewer_->controller().pointerDown(e.button, e.x, e.y, e.shift, e.ctrl);
          cameraOwnsPointer_ = true;
        }
        break;
      case InputEvent::Type::PointerMove: {
        // Hovering changes the panels' highlights, also when the pointer leaves a window.
        const bool over = ui::imguiBrowserCovers(e.x, e.y);
        if (over || pointerOverUi_ || (!cameraOwnsPointer_ && ImGui::IsAnyItemActive())) uiInput_ = true;
        pointerOverUi_ = over;
        ui::imguiBrowserPointerMove(e.x, e.y);
        cursor_ = std::make_pair(e.x, e.y);
        if (cameraOwnsPointer_) viewer_->controller().pointerMove(e.x, e.y);
        break;
      }
      case InputEvent::Type::PointerUp:
        ui::imguiBrowserPointerUp(e.button);
        if (cameraOwnsPointer_) {
          const bool click = viewer_->controller().isClick() && e.button == 0;
          viewer_->controller().pointerUp(e.button);
          if (!viewer_->controller().dragging()) cameraOwnsPointer_ = false;
          if (click) selectAt(e.x, e.y);
        }
        break;
      case InputEvent::Type::Wheel:
        if (!ui::imguiBrowserWheel(e.x, e.y, e.wheelY)) viewer_->controller().wheel(e.x, e.y, e.wheelY);
        break;
      case InputEvent::Type::Touch:
        if (dispatchTouch(events, i)) stop = true;
        break;
      case InputEvent::Type::KeyDown:
      case InputEvent::Type::KeyUp:
        dispatchKey(e);
        break;
      case InputEvent::Type::Text:
        // The '/' that opened the search is not its first character.
        if (!(swallowSlashText_ && e.code == "/")) ui::imguiBrowserText(e.code);
        swallowSlashText_ = false;
        break;
    }
  }
  deferred_.assign(std::make_move_iterator(events.begin() + static_cast<std::ptrdiff_t>(i)),
                   std::make_move_iterator(events.end()));
}

bool App::dispatchTouch(std::vector<InputEvent>& events, std::size_t at) {
  const std::vector<TouchPoint> touches = events[at].touches;
  const bool starting = touchGesture_.kind() == TouchGestureKind::None && !touches.empty();
  const TouchGestureState g = touchGesture_.update(touches, browser::nowSeconds());
  if (starting) {
    // A new gesture: the UI's if it begins on a window. ImGui's pointer goes there at once, so
    // that a tap's press, a frame later, lands on the item ImGui already sees under it.
    touchOnUi_ = ui::imguiBrowserCovers(g.startX, g.startY);
    touchLastY_ = g.startY;
    ui::imguiBrowserPointerMove(g.startX, g.startY);
  }
  CameraController& camera = viewer_->controller();
  switch (g.kind) {
    case TouchGestureKind::Pending:
      break;  // nothing yet: a tap must neither press the UI early nor nudge the camera
    case TouchGestureKind::Drag:
      if (touchOnUi_) {
        // A finger dragged over the panel scrolls it (content follows the finger).
        ui::imguiBrowserTouchScroll(touches[0].x, touches[0].y, touches[0].y - touchLastY_);
        touchLastY_ = touches[0].y;
      } else {
        // The pan starts where the finger went down, so the motion within the slop is not lost.
        if (g.changed) {
          const TouchPoint start[] = {{touches[0].id, g.startX, g.startY}};
          camera.touches(start);
        }
        camera.touches(touches);
      }
      break;
    case TouchGestureKind::Pinch:
      if (!touchOnUi_) camera.touches(touches);
      break;
    case TouchGestureKind::Tap:
      if (!touchOnUi_) {
        selectAt(g.startX, g.startY);
      } else if (!ui::imguiBrowserTapTitleBar(g.startX, g.startY)) {
        // A click at the tap's point: ImGui samples input once a frame and needs the pointer, the
        // press and the release on separate frames. The press waits for the next frame (the
        // pointer is set now); the release then waits one more (imguiBrowserMustDeferButtonUp).
        InputEvent down;
        down.type = InputEvent::Type::PointerDown;
        down.x = g.startX;
        down.y = g.startY;
        InputEvent up = down;
        up.type = InputEvent::Type::PointerUp;
        ui::imguiBrowserPointerMove(g.startX, g.startY);
        events[at] = down;
        events.insert(events.begin() + static_cast<std::ptrdiff_t>(at) + 1, up);
        return true;
      }
      break;
    case TouchGestureKind::None:
      if (!touchOnUi_) camera.touches(touches);  // a drag or pinch ended
      break;
  }
  return false;
}

void App::selectAt(double x, double y) {
  const auto hit = viewer_->pick(x, y);
  viewer_->select(hit ? hit->attributes.id : std::string());
}

void App::keepSelectionAboveSheet(double cssWidth, double cssHeight) {
  const std::string& id = viewer_->selection();
  if (id == revealedSelection_) return;
  revealedSelection_ = id;
  if (id.empty() || !ControlPanel::narrowLayout(cssWidth)) return;
  const auto info = viewer_->building(id);
  if (!info) return;
  const BuildingAttributes& a = info->attributes;
  const auto at = viewer_->worldToScreen(a.centroidX, a.centroidY, 0.5 * static_cast<double>(a.heightM));
  const double sheetTop = cssHeight * (1.0 - static_cast<double>(ControlPanel::kBottomSheetFraction));
  const bool visible = at && at->x > 0.0 && at->x < cssWidth && at->y > 0.0 && at->y < sheetTop - 20.0;
  // The camera looks at the building: its middle is then at the centre of the view, above the sheet.
  if (!visible) viewer_->flyTo(a.centroidX, a.centroidY, viewer_->camera().distance);
}

void App::dispatchKey(const InputEvent& e) {
  const bool down = e.type == InputEvent::Type::KeyDown;
  // A release goes everywhere (whoever got the press); a press goes where routeKeyDown says: a
  // text field swallows the shortcuts, and while a control shows the keyboard focus the
  // navigation keys move and press it instead of the camera.
  const ui::KeyRoute route = down ? ui::routeKeyDown(e.code, ui::imguiBrowserKeyboard()) : ui::KeyRoute{true, true};
  if (route.ui) {
    ui::imguiBrowserKey(e.code, down, e.shift, e.ctrl, e.alt);
  } else {
    ui::imguiBrowserModifiers(e.shift, e.ctrl, e.alt);
  }
  if (!route.app) return;
  if (down && e.code == "Space") {
    if (viewer_->playing())
      viewer_->pause();
    else
      viewer_->play();
  }
  if (down && (e.code == "Comma" || e.code == "Period")) {
    viewer_->pause();
    viewer_->setTime(viewer_->time() + (e.code == "Comma" ? -1.0 : 1.0));
  }
  if (down && e.code == "KeyF") viewer_->flyToSelection();
  if (down && e.code == "Escape") viewer_->select("");
  if (down && e.code == "Slash" && !e.ctrl && !e.alt) {
    panel_.focusSearch();
    searchPendingFrames_ = kSearchPendingFrames;
    swallowSlashText_ = true;
  }
  viewer_->controller().key(cameraKeyForCode(e.code), down);
}

void App::adaptQuality(double frameMs, bool judgeFrame) {
  if (quality_.fullQualityRequested) {
    quality_.fullQualityRequested = false;
    quality_.weakStart = false;
    quality_.maxPixelRatio = 0.0;
    quality_.governorOn = false;
    panel_.setQuality(QualityPreset::High);
    governor_.reset();
    appliedStep_ = 0;
    ControlPanel::applyQuality(*viewer_, QualityPreset::High);
  }
  if (quality_.presetChosen || quality_.governorToggled) {
    // The preset was just applied as it is (step 0); the governor starts again from there.
    if (quality_.governorToggled && appliedStep_ != 0) ControlPanel::applyQuality(*viewer_, panel_.quality());
    quality_.presetChosen = false;
    quality_.governorToggled = false;
    governor_.reset();
    appliedStep_ = 0;
  }
  if (quality_.governorOn && judgeFrame) {
    const int step = governor_.addFrame(frameMs);
    if (step != appliedStep_) {
      appliedStep_ = step;
      ControlPanel::applyQuality(*viewer_, panel_.quality(), step);
    }
  }
  quality_.governorStep = appliedStep_;
  quality_.governorReason = governor_.reason();
  quality_.governorChangeMedianMs = governor_.lastChangeMedianMs();
  quality_.governorMedianMs = governor_.medianMs();
}

std::string App::statsJson(const MemoryInfo& memory) const {
  std::string json = viewer_->statsJson(memory);
  JsonWriter w;
  w.beginObject();
  w.field("softwareRenderer", quality_.softwareRenderer).field("renderer", quality_.renderer);
  w.field("antialias", quality_.antialias).field("maxPixelRatio", quality_.maxPixelRatio);
  w.field("quality", qualityName(panel_.quality())).field("governor", quality_.governorOn);
  w.field("qualityStep", quality_.governorStep);
  // This frame's drawing buffer (pixels: width x height; samples: x the MSAA samples, = pixels
  // without antialiasing) and this frame's triangles and draw calls (the fields above are medians).
  w.field("pixels", quality_.pixels()).field("samples", quality_.samples());
  const FrameCounts latest = viewer_->stats().latest;
  w.key("lastFrame").beginObject();
  w.field("triangles", latest.triangles).field("drawCalls", latest.drawCalls);
  // The panels' share of the frame (drawn after the city; not in the counts above).
  const GlImGuiRenderer::FrameStats ui = uiRenderer_ ? uiRenderer_->lastFrame() : GlImGuiRenderer::FrameStats{};
  w.key("ui").beginObject();
  w.field("vertices", ui.vertices).field("triangles", ui.indices / 3).field("drawCalls", ui.drawCalls);
  w.field("uploadBytes", ui.uploadBytes);
  // Drawn through the cached picture: whether this frame redrew it, the pixels copied from it, and
  // since the page opened, the redraws and the frames that showed it older than their content.
  w.field("cached", ui.cached).field("redrawn", ui.redrawn).field("copiedPixels", ui.copiedPixels);
  w.field("redraws", panelRefresh_.redraws()).field("staleFrames", panelRefresh_.staleFrames());
  w.endObject();
  w.endObject();
  w.endObject();
  const std::string extra = w.take();
  // Both are JSON objects: the extra fields go before the viewer's closing brace.
  if (json.size() < 2 || json.back() != '}' || extra.size() < 3) return json;
  json.pop_back();
  json += ",";
  json += extra.substr(1);
  return json;
}

void App::drawPanels(double nowSeconds) {
  const ImDrawData& all = *ImGui::GetDrawData();
  // The map's names (ImGui's background list: ControlPanel::drawMapLabels) follow the camera every
  // frame: they are drawn now, directly over the city, and kept out of the panels' picture, which
  // is redrawn only when the panels change.
  ImDrawList* background = ImGui::GetBackgroundDrawList();
  std::vector<ImDrawList*> panelLists;
  panelLists.reserve(static_cast<std::size_t>(std::max(all.CmdListsCount, 0)));
  ImDrawData data = all;
  data.TotalVtxCount = 0;
  data.TotalIdxCount = 0;
  for (int i = 0; i < all.CmdListsCount; ++i) {
    ImDrawList* list = all.CmdLists[i];
    if (list == background) {
      if (list->IdxBuffer.Size == 0) continue;
      ImDrawData names = all;
      names.CmdLists = &background;
      names.CmdListsCount = 1;
      names.TotalVtxCount = list->VtxBuffer.Size;
      names.TotalIdxCount = list->IdxBuffer.Size;
      uiRenderer_->render(names);
      continue;
    }
    panelLists.push_back(list);
    data.TotalVtxCount += list->VtxBuffer.Size;
    data.TotalIdxCount += list->IdxBuffer.Size;
  }
  data.CmdLists = panelLists.data();
  data.CmdListsCount = static_cast<int>(panelLists.size());
  // Passive changes at 4 Hz where the panels' triangles are dear (the Low preset: software
  // renderers, weak devices); elsewhere every change is drawn at once.
  const bool weak = panel_.quality() == QualityPreset::Low;
  panelRefresh_.setOptions({.passiveSeconds = weak ? 0.25 : 0.0, .inputSeconds = 0.2, .inputFrames = 3});
  if (!uiRenderer_->cacheFits(data)) panelRefresh_.invalidate();
  const std::vector<PixelRect> rects = ui::panelRects(data);
  const bool redraw = panelRefresh_.redraw(ui::drawDataKey(data), rects, uiInput_, nowSeconds);
  uiInput_ = false;
  if (redraw) {
    panelCover_ = disjointCover(rects, static_cast<int>(data.DisplaySize.x * data.FramebufferScale.x),
                                static_cast<int>(data.DisplaySize.y * data.FramebufferScale.y));
  }
  uiRenderer_->renderCached(data, redraw, panelCover_);
}

bool App::pacedForFirstView(double now) const {
  // While the first view of a city loads, at most kFirstViewFps frames a second, unless the user
  // is acting: the files arrive through the page's one thread, between frames, and on a software
  // renderer each frame also takes the cores the download needs. Measured on the 100,000-building
  // demo in headless Chromium (SwiftShader, 2 cores): open to first full frame 3.1-3.5 s drawing
  // every frame, 2.3-2.6 s paced (its 45 MB coarse summary then arrives in 0.9-1.3 s instead of
  // 2.1 s). Never for more than kFirstViewPacingSeconds.
  constexpr double kFirstViewFps = 5.0;
  constexpr double kFirstViewPacingSeconds = 15.0;
  if (readySent_ || viewer_->city() == nullptr || (input_ && input_->pending())) return false;
  if (now - startSeconds_ > kFirstViewPacingSeconds) return false;
  return now - lastFrameSeconds_ < 1.0 / kFirstViewFps;
}

void App::frame(bool forced) {
  const double now = browser::nowSeconds();
  if (!forced && pacedForFirstView(now)) return;
  const double frameMs = (now - lastFrameSeconds_) * 1000.0;
  const double dt = std::clamp(now - lastFrameSeconds_, 0.0, 0.25);
  lastFrameSeconds_ = now;
  // The governor judges the frames of the city as it is viewed, not of its first load (paced).
  adaptQuality(frameMs, readySent_);

  const browser::CanvasSize canvas = browser::syncCanvasSize(kCanvas, pixelRatio_, dt, quality_.maxPixelRatio);
  viewer_->setViewport(canvas.pixelWidth, canvas.pixelHeight, canvas.cssWidth, canvas.cssHeight);
  quality_.pixelWidth = canvas.pixelWidth;
  quality_.pixelHeight = canvas.pixelHeight;
  ui::imguiBrowserNewFrame(canvas.cssWidth, canvas.cssHeight, canvas.devicePixelRatio, dt);
  ImGui::NewFrame();
  dispatchInput();
  if (input_) input_->setUiWantsKeyboard(ui::imguiBrowserKeyboard() == ui::UiKeyboard::Typing);

  // The city's view is framed beside the panel (at its usual width, as it was last drawn: open or
  // folded).
  viewer_->setFramingInsetCss(panel_.framingRightCss(),
                              ControlPanel::narrowLayout(canvas.cssWidth)
                                  ? 0.0
                                  : ControlPanel::widestPanelRightCss(static_cast<float>(canvas.cssWidth)));
  // The 2D city is seen from straight above, north up.
  const auto topDown = [this] {
    if (!map2d_) return;
    viewer_->camera().pitchDeg = 90.0;
    viewer_->camera().headingDeg = 0.0;
  };
  topDown();
  viewer_->frame(dt);
  topDown();

  // The shareable view's time and selection, once the city is there to apply them to.
  if ((pendingTime_ || !pendingSelect_.empty()) && viewer_->settled()) {
    if (pendingTime_) {
      if (*pendingTime_ > viewer_->duration()) {
        viewer_->reportError("The time in the link is beyond the end of the record; showing its end.");
      }
      viewer_->setTime(*pendingTime_);
      pendingTime_.reset();
    }
    // A building in no loaded tile is found through the search index, which the scene requests
    // once the view has settled: an unknown id is reported only when the index is there (or failed).
    if (!pendingSelect_.empty()) {
      if (viewer_->select(pendingSelect_)) {
        pendingSelect_.clear();
      } else if (viewer_->city() == nullptr || viewer_->city()->searchIndexSettled()) {
        viewer_->reportError("The building '" + pendingSelect_ +
                             "' in the link is not in this city; nothing is selected.");
        pendingSelect_.clear();
      }
    }
  }

  keepSelectionAboveSheet(canvas.cssWidth, canvas.cssHeight);

  const MemoryInfo memory = browser::memoryInfo();
  viewer_->setMeasuredHeapBytes(memory.heapBytes);
  mirror_.beginFrame();
  ui::Widgets widgets(mirror_);
  panel_.setCursor(cursor_);
  panel_.draw(*viewer_, widgets, memory, host_);
  ImGui::Render();
  if (uiRenderer_) drawPanels(now);
  mirror_.endFrame();
  focusedControl_ = ui::imguiBrowserFocusedControl();

  if (!readySent_ && viewer_->settled()) {
    readySent_ = true;
    browser::notifyReady();
  }
  if (!benchSent_ && !viewer_->benchResult().empty()) {
    benchSent_ = true;
    browser::notifyBenchDone(viewer_->benchResult());
  }
}

}  // namespace qv
