// fuzz_obj: OBJ files through our reader (tinyobjloader) and the whole LOD2 finishing step
// (re-meshing at floor planes, skinning, far mesh): a model or an error naming the file, never a
// crash; a finished model keeps the skinning contract.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "IngestFuzzSupport.h"
#include "qv/prep/Lod2Finish.h"
#include "qv/prep/Lod2Obj.h"
#include "qv/prep/Projection.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path =
      qv::fuzz::writeInput(std::string_view(reinterpret_cast<const char*>(data), size), "model.obj");
  const qv::prep::CityProjection projection(-74.0, 40.71);
  qv::prep::ObjPlacement placement;
  placement.lon = -74.0;
  placement.lat = 40.71;
  auto model = qv::prep::readObjModel(path, placement, projection);
  if (!model.ok()) {
    qv::fuzz::check(model.error().find("model.obj") != std::string::npos,
                    "OBJ error does not name the file:", model.error());
    return 0;
  }
  qv::prep::FinishOptions options;
  options.remesh.maxVertices = 200000;  // bounded work per input
  const qv::Status finished = qv::prep::finishModel(*model, options);
  if (!finished.ok()) return 0;
  const auto& skinned = model->skinned;
  qv::fuzz::check(skinned.finished, "a finished model is marked finished");
  for (const std::uint32_t i : skinned.mesh.triangles)
    qv::fuzz::check(i < skinned.mesh.positions.size(), "re-meshed index out of range");
  return 0;
}
