// Viewer: the platform-independent heart of the app. It owns the camera, the playback clock and
// the content, and each frame culls, animates and asks the RenderDevice to draw, timing every
// phase. The platform layer feeds it input and time; the UI layer reads and steers it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "qv/geometry/GeoFrame.h"
#include "qv/scene/Bench.h"
#include "qv/scene/CameraController.h"
#include "qv/scene/CityScenarios.h"
#include "qv/scene/CityScene.h"
#include "qv/scene/FrameStats.h"
#include "qv/scene/RenderDevice.h"
#include "qv/scene/TestScene.h"
#include "qv/scene/ViewConsequences.h"

namespace qv {

/// Where a switch to another scenario of the city stands (Viewer::selectScenario).
struct ScenarioSwitch {
  enum class State : std::uint8_t {
    None,      ///< no switch asked for
    Checking,  ///< fetching the scenario's manifest to see that it is there and valid
    Loading,   ///< its city is loading: until the view has loaded and the city's totals with it
    Loaded,    ///< done: the scenario is shown, its consequences loaded (or failed, or none)
    Failed,    ///< the scenario is not ready or broken, or its city failed to load: `problem` says why
  };
  std::uint64_t serial = 0;  ///< grows with every selectScenario call that starts a switch
  std::uint32_t index = 0;   ///< the scenario asked for
  State state = State::None;
  std::string problem;
};

/// Memory figures only the platform knows (the WASM heap).
struct MemoryInfo {
  std::uint64_t heapBytes = 0;          ///< live allocated bytes
  std::uint64_t heapReservedBytes = 0;  ///< size of the WASM memory
};

class Viewer {
 public:
  explicit Viewer(RenderDevice& device);
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  /// Shows the built-in test scene (see TestScene.h) and frames the camera on it.
  void showTestScene();
  /// Streams the city whose tileset.json is at `manifestUrl`; the camera frames the whole city
  /// once the manifest arrives unless setCamera() was called before.
  void openCity(const std::string& manifestUrl, Fetcher& fetcher, const CitySceneOptions& options = {});
  /// The address of the manifest shown: openCity's, or the scenario's selectScenario switched to
  /// (resolved beside the first, so a link made from it opens the same scenario); empty without a city.
  [[nodiscard]] const std::string& manifestUrl() const { return manifestUrl_; }
  /// The city folder's scenario catalogue (scenarios.json beside the manifest openCity opened,
  /// requested once that manifest has loaded, kept while switching between its scenarios); nullptr
  /// before, and for the test scene. CityScenarios::available() says whether there is one to show.
  [[nodiscard]] const CityScenarios* scenarios() const { return scenarios_.get(); }
  /// Shows scenario `index` of the catalogue in place of the city's current manifest, keeping the
  /// camera, the time (at the end of the record when it was there, else clamped to the new record),
  /// playing or paused, the colour mode, the filters, the levels of detail shown and the selection.
  /// A scenario not known to be Ready is fetched first (its manifest), and the switch fails with
  /// its problem when it is not there yet or not valid; the city shown stays until then (and comes
  /// back when the scenario's manifest fails to load after all, gone since it was checked). Selecting
  /// the scenario shown only waits for it to load. Returns the switch's serial (see
  /// scenarioSwitch()), or 0 with `problem` set when the catalogue has no such scenario (or has
  /// not loaded). A newer call supersedes a switch not finished yet.
  std::uint64_t selectScenario(std::uint32_t index, std::string* problem = nullptr);
  /// The last switch asked for.
  [[nodiscard]] const ScenarioSwitch& scenarioSwitch() const { return switch_; }
  /// Where the city's files come from under the data origin policy of openCity's options ("this
  /// site (https://…)", or an origin the site's configuration allows; empty without a policy). The
  /// panel shows it beside the manifest's own name.
  [[nodiscard]] const std::string& dataSource() const { return dataSource_; }
  [[nodiscard]] CityScene* city() { return city_.get(); }
  /// The 2D map of the last frame's view (qv/scene/Map2d.h; empty without a city).
  void map2d(Map2dFrame& out) const;
  [[nodiscard]] const CityScene* city() const { return city_.get(); }

  /// Drawing-buffer size in device pixels, and the canvas size in CSS pixels (input coordinates).
  void setViewport(int widthPixels, int heightPixels, double widthCss, double heightCss);
  /// How much of the canvas's left side the panels cover (CSS px, from the left edge; 0: none):
  /// the view's centre (the looked-at point) is drawn in the middle of the rest, and the city's
  /// first view (and home, R) is framed to fit there. Once the city is framed, changes of at most
  /// kFramingInsetStepCss are ignored (the panel's width follows its content; the view stays put).
  /// `widestLeft` (>= 0) is the most the panels may cover in this layout: the first view's distance
  /// is chosen to fit beside that, so it does not depend on how wide the panel happened to be drawn
  /// when the manifest arrived (its content still loading); < 0: the current inset.
  void setFramingInsetCss(double left, double widestLeft = -1.0);
  static constexpr double kFramingInsetStepCss = 120.0;
  /// The view's lens shift from the inset (CameraView's shiftNdcX).
  [[nodiscard]] float lensShift() const;

  [[nodiscard]] CameraState& camera() { return camera_; }
  [[nodiscard]] const CameraState& camera() const { return camera_; }
  [[nodiscard]] CameraController& controller() { return controller_; }
  /// Sets the camera, clamping invalid fields to the current values; false if any was invalid.
  bool setCamera(const CameraState& camera);

  // Playback of simulation time. Playing runs to the end of the record and stops there (the city
  // then shows its damage: shownColorMode), unless looping; play() at the end starts again from
  // the opening moment (a second before the shaking arrives).
  void play();
  void pause() { playing_ = false; }
  [[nodiscard]] bool playing() const { return playing_; }
  /// At the end of the record (time() == duration() > 0).
  [[nodiscard]] bool ended() const { return duration_ > 0.0 && time_ >= duration_; }
  /// Playback starts again from 0 at the end instead of stopping (off by default; the ?bench
  /// flight and the test scene loop).
  void setLoop(bool loop) { loop_ = loop; }
  [[nodiscard]] bool loop() const { return loop_; }
  /// Clamped into [0, duration()]; non-finite values are ignored (returns false).
  bool setTime(double seconds);
  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] double duration() const { return duration_; }
  void setSpeed(double speed) { speed_ = speed; }
  [[nodiscard]] double speed() const { return speed_; }
  void setAmplitude(float amplitude) { amplitude_ = amplitude; }
  [[nodiscard]] float amplitude() const { return amplitude_; }
  void setColorMode(ColorMode mode) { colorMode_ = mode; }
  /// The mode chosen (the panel's combo, setColorMode).
  [[nodiscard]] ColorMode colorMode() const { return colorMode_; }
  /// The mode the city is drawn in: the chosen one, except that in the current-drift mode, once the
  /// shaking is over (at the end of the record) and when the results carry damage probabilities,
  /// each building shows its probability of moderate damage or worse (the Consequences table's
  /// numbers, per building) unless setDamageAfterShaking(false). Paused during the shaking, the
  /// drift of that moment stays.
  [[nodiscard]] ColorMode shownColorMode() const;
  /// True while shownColorMode() differs from colorMode() because the shaking is over.
  [[nodiscard]] bool showingDamageAfterShaking() const { return shownColorMode() != colorMode_; }
  void setDamageAfterShaking(bool on) { damageAfterShaking_ = on; }
  [[nodiscard]] bool damageAfterShaking() const { return damageAfterShaking_; }

  /// Advances the clock by dtSeconds of wall time (× speed while playing) and draws a frame.
  void frame(double dtSeconds);
  /// The live heap measured after the last frame (CityScene::setMeasuredHeapBytes); 0: unknown.
  void setMeasuredHeapBytes(std::uint64_t bytes);

  /// Starts the benchmark flight of `seconds` once the initial view has loaded (see Bench.h).
  void startBench(double seconds);
  /// The benchmark's result JSON once the flight has ended; empty before.
  [[nodiscard]] const std::string& benchResult() const { return benchResult_; }
  [[nodiscard]] bool benchRunning() const { return benchSeconds_ > 0.0 && benchResult_.empty(); }

  // Interaction (city content).
  /// The building under a canvas point (CSS pixels from the top-left corner), if any.
  [[nodiscard]] std::optional<BuildingInfo> pick(double cssX, double cssY) const;
  /// Everything known about a loaded building (its leaf's data when loaded).
  [[nodiscard]] std::optional<BuildingInfo> building(const std::string& id) const;
  /// Selects a building of the city by id ("" clears); false (selection unchanged) when no
  /// building has that id.
  bool select(const std::string& id);
  [[nodiscard]] const std::string& selection() const;
  /// Moves the camera smoothly to look at (x, y) from `distance` metres (keeps heading/pitch).
  void flyTo(double x, double y, double distance);
  /// Flies to the selected building so that it is seen: the framing distance, from the heading and
  /// pitch nearest the current ones along which no loaded building hides its centre or roof
  /// (qv::chooseFlyToPose). False when nothing is selected or the building is unknown.
  bool flyToSelection();
  /// Flies to the district `name` of the consequences (its outline's box filling most of the view)
  /// and outlines it until another is shown or "" given (the panel draws shownDistrictOutline).
  /// False, and nothing changes, when the city has no such district with an outline.
  bool showDistrict(const std::string& name);
  [[nodiscard]] const std::string& shownDistrict() const { return shownDistrict_; }
  /// The shown district's outline rings in the city frame (metres); empty when none is shown.
  /// Valid until the next call or another district is shown.
  [[nodiscard]] const std::vector<std::vector<glm::dvec2>>& shownDistrictOutline() const;
  /// Moves the camera smoothly to `pose` (invalid fields keep the current values).
  void flyToPose(const CameraState& pose);
  /// The ground point under a canvas point (CSS pixels), metres in the city frame.
  [[nodiscard]] std::optional<glm::dvec2> groundAt(double cssX, double cssY) const;
  /// The geographic frame of the city (invalid before the manifest arrives or for the test scene).
  [[nodiscard]] const GeoFrame& geo() const { return geo_; }
  /// The ground the view's totals cover (CityScene::viewBox in degrees); nullopt without a city,
  /// with nothing in view or before the manifest gives the frame.
  [[nodiscard]] std::optional<ViewArea> viewArea() const;
  [[nodiscard]] bool showFeet() const { return showFeet_; }
  void setShowFeet(bool feet) { showFeet_ = feet; }
  /// Metres of the city frame per CSS pixel at the looked-at point.
  [[nodiscard]] double metresPerCssPixel() const;

  /// True once everything of the initial view has loaded or failed.
  [[nodiscard]] bool settled() const { return settled_; }

  /// Shows `message`; `key` names what failed (a file's URL), empty when it is never withdrawn.
  void reportError(std::string message, std::string key = {});
  /// Removes the messages reported with `key` (what they reported has recovered); "" removes none.
  void withdrawErrors(const std::string& key);
  [[nodiscard]] const std::vector<std::string>& errors() const { return errors_; }

  [[nodiscard]] StatsSummary stats() const { return stats_.summary(); }
  [[nodiscard]] std::string statsJson(const MemoryInfo& memory) const;
  [[nodiscard]] std::string cameraJson() const;
  /// Where a city-frame point (metres) appears on the canvas, in CSS pixels from its top-left
  /// corner; nullopt when behind the eye.
  [[nodiscard]] std::optional<glm::dvec2> worldToScreen(double x, double y, double z) const;
  /// The current view's view-projection matrix, and the canvas in CSS pixels: with them a point
  /// projects to the CSS pixels worldToScreen gives (the map's names are placed this way).
  [[nodiscard]] glm::mat4 viewProjection() const;
  [[nodiscard]] glm::dvec2 cssSize() const { return {widthCss_, heightCss_}; }

 private:
  // The steps of frame(), in order.
  void frameCityOnce();                  ///< the first frame with a manifest: duration, home camera
  void advanceBench(double dtSeconds);   ///< the ?bench flight moves the camera
  void advanceFlight(double dtSeconds);  ///< Fly to's eased camera move
  void frameTestScene(const CameraView& view, FrameTimesMs& times, FrameCounts& counts, std::vector<DrawItem>& items,
                      FrameUniforms& uniforms);
  void advanceScenarios();  ///< a scenario switch's steps, the catalogue's checks, a kept selection
  void addError(std::string message, std::string key, bool ofCity);
  /// Replaces the city by the manifest at `url`, keeping the view's state (selectScenario).
  void switchCity(const std::string& url);
  /// The city scene for `url`; its errors are the city's (dropped when it is replaced).
  void createCity(const std::string& url, const CitySceneOptions& options);

  RenderDevice& device_;
  CameraState camera_;
  CameraController controller_;
  int widthPixels_ = 1, heightPixels_ = 1;
  double widthCss_ = 1.0, heightCss_ = 1.0;
  double time_ = 0.0;
  bool timeChosen_ = false;      // setTime() was called (a link, the user): the opening time stays
  bool openingTimeSet_ = false;  // the first view was moved to the shaking's arrival
  double framingInsetCss_ = 0.0;
  std::string shownDistrict_;  // showDistrict
  // shownDistrictOutline's projected rings and the district they were projected from.
  mutable const seismic::ConsequenceTotals::District* outlineSource_ = nullptr;
  mutable std::vector<std::vector<glm::dvec2>> outline_;
  double widestInsetCss_ = -1.0;  // setFramingInsetCss's widestLeft
  double duration_ = 0.0;
  double speed_ = 1.0;
  float amplitude_ = 1.0f;
  bool playing_ = true;
  bool loop_ = false;
  bool damageAfterShaking_ = true;
  ColorMode colorMode_ = ColorMode::CurrentDrift;
  std::vector<MapMarker> markers_;  // this frame's (FrameUniforms::markers points here)
  bool settled_ = false;
  std::vector<std::string> errors_;
  std::vector<std::string> errorKeys_;  // of errors_, same order (errors() hands out the messages)
  std::vector<bool> errorOfCity_;       // of errors_: reported by the city scene (gone with it)
  std::string dataSource_;
  FrameStats stats_;

  struct TestContent;
  std::unique_ptr<TestContent> test_;
  std::unique_ptr<CityScene> city_;
  Fetcher* fetcher_ = nullptr;  // openCity's, for the scenarios' manifests
  std::string manifestUrl_;
  std::string previousManifestUrl_;  // shown before the last switch: back to it when the switch fails
  std::unique_ptr<CityScenarios> scenarios_;
  ScenarioSwitch switch_;
  bool keepEndAfterSwitch_ = false;  // the record had ended when the scenario was switched
  bool framingKept_ = false;         // a switch keeps the lens shift as the first view set it
  std::string pendingSelection_;     // the selection kept over a switch, applied once the new city knows it
  bool cameraSetByUser_ = false;
  GeoFrame geo_{0.0, 1000.0};  // invalid until a city's manifest arrives
  bool showFeet_ = false;
  struct Flight {
    CameraState from, to;
    double elapsed = 0.0, duration = 1.2;
  };
  std::optional<Flight> flight_;
  double benchSeconds_ = 0.0;
  double benchElapsed_ = 0.0;
  std::unique_ptr<BenchRun> bench_;
  std::string benchResult_;
  bool cityFramed_ = false;
};

}  // namespace qv
