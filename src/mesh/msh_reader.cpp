#include "mesh/msh_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <set>
#include <unordered_map>

#include "config/text.hpp"
#include "mesh/gmsh_model.hpp"
#include "mesh/msh_check.hpp"

namespace snapjump::mesh {
namespace {

constexpr int kTet4 = 4, kTet10 = 11, kTri3 = 2, kTri6 = 9;

std::string element_name(int type) {
  std::string name;
  int dim = 0, order = 0, nn = 0, np = 0;
  std::vector<double> coords;
  gmsh::model::mesh::getElementProperties(type, name, dim, order, nn, coords, np);
  return name;
}

// Physical group (dim, tag) by name, or (-1, -1).
std::pair<int, int> find_group(const std::string& wanted) {
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  for (const auto& [dim, tag] : groups) {
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    if (name == wanted) return {dim, tag};
  }
  return {-1, -1};
}

// The physical groups for a message: each name a short excerpt, the first few groups.
std::string group_names() {
  constexpr std::size_t kMostShown = 8;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups);
  std::string out;
  for (std::size_t k = 0; k < groups.size() && k < kMostShown; ++k) {
    const auto [dim, tag] = groups[k];
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    out += fmt::format("{}'{}' (dim {})", out.empty() ? "" : ", ",
                       name.empty() ? "<unnamed>" : text::excerpt(name), dim);
  }
  if (groups.size() > kMostShown) out += fmt::format(" and {} more", groups.size() - kMostShown);
  return out.empty() ? "none" : out;
}

}  // namespace

ModelTets tets_of_current_model(const std::function<MeshError(const std::string&)>& fail) {
  // Volume elements: only 10-node tetrahedra.
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags, nodes;
  gmsh::model::mesh::getElements(types, tags, nodes, 3);
  std::vector<std::size_t> tet_nodes;
  for (std::size_t k = 0; k < types.size(); ++k) {
    if (types[k] == kTet10) {
      tet_nodes = nodes[k];
    } else if (types[k] == kTet4) {
      throw fail(
          fmt::format("has {} linear 4-node tetrahedra; snapjump needs 10-node (quadratic) "
                      "ones: mesh with `-order 2` (Mesh.ElementOrder = 2)",
                      tags[k].size()));
    } else {
      throw fail(
          fmt::format("has {} volume elements of type '{}'; only 10-node tetrahedra are "
                      "supported",
                      tags[k].size(), element_name(types[k])));
    }
  }
  if (tet_nodes.empty()) throw fail("has no 10-node tetrahedra");

  ModelTets out;
  Mesh& m = out.mesh;
  auto& index = out.index;
  {
    std::vector<std::size_t> node_tags;
    std::vector<double> coords, params;
    gmsh::model::mesh::getNodes(node_tags, coords, params, -1, -1, false, false);
    std::unordered_map<std::size_t, std::size_t> where;
    for (std::size_t i = 0; i < node_tags.size(); ++i) where[node_tags[i]] = i;
    for (std::size_t tag : tet_nodes) {
      if (index.count(tag)) continue;
      const auto it = where.find(tag);
      if (it == where.end()) throw fail(fmt::format("element refers to unknown node {}", tag));
      index[tag] = static_cast<int>(m.nodes.size());
      m.nodes.push_back(coords[3 * it->second], coords[3 * it->second + 1],
                        coords[3 * it->second + 2]);
    }
  }
  for (std::size_t e = 0; e < tet_nodes.size() / 10; ++e) {
    std::array<int, 10> tet{};
    for (int a = 0; a < 10; ++a) tet[a] = index.at(tet_nodes[10 * e + a]);
    m.tets.push_back(tet);
  }
  return out;
}

namespace {

using Fail = std::function<MeshError(const std::string&)>;

// Refuses what is not a file, and what gmsh should not see (the structure check).
void check_before_gmsh(const std::filesystem::path& path) {
  if (!std::filesystem::is_regular_file(path)) {
    throw MeshError(fmt::format("{}: no such mesh file", path.string()));
  }
  // gmsh::open reads any file it does not recognise as a .geo script: a script can run commands
  // (SystemCall) and a malformed one crashed gmsh's parser (a division by zero). And gmsh's .msh
  // parser trusts the file: a damaged one can crash it. Only a file that passes the structure
  // check (an MSH 4.1 file that starts with $MeshFormat, msh_check.hpp) reaches gmsh.
  check_msh_file(path);
}

// Opens the file in gmsh's current session.
void open_in_gmsh(const std::filesystem::path& path) {
  // gmsh keeps its last error across sessions: only a new one is this file's.
  std::string before, error;
  gmsh::logger::getLastError(before);
  gmsh::open(path.string());
  gmsh::logger::getLastError(error);
  if (!error.empty() && error != before) {
    throw MeshError(
        fmt::format("{}: gmsh cannot read it: {}", path.string(), text::library_message(error)));
  }
}

// The mesh's nodes of the model's physical groups.
class GroupNodes {
 public:
  GroupNodes(const std::unordered_map<std::size_t, int>& index, Fail fail)
      : index_(index), fail_(std::move(fail)) {}

  // The mesh node of gmsh's node `tag`, which must belong to a tetrahedron.
  [[nodiscard]] int local(std::size_t tag, const char* what) const {
    const auto it = index_.find(tag);
    if (it == index_.end()) {
      throw fail_(fmt::format("{} node {} belongs to no tetrahedron", what, tag));
    }
    return it->second;
  }

  // The group's nodes, sorted, each once.
  [[nodiscard]] std::vector<int> of(std::pair<int, int> group, const char* what) const {
    std::vector<std::size_t> node_tags;
    std::vector<double> coords;
    gmsh::model::mesh::getNodesForPhysicalGroup(group.first, group.second, node_tags, coords);
    std::vector<int> out;
    for (auto tag : node_tags) out.push_back(local(tag, what));
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  [[nodiscard]] const Fail& fail() const { return fail_; }

 private:
  const std::unordered_map<std::size_t, int>& index_;
  Fail fail_;
};

// The inner surface's and the clamped faces' groups, which a shell mesh must have.
std::pair<std::pair<int, int>, std::pair<int, int>> required_groups(const Fail& fail) {
  const auto inner = find_group("inner");
  if (inner.first != 2) {
    throw fail(
        fmt::format("has no surface physical group named 'inner' (the pressurised inner "
                    "surface); its groups: {}",
                    group_names()));
  }
  const auto clamped = find_group("clamped");
  if (clamped.first < 0) {
    throw fail(
        fmt::format("has no physical group named 'clamped' (the faces glued to the "
                    "container); its groups: {}",
                    group_names()));
  }
  return {inner, clamped};
}

// The face turned, if need be, to point into tetrahedron `owner` (out of the cavity).
void orient_into(const Mesh& m, int owner, std::array<int, 6>& face) {
  double c[3] = {}, n[3], d[3][3];
  for (int a = 0; a < 4; ++a) {
    const int i = m.tets[owner][a];
    c[0] += 0.25 * m.nodes.x[i];
    c[1] += 0.25 * m.nodes.y[i];
    c[2] += 0.25 * m.nodes.z[i];
  }
  for (int a = 0; a < 3; ++a) {
    d[a][0] = m.nodes.x[face[a]];
    d[a][1] = m.nodes.y[face[a]];
    d[a][2] = m.nodes.z[face[a]];
  }
  const double u[3] = {d[1][0] - d[0][0], d[1][1] - d[0][1], d[1][2] - d[0][2]};
  const double v[3] = {d[2][0] - d[0][0], d[2][1] - d[0][1], d[2][2] - d[0][2]};
  n[0] = u[1] * v[2] - u[2] * v[1];
  n[1] = u[2] * v[0] - u[0] * v[2];
  n[2] = u[0] * v[1] - u[1] * v[0];
  const double into = n[0] * (c[0] - d[0][0]) + n[1] * (c[1] - d[0][1]) + n[2] * (c[2] - d[0][2]);
  if (into < 0) {  // flip: swap corners 1 and 2 and edge nodes (0,1) <-> (0,2)
    std::swap(face[1], face[2]);
    std::swap(face[3], face[5]);
  }
}

// The inner group's 6-node triangles, oriented into the tetrahedron they bound.
std::vector<std::array<int, 6>> inner_faces(const Mesh& m, std::pair<int, int> inner,
                                            const GroupNodes& nodes) {
  const auto& fail = nodes.fail();
  std::map<std::array<int, 3>, int> face_owner;
  constexpr int corner_faces[4][3] = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  for (std::size_t e = 0; e < m.tets.size(); ++e) {
    for (const auto& f : corner_faces) {
      std::array<int, 3> key{m.tets[e][f[0]], m.tets[e][f[1]], m.tets[e][f[2]]};
      std::sort(key.begin(), key.end());
      face_owner[key] = static_cast<int>(e);
    }
  }
  std::vector<std::array<int, 6>> out;
  std::vector<int> entities;
  gmsh::model::getEntitiesForPhysicalGroup(inner.first, inner.second, entities);
  for (int entity : entities) {
    std::vector<int> ftypes;
    std::vector<std::vector<std::size_t>> ftags, fnodes;
    gmsh::model::mesh::getElements(ftypes, ftags, fnodes, 2, entity);
    for (std::size_t k = 0; k < ftypes.size(); ++k) {
      if (ftypes[k] == kTri3) {
        throw fail("the 'inner' surface has linear 3-node triangles; mesh with order 2");
      }
      if (ftypes[k] != kTri6) {
        throw fail(
            fmt::format("the 'inner' surface has elements of type '{}'; only 6-node "
                        "triangles are supported",
                        element_name(ftypes[k])));
      }
      for (std::size_t f = 0; f < ftags[k].size(); ++f) {
        std::array<int, 6> face{};
        for (int a = 0; a < 6; ++a) face[a] = nodes.local(fnodes[k][6 * f + a], "inner-face");
        std::array<int, 3> key{face[0], face[1], face[2]};
        std::sort(key.begin(), key.end());
        const auto owner = face_owner.find(key);
        if (owner == face_owner.end()) {
          throw fail(fmt::format("inner face {} is not a face of any tetrahedron", ftags[k][f]));
        }
        orient_into(m, owner->second, face);
        out.push_back(face);
      }
    }
  }
  if (out.empty()) throw fail("the 'inner' group has no faces");
  return out;
}

// Without an 'outer' group: the nodes of the boundary faces that are neither inner nor clamped.
std::vector<int> outer_from_boundary(const Mesh& m) {
  std::set<std::array<int, 3>> inner_keys;
  for (const auto& f : m.inner_faces) {
    std::array<int, 3> key{f[0], f[1], f[2]};
    std::sort(key.begin(), key.end());
    inner_keys.insert(key);
  }
  std::vector<char> clamped_flag(m.nodes.size(), 0);
  for (int a : m.clamped) clamped_flag[a] = 1;
  std::set<int> out;
  for (const auto& f : boundary_faces(m)) {
    std::array<int, 3> key{f[0], f[1], f[2]};
    std::sort(key.begin(), key.end());
    const bool all_clamped = clamped_flag[f[0]] && clamped_flag[f[1]] && clamped_flag[f[2]];
    if (inner_keys.count(key) || all_clamped) continue;
    out.insert(f.begin(), f.end());
  }
  return {out.begin(), out.end()};
}

// The 'apex' group's one node, or else the lowest outer node.
int apex_of(const Mesh& m, const GroupNodes& nodes) {
  const auto apex = find_group("apex");
  if (apex.first >= 0) {
    const auto a = nodes.of(apex, "apex");
    if (a.size() != 1) throw nodes.fail()("the 'apex' group must hold exactly one node");
    return a.front();
  }
  int lowest = -1;
  for (int a : m.outer) {
    if (lowest < 0 || m.nodes.z[a] < m.nodes.z[lowest]) lowest = a;
  }
  return lowest;
}

Mesh read_msh_unguarded(const std::filesystem::path& path) {
  check_before_gmsh(path);
  GmshSession session;
  open_in_gmsh(path);
  const Fail fail = [&](const std::string& what) {
    return MeshError(fmt::format("{}: {}", path.string(), what));
  };
  auto model = tets_of_current_model(fail);
  Mesh m = std::move(model.mesh);
  m.description = fmt::format("gmsh mesh {}", path.string());
  const GroupNodes nodes(model.index, fail);
  const auto [inner, clamped] = required_groups(fail);
  m.clamped = nodes.of(clamped, "clamped");
  m.inner_faces = inner_faces(m, inner, nodes);
  const auto outer = find_group("outer");
  m.outer = outer.first >= 0 ? nodes.of(outer, "outer") : outer_from_boundary(m);
  m.apex = apex_of(m, nodes);
  try {
    check_mesh(m);
    check_shell_sets(m);
  } catch (const MeshError& e) {
    throw fail(e.what());
  }
  return m;
}

}  // namespace

Mesh read_msh(const std::filesystem::path& path) {
  // gmsh reports some errors by throwing a std::string or an int, which nothing else here
  // expects: every error leaves as a MeshError naming the file. The damage known to crash gmsh
  // itself is refused by the structure check before gmsh sees the file.
  try {
    return read_msh_unguarded(path);
  } catch (const MeshError&) {
    throw;
  } catch (const std::string& e) {
    throw MeshError(
        fmt::format("{}: gmsh cannot read it: {}", path.string(), text::library_message(e)));
  } catch (const std::exception& e) {
    throw MeshError(fmt::format("{}: cannot be read as a shell mesh: {}", path.string(),
                                text::library_message(e.what())));
  } catch (int code) {
    throw MeshError(fmt::format("{}: gmsh cannot read it (error {})", path.string(), code));
  }
}

}  // namespace snapjump::mesh

namespace snapjump::mesh {

void write_msh(const Mesh& m, const std::filesystem::path& path) {
  GmshSession session;
  gmsh::model::add("snapjump");
  const std::size_t n = m.nodes.size();
  std::vector<std::size_t> node_tags(n);
  std::vector<double> coords(3 * n);
  for (std::size_t a = 0; a < n; ++a) {
    node_tags[a] = a + 1;
    coords[3 * a] = m.nodes.x[a];
    coords[3 * a + 1] = m.nodes.y[a];
    coords[3 * a + 2] = m.nodes.z[a];
  }
  const int volume = gmsh::model::addDiscreteEntity(3);
  gmsh::model::mesh::addNodes(3, volume, node_tags, coords);
  std::size_t next_element = 1;
  const auto add = [&](int dim, int entity, int type, const auto& elements) {
    std::vector<std::size_t> tags, conn;
    for (const auto& el : elements) {
      tags.push_back(next_element++);
      for (int a : el) conn.push_back(static_cast<std::size_t>(a) + 1);
    }
    gmsh::model::mesh::addElementsByType(entity, type, tags, conn);
    (void)dim;
  };
  add(3, volume, kTet10, m.tets);
  const int inner = gmsh::model::addDiscreteEntity(2);
  add(2, inner, kTri6, m.inner_faces);
  std::vector<char> clamped(n, 0), outer(n, 0);
  for (int a : m.clamped) clamped[a] = 1;
  for (int a : m.outer) outer[a] = 1;
  std::vector<std::array<int, 6>> rim_faces, outer_faces;
  for (const auto& f : boundary_faces(m)) {
    bool all_clamped = true, all_outer = true;
    for (int a : f) {
      all_clamped = all_clamped && clamped[a];
      all_outer = all_outer && outer[a];
    }
    if (all_clamped)
      rim_faces.push_back(f);
    else if (all_outer)
      outer_faces.push_back(f);
  }
  const int rim = gmsh::model::addDiscreteEntity(2);
  add(2, rim, kTri6, rim_faces);
  const int out = gmsh::model::addDiscreteEntity(2);
  add(2, out, kTri6, outer_faces);
  gmsh::model::setPhysicalName(3, gmsh::model::addPhysicalGroup(3, {volume}), "shell");
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {inner}), "inner");
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {rim}), "clamped");
  gmsh::model::setPhysicalName(2, gmsh::model::addPhysicalGroup(2, {out}), "outer");
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.SaveAll", 0);
  std::string before, error;
  gmsh::logger::getLastError(before);  // gmsh keeps its last error: only a new one is ours
  gmsh::write(path.string());
  gmsh::logger::getLastError(error);
  if (!error.empty() && error != before) {
    throw MeshError(fmt::format("{}: cannot write: {}", path.string(), error));
  }
}

}  // namespace snapjump::mesh
