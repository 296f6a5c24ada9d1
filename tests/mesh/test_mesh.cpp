#include <fmt/format.h>
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mesh/cap_mesher.hpp"
#include "mesh/gmsh_session.hpp"
#include "mesh/msh_check.hpp"
#include "mesh/msh_reader.hpp"
#include "support/hostile_text.hpp"

namespace snapjump::mesh {
namespace {

constexpr double kR = 0.030, kH = 0.002;
const double kPhi = 80.0 * std::numbers::pi / 180.0;

const Mesh& cap() {
  static const Mesh m =
      make_cap_mesh({.R = kR, .h = kH, .phi = kPhi, .element_size = 0.006, .layers = 2});
  return m;
}

double radius(const Mesh& m, int a) { return std::hypot(m.nodes.x[a], m.nodes.y[a], m.nodes.z[a]); }
double polar(const Mesh& m, int a) { return std::acos(-m.nodes.z[a] / radius(m, a)); }

// One folder per process: ctest runs the tests of this file side by side, each writing its files.
std::filesystem::path temp_file(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("snapjump_mesh_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

void expect_mesh_error(const std::function<void()>& f, const std::string& fragment) {
  try {
    f();
    FAIL() << "expected MeshError containing: " << fragment;
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(CapMesh, NodeSetsLieWhereTheyShould) {
  const auto& m = cap();
  ASSERT_FALSE(m.tets.empty());
  for (int a : m.clamped) EXPECT_NEAR(polar(m, a), kPhi, 1e-9) << a;
  for (int a : m.outer) EXPECT_NEAR(radius(m, a), kR + kH / 2, 1e-12) << a;
  for (const auto& f : m.inner_faces) {
    for (int a : f) EXPECT_NEAR(radius(m, a), kR - kH / 2, 1e-12);
  }
  EXPECT_NEAR(m.nodes.x[m.apex], 0.0, 1e-12);
  EXPECT_NEAR(m.nodes.y[m.apex], 0.0, 1e-12);
  EXPECT_NEAR(m.nodes.z[m.apex], -(kR + kH / 2), 1e-12);
  // every node lies within the shell
  for (std::size_t a = 0; a < m.nodes.size(); ++a) {
    EXPECT_LE(radius(m, static_cast<int>(a)), kR + kH / 2 + 1e-12);
    EXPECT_GE(radius(m, static_cast<int>(a)), kR - kH / 2 - 1e-12);
    EXPECT_LE(polar(m, static_cast<int>(a)), kPhi + 1e-9);
  }
}

// The curve order renumbers the same body: every element, face and node set is where it was,
// and nodes that follow each other in the new numbering lie closer together.
TEST(CapMesh, SortingAlongTheCurveRenumbersTheSameBody) {
  const auto& m = cap();
  Mesh s = m;
  sort_along_curve(s);
  ASSERT_EQ(s.nodes.size(), m.nodes.size());
  EXPECT_NO_THROW(check_mesh(s));
  EXPECT_NO_THROW(check_shell_sets(s));
  using Position = std::array<double, 3>;
  const auto at = [](const Mesh& mesh, int a) {
    const auto i = static_cast<std::size_t>(a);
    return Position{mesh.nodes.x[i], mesh.nodes.y[i], mesh.nodes.z[i]};
  };
  // Every position once in each numbering.
  std::map<Position, int> before, after;
  for (std::size_t a = 0; a < m.nodes.size(); ++a) {
    before[at(m, static_cast<int>(a))] = static_cast<int>(a);
    after[at(s, static_cast<int>(a))] = static_cast<int>(a);
  }
  ASSERT_EQ(before.size(), m.nodes.size());
  ASSERT_EQ(after.size(), m.nodes.size());
  for (const auto& [x, a] : after) EXPECT_EQ(before.count(x), 1u) << "node " << a;
  // Items as the positions of their nodes, in their local order: the same multiset in both.
  const auto shapes = [&](const Mesh& mesh, const auto& items) {
    std::multiset<std::vector<Position>> out;
    for (const auto& item : items) {
      std::vector<Position> shape;
      for (int a : item) shape.push_back(at(mesh, a));
      out.insert(shape);
    }
    return out;
  };
  EXPECT_EQ(shapes(s, s.tets), shapes(m, m.tets));
  EXPECT_EQ(shapes(s, s.inner_faces), shapes(m, m.inner_faces));
  const auto positions = [&](const Mesh& mesh, const std::vector<int>& set) {
    std::set<Position> out;
    for (int a : set) out.insert(at(mesh, a));
    return out;
  };
  EXPECT_EQ(positions(s, s.clamped), positions(m, m.clamped));
  EXPECT_EQ(positions(s, s.outer), positions(m, m.outer));
  EXPECT_TRUE(std::is_sorted(s.clamped.begin(), s.clamped.end()));
  EXPECT_TRUE(std::is_sorted(s.outer.begin(), s.outer.end()));
  EXPECT_EQ(at(s, s.apex), at(m, m.apex));
  const auto mean_step = [](const Mesh& mesh) {
    double sum = 0.0;
    for (std::size_t a = 1; a < mesh.nodes.size(); ++a) {
      sum +=
          std::hypot(mesh.nodes.x[a] - mesh.nodes.x[a - 1], mesh.nodes.y[a] - mesh.nodes.y[a - 1],
                     mesh.nodes.z[a] - mesh.nodes.z[a - 1]);
    }
    return sum / static_cast<double>(mesh.nodes.size() - 1);
  };
  std::printf("mean distance between consecutive nodes: %.3g mm before, %.3g mm after\n",
              1e3 * mean_step(m), 1e3 * mean_step(s));
  EXPECT_LT(mean_step(s), mean_step(m));
}

// gmsh sets the OpenMP thread count to its own option when it starts; meshing must leave the
// caller's count as it was (else the simulation after it runs on one thread).
TEST(CapMesh, MeshingKeepsTheOpenMpThreadCount) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(3);
  const auto m = make_cap_mesh({.R = kR, .h = kH, .phi = kPhi, .element_size = 6e-3, .layers = 1});
  EXPECT_EQ(omp_get_max_threads(), 3);
  omp_set_num_threads(before);
  EXPECT_FALSE(m.tets.empty());
}

TEST(CapMesh, LayersThroughTheThickness) {
  // With 2 layers, the vertex radii take the values R - h/2, R, R + h/2 (and edge nodes between).
  const auto& m = cap();
  int mid = 0;
  for (std::size_t a = 0; a < m.nodes.size(); ++a) {
    if (std::abs(radius(m, static_cast<int>(a)) - kR) < 1e-12) ++mid;
  }
  EXPECT_GT(mid, 0);
  const Mesh one =
      make_cap_mesh({.R = kR, .h = kH, .phi = kPhi, .element_size = 0.006, .layers = 1});
  EXPECT_EQ(one.tets.size() * 2, m.tets.size());
}

TEST(CapMesh, BoundaryIsInnerOuterAndRim) {
  const auto& m = cap();
  std::vector<char> clamped(m.nodes.size(), 0);
  for (int a : m.clamped) clamped[a] = 1;
  std::size_t inner = 0, outer = 0, rim = 0;
  for (const auto& f : boundary_faces(m)) {
    const double r = radius(m, f[0]) + radius(m, f[1]) + radius(m, f[2]);
    if (std::abs(r / 3 - (kR - kH / 2)) < 1e-12)
      ++inner;
    else if (std::abs(r / 3 - (kR + kH / 2)) < 1e-12)
      ++outer;
    else if (clamped[f[0]] && clamped[f[1]] && clamped[f[2]])
      ++rim;
    else
      ADD_FAILURE() << "a boundary face that is neither inner, outer nor rim";
  }
  EXPECT_EQ(inner, m.inner_faces.size());
  EXPECT_EQ(outer, m.inner_faces.size());
  EXPECT_GT(rim, 0u);
}

TEST(CapMesh, SpecFromACase) {
  auto c = config::default_case();
  auto s = cap_spec(c);
  EXPECT_EQ(s.layers, 1);
  EXPECT_NEAR(s.element_size, std::sqrt(0.002 * 0.030) / 2.0, 1e-15);
  EXPECT_DOUBLE_EQ(s.R, 0.030);
  c.numerics.resolution = config::Resolution::Fine;  // finer in the plane and through h
  EXPECT_LT(cap_spec(c).element_size, s.element_size);
  EXPECT_EQ(cap_spec(c).layers, 2);
  c.numerics.resolution = config::Resolution::Coarse;  // coarser in the plane
  EXPECT_GT(cap_spec(c).element_size, s.element_size);
  EXPECT_EQ(cap_spec(c).layers, 1);
  c.numerics.element_size = 0.004;
  c.numerics.elements_through_thickness = 3;
  s = cap_spec(c);
  EXPECT_DOUBLE_EQ(s.element_size, 0.004);
  EXPECT_EQ(s.layers, 3);
}

TEST(CapMesh, BadSpecIsRefused) {
  expect_mesh_error(
      [] {
        (void)make_cap_mesh({.R = kR, .h = kR, .phi = kPhi, .element_size = 0.006, .layers = 2});
      },
      "0 < h < R");
  expect_mesh_error(
      [] {
        (void)make_cap_mesh({.R = kR, .h = kH, .phi = kPhi, .element_size = 0.0, .layers = 2});
      },
      "element_size > 0");
  expect_mesh_error(
      [] {
        (void)make_cap_mesh({.R = kR, .h = kH, .phi = kPhi, .element_size = 0.5, .layers = 2});
      },
      "too coarse");
}

// One straight-sided tetrahedron with its node sets, for element checks.
Mesh one_tet() {
  Mesh m;
  const double xyz[10][3] = {{0, 0, 0},   {1, 0, 0},  {0, 1, 0},  {0, 0, 1},   {.5, 0, 0},
                             {.5, .5, 0}, {0, .5, 0}, {0, 0, .5}, {0, .5, .5}, {.5, 0, .5}};
  for (const auto& p : xyz) m.nodes.push_back(p[0], p[1], p[2]);
  m.tets.push_back({0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  m.inner_faces.push_back({0, 2, 1, 6, 5, 4});
  m.clamped = {0, 1, 2};
  m.outer = {3};
  m.apex = 3;
  return m;
}

TEST(MeshCheck, InvertedAndDegenerateElementsAreNamed) {
  EXPECT_NO_THROW(check_mesh(one_tet()));
  auto inverted = one_tet();
  inverted.nodes.z[3] = -1.0;
  inverted.nodes.z[7] = inverted.nodes.z[8] = inverted.nodes.z[9] = -0.5;
  expect_mesh_error([&] { check_mesh(inverted); }, "is inverted");
  auto flat = one_tet();
  flat.nodes.z[3] = 0.0;
  flat.nodes.z[7] = flat.nodes.z[8] = flat.nodes.z[9] = 0.0;
  expect_mesh_error([&] { check_mesh(flat); }, "is degenerate");
  auto bent = one_tet();
  bent.nodes.x[4] = 1.4;  // edge node of (0,1) pushed beyond corner 1
  expect_mesh_error([&] { check_mesh(bent); }, "is distorted");
  // and in a real mesh, the element is named
  auto m = cap();
  std::swap(m.tets[3][1], m.tets[3][2]);
  std::swap(m.tets[3][4], m.tets[3][6]);
  std::swap(m.tets[3][8], m.tets[3][9]);
  expect_mesh_error([&] { check_mesh(m); }, "element 3 ");
}

TEST(Msh, DamagedFilesGiveAMeshErrorNamingTheFile) {
  // Whatever gmsh throws (a std::string, an int, a std::exception) leaves read_msh as a
  // MeshError with the file's name: cut files, a bad version, garbage where nodes should be.
  const auto& m = cap();
  const auto good_path = temp_file("good.msh");
  write_msh(m, good_path);
  std::ifstream in(good_path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string good = text.str();
  const auto nodes = good.find("$Nodes"), end_nodes = good.find("$EndNodes");
  ASSERT_NE(nodes, std::string::npos);
  ASSERT_NE(end_nodes, std::string::npos);
  const std::vector<std::string> damaged = {
      "",
      good.substr(0, good.size() / 2),
      "$MeshFormat\n9.9 0 8\n$EndMeshFormat\n",
      good.substr(0, nodes + 7) + "99999999999 -3 x y\n" + good.substr(end_nodes),
      good.substr(0, good.find("$Elements") + 20),
  };
  const auto path = temp_file("damaged.msh");
  for (const auto& d : damaged) {
    std::ofstream(path) << d;
    try {
      (void)read_msh(path);
      ADD_FAILURE() << "read a damaged file of " << d.size() << " bytes";
    } catch (const MeshError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  }
}

// gmsh reads a file it does not take for a mesh as a .geo script, and a script can run commands:
// such a file is refused before gmsh sees it, and its command never runs.
TEST(Msh, AGeoScriptIsNotRunAsAMesh) {
  const auto marker = std::filesystem::temp_directory_path() / "snapjump-geo-marker-test";
  std::filesystem::remove(marker);
  const auto path = temp_file("script.msh");
  std::ofstream(path) << "SystemCall \"touch " << marker.string() << "\";\n";
  try {
    (void)read_msh(path);
    ADD_FAILURE() << "read a .geo script as a mesh";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("$MeshFormat"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(marker));
}

// gmsh reads the user's ~/.gmshrc (a script, which can run commands) and adds its own folder to
// PATH and PYTHONPATH when it starts: a mesh session reads no such file and leaves the
// environment as it found it, however many sessions a process opens.
TEST(Msh, AGmshSessionReadsNoUserScriptAndLeavesTheEnvironment) {
  const auto home = std::filesystem::temp_directory_path() / "snapjump-gmshrc-test";
  std::filesystem::create_directories(home);
  const auto marker = home / "marker";
  std::filesystem::remove(marker);
  std::ofstream(home / ".gmshrc") << "SystemCall \"touch " << marker.string() << "\";\n";
  const char* old_home = std::getenv("HOME");
  const std::string saved_home = old_home ? old_home : "";
  ::setenv("HOME", home.c_str(), 1);
  ::unsetenv("PYTHONPATH");
  ::setenv("PATH", "/usr/bin:/bin", 1);
  const std::string path = std::getenv("PATH");
  for (int k = 0; k < 3; ++k)
    (void)make_cap_mesh({.R = kR, .h = kH, .phi = kPhi, .element_size = 0.012, .layers = 1});
  if (old_home) {
    ::setenv("HOME", saved_home.c_str(), 1);
  } else {
    ::unsetenv("HOME");
  }
  EXPECT_FALSE(std::filesystem::exists(marker));
  EXPECT_EQ(std::getenv("PATH"), path);
  EXPECT_EQ(std::getenv("PYTHONPATH"), nullptr);
}

TEST(Msh, RoundTripKeepsMeshAndGroups) {
  const auto& m = cap();
  const auto path = temp_file("cap.msh");
  write_msh(m, path);
  const Mesh r = read_msh(path);
  EXPECT_EQ(r.nodes.size(), m.nodes.size());
  EXPECT_EQ(r.tets.size(), m.tets.size());
  EXPECT_EQ(r.inner_faces.size(), m.inner_faces.size());
  EXPECT_EQ(r.clamped.size(), m.clamped.size());
  EXPECT_EQ(r.outer.size(), m.outer.size());
  EXPECT_NEAR(r.nodes.z[r.apex], -(kR + kH / 2), 1e-12);
  // inner faces keep the orientation out of the cavity (away from the centre)
  for (const auto& f : r.inner_faces) {
    const double u[3] = {r.nodes.x[f[1]] - r.nodes.x[f[0]], r.nodes.y[f[1]] - r.nodes.y[f[0]],
                         r.nodes.z[f[1]] - r.nodes.z[f[0]]};
    const double v[3] = {r.nodes.x[f[2]] - r.nodes.x[f[0]], r.nodes.y[f[2]] - r.nodes.y[f[0]],
                         r.nodes.z[f[2]] - r.nodes.z[f[0]]};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                         u[0] * v[1] - u[1] * v[0]};
    EXPECT_GT(n[0] * r.nodes.x[f[0]] + n[1] * r.nodes.y[f[0]] + n[2] * r.nodes.z[f[0]], 0.0);
  }
}

// A one-element .msh 4.1 file; `type` 4 (linear) or 11 (quadratic), with or without groups.
std::string one_tet_msh(bool quadratic, bool groups) {
  const int nn = quadratic ? 10 : 4;
  std::string s = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  if (groups) s += "$PhysicalNames\n1\n2 1 \"inner\"\n$EndPhysicalNames\n";
  s += fmt::format("$Entities\n0 0 1 1\n1 0 0 0 1 1 1 {} 0\n1 0 0 0 1 1 1 0 0\n$EndEntities\n",
                   groups ? "1 1" : "0");
  s += fmt::format("$Nodes\n1 {0} 1 {0}\n3 1 0 {0}\n", nn);
  for (int i = 1; i <= nn; ++i) s += fmt::format("{}\n", i);
  const char* xyz[10] = {"0 0 0",     "1 0 0",   "0 1 0",   "0 0 1",     "0.5 0 0",
                         "0.5 0.5 0", "0 0.5 0", "0 0 0.5", "0 0.5 0.5", "0.5 0 0.5"};
  for (int i = 0; i < nn; ++i) s += fmt::format("{}\n", xyz[i]);
  s += fmt::format("$EndNodes\n$Elements\n1 1 1 1\n3 1 {} 1\n1", quadratic ? 11 : 4);
  for (int i = 1; i <= nn; ++i) s += fmt::format(" {}", i);
  s += "\n$EndElements\n";
  return s;
}

TEST(Msh, LinearTetrahedraAreRefused) {
  const auto path = temp_file("linear.msh");
  std::ofstream(path) << one_tet_msh(false, false);
  expect_mesh_error([&] { (void)read_msh(path); }, "linear 4-node tetrahedra");
}

TEST(Msh, MissingGroupsAreNamed) {
  const auto path = temp_file("nogroups.msh");
  std::ofstream(path) << one_tet_msh(true, false);
  expect_mesh_error([&] { (void)read_msh(path); }, "no surface physical group named 'inner'");
}

TEST(Msh, MissingFile) {
  expect_mesh_error([] { (void)read_msh("/nonexistent/x.msh"); }, "no such mesh file");
}

}  // namespace
}  // namespace snapjump::mesh

namespace snapjump::mesh {
namespace {

// Damaged .msh files are refused by the structure check before gmsh reads them: files that
// crashed gmsh (an element on a node tag gmsh cannot look up, a negative tag), a node count no
// file of that length can hold (gmsh reserved it and went on), cut files. The message names the
// file, the line and the section.

std::string text_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The cap as write_msh writes it (MSH 4.1, ASCII).
const std::string& cap_msh() {
  static const std::string text = [] {
    const auto path = temp_file("check-cap.msh");
    write_msh(cap(), path);
    return text_of(path);
  }();
  return text;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

std::vector<std::string> words(const std::string& line) {
  std::stringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// The index (from 0) of the line of the first 10-node tetrahedron.
std::size_t first_tet_line(const std::vector<std::string>& lines) {
  const auto begin = std::find(lines.begin(), lines.end(), "$Elements") - lines.begin();
  for (auto k = static_cast<std::size_t>(begin) + 2; k < lines.size(); ++k) {
    const auto w = words(lines[k]);
    if (w.size() == 4 && w[2] == "11") return k + 1;
  }
  ADD_FAILURE() << "no tetrahedra";
  return 0;
}

// The cap with its first tetrahedron's first node tag replaced.
std::string with_first_tet_node(const std::string& tag) {
  auto lines = lines_of(cap_msh());
  const auto k = first_tet_line(lines);
  auto w = words(lines[k]);
  w[1] = tag;
  lines[k].clear();
  for (const auto& x : w) lines[k] += x + " ";
  return joined(lines);
}

// The cap with one whole line replaced.
std::string with_line(const std::string& old_line, const std::string& new_line) {
  auto lines = lines_of(cap_msh());
  const auto it = std::find(lines.begin(), lines.end(), old_line);
  EXPECT_NE(it, lines.end()) << old_line;
  if (it != lines.end()) *it = new_line;
  return joined(lines);
}

void expect_refused(const std::string& bytes, const std::vector<std::string>& fragments) {
  const auto path = temp_file("check-damaged.msh");
  std::ofstream(path, std::ios::binary) << bytes;
  try {
    (void)read_msh(path);
    ADD_FAILURE() << "read a damaged file; expected: " << fragments.front();
  } catch (const MeshError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string()), std::string::npos) << what;
    for (const auto& f : fragments) EXPECT_NE(what.find(f), std::string::npos) << f << ": " << what;
    EXPECT_LT(what.size(), 400u) << what;
  }
}

TEST(MshCheck, AnElementOnANodeTheFileDoesNotHaveIsRefused) {
  const auto line = fmt::format("line {}", first_tet_line(lines_of(cap_msh())) + 1);
  expect_refused(with_first_tet_node("3000000000"), {line, "$Elements", "node 3000000000"});
  expect_refused(with_first_tet_node("999999"), {line, "$Elements", "node 999999"});
}

TEST(MshCheck, ANegativeOrZeroTagIsRefused) {
  const auto line = fmt::format("line {}", first_tet_line(lines_of(cap_msh())) + 1);
  expect_refused(with_first_tet_node("-5"), {line, "$Elements", "\"-5\""});
  expect_refused(with_first_tet_node("0"), {line, "$Elements", "\"0\""});
  // A node's own tag.
  auto lines = lines_of(cap_msh());
  const auto nodes = std::find(lines.begin(), lines.end(), "$Nodes") - lines.begin();
  const auto first = std::find(lines.begin() + nodes, lines.end(), "1") - lines.begin();
  lines[first] = "-1";
  expect_refused(joined(lines), {fmt::format("line {}", first + 1), "$Nodes", "\"-1\""});
  lines[first] = "2";
  expect_refused(joined(lines), {"$Nodes", "node tag 2", "twice"});
}

TEST(MshCheck, ACountTheFileCannotHoldIsRefusedAtOnce) {
  const auto lines = lines_of(cap_msh());
  const auto nodes = std::find(lines.begin(), lines.end(), "$Nodes") - lines.begin();
  const auto header = words(lines[nodes + 1]);
  ASSERT_EQ(header.size(), 4u);
  const auto start = std::chrono::steady_clock::now();
  expect_refused(with_line(lines[nodes + 1],
                           fmt::format("{} 300000000 {} {}", header[0], header[2], header[3])),
                 {"$Nodes", "300000000 nodes", "bytes"});
  const auto elements = std::find(lines.begin(), lines.end(), "$Elements") - lines.begin();
  const auto eh = words(lines[elements + 1]);
  expect_refused(
      with_line(lines[elements + 1], fmt::format("{} 300000000 {} {}", eh[0], eh[2], eh[3])),
      {"$Elements", "300000000 elements", "bytes"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
}

TEST(MshCheck, ANonFiniteNodeCoordinateIsNamedWithItsLine) {
  // A NaN coordinate would otherwise reach the model (its gas volume comes out NaN).
  auto lines = lines_of(cap_msh());
  const auto nodes = std::find(lines.begin(), lines.end(), "$Nodes") - lines.begin();
  std::size_t k = static_cast<std::size_t>(nodes) + 2;
  while (k < lines.size() && (words(lines[k]).size() != 3 || words(lines[k])[0] == "2" ||
                              lines[k].find('.') == std::string::npos)) {
    ++k;
  }
  ASSERT_LT(k, lines.size());
  const auto w = words(lines[k]);
  for (const std::string bad : {"nan", "NaN", "-nan", "inf", "1e999"}) {
    auto damaged = lines;
    damaged[k] = fmt::format("{} {} {}", w[0], bad, w[2]);
    expect_refused(joined(damaged),
                   {fmt::format("line {}", k + 1), "$Nodes",
                    "a node coordinate must be a finite number", "\"" + bad + "\""});
  }
}

TEST(MshCheck, ATruncatedFileIsRefused) {
  const auto& good = cap_msh();
  for (const std::size_t cut : {good.size() / 3, 2 * good.size() / 3, good.find("$Elements") + 10,
                                good.find("$EndElements")}) {
    expect_refused(good.substr(0, cut), {"ends"});
  }
}

TEST(MshCheck, OtherDamageIsNamed) {
  expect_refused(with_line("4.1 0 8", "2.2 0 8"), {"line 2", "$MeshFormat", "4.1"});
  expect_refused(with_line("$EndNodes", "$EndNodez"), {"$Nodes", "$EndNodes", "$EndNodez"});
  expect_refused(with_line("2 2 \"inner\"", "7 2 \"inner\""), {"$PhysicalNames", "dimension"});
  auto lines = lines_of(cap_msh());
  const auto k = first_tet_line(lines) - 1;
  auto w = words(lines[k]);
  lines[k] = fmt::format("{} {} 99 {}", w[0], w[1], w[3]);
  expect_refused(joined(lines), {fmt::format("line {}", k + 1), "element type 99"});
  expect_refused(cap_msh() + "$Periodic\n0\n$EndPeriodic\n", {"$Periodic"});
}

// `text` with its first `from` replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

TEST(MshCheck, ANaNCoordinateIsRefusedNamingTheFileAndTheNode) {
  // Node 4 of the one-tetrahedron file is at (0, 0, 1); the reader would otherwise build a body
  // whose gas volume comes out NaN ("reference gas volume must be positive").
  const auto good = one_tet_msh(true, true);
  const auto lines = lines_of(good);
  const auto line = std::find(lines.begin(), lines.end(), "0 0 1") - lines.begin() + 1;
  expect_refused(replaced(good, "\n0 0 1\n", "\n0 nan 1\n"),
                 {fmt::format("line {} ($Nodes)", line),
                  "a node coordinate must be a finite number, not \"nan\"", "(node 4)"});
  expect_refused(replaced(good, "\n0 0 1\n", "\n0 0 -inf\n"),
                 {fmt::format("line {}", line), "(node 4)"});
}

TEST(MshCheck, AnErrorQuotesAShortEscapedExcerptOfTheFile) {
  using test_support::quotes_only_an_excerpt;
  const auto message = [](const std::string& bytes) {
    const auto path = temp_file("check-hostile.msh");
    std::ofstream(path, std::ios::binary) << bytes;
    try {
      (void)read_msh(path);
    } catch (const MeshError& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << "read a damaged file";
    return std::string();
  };
  const auto good = one_tet_msh(true, true);
  const auto word = test_support::hostile_word();
  const auto hostile = test_support::hostile_text();
  // A coordinate, a section header, a closing line (the structure check).
  EXPECT_TRUE(quotes_only_an_excerpt(message(replaced(good, "\n0 0 1\n", "\n0 0 " + word + "\n"))));
  EXPECT_TRUE(quotes_only_an_excerpt(message(good + hostile + "\n")));
  EXPECT_TRUE(quotes_only_an_excerpt(message(replaced(good, "$EndNodes", "$EndNodes" + hostile))));
  // A physical name is the file's text too, when the reader lists the groups it found.
  const auto name = word.substr(0, 104) + "\x1b[31m";
  const auto listed = message(replaced(good, "\"inner\"", "\"" + name + "\""));
  EXPECT_NE(listed.find("no surface physical group named 'inner'"), std::string::npos) << listed;
  EXPECT_TRUE(quotes_only_an_excerpt(listed));
}

// A mesh gmsh wrote in binary, for the binary paths of the check.
std::string binary_of(const std::filesystem::path& ascii) {
  const auto path = temp_file("check-binary.msh");
  {
    GmshSession session;
    gmsh::open(ascii.string());
    gmsh::option::setNumber("Mesh.Binary", 1);
    gmsh::write(path.string());
  }
  return text_of(path);
}

void expect_same_mesh(const Mesh& a, const Mesh& b) {
  EXPECT_EQ(a.nodes.x, b.nodes.x);
  EXPECT_EQ(a.nodes.y, b.nodes.y);
  EXPECT_EQ(a.nodes.z, b.nodes.z);
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.inner_faces, b.inner_faces);
  EXPECT_EQ(a.clamped, b.clamped);
  EXPECT_EQ(a.outer, b.outer);
  EXPECT_EQ(a.apex, b.apex);
}

TEST(MshCheck, AValidMeshIsReadTheSameInAsciiAndInBinary) {
  const auto ascii = temp_file("check-valid.msh");
  std::ofstream(ascii, std::ios::binary) << cap_msh();
  const Mesh from_ascii = read_msh(ascii);
  EXPECT_EQ(from_ascii.tets.size(), cap().tets.size());
  const auto binary = temp_file("check-valid-binary.msh");
  const auto bytes = binary_of(ascii);
  ASSERT_NE(bytes.find("4.1 1 8"), std::string::npos);
  std::ofstream(binary, std::ios::binary) << bytes;
  expect_same_mesh(read_msh(binary), from_ascii);
  // Damage in the binary form is refused too: a cut, a node tag no node has.
  expect_refused(bytes.substr(0, bytes.size() / 2), {"ends"});
  const auto elements = bytes.find("$Elements\n") + 10;
  auto bad = bytes;
  const std::size_t huge = 3000000000;
  // The first block's first element: 4 size_t of header, 3 ints and a size_t of block header,
  // then the element's tag and its first node.
  std::memcpy(bad.data() + elements + 4 * 8 + 3 * 4 + 8 + 8, &huge, sizeof huge);
  expect_refused(bad, {"$Elements", "node 3000000000"});
}

// The check's table of element types is gmsh's own.
TEST(MshCheck, ItsElementTypesAreGmshs) {
  GmshSession session;
  for (int type = 1; type <= 31; ++type) {
    std::string name;
    int dim = 0, order = 0, nodes = 0, primary = 0;
    std::vector<double> coords;
    gmsh::model::mesh::getElementProperties(type, name, dim, order, nodes, coords, primary);
    const auto t = msh_element_type(type);
    ASSERT_TRUE(t.has_value()) << type;
    EXPECT_EQ(t->dim, dim) << name;
    EXPECT_EQ(t->nodes, nodes) << name;
  }
  EXPECT_FALSE(msh_element_type(0).has_value());
  EXPECT_FALSE(msh_element_type(32).has_value());
}

}  // namespace
}  // namespace snapjump::mesh
