// GLSL ES 3.00 sources of the render layer's programs.
#pragma once

namespace qv::shaders {

extern const char* const kBuildingVertex;
extern const char* const kBuildingFragment;
extern const char* const kGroundVertex;
extern const char* const kGroundFragment;

}  // namespace qv::shaders
