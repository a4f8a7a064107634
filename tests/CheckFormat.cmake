# Fails when a C++ file of the project differs from .clang-format's layout.
# Run: cmake -DSOURCE_DIR=<repo> -P tests/CheckFormat.cmake   (fix: clang-format -i <files>)
find_program(CLANG_FORMAT NAMES clang-format clang-format-14)
if(NOT CLANG_FORMAT)
  message(FATAL_ERROR "clang-format not found: run scripts/setup.sh")
endif()
file(GLOB_RECURSE files
  "${SOURCE_DIR}/engine/*.h" "${SOURCE_DIR}/engine/*.cpp"
  "${SOURCE_DIR}/preprocess/*.h" "${SOURCE_DIR}/preprocess/*.cpp"
  "${SOURCE_DIR}/tests/*.h" "${SOURCE_DIR}/tests/*.cpp")
list(FILTER files EXCLUDE REGEX "/tests/data/|/node_modules/")
execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror ${files}
                RESULT_VARIABLE rc ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "Files not formatted per .clang-format (run clang-format -i on them):\n${out}")
endif()
list(LENGTH files n)
message(STATUS "Format ok: ${n} files")
