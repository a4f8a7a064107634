// Wavefront OBJ models (tinyobjloader) placed in the city by the caller: OBJ files carry no
// georeference, so an anchor longitude/latitude, a rotation, a scale, the file's length unit and
// its up axis say where and how the model stands.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "qv/core/Result.h"
#include "qv/prep/Lod2Model.h"
#include "qv/prep/Projection.h"

namespace qv::prep {

/// Length unit of a model file's coordinates.
enum class ModelUnit : std::uint8_t { Metre, Centimetre, Millimetre, Foot };
/// "m"/"metre"/"meter", "cm", "mm", "ft"/"foot"/"feet"; nullopt otherwise.
std::optional<ModelUnit> parseModelUnit(std::string_view text);
double metresPerUnit(ModelUnit unit);  ///< 1, 0.01, 0.001, 0.3048

/// Which model axis points up. Y-up (most OBJ exporters, Blender's default) maps a model point
/// (x, y, z) to east x, north -z, up y (the glTF convention); Z-up maps it as is.
enum class UpAxis : std::uint8_t { Y, Z };
std::optional<UpAxis> parseUpAxis(std::string_view text);  ///< "y", "z" (any case)

struct ObjPlacement {
  double lon = 0.0;  ///< anchor, WGS84 degrees
  double lat = 0.0;
  double rotationDeg = 0.0;  ///< clockwise from north, about the anchor
  double scale = 1.0;        ///< applied after the unit conversion
  ModelUnit unit = ModelUnit::Metre;
  UpAxis up = UpAxis::Y;
  /// false: the model's origin (0, 0) goes to the anchor; true: its footprint centre (the centre of
  /// its horizontal bounds, as the CityJSON placement does).
  bool centreOnAnchor = false;
};

/// Reads an OBJ file as one model (all objects and groups merged): id "obj:<file stem>", source
/// "obj:<file name>", kinds by normal, ground at the lowest vertex, attributes of a new building
/// (use "unknown", height from the geometry, storeys inferred), lod 2. Not yet re-meshed (see
/// finishModel). Fails, naming the file and the line or face, for unreadable or malformed files
/// (tinyobjloader's message), vertex indices out of range, non-finite coordinates, files without
/// faces, flat models and models larger than kMaxModelExtentM / kMaxModelHeightM (a wrong unit).
Result<Lod2Model> readObjModel(const std::string& path, const ObjPlacement& placement,
                               const CityProjection& projection);

}  // namespace qv::prep
