// Runs a built command-line tool for the native command tests and collects what it prints.
#pragma once

#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdio>
#include <string>

namespace qv::test {

struct ToolRun {
  int exitCode = -1;  ///< the tool's exit code, -1 when it did not exit normally
  std::string output;
};

/// Runs `'tool' arguments` through the shell: stdout only, or stdout and stderr together.
inline ToolRun runTool(const std::string& tool, const std::string& arguments, bool withStderr = false) {
  const std::string command = "'" + tool + "' " + arguments + (withStderr ? " 2>&1" : " 2>/dev/null");
  ToolRun r;
  std::FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  char buffer[4096];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace qv::test
