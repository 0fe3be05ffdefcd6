// pdesurf: the command line (apps/cli/cli.cpp runs it).
#include <csignal>

#include "cli.hpp"

int main(int argc, char** argv) {
  // Past a file-size limit, a write should fail (and the temporary file go) rather than
  // the process be killed mid-write.
  std::signal(SIGXFSZ, SIG_IGN);
  return pdesurf::cli::runCli(argc, argv);
}
