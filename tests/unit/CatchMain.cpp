// The one translation unit that holds Catch2's runner. Every run of every test executable fails
// on a test that checks nothing, whatever its command line: a test case or section that ran no
// assertion (Catch2's NoAssertions warning) and a test name that matches no test case (NoTests).
// Catch2 2.x takes one --warn on the command line, so both are set here.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

int main(int argc, char* argv[]) {
  Catch::Session session;
  if (const int status = session.applyCommandLine(argc, argv); status != 0) return status;
  Catch::ConfigData& config = session.configData();
  config.warnings =
      static_cast<Catch::WarnAbout::What>(config.warnings | Catch::WarnAbout::NoAssertions | Catch::WarnAbout::NoTests);
  session.useConfigData(config);
  return session.run();
}
