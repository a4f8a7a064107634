// OBJ through tinyobjloader, which reports with a bool and message strings. It only warns about
// vertex indices out of range (and would read past its arrays if asked to triangulate them), so its
// own triangulation is off: indices are checked here and faces are triangulated in their plane.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <unordered_map>

#include <tiny_obj_loader.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "qv/core/NumberFormat.h"
#include "qv/prep/Files.h"
#include "qv/prep/Lod2Attributes.h"
#include "qv/prep/Lod2Geometry.h"
#include "qv/prep/Lod2Georeference.h"
#include "qv/prep/Lod2Obj.h"

namespace qv::prep {
namespace {

std::string lower(std::string_view text) {
  std::string out;
  for (char c : text) out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

std::string trimmed(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  return text;
}

}  // namespace

std::optional<ModelUnit> parseModelUnit(std::string_view text) {
  const std::string t = lower(text);
  if (t == "m" || t == "metre" || t == "meter" || t == "metres" || t == "meters") return ModelUnit::Metre;
  if (t == "cm" || t == "centimetre" || t == "centimeter") return ModelUnit::Centimetre;
  if (t == "mm" || t == "millimetre" || t == "millimeter") return ModelUnit::Millimetre;
  if (t == "ft" || t == "foot" || t == "feet") return ModelUnit::Foot;
  return std::nullopt;
}

double metresPerUnit(ModelUnit unit) {
  switch (unit) {
    case ModelUnit::Metre:
      return 1.0;
    case ModelUnit::Centimetre:
      return 0.01;
    case ModelUnit::Millimetre:
      return 0.001;
    case ModelUnit::Foot:
      return 0.3048;
  }
  return 1.0;
}

std::optional<UpAxis> parseUpAxis(std::string_view text) {
  const std::string t = lower(text);
  if (t == "y" || t == "y-up" || t == "+y") return UpAxis::Y;
  if (t == "z" || t == "z-up" || t == "+z") return UpAxis::Z;
  return std::nullopt;
}

Result<Lod2Model> readObjModel(const std::string& path, const ObjPlacement& placement,
                               const CityProjection& projection) {
  if (!(placement.scale > 0.0) || !std::isfinite(placement.scale) || !std::isfinite(placement.rotationDeg))
    return Error{path + ": the OBJ placement needs a positive scale and a finite rotation"};
  Result<std::string> text = readTextFile(path, 2ull << 30);
  if (!text.ok()) return Error{text.error()};
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // From a string: materials are not needed and no other file is opened.
  if (!reader.ParseFromString(*text, "", config)) {
    const std::string error = trimmed(reader.Error());
    return Error{path + ": malformed OBJ: " + (error.empty() ? std::string("tinyobjloader gave no reason") : error)};
  }
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const std::size_t vertexCount = attrib.vertices.size() / 3;
  const double unitScale = metresPerUnit(placement.unit) * placement.scale;

  // Model coordinates to metres, east/north/up, before placement.
  std::vector<glm::dvec3> local(vertexCount);
  for (std::size_t i = 0; i < vertexCount; ++i) {
    const double x = static_cast<double>(attrib.vertices[3 * i]);
    const double y = static_cast<double>(attrib.vertices[3 * i + 1]);
    const double z = static_cast<double>(attrib.vertices[3 * i + 2]);
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
      return Error{path + ": vertex " + std::to_string(i + 1) + " has a coordinate that is not a finite number"};
    local[i] = placement.up == UpAxis::Y ? glm::dvec3(x, -z, y) : glm::dvec3(x, y, z);
    local[i] *= unitScale;
  }

  Lod2Mesh mesh;
  std::unordered_map<std::uint32_t, std::uint32_t> used;  // OBJ vertex -> mesh vertex
  std::vector<glm::dvec3> facePoints;
  std::vector<std::uint32_t> faceIds;
  std::vector<std::uint32_t> faceTriangles;
  std::uint64_t facesSkipped = 0;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const std::string object = shape.name.empty() ? std::string("(unnamed)") : "\"" + shape.name + "\"";
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const std::size_t count = shape.mesh.num_face_vertices[f];
      if (offset + count > shape.mesh.indices.size())
        return Error{path + ": object " + object + " face " + std::to_string(f + 1) +
                     ": more vertices than the file lists (a face with more than 255 corners?)"};
      facePoints.clear();
      faceIds.clear();
      for (std::size_t k = 0; k < count; ++k) {
        const int index = shape.mesh.indices[offset + k].vertex_index;
        if (index < 0 || static_cast<std::size_t>(index) >= vertexCount)
          return Error{path + ": object " + object + " face " + std::to_string(f + 1) + ": vertex index " +
                       std::to_string(index + 1) + " out of range (" + std::to_string(vertexCount) + " vertices)"};
        const auto id = static_cast<std::uint32_t>(index);
        if (!faceIds.empty() && faceIds.back() == id) continue;
        faceIds.push_back(id);
        facePoints.push_back(local[id]);
      }
      offset += count;
      while (faceIds.size() > 1 && faceIds.back() == faceIds.front()) {
        faceIds.pop_back();
        facePoints.pop_back();
      }
      faceTriangles.clear();
      const std::uint32_t ringEnd = static_cast<std::uint32_t>(faceIds.size());
      if (faceIds.size() < 3 ||
          !triangulateFace(facePoints, std::span<const std::uint32_t>(&ringEnd, 1), faceTriangles)) {
        ++facesSkipped;
        continue;
      }
      for (std::uint32_t t : faceTriangles) {
        const auto [it, inserted] = used.emplace(faceIds[t], static_cast<std::uint32_t>(mesh.positions.size()));
        if (inserted) mesh.positions.push_back(local[faceIds[t]]);
        mesh.triangles.push_back(it->second);
      }
    }
    if (offset != shape.mesh.indices.size())
      return Error{path + ": object " + object +
                   ": face vertex counts do not match the indices (a face with more "
                   "than 255 corners?)"};
  }
  if (mesh.triangles.empty())
    return Error{path + ": no faces with an area (" + std::to_string(facesSkipped) + " degenerate faces, " +
                 std::to_string(vertexCount) + " vertices)"};

  // Placement: ground at the lowest vertex, the anchor point at the city position of lon/lat.
  glm::dvec3 lowest = mesh.positions.front();
  glm::dvec3 highest = lowest;
  for (const glm::dvec3& p : mesh.positions) {
    lowest = glm::min(lowest, p);
    highest = glm::max(highest, p);
  }
  if (!(highest.z - lowest.z > 0.0))
    return Error{path + ": the model is flat (no height after the up-axis conversion: is the up axis right?)"};
  const glm::dvec3 size = highest - lowest;
  if (!(size.z <= kMaxModelHeightM) || !(size.x <= kMaxModelExtentM) || !(size.y <= kMaxModelExtentM))
    return Error{path + ": the model measures " + formatDouble(size.x) + " x " + formatDouble(size.y) + " x " +
                 formatDouble(size.z) + " m (at most " + formatDouble(kMaxModelExtentM) + " m wide and " +
                 formatDouble(kMaxModelHeightM) + " m tall): are the unit and scale right?"};
  const glm::dvec2 centre =
      placement.centreOnAnchor ? 0.5 * (glm::dvec2(lowest) + glm::dvec2(highest)) : glm::dvec2(0.0);
  const glm::dvec2 anchor = projection.forward(placement.lon, placement.lat);
  for (glm::dvec3& p : mesh.positions) {
    const glm::dvec2 xy = rotateClockwise(glm::dvec2(p) - centre, placement.rotationDeg) + anchor;
    p = glm::dvec3(xy, p.z - lowest.z);
  }
  mesh.kinds.reserve(mesh.triangles.size() / 3);
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    const glm::dvec3& a = mesh.positions[mesh.triangles[t]];
    const glm::dvec3& b = mesh.positions[mesh.triangles[t + 1]];
    const glm::dvec3& c = mesh.positions[mesh.triangles[t + 2]];
    mesh.kinds.push_back(kindFromNormal(glm::cross(b - a, c - a), std::max({a.z, b.z, c.z}) <= 0.01));
  }

  const std::filesystem::path file(path);
  Lod2Model model;
  model.id = "obj:" + file.stem().string();
  model.source = "obj:" + file.filename().string();
  model.footprint = groundFootprint(mesh);
  NewModelFacts facts;
  facts.id = model.id;
  model.attributes = newModelAttributes(facts, mesh, model.footprint);
  model.verticesBefore = static_cast<std::uint32_t>(mesh.positions.size());
  model.skinned.mesh = std::move(mesh);
  return model;
}

}  // namespace qv::prep
