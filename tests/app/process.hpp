// Runs the real ghostspace executable for end-to-end tests.
#pragma once

#include <string>
#include <vector>

namespace gs::test {

struct ProcessResult {
  int exitCode = -1;  // -1 when the process did not exit normally (signal)
  std::string out;    // stdout
  std::string err;    // stderr
};

/// Runs GS_EXECUTABLE with `args` (no shell), waits for it, captures stdout and stderr.
/// `env` entries ("NAME=value") are added to the environment.
ProcessResult runGhostspace(const std::vector<std::string>& args,
                            const std::vector<std::string>& env = {});

}  // namespace gs::test
