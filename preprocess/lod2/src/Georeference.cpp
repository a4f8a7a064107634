// PROJ through its C API: every object checked for null, errors read from the context, logging
// off (PROJ would otherwise print to stderr), one context per transformation.
#include "qv/prep/Lod2Georeference.h"

#include <cctype>
#include <cmath>
#include <numbers>

#include <proj.h>

#include "qv/prep/Cli.h"
#include "qv/prep/Projection.h"

namespace qv::prep {

struct CrsToLonLat::Impl {
  PJ_CONTEXT* context = nullptr;
  PJ* transformation = nullptr;
  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  ~Impl() {
    if (transformation != nullptr) proj_destroy(transformation);
    if (context != nullptr) proj_context_destroy(context);
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
    if (pj_ != nullptr) proj_destroy(pj_);
  }
  void reset(PJ* pj) {
    if (pj_ != nullptr) proj_destroy(pj_);
    pj_ = pj;
  }
  [[nodiscard]] PJ* get() const { return pj_; }

 private:
  PJ* pj_;
};

std::string projError(PJ_CONTEXT* context) {
  const int code = proj_context_errno(context);
  const char* text = code != 0 ? proj_context_errno_string(context, code) : nullptr;
  return text != nullptr ? std::string(text) : std::string("no details");
}

/// The conversion factor of a CRS's first axis to SI (metres, or radians for angles); 0 when unknown.
double firstAxisFactor(PJ_CONTEXT* context, const PJ* crs) {
  PjHandle cs(proj_crs_get_coordinate_system(context, crs));
  if (cs.get() == nullptr) return 0.0;
  double factor = 0.0;
  if (!proj_cs_get_axis_info(context, cs.get(), 0, nullptr, nullptr, nullptr, &factor, nullptr, nullptr, nullptr))
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
  impl->context = proj_context_create();
  if (impl->context == nullptr) return Error{"PROJ: cannot create a context"};
  PJ_CONTEXT* context = impl->context;
  proj_log_level(context, PJ_LOG_NONE);

  PjHandle source(proj_create(context, crs.c_str()));
  if (source.get() == nullptr)
    return Error{"unknown coordinate reference system \"" + crs + "\" (PROJ: " + projError(context) + ")"};
  if (!proj_is_crs(source.get())) return Error{"\"" + crs + "\" is not a coordinate reference system"};
  const char* sourceName = proj_get_name(source.get());

  // A compound CRS (RD New + NAP, LV95 + LN02): the horizontal part is transformed, the vertical
  // part only tells the unit of heights.
  PjHandle horizontal;
  PjHandle vertical;
  PJ* horizontalCrs = source.get();
  if (proj_get_type(source.get()) == PJ_TYPE_COMPOUND_CRS) {
    horizontal.reset(proj_crs_get_sub_crs(context, source.get(), 0));
    vertical.reset(proj_crs_get_sub_crs(context, source.get(), 1));
    if (horizontal.get() == nullptr)
      return Error{"coordinate reference system \"" + crs + "\" has no horizontal part (PROJ: " + projError(context) +
                   ")"};
    horizontalCrs = horizontal.get();
  }
  const PJ_TYPE type = proj_get_type(horizontalCrs);
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

  PjHandle wgs84(proj_create(context, "EPSG:4326"));
  if (wgs84.get() == nullptr)
    return Error{"PROJ cannot create EPSG:4326 (is proj.db installed?): " + projError(context)};
  PjHandle operation(proj_create_crs_to_crs_from_pj(context, horizontalCrs, wgs84.get(), nullptr, nullptr));
  if (operation.get() == nullptr)
    return Error{"PROJ finds no transformation from \"" + crs + "\" to WGS84: " + projError(context)};
  // Longitude/latitude and easting/northing order, whatever the CRS's official axis order.
  impl->transformation = proj_normalize_for_visualization(context, operation.get());
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
  PJ_COORD in = proj_coord(x, y, 0.0, 0.0);
  const PJ_COORD out = proj_trans(impl_->transformation, PJ_FWD, in);
  if (proj_errno(impl_->transformation) != 0) {
    proj_errno_reset(impl_->transformation);
    return std::nullopt;
  }
  const double lon = out.xy.x;
  const double lat = out.xy.y;
  if (!validLonLat(lon, lat)) return std::nullopt;
  return glm::dvec2(lon, lat);
}

}  // namespace qv::prep
