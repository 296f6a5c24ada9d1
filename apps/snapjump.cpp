#include <unistd.h>

#include <cstdlib>
#include <iostream>

#include "app/cli.hpp"

int main(int argc, char** argv) {
  // OpenMP threads that wait for each other by spinning make a step a hundred times slower when
  // another process keeps a core busy (docs/performance.md, "Threads under load"). libgomp reads
  // its wait policy when it is loaded, before main, so the program starts itself again once with
  // the passive policy, unless the user has chosen a policy. If that fails it goes on as it is.
  if (std::getenv("OMP_WAIT_POLICY") == nullptr) {
    ::setenv("OMP_WAIT_POLICY", "passive", 1);
    ::execv("/proc/self/exe", argv);
  }
  return snapjump::app::run_cli(argc, argv, std::cout, std::cerr);
}
