// Every input kept for the fuzz targets (tests/data/fuzz/<target>/: the seeds of `make fuzz` and
// every input that ever made a reader crash, hang or throw what it does not document) is refused
// or read cleanly by the readers as built for the suite.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "fuzz/targets.hpp"

namespace snapjump::fuzz {
namespace {

namespace fs = std::filesystem;

TEST(FuzzReplay, EveryKeptInputIsReadOrRefusedWithTheReadersError) {
  const fs::path root = fs::path(SNAPJUMP_SOURCE_DIR) / "tests" / "data" / "fuzz";
  int inputs = 0;
  for (const auto& target : targets()) {
    const fs::path dir = root / target.name;
    ASSERT_TRUE(fs::is_directory(dir)) << dir << ": every target keeps at least its seeds";
    int here = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (!entry.is_regular_file()) continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::stringstream bytes;
      bytes << in.rdbuf();
      EXPECT_NO_THROW(target.run(bytes.str())) << target.name << ": " << entry.path();
      ++here;
    }
    EXPECT_GT(here, 0) << dir;
    inputs += here;
  }
  EXPECT_GT(inputs, 8);
}

TEST(FuzzReplay, TargetsAreFoundByName) {
  EXPECT_NE(find_target("case"), nullptr);
  EXPECT_NE(find_target("msh"), nullptr);
  EXPECT_EQ(find_target("nothing"), nullptr);
}

}  // namespace
}  // namespace snapjump::fuzz
