#include "mesh/cap_mesher.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>

#include "mesh/gmsh_session.hpp"
#include "mesh/tet10.hpp"

namespace snapjump::mesh {
namespace {

struct Vec {
  double x, y, z;
};
Vec operator+(Vec a, Vec b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec operator-(Vec a, Vec b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec operator*(double s, Vec a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(Vec a, Vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Vec cross(Vec a, Vec b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm(Vec a) { return std::sqrt(dot(a, a)); }

// The mid-surface triangulation from gmsh: unit directions of the vertices and triangles.
struct SurfaceMesh {
  std::vector<Vec> dir;
  std::vector<std::array<int, 3>> tris;
};

SurfaceMesh triangulate_mid_surface(const CapSpec& s) {
  GmshSession session;
  gmsh::model::add("snapjump-cap");
  // OCC sphere limited in latitude: from the south pole (-pi/2) up to -pi/2 + phi.
  const int volume = gmsh::model::occ::addSphere(
      0, 0, 0, s.R, -1, -std::numbers::pi / 2, -std::numbers::pi / 2 + s.phi, 2 * std::numbers::pi);
  gmsh::model::occ::synchronize();
  std::vector<std::pair<int, int>> boundary;
  gmsh::model::getBoundary({{3, volume}}, boundary, false, false, false);
  int face = -1;
  for (const auto& [dim, tag] : boundary) {
    std::string type;
    gmsh::model::getType(dim, tag, type);
    if (type == "Sphere") face = tag;
  }
  if (face < 0) throw MeshError("gmsh produced no spherical face for the cap");
  gmsh::option::setNumber("Mesh.MeshSizeMax", s.element_size);
  if (s.graded()) {
    const double finest = std::min(s.rim_size > 0.0 ? s.rim_size : s.element_size,
                                   s.contact_size > 0.0 ? s.contact_size : s.element_size);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.5 * finest);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::model::mesh::setSizeCallback([s](int, int, double x, double y, double z) {
      const double r = std::sqrt(x * x + y * y + z * z);
      return cap_element_size(s, s.R * std::acos(std::clamp(-z / r, -1.0, 1.0)));
    });
  } else {
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.5 * s.element_size);
  }
  gmsh::option::setNumber("Mesh.Algorithm", 6);  // Frontal-Delaunay: well-shaped triangles
  gmsh::model::mesh::generate(2);

  std::vector<std::size_t> node_tags;
  std::vector<double> coords, params;
  gmsh::model::mesh::getNodes(node_tags, coords, params, 2, face, true, false);
  std::unordered_map<std::size_t, std::size_t> where;
  for (std::size_t i = 0; i < node_tags.size(); ++i) where[node_tags[i]] = i;
  std::vector<std::size_t> tri_tags, tri_nodes;
  gmsh::model::mesh::getElementsByType(2, tri_tags, tri_nodes, face);
  // Keep only the nodes that triangles use (gmsh also lists points of the degenerate pole edge).
  std::unordered_map<std::size_t, int> index;
  SurfaceMesh sm;
  for (std::size_t e = 0; e < tri_tags.size(); ++e) {
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const std::size_t tag = tri_nodes[3 * e + k];
      auto it = index.find(tag);
      if (it == index.end()) {
        const auto w = where.find(tag);
        if (w == where.end()) throw MeshError("gmsh triangle refers to a node off the cap face");
        const Vec p{coords[3 * w->second], coords[3 * w->second + 1], coords[3 * w->second + 2]};
        it = index.emplace(tag, static_cast<int>(sm.dir.size())).first;
        sm.dir.push_back((1.0 / norm(p)) * p);
      }
      t[k] = it->second;
    }
    sm.tris.push_back(t);
  }
  if (sm.tris.empty()) throw MeshError("gmsh produced no triangles for the cap");
  return sm;
}

double polar_angle(Vec d) { return std::acos(std::clamp(-d.z, -1.0, 1.0)); }

// Throws MeshError for a spec the mesher cannot use.
void check_spec(const CapSpec& s) {
  if (!(s.R > 0 && s.h > 0 && s.h < s.R && s.phi > 0 && s.phi < std::numbers::pi &&
        s.element_size > 0 && s.layers >= 1)) {
    throw MeshError(fmt::format(
        "cap mesh needs 0 < h < R, 0 < phi < pi, element_size > 0 and layers >= 1 (got R = {}, "
        "h = {}, phi = {}, element_size = {}, layers = {})",
        s.R, s.h, s.phi, s.element_size, s.layers));
  }
  for (const auto& [name, v] : {std::pair{"rim size", s.rim_size},
                                {"rim band", s.rim_band},
                                {"contact size", s.contact_size},
                                {"contact band", s.contact_band}}) {
    if (!(v >= 0.0 && std::isfinite(v))) {
      throw MeshError(fmt::format("cap mesh: the {} must be a finite length (got {})", name, v));
    }
  }
  // A bound on what the grading may ask of gmsh: below h / 10 the cap would hold millions of
  // elements for a zone that thin elements through h cannot resolve anyway.
  for (const double fine : {s.rim_size, s.contact_size}) {
    if (fine > 0.0 && fine < 0.1 * s.h) {
      throw MeshError(fmt::format(
          "cap mesh: a graded size of {} m is below a tenth of the thickness h = {} m", fine, s.h));
    }
  }
  if (s.element_size > 0.5 * s.R * s.phi) {
    throw MeshError(fmt::format("element size {} m is too coarse for a cap of arc length {} m",
                                s.element_size, s.R * s.phi));
  }
}

std::string describe(const CapSpec& s) {
  const int L = s.layers;
  std::string d = fmt::format(
      "spherical cap R = {} m, h = {} m, phi = {} rad, element size {} m, "
      "{} layers",
      s.R, s.h, s.phi, s.element_size, L);
  return d + grading_summary(s);
}

// The clamped (rim) and outer node sets, and the apex: the lowest outer node, on the axis.
void mark_sets(const CapSpec& s, const std::vector<bool>& rim_of, const std::vector<bool>& outer_of,
               Mesh& m) {
  double lowest = 0.0;
  for (int a = 0; a < static_cast<int>(m.nodes.size()); ++a) {
    if (rim_of[a]) m.clamped.push_back(a);
    if (outer_of[a]) {
      m.outer.push_back(a);
      if (m.apex < 0 || m.nodes.z[a] < lowest) {
        m.apex = a;
        lowest = m.nodes.z[a];
      }
    }
  }
  const double off_axis = std::hypot(m.nodes.x[m.apex], m.nodes.y[m.apex]);
  if (off_axis > 1e-9 * s.R) {
    throw MeshError(
        fmt::format("the cap mesh has no node at the apex (nearest is {} m off axis)", off_axis));
  }
}

}  // namespace

std::string grading_summary(const CapSpec& s) {
  std::string out;
  if (s.rim_size > 0.0) {
    out +=
        fmt::format(", {:.3g} mm within {:.3g} mm of the rim", 1e3 * s.rim_size, 1e3 * s.rim_band);
  }
  if (s.contact_size > 0.0) {
    out += fmt::format(", {:.3g} mm within {:.3g} mm of the apex", 1e3 * s.contact_size,
                       1e3 * s.contact_band);
  }
  return out;
}

double cap_element_size(const CapSpec& s, double arc) {
  const auto zone = [](double fine, double band, double distance) {
    if (!(fine > 0.0)) return std::numeric_limits<double>::infinity();
    return fine + kSizeGrowth * std::max(0.0, distance - band);
  };
  return std::min({s.element_size, zone(s.contact_size, s.contact_band, arc),
                   zone(s.rim_size, s.rim_band, s.R * s.phi - arc)});
}

CapSpec cap_spec(const config::Case& c) {
  const auto& preset = config::preset(c.numerics.resolution);
  CapSpec s;
  s.R = c.shell.R;
  s.h = c.shell.h;
  s.phi = c.shell.phi;
  s.element_size = c.numerics.element_size.value_or(preset.element_size_over_sqrt_hR *
                                                    std::sqrt(c.shell.h * c.shell.R));
  s.layers = c.numerics.elements_through_thickness.value_or(preset.layers);
  s.rim_size = c.numerics.rim_element_size.value_or(0.0);
  s.rim_band = c.numerics.rim_band.value_or(0.0);
  s.contact_size = c.numerics.contact_element_size.value_or(0.0);
  s.contact_band = c.numerics.contact_band.value_or(0.0);
  return s;
}

Mesh make_cap_mesh(const CapSpec& s) {
  check_spec(s);
  const SurfaceMesh sm = triangulate_mid_surface(s);
  const int ns = static_cast<int>(sm.dir.size());
  const int L = s.layers;
  const double rim_tol = 1e-6;
  std::vector<bool> on_rim(ns);
  for (int i = 0; i < ns; ++i) on_rim[i] = polar_angle(sm.dir[i]) >= s.phi - rim_tol;

  Mesh m;
  m.description = describe(s);
  // Vertices: layer k (0 = inner surface, L = outer) of surface vertex i is k * ns + i.
  const auto radius = [&](int k) { return s.R - 0.5 * s.h + s.h * k / L; };
  std::vector<Vec> dir_of;
  std::vector<double> radius_of;
  std::vector<bool> rim_of, outer_of;
  const auto add_node = [&](Vec d, double r, bool rim, bool outer) {
    const Vec p = r * d;
    m.nodes.push_back(p.x, p.y, p.z);
    dir_of.push_back(d);
    radius_of.push_back(r);
    rim_of.push_back(rim);
    outer_of.push_back(outer);
    return static_cast<int>(m.nodes.size()) - 1;
  };
  for (int k = 0; k <= L; ++k) {
    for (int i = 0; i < ns; ++i) add_node(sm.dir[i], radius(k), on_rim[i], k == L);
  }
  const auto vid = [&](int k, int i) { return k * ns + i; };

  // Edge nodes, created on demand, placed on the sphere (or rim cone) of their edge.
  std::unordered_map<std::uint64_t, int> edge_node;
  const auto edge = [&](int a, int b) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
    if (const auto it = edge_node.find(key); it != edge_node.end()) return it->second;
    Vec d = dir_of[a] + dir_of[b];
    d = (1.0 / norm(d)) * d;
    const bool rim = rim_of[a] && rim_of[b];
    if (rim) {  // keep the rim face a cone of half-angle phi
      const double theta = std::atan2(d.y, d.x);
      d = {std::sin(s.phi) * std::cos(theta), std::sin(s.phi) * std::sin(theta), -std::cos(s.phi)};
    }
    const int id =
        add_node(d, 0.5 * (radius_of[a] + radius_of[b]), rim, outer_of[a] && outer_of[b]);
    edge_node.emplace(key, id);
    return id;
  };
  const auto position = [&](int a) { return Vec{m.nodes.x[a], m.nodes.y[a], m.nodes.z[a]}; };

  for (const auto& tri : sm.tris) {
    std::array<int, 3> t = tri;
    std::sort(t.begin(), t.end());  // conforming split: diagonals from lower to higher index
    for (int l = 0; l < L; ++l) {
      const int ai = vid(l, t[0]), aj = vid(l, t[1]), ak = vid(l, t[2]);
      const int bi = vid(l + 1, t[0]), bj = vid(l + 1, t[1]), bk = vid(l + 1, t[2]);
      const std::array<std::array<int, 4>, 3> corners{
          {{ai, aj, ak, bk}, {ai, aj, bj, bk}, {ai, bi, bj, bk}}};
      for (auto c : corners) {
        const Vec p0 = position(c[0]);
        const double vol6 =
            dot(position(c[1]) - p0, cross(position(c[2]) - p0, position(c[3]) - p0));
        if (vol6 < 0) std::swap(c[1], c[2]);
        std::array<int, 10> tet{};
        for (int a = 0; a < 4; ++a) tet[a] = c[a];
        for (int e = 0; e < 6; ++e) tet[4 + e] = edge(c[kTetEdges[e][0]], c[kTetEdges[e][1]]);
        m.tets.push_back(tet);
      }
    }
    // The inner face: layer 0, normal away from the centre (out of the cavity, into the shell).
    std::array<int, 3> c{vid(0, tri[0]), vid(0, tri[1]), vid(0, tri[2])};
    const Vec p0 = position(c[0]);
    const Vec n = cross(position(c[1]) - p0, position(c[2]) - p0);
    if (dot(n, p0 + position(c[1]) + position(c[2])) < 0) std::swap(c[1], c[2]);
    m.inner_faces.push_back(
        {c[0], c[1], c[2], edge(c[0], c[1]), edge(c[1], c[2]), edge(c[0], c[2])});
  }

  mark_sets(s, rim_of, outer_of, m);
  check_mesh(m);
  check_shell_sets(m);
  return m;
}

}  // namespace snapjump::mesh
