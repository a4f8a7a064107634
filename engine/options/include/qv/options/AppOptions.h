// The viewer's start-up options. The page shell (web/quakeview.js) turns the page's URL and its
// config.json into engine arguments ("--camera", "12,34,900,0,45"); this parses and checks them.
// The URL names are a contract with everyone who shares a link (README, "URL options" and
// "Sharing a view"):
//   query: ?data=URL ?scene=test ?aa=0|1 ?quality=high|balanced|low ?memory=MB ?bench=SECONDS
//   hash:  #cam=x,y,distance,heading,pitch[,fov] &t=seconds &play=0|1 &sel=id &f=minDamage,use,critical[,probability]
// A bad value never stops the viewer: the option keeps its default and a message for the person
// reading the page names the URL parameter and the value given ("The time in the link (t=-3) is
// not a number of seconds from 0; starting at 0 s.").
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "qv/core/Result.h"
#include "qv/geometry/OrbitCamera.h"
#include "qv/scene/CityIndex.h"
#include "qv/scene/CityScene.h"

namespace qv {

/// The quality the viewer starts in (?quality=).
enum class QualityChoice : std::uint8_t { Auto, High, Balanced, Low };

struct AppOptions {
  std::string scene;             ///< "test" for the built-in test scene (then dataUrl is empty)
  std::string dataUrl;           ///< tileset.json URL, as the page gave it (checked later by the origin policy)
  bool antialias = true;         ///< ?aa=0: false
  bool antialiasForced = false;  ///< ?aa=1: on, and full quality even on a software renderer
  /// ?quality=: a fixed preset (the frame-time governor off); Auto: the device decides (the
  /// weak-device preset on a software renderer) and the governor adapts.
  QualityChoice quality = QualityChoice::Auto;
  /// The WebGL renderer's name as the shell's probe read it (UNMASKED_RENDERER_WEBGL or RENDERER);
  /// empty when unknown.
  std::string webGlRenderer;
  /// --map2d (the shell, when no WebGL2 context can be made): no 3D view; the page draws the 2D
  /// city (qv/scene/Map2d.h) and the panels as HTML.
  bool map2d = false;
  double benchSeconds = 0.0;  ///< > 0: run the benchmark flight for this long
  CitySceneOptions city;      ///< memoryBudgetBytes and the data origin policy set here
  // The shareable view (from the URL hash), applied once the city is there.
  std::optional<CameraState> camera;
  std::optional<double> timeSeconds;  ///< >= 0
  bool playing = true;                ///< false: the link was copied while paused, and opens paused
  std::string select;                 ///< building id; empty: none
  std::optional<BuildingFilters> filters;
};

/// Where the shell takes an engine argument from.
enum class ArgumentSource : std::uint8_t {
  UrlQuery,  ///< ?name=value
  UrlHash,   ///< #name=value (the shareable view)
  Shell,     ///< the shell itself: the page's origin, config.json, its own problems
};

/// One engine argument and the URL parameter behind it.
struct AppArgument {
  std::string_view argument;  ///< "--camera"
  ArgumentSource source = ArgumentSource::Shell;
  std::string_view urlName;  ///< "cam"; empty for Shell
  bool takesValue = true;    ///< false: a flag ("--no-antialias" from ?aa=0, "--antialias" from ?aa=1)
};

/// Every argument parseAppOptions understands (a fixed table; the strings are static).
std::span<const AppArgument> appArguments();

/// Parses the engine's arguments in order (a later repeat of an option wins; --allow-origin
/// accumulates). Each unknown argument, argument without its value and bad value adds one message
/// to `errors` and is otherwise ignored; a --shell-error value is passed through as a message.
AppOptions parseAppOptions(const std::vector<std::string>& args, std::vector<std::string>& errors);

/// Longest filter text parseFilters accepts, bytes.
inline constexpr std::size_t kMaxFilterTextBytes = 300;

/// Parses the hash's filter text "minDamage,use,critical[,probability]": three or four fields, each
/// empty for "any": minDamage a digit 0..4 (none .. complete); use one normalized use (lower-case letters
/// and '_': "hospital") or several joined by '+' ("hospital+school+fire_station"); critical "0" or
/// "1" (1: critical facilities, FacilityCategory Essential or SchoolShelter) or facility category
/// names joined by '+' ("essential+school_shelter+high_occupancy+hazardous", facilityCategoryName);
/// probability "state:percent", P(structural damage >= state) at least percent % (state 1..4 for
/// slight .. complete, percent 1..100: "2:10"). At most kMaxFilterTextBytes. The error names the field at fault and its
/// value ("minDamage '9' is not a damage state 0 to 4").
Result<BuildingFilters> parseFilters(std::string_view text);

}  // namespace qv
