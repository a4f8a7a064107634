// PROJ through its C API: every object checked for null, errors read from the context, logging
// off (PROJ would otherwise print to stderr), one context per transformation.
//
// The library is loaded the first time a model needs a CRS transformation (dlopen of the PROJ that
// CMake found, QUAKEVIEW_PROJ_LIBRARY): with its dependencies (curl, TLS, Kerberos, TIFF, SQLite:
// some forty shared libraries, all bound at load) it cost 9 of the 11 ms that every quakeview-prep
// run spent before main, whichever command it ran.
#include "qv/prep/Lod2Georeference.h"

#include <dlfcn.h>

#include <cctype>
#include <cmath>
#include <mutex>
#include <numbers>

#include <proj.h>

#include "qv/prep/Cli.h"
#include "qv/prep/Projection.h"

namespace qv::prep {
namespace {

// The PROJ functions used here, resolved once from the loaded library.
// clang-format off
#define QV_PROJ_FUNCTIONS(X)                                                                  \
  X(proj_context_create) X(proj_context_destroy) X(proj_context_errno)                        \
  X(proj_context_errno_string) X(proj_coord) X(proj_create) X(proj_create_crs_to_crs_from_pj) \
  X(proj_crs_get_coordinate_system) X(proj_crs_get_sub_crs) X(proj_cs_get_axis_info)         \
  X(proj_destroy) X(proj_errno) X(proj_errno_reset) X(proj_get_name) X(proj_get_type)         \
  X(proj_is_crs) X(proj_log_level) X(proj_normalize_for_visualization) X(proj_trans)
// clang-format on

struct ProjApi {
#define QV_PROJ_POINTER(name) decltype(&::name) name = nullptr;
  QV_PROJ_FUNCTIONS(QV_PROJ_POINTER)
#undef QV_PROJ_POINTER
};

ProjApi gProj;
std::string gProjError;

/// Loads PROJ once; empty on success, else why it could not be loaded.
const std::string& loadProj() {
  static std::once_flag once;
  std::call_once(once, [] {
    void* library = ::dlopen(QUAKEVIEW_PROJ_LIBRARY, RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) {
      const char* why = ::dlerror();
      gProjError = std::string("cannot load PROJ (") + QUAKEVIEW_PROJ_LIBRARY + "): " + (why != nullptr ? why : "");
      return;
    }
#define QV_PROJ_RESOLVE(name)                                                         \
  gProj.name = reinterpret_cast<decltype(&::name)>(::dlsym(library, #name));          \
  if (gProj.name == nullptr) {                                                        \
    gProjError = std::string("PROJ (") + QUAKEVIEW_PROJ_LIBRARY + ") lacks " + #name; \
    return;                                                                           \
  }
    QV_PROJ_FUNCTIONS(QV_PROJ_RESOLVE)
#undef QV_PROJ_RESOLVE
  });
  return gProjError;
}

}  // namespace

struct CrsToLonLat::Impl {
  PJ_CONTEXT* context = nullptr;
  PJ* transformation = nullptr;
  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (transformation != nullptr) gProj.proj_destroy(transformation);
    if (context != nullptr) gProj.proj_context_destroy(context);
  }
};

namespace {

/// Owns one PJ object for the duration of create().
class PjHandle {
 public:
  explicit PjHandle(PJ* pj = nullptr) : pj_(pj) {}
  PjHandle(const PjHandle&) = delete;
  PjHandle& operator=(const PjHandle&) = delete;
  ~PjHandle() {
    if (pj_ != nullptr) gProj.proj_destroy(pj_);
  }
  void reset(PJ* pj) {
    if (pj_ != nullptr) gProj.proj_destroy(pj_);
    pj_ = pj;
  }
  [[nodiscard]] PJ* get() const { return pj_; }

 private:
  PJ* pj_;
};

std::string projError(PJ_CONTEXT* context) {
  const int code = gProj.proj_context_errno(context);
  const char* text = code != 0 ? gProj.proj_context_errno_string(context, code) : nullptr;
  return text != nullptr ? std::string(text) : std::string("no details");
}

/// The conversion factor of a CRS's first axis to SI (metres, or radians for angles); 0 when unknown.
double firstAxisFactor(PJ_CONTEXT* context, const PJ* crs) {
  PjHandle cs(gProj.proj_crs_get_coordinate_system(context, crs));
  if (cs.get() == nullptr) return 0.0;
  double factor = 0.0;
  if (!gProj.proj_cs_get_axis_info(context, cs.get(), 0, nullptr, nullptr, nullptr, &factor, nullptr, nullptr, nullptr))
    return 0.0;
  return factor;
}

}  // namespace

std::optional<Placement> parsePlacement(std::string_view text) {
  auto numbers = parseNumberList(text, 3);
  if (!numbers) numbers = parseNumberList(text, 2);
  if (!numbers) return std::nullopt;
  Placement placement{(*numbers)[0], (*numbers)[1], numbers->size() == 3 ? (*numbers)[2] : 0.0};
  if (!validLonLat(placement.lon, placement.lat) || std::abs(placement.lat) >= 89.0) return std::nullopt;
  return placement;
}

std::string epsgFromReferenceSystem(std::string_view text) {
  std::string upper;
  for (char c : text) upper.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
  if (upper.find("EPSG") == std::string::npos) return "";
  std::size_t begin = text.size();
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(text[begin - 1]))) --begin;
  if (begin == text.size() || begin == 0) return "";
  const char separator = text[begin - 1];
  if (separator != ':' && separator != '/') return "";
  return "EPSG:" + std::string(text.substr(begin));
}

glm::dvec2 rotateClockwise(glm::dvec2 xy, double degrees) {
  const double radians = degrees * std::numbers::pi / 180.0;
  const double c = std::cos(radians);
  const double s = std::sin(radians);
  return {xy.x * c + xy.y * s, -xy.x * s + xy.y * c};
}

CrsToLonLat::CrsToLonLat(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CrsToLonLat::CrsToLonLat(CrsToLonLat&&) noexcept = default;
CrsToLonLat& CrsToLonLat::operator=(CrsToLonLat&&) noexcept = default;
CrsToLonLat::~CrsToLonLat() = default;

Result<CrsToLonLat> CrsToLonLat::create(const std::string& crs) {
  auto impl = std::make_unique<Impl>();
  if (const std::string& error = loadProj(); !error.empty()) return Error{error};
  impl->context = gProj.proj_context_create();
  if (impl->context == nullptr) return Error{"PROJ: cannot create a context"};
  PJ_CONTEXT* context = impl->context;
  gProj.proj_log_level(context, PJ_LOG_NONE);

  PjHandle source(gProj.proj_create(context, crs.c_str()));
  if (source.get() == nullptr)
    return Error{"unknown coordinate reference system \"" + crs + "\" (PROJ: " + projError(context) + ")"};
  if (!gProj.proj_is_crs(source.get())) return Error{"\"" + crs + "\" is not a coordinate reference system"};
  const char* sourceName = gProj.proj_get_name(source.get());

  // A compound CRS (RD New + NAP, LV95 + LN02): the horizontal part is transformed, the vertical
  // part only tells the unit of heights.
  PjHandle horizontal;
  PjHandle vertical;
  PJ* horizontalCrs = source.get();
  if (gProj.proj_get_type(source.get()) == PJ_TYPE_COMPOUND_CRS) {
    horizontal.reset(gProj.proj_crs_get_sub_crs(context, source.get(), 0));
    vertical.reset(gProj.proj_crs_get_sub_crs(context, source.get(), 1));
    if (horizontal.get() == nullptr)
      return Error{"coordinate reference system \"" + crs + "\" has no horizontal part (PROJ: " + projError(context) +
                   ")"};
    horizontalCrs = horizontal.get();
  }
  const PJ_TYPE type = gProj.proj_get_type(horizontalCrs);
  const bool geographic = type == PJ_TYPE_GEOGRAPHIC_2D_CRS || type == PJ_TYPE_GEOGRAPHIC_3D_CRS;
  if (!geographic && type != PJ_TYPE_PROJECTED_CRS)
    return Error{"coordinate reference system \"" + crs +
                 "\" is neither projected nor geographic (geocentric, vertical or engineering CRSs are not supported)"};
  double horizontalFactor = 1.0;
  if (!geographic) {
    horizontalFactor = firstAxisFactor(context, horizontalCrs);
    if (!(horizontalFactor > 0.0)) return Error{"coordinate reference system \"" + crs + "\" has no known length unit"};
  }
  double verticalFactor = geographic ? 1.0 : horizontalFactor;
  if (vertical.get() != nullptr) {
    const double factor = firstAxisFactor(context, vertical.get());
    if (factor > 0.0) verticalFactor = factor;
  }

  PjHandle wgs84(gProj.proj_create(context, "EPSG:4326"));
  if (wgs84.get() == nullptr)
    return Error{"PROJ cannot create EPSG:4326 (is proj.db installed?): " + projError(context)};
  PjHandle operation(gProj.proj_create_crs_to_crs_from_pj(context, horizontalCrs, wgs84.get(), nullptr, nullptr));
  if (operation.get() == nullptr)
    return Error{"PROJ finds no transformation from \"" + crs + "\" to WGS84: " + projError(context)};
  // Longitude/latitude and easting/northing order, whatever the CRS's official axis order.
  impl->transformation = gProj.proj_normalize_for_visualization(context, operation.get());
  if (impl->transformation == nullptr)
    return Error{"PROJ cannot normalize the transformation from \"" + crs + "\": " + projError(context)};

  CrsToLonLat result(std::move(impl));
  result.geographic_ = geographic;
  result.horizontalMetresPerUnit_ = horizontalFactor;
  result.verticalMetresPerUnit_ = verticalFactor;
  result.name_ = sourceName != nullptr ? sourceName : crs;
  return result;
}

std::optional<glm::dvec2> CrsToLonLat::toLonLat(double x, double y) const {
  if (!std::isfinite(x) || !std::isfinite(y)) return std::nullopt;
  PJ_COORD in = gProj.proj_coord(x, y, 0.0, 0.0);
  const PJ_COORD out = gProj.proj_trans(impl_->transformation, PJ_FWD, in);
  if (gProj.proj_errno(impl_->transformation) != 0) {
    gProj.proj_errno_reset(impl_->transformation);
    return std::nullopt;
  }
  const double lon = out.xy.x;
  const double lat = out.xy.y;
  if (!validLonLat(lon, lat)) return std::nullopt;
  return glm::dvec2(lon, lat);
}

}  // namespace qv::prep
