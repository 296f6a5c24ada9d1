// libFuzzer entry: the target is named by the environment variable SNAPJUMP_FUZZ_TARGET (one of
// fuzz::targets()); `make fuzz` runs each in turn. Built only with -DSNAPJUMP_FUZZ=ON and clang.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "fuzz/targets.hpp"

namespace {
const snapjump::fuzz::Target* chosen() {
  static const snapjump::fuzz::Target* t = [] {
    const char* name = std::getenv("SNAPJUMP_FUZZ_TARGET");
    const auto* found = name != nullptr ? snapjump::fuzz::find_target(name) : nullptr;
    if (found == nullptr) {
      std::fprintf(stderr, "set SNAPJUMP_FUZZ_TARGET to one of:");
      for (const auto& x : snapjump::fuzz::targets()) std::fprintf(stderr, " %s", x.name);
      std::fprintf(stderr, "\n");
      std::exit(2);
    }
    return found;
  }();
  return t;
}
}  // namespace

// Called once before the first input: the chosen target's one-time setup runs here, outside the
// time that -timeout allows each input.
extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  if (const auto* t = chosen(); t->setup != nullptr) t->setup();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  chosen()->run(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}
