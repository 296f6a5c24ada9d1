// Checkpoints are checked before anything in them is used: a checksum over the bytes, then every
// field of the release loop's state. The axisymmetric coarse popper keeps these tests cheap; the
// format is the same for both models.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "app/checkpoint.hpp"
#include "io/atomic_file.hpp"
#include "io/vtu.hpp"
#include "support/cases.hpp"
#include "support/hostile_text.hpp"

namespace snapjump::app {
namespace {

using test_support::coarse_axisymmetric_default;

// A released popper a few steps on, and a loop state with two snapshots.
struct Fixture {
  config::Case c = coarse_axisymmetric_default();
  popper::Numerics n = popper::resolve_numerics(c);
  popper::Popper pop{c, n};
  LoopState loop;
  Fixture() {
    EXPECT_TRUE(pop.prepare().held);
    pop.release();
    for (int k = 0; k < 50; ++k) pop.step();
    loop.next_sample = 2e-4;
    loop.next_snapshot = 5e-3;
    loop.next_checkpoint = 0.02;
    loop.rows = 2;
    loop.frames = {{0.0, "snapshots/frame_00000.vtu"}, {5e-3, "snapshots/frame_00001.vtu"}};
  }
};

std::string error_of(const std::string& bytes) {
  const auto c = coarse_axisymmetric_default();
  popper::Popper fresh(c, popper::resolve_numerics(c));
  try {
    (void)decode_checkpoint(bytes, fresh, "checkpoint.bin");
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

TEST(Checkpoint, RoundTripRestoresThePopperAndTheLoop) {
  Fixture f;
  const auto bytes = encode_checkpoint(f.pop, f.loop);
  popper::Popper back(f.c, f.n);
  const auto loop = decode_checkpoint(bytes, back, "checkpoint.bin");
  EXPECT_EQ(loop.frames, f.loop.frames);
  EXPECT_EQ(loop.rows, 2u);
  EXPECT_EQ(loop.next_sample, 2e-4);
  EXPECT_EQ(encode_checkpoint(back, loop), bytes);
  // Both step on identically.
  for (int k = 0; k < 20; ++k) {
    f.pop.step();
    back.step();
  }
  EXPECT_EQ(encode_checkpoint(back, loop), encode_checkpoint(f.pop, f.loop));
}

TEST(Checkpoint, AnyDamagedByteIsFound) {
  Fixture f;
  const auto bytes = encode_checkpoint(f.pop, f.loop);
  for (std::size_t at : {std::size_t{0}, std::size_t{30}, bytes.size() / 3, bytes.size() / 2,
                         bytes.size() - 40, bytes.size() - 1}) {
    auto damaged = bytes;
    damaged[at] = static_cast<char>(damaged[at] ^ 0x10);
    EXPECT_NE(error_of(damaged), "") << "byte " << at;
  }
  EXPECT_NE(error_of(bytes.substr(0, bytes.size() / 2)).find("checkpoint.bin"), std::string::npos);
  EXPECT_NE(error_of("not a checkpoint at all"), "");
  EXPECT_NE(error_of(""), "");
}

TEST(Checkpoint, FieldsAreCheckedEvenWithAValidChecksum) {
  Fixture f;
  const auto bad = [&](LoopState loop) { return error_of(encode_checkpoint(f.pop, loop)); };
  auto loop = f.loop;
  loop.next_sample = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(bad(loop).find("next sample"), std::string::npos);
  loop = f.loop;
  loop.next_checkpoint = -1.0;
  EXPECT_NE(bad(loop), "");
  loop = f.loop;
  loop.flight.airborne_since = std::numeric_limits<double>::infinity();
  EXPECT_NE(bad(loop).find("flight start"), std::string::npos);
  loop = f.loop;
  loop.frames.emplace_back(0.01, "../../../../etc/passwd");
  EXPECT_NE(bad(loop).find("snapshot name"), std::string::npos);
  loop = f.loop;
  loop.frames.emplace_back(std::numeric_limits<double>::quiet_NaN(), "snapshots/frame_00002.vtu");
  EXPECT_NE(bad(loop).find("snapshot at"), std::string::npos);
}

// A checkpoint whose checksum trailer was cut off (here with its row count set to 0 as well,
// which would drop the rows recorded before it) is refused: no trailer, no resume.
TEST(Checkpoint, WithoutTheTrailerItIsRefused) {
  Fixture f;
  auto loop = f.loop;
  loop.frames.clear();
  loop.rows = 0;
  const auto bytes = encode_checkpoint(f.pop, loop);
  const std::size_t trailer = sizeof("snapjump-checksum-1") + 8;
  const auto cut = bytes.substr(0, bytes.size() - trailer);
  EXPECT_NE(error_of(cut).find("without its checksum"), std::string::npos) << error_of(cut);
  EXPECT_EQ(error_of(bytes), "");
}

// A checkpoint is binary: its errors quote none of it, whether the text has no trailer or is
// sealed with a valid one.
TEST(Checkpoint, AnErrorQuotesNoneOfTheFile) {
  const auto text = test_support::hostile_text();
  std::string sealed = text;
  const std::uint64_t sum = fnv1a64(text);
  sealed.append("snapjump-checksum-1", sizeof("snapjump-checksum-1"));
  sealed.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  for (const auto& bytes : {text, sealed}) {
    const auto e = error_of(bytes);
    EXPECT_NE(e.find("checkpoint.bin: "), std::string::npos) << e;
    EXPECT_TRUE(test_support::quotes_only_an_excerpt(e, false));
    EXPECT_EQ(e.find(test_support::kHostileLetter), std::string::npos) << e;
  }
}

TEST(AtomicFile, ReplacesWholeOrNotAtAll) {
  const auto dir = std::filesystem::temp_directory_path() / "snapjump_atomic_file_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto path = dir / "summary.json";
  const auto read = [&] {
    std::ifstream f(path);
    std::stringstream s;
    s << f.rdbuf();
    return s.str();
  };
  io::write_file_atomically(path, "first\n");
  io::write_file_atomically(path, "second\n");
  EXPECT_EQ(read(), "second\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "summary.json.tmp"));
  // A file that cannot be written leaves the old one as it was and names itself.
  std::filesystem::create_directories(dir / "blocked.json.tmp");
  try {
    io::write_file_atomically(dir / "blocked.json", "x");
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("blocked.json"), std::string::npos);
  }
  EXPECT_EQ(read(), "second\n");
}

// A snapshot and its collection go through the atomic writer: on a full disk (the temporary a
// link to /dev/full, where every write fails with ENOSPC) no file of that name appears, empty or
// cut, no temporary is left, and the error names the file.
TEST(AtomicFile, ASnapshotThatCannotBeWrittenLeavesNoFile) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("snapjump_snapshot_disk_full_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto expect_no_file = [&](const std::filesystem::path& path, const auto& write) {
    std::filesystem::create_symlink("/dev/full", path.string() + ".tmp");
    try {
      write();
      ADD_FAILURE() << "a write to a full disk succeeded: " << path;
    } catch (const io::WriteFailed& e) {
      EXPECT_EQ(e.path(), path);
      EXPECT_NE(std::string(e.what()).find("could not write " + path.string()), std::string::npos)
          << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(path)));
    EXPECT_FALSE(std::filesystem::exists(std::filesystem::symlink_status(path.string() + ".tmp")));
  };
  const auto vtu = dir / "apparatus_00000.vtu";
  expect_no_file(vtu, [&] { io::write_apparatus_vtu(vtu, 0.06, 0.03, 0.0, 0.03); });
  const auto pvd = dir / "run.pvd";
  io::PvdCollection collection(pvd);
  expect_no_file(pvd, [&] { collection.add(0.0, "snapshots/frame_00000.vtu"); });
  // With room on the disk, the same snapshot is written whole.
  io::write_apparatus_vtu(vtu, 0.06, 0.03, 0.0, 0.03);
  std::ifstream in(vtu);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_TRUE(text.str().ends_with("</VTKFile>\n")) << text.str().size();
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace snapjump::app
