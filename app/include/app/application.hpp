// The ghostspace command line: window, --snapshot, info.
#pragma once

namespace gs::app {

/// Runs the program with its command-line arguments; returns the process exit code
/// (0 success, 1 runtime failure, 2 bad usage).
int run(int argc, char** argv);

}  // namespace gs::app
