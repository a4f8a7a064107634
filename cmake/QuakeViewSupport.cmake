# Helpers shared by every CMakeLists.txt of the project: dependency discovery for both toolchains,
# the project's warning set, sanitizers, and the library/test/executable conventions.

# ---------------------------------------------------------------------------------------------
# Emscripten version pin: emsdk-version.txt holds the one version the project is built and tested
# with (Debian 12's package). Another version fails here, before anything is compiled.
function(quakeview_check_emscripten_version)
  file(READ "${CMAKE_SOURCE_DIR}/emsdk-version.txt" wanted)
  string(STRIP "${wanted}" wanted)
  execute_process(COMMAND "${CMAKE_C_COMPILER}" --version
                  OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
  string(REGEX MATCH "emcc \\([^)]*\\) ([0-9]+\\.[0-9]+\\.[0-9]+)" _ "${out}")
  set(found "${CMAKE_MATCH_1}")
  if(NOT rc EQUAL 0 OR found STREQUAL "")
    message(FATAL_ERROR "Could not read the Emscripten version from '${CMAKE_C_COMPILER} --version' "
                        "(exit ${rc}): ${out}${err}")
  endif()
  if(NOT found STREQUAL wanted)
    message(FATAL_ERROR "Emscripten ${found} found, but this project is pinned to ${wanted} "
                        "(emsdk-version.txt). Install Debian 12's emscripten package "
                        "(scripts/setup.sh does) or put emcc ${wanted} first on PATH.")
  endif()
  message(STATUS "Emscripten ${found} (pinned ${wanted})")
endfunction()

# ---------------------------------------------------------------------------------------------
# Dependencies. Natively they come from Debian's packages. In the WebAssembly build only
# header-only libraries are used from /usr/include, through build-tree folders that link just the
# one library (adding /usr/include itself would let host headers shadow Emscripten's sysroot), and
# compiled libraries come from the Debian source packages unpacked by scripts/setup.sh.
function(quakeview_link_headers name source)
  set(dir "${CMAKE_BINARY_DIR}/system-include/${name}")
  file(MAKE_DIRECTORY "${dir}")
  get_filename_component(leaf "${source}" NAME)
  if(NOT EXISTS "${dir}/${leaf}")
    file(CREATE_LINK "${source}" "${dir}/${leaf}" SYMBOLIC)
  endif()
  set(QUAKEVIEW_LINK_DIR "${dir}" PARENT_SCOPE)
endfunction()

macro(quakeview_require_deps_file path what)
  if(NOT EXISTS "${QUAKEVIEW_DEPS_DIR}/${path}")
    message(FATAL_ERROR "${what} not found at ${QUAKEVIEW_DEPS_DIR}/${path}. "
                        "Run scripts/setup.sh (it unpacks Debian's source packages there).")
  endif()
endmacro()

macro(quakeview_find_dependencies)
  # GLM: header-only, always as a SYSTEM include (0.9.9.8 is not -Werror clean under C++20).
  add_library(quakeview_glm INTERFACE)
  # Through a link folder in both builds: never -isystem /usr/include (it breaks #include_next in
  # libstdc++ natively and lets host headers shadow the sysroot in WASM).
  if(NOT EXISTS /usr/include/glm/glm.hpp)
    message(FATAL_ERROR "GLM not found in /usr/include/glm: run scripts/setup.sh (libglm-dev)")
  endif()
  quakeview_link_headers(glm /usr/include/glm)
  target_include_directories(quakeview_glm SYSTEM INTERFACE "${QUAKEVIEW_LINK_DIR}")
  target_compile_definitions(quakeview_glm INTERFACE GLM_FORCE_XYZW_ONLY GLM_ENABLE_EXPERIMENTAL)
  add_library(glm::quakeview ALIAS quakeview_glm)

  # simdjson: Debian's library natively; the source package's single header in WASM (its portable
  # "fallback" kernel). Compiled without the project's warnings.
  if(EMSCRIPTEN)
    quakeview_require_deps_file(simdjson/singleheader/simdjson.cpp "simdjson 3.0.1 sources")
    add_library(quakeview_simdjson STATIC "${QUAKEVIEW_DEPS_DIR}/simdjson/singleheader/simdjson.cpp")
    target_include_directories(quakeview_simdjson SYSTEM PUBLIC "${QUAKEVIEW_DEPS_DIR}/simdjson/singleheader")
    target_compile_definitions(quakeview_simdjson PUBLIC SIMDJSON_EXCEPTIONS=0)
    add_library(simdjson::quakeview ALIAS quakeview_simdjson)
  else()
    find_package(simdjson REQUIRED CONFIG)
    add_library(quakeview_simdjson INTERFACE)
    target_link_libraries(quakeview_simdjson INTERFACE simdjson::simdjson)
    add_library(simdjson::quakeview ALIAS quakeview_simdjson)
  endif()

  # Zstandard (response files are stored as zstd frames, docs/formats.md "Compressed files"):
  # Debian's library natively; in WASM Debian's source package 1.5.4 in portable C (no x86
  # assembly), without threads. The viewer links only the decoder (a static library's unused
  # objects stay out); the wasm unit tests make frames with its encoder. No project warnings.
  if(EMSCRIPTEN)
    quakeview_require_deps_file(zstd/lib/zstd.h "Zstandard 1.5.4 sources")
    set(zstd_lib "${QUAKEVIEW_DEPS_DIR}/zstd/lib")
    file(GLOB zstd_sources "${zstd_lib}/common/*.c" "${zstd_lib}/compress/*.c" "${zstd_lib}/decompress/*.c")
    add_library(quakeview_zstd STATIC ${zstd_sources})
    target_include_directories(quakeview_zstd SYSTEM PUBLIC "${zstd_lib}")
    target_compile_definitions(quakeview_zstd PRIVATE ZSTD_DISABLE_ASM=1 ZSTD_LEGACY_SUPPORT=0)
  else()
    find_path(QUAKEVIEW_ZSTD_INCLUDE zstd.h REQUIRED)
    find_library(QUAKEVIEW_ZSTD_LIBRARY zstd REQUIRED)
    add_library(quakeview_zstd INTERFACE)
    target_link_libraries(quakeview_zstd INTERFACE "${QUAKEVIEW_ZSTD_LIBRARY}")
  endif()
  add_library(zstd::quakeview ALIAS quakeview_zstd)

  # GeographicLib (transverse Mercator, for lon/lat in the viewer and the tools): Debian's library
  # natively; in WASM the two source files it needs, from Debian's source package 2.1.2, with a
  # Config.h written here (the package generates it at configure time).
  if(EMSCRIPTEN)
    quakeview_require_deps_file(geographiclib/src/TransverseMercator.cpp "GeographicLib 2.1.2 sources")
    set(geo_config "${CMAKE_BINARY_DIR}/geographiclib-config/GeographicLib/Config.h")
    file(WRITE "${geo_config}.in"
      "#define GEOGRAPHICLIB_VERSION_STRING \"2.1.2\"\n#define GEOGRAPHICLIB_VERSION_MAJOR 2\n"
      "#define GEOGRAPHICLIB_VERSION_MINOR 1\n#define GEOGRAPHICLIB_VERSION_PATCH 2\n"
      "#define GEOGRAPHICLIB_DATA \"\"\n#define GEOGRAPHICLIB_HAVE_LONG_DOUBLE 1\n"
      "#define GEOGRAPHICLIB_WORDS_BIGENDIAN 0\n#define GEOGRAPHICLIB_PRECISION 2\n"
      "#define GEOGRAPHICLIB_SHARED_LIB 0\n")
    configure_file("${geo_config}.in" "${geo_config}" COPYONLY)
    add_library(quakeview_geographiclib STATIC
      "${QUAKEVIEW_DEPS_DIR}/geographiclib/src/Math.cpp"
      "${QUAKEVIEW_DEPS_DIR}/geographiclib/src/TransverseMercator.cpp")
    target_include_directories(quakeview_geographiclib SYSTEM PUBLIC
      "${CMAKE_BINARY_DIR}/geographiclib-config" "${QUAKEVIEW_DEPS_DIR}/geographiclib/include")
  else()
    list(APPEND CMAKE_MODULE_PATH /usr/share/cmake/geographiclib)
    find_package(GeographicLib REQUIRED)
    add_library(quakeview_geographiclib INTERFACE)
    target_include_directories(quakeview_geographiclib SYSTEM INTERFACE ${GeographicLib_INCLUDE_DIRS})
    target_link_libraries(quakeview_geographiclib INTERFACE ${GeographicLib_LIBRARIES})
  endif()
  add_library(geographiclib::quakeview ALIAS quakeview_geographiclib)

  # Dear ImGui 1.86 from Debian's source package, for both builds (the UI layer is also compiled
  # natively so its text mirror can be tested without a browser).
  quakeview_require_deps_file(imgui/imgui.cpp "Dear ImGui 1.86 sources")
  set(imgui_dir "${QUAKEVIEW_DEPS_DIR}/imgui")
  add_library(quakeview_imgui STATIC
    "${imgui_dir}/imgui.cpp"
    "${imgui_dir}/imgui_draw.cpp"
    "${imgui_dir}/imgui_tables.cpp"
    "${imgui_dir}/imgui_widgets.cpp")
  target_include_directories(quakeview_imgui SYSTEM PUBLIC "${imgui_dir}")
  target_compile_definitions(quakeview_imgui PUBLIC IMGUI_DISABLE_OBSOLETE_FUNCTIONS)
  add_library(imgui::imgui ALIAS quakeview_imgui)
  # The panels are drawn by engine::render's GlImGuiRenderer, not by ImGui's OpenGL3 backend (which
  # re-specifies its buffers every frame: see GlImGuiRenderer.h).

  # Catch2 v2 (header-only): Debian's package natively, its header through a link folder in WASM.
  if(QUAKEVIEW_TESTS OR QUAKEVIEW_BENCHMARKS)
    if(EMSCRIPTEN)
      quakeview_link_headers(catch2 /usr/include/catch2)
      add_library(quakeview_catch2 INTERFACE)
      target_include_directories(quakeview_catch2 SYSTEM INTERFACE "${QUAKEVIEW_LINK_DIR}")
      add_library(Catch2::Catch2 ALIAS quakeview_catch2)
    else()
      find_package(Catch2 2 REQUIRED CONFIG)
      include(Catch)
    endif()
  endif()

  if(NOT EMSCRIPTEN)
    find_package(Threads REQUIRED)
  endif()
endmacro()

# ---------------------------------------------------------------------------------------------
# Warnings and sanitizers, applied to the project's own targets only.
set(QUAKEVIEW_WARNINGS -Wall -Wextra -Wconversion -Wshadow -Wpedantic -Wnon-virtual-dtor
    -Wold-style-cast -Wcast-align -Woverloaded-virtual -Wnull-dereference
    -Wimplicit-fallthrough)
if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  list(APPEND QUAKEVIEW_WARNINGS -Wsign-conversion -Wshorten-64-to-32)
else()
  list(APPEND QUAKEVIEW_WARNINGS -Wsign-conversion)
endif()

if(QUAKEVIEW_SANITIZE AND NOT EMSCRIPTEN)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=undefined
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
  if(QUAKEVIEW_FUZZ)
    # libosmium's PBF parser passes a null pointer with size 0 to memcpy on malformed blob headers
    # (third-party code): recoverable, and suppressed in scripts/fuzz.sh (tests/fuzz/ubsan-suppressions.txt).
    add_compile_options(-fsanitize-recover=nonnull-attribute)
  endif()
endif()

function(quakeview_apply_warnings target)
  target_compile_options(${target} PRIVATE ${QUAKEVIEW_WARNINGS})
  if(QUAKEVIEW_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

# quakeview_add_library(<name> SOURCES ... [PUBLIC ...] [PRIVATE ...])
# Creates target engine_<name> (alias engine::<name>) with public headers under include/.
function(quakeview_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(engine_${name} STATIC ${ARG_SOURCES})
  add_library(engine::${name} ALIAS engine_${name})
  target_include_directories(engine_${name} PUBLIC "${CMAKE_CURRENT_SOURCE_DIR}/include")
  target_link_libraries(engine_${name} PUBLIC ${ARG_PUBLIC} PRIVATE ${ARG_PRIVATE})
  quakeview_apply_warnings(engine_${name})
endfunction()
