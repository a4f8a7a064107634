// GLSL ES 3.00 sources of the render layer's programs, and the one function that builds them.
#pragma once

#include <string>

namespace qv::shaders {

extern const char* const kBuildingVertex;
extern const char* const kBuildingFragment;
extern const char* const kGroundVertex;
extern const char* const kGroundFragment;
extern const char* const kGroundMapVertex;
extern const char* const kGroundMapFragment;
extern const char* const kMarkerVertex;
extern const char* const kMarkerFragment;
extern const char* const kUiVertex;
extern const char* const kUiFragment;
extern const char* const kUiCopyVertex;
extern const char* const kUiCopyFragment;

/// Compiles and links a program from a vertex and a fragment shader (GlProgram.cpp). Returns 0 and sets `error`
/// (which shader, and the driver's log) on failure. Needs a current context.
unsigned linkProgram(const char* vertex, const char* fragment, std::string& error);

}  // namespace qv::shaders
