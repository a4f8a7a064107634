// Building attributes of LOD2 models, by the rules of docs/attributes.md (prep::ingest's functions):
// a new building gets its height from its geometry and its storeys from the source or inferred by
// use; a replacement keeps the attributes of the LOD1 building it replaces, growing only when the
// model is taller. docs/lod2.md "Attributes" has the details.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "qv/format/BuildingAttributes.h"
#include "qv/prep/Lod2Model.h"

namespace qv::prep {

/// What a source says about a new building besides its geometry.
struct NewModelFacts {
  std::string id;  ///< cj:<id>, obj:<stem>
  std::string name;
  std::string function;           ///< a use in the words of docs/attributes.md ("office", "hospital"); else "unknown"
  std::optional<double> storeys;  ///< storeys above ground when the source gives them
  int startYear = 0;              ///< 0 when unknown
  std::uint32_t parts = 1;        ///< parts merged into the model (more than one: a complex building)
};

/// Attributes of a new building: heightM = the mesh's top above its ground (tagged: measured),
/// minHeightM 0, storeys from the facts (when 1 .. 255 and at least 1.5 m each) or
/// round(height / storey height of the use) (at least 1),
/// footprint area and centroid of `footprint`, the seismic attributes inferred, lod 2.
BuildingAttributes newModelAttributes(const NewModelFacts& facts, const Lod2Mesh& mesh,
                                      const std::vector<glm::dvec2>& footprint);

/// Makes `attributes` those of the existing building with lod 2. When the model's top
/// (`modelHeightM`) is higher than the existing height by more than 1 cm, heightM becomes the
/// model's top, storeys are re-inferred unless they were tagged, and the seismic attributes are
/// inferred again. The footprint area and centroid become the model's (`footprint`, when it has
/// three points or more): what is drawn, picked and flown to is the model.
BuildingAttributes replacementAttributes(const BuildingAttributes& existing, double modelHeightM, bool hasParts,
                                         const std::vector<glm::dvec2>& footprint = {});

}  // namespace qv::prep
