# Fails when a pure engine library includes GL, Emscripten or ImGui headers or tests for
# __EMSCRIPTEN__. Pure libraries must compile natively and in WASM unchanged (STYLE.md, rule 1).
# Run: cmake -DSOURCE_DIR=<repo> -P tests/CheckLayering.cmake
set(pure_libraries core geometry scene spatial lod anim format seismic options quality)
set(forbidden "#[ \t]*include[ \t]*[<\"](GLES[23]?/|GL/|emscripten|imgui)|__EMSCRIPTEN__")
set(violations "")
foreach(lib IN LISTS pure_libraries)
  file(GLOB_RECURSE files "${SOURCE_DIR}/engine/${lib}/*.h" "${SOURCE_DIR}/engine/${lib}/*.cpp")
  foreach(f IN LISTS files)
    file(STRINGS "${f}" lines REGEX "${forbidden}")
    foreach(line IN LISTS lines)
      string(APPEND violations "  ${f}: ${line}\n")
    endforeach()
  endforeach()
endforeach()
if(violations)
  message(FATAL_ERROR "Pure engine libraries must not depend on a platform:\n${violations}")
endif()
message(STATUS "Layering ok: pure libraries include no GL, Emscripten or ImGui headers")
