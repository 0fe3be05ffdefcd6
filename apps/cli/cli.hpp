// The command line as a function: apps/cli/main.cpp runs it as `pdesurf`, and tests run it
// in-process (tests/model/toy_method_test.cpp, with a surface method of its own registered).
#pragma once

namespace pdesurf::cli {

/// Parses argv (argv[0] the program) and runs the command: 0 success, 1 bad input, 2 usage
/// error (apps/cli/cli_common.hpp). Prints to stdout and stderr.
int runCli(int argc, char** argv);

}  // namespace pdesurf::cli
