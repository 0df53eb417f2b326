// SPDX-License-Identifier: MIT
// A generated sweep of wireframe models whose faces and volumes are known by construction,
// each one relabelled at random (vertex order, edge order, edge directions) and some of them
// moved by a random rigid motion: the yardstick of the wireframe → cell complex face selection
// (tests/test_wireframe_sweep.cpp runs it).
//
// The truth follows one rule: a face exists only where some edge needs it. An edge needs a
// face F on it when without F the edge would lie on fewer than two faces, or on exactly two
// coplanar faces. Every face of every model is needed by one of its edges
// (faces_no_edge_needs(m) == 0) except in k×m×n grids with k, m, n >= 3: there some walls and
// the middles of the outer faces are needed by no edge, the wireframe cannot say which to
// drop, so the truth keeps every cube and `unforced_faces` counts the faces no edge needs.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/algorithms/convex_hull.hpp"
#include "cellforge/cells/validate.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/samples/drawings.hpp"
#include "cellforge/samples/wireframe_models.hpp"
#include "cellforge/wireframe/wireframe_to_cells.hpp"

namespace wireframe_sweep {

/// How much of the sweep to build: every model (Release) or a sample of every family (sanitizers).
enum class sweep_size { sample, full };

/// One model of the sweep and the family it belongs to.
struct sweep_model {
  std::string family;
  cellforge::samples::sample_model model;
};

/// Draws of a random family: how many were kept and why the others were thrown away.
struct family_draws {
  std::string family;
  std::size_t kept = 0;
  std::size_t not_manifold =
      0;                     ///< touching itself at an edge or a vertex, a cavity, a cell empty or in pieces
  std::size_t outline = 0;   ///< make_voxel_model refused it (a face outline touches itself)
  std::size_t unneeded = 0;  ///< a face no edge needs (an inner wall, a face surrounded by walls)
  std::size_t rejected() const { return not_manifold + outline + unneeded; }
};

/// The whole sweep: models, the draws of the random families, the library models left out
/// (some face of their truth is needed by no edge) and generator faults (must stay empty).
struct sweep_set {
  bool shuffle = true;  ///< whether the models were relabelled and moved (make_sweep's argument)
  std::vector<sweep_model> models;
  std::vector<family_draws> draws;
  std::vector<std::string> left_out;
  std::vector<std::string> faults;
};

/// The family names, in the order the sweep builds them.
/// O(1).
inline const std::vector<std::string>& sweep_families() {
  static const std::vector<std::string> names{
      "frame",        "plate",     "box ring",       "torus",         "bipyramid",      "house",
      "dent",         "notch",     "barrel",         "hourglass",     "geodesic",       "polytope",
      "cross",        "polycube",  "polycube cells", "linked frames", "solid in frame", "touching",
      "grid",         "hole grid", "double frame",   "linked tori",   "stepped bore",   "holed face",
      "big polycube", "library"};
  return names;
}

/// Random numbers taken straight from std::mt19937_64's output, whose sequence the standard
/// fixes (the std distributions differ between libraries). O(1) per number.
class random_source {
 public:
  explicit random_source(std::uint64_t seed) : engine_(seed) {}
  /// A double in [0, 1) from the top 53 bits of one draw.
  /// O(1).
  double unit() { return static_cast<double>(engine_() >> 11) * 0x1p-53; }
  /// A double in [lo, hi).
  /// O(1).
  double between(double lo, double hi) { return lo + (hi - lo) * unit(); }
  /// An integer in [0, n) for n > 0 (modulo bias below n / 2^64).
  /// O(1).
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(engine_() % n); }
  /// An integer in [lo, hi].
  /// O(1).
  std::size_t in(std::size_t lo, std::size_t hi) { return lo + below(hi - lo + 1); }
  /// True with probability p.
  /// O(1).
  bool chance(double p) { return unit() < p; }

 private:
  std::mt19937_64 engine_;
};

/// FNV-1a hash of a name: the seed of a model's relabelling depends on its name only, so the
/// sample and the full sweep shuffle a model they share the same way. O(length).
inline std::uint64_t name_seed(const std::string& name) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : name) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  return h;
}

/// For each face of the truth: does one of its edges need it (without the face the edge would
/// lie on fewer than two faces, or on exactly two coplanar ones)? O(L), L the total loop length.
inline std::vector<bool> faces_needed(const cellforge::samples::sample_model& m) {
  const auto key = [](std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> faces_at;  // edge → faces on it
  std::vector<glm::dvec3> unit_normal(m.faces.size());
  for (std::uint32_t f = 0; f < m.faces.size(); ++f) {
    unit_normal[f] = glm::normalize(cellforge::samples::detail::newell_normal(m.wire.points, m.faces[f][0]));
    for (const auto& loop : m.faces[f])
      for (std::size_t i = 0; i < loop.size(); ++i)
        faces_at[key(loop[i], loop[(i + 1) % loop.size()])].push_back(f);
  }
  const auto needs = [&](std::uint32_t f, const std::vector<std::uint32_t>& on_edge) {
    std::vector<std::uint32_t> rest;
    for (const std::uint32_t g : on_edge)
      if (g != f) rest.push_back(g);
    if (rest.size() != 2) return rest.size() < 2;
    // Two faces through one edge with parallel normals lie in one plane: a flat seam.
    return glm::length(glm::cross(unit_normal[rest[0]], unit_normal[rest[1]])) < 1e-9;
  };
  std::vector<bool> needed(m.faces.size(), false);
  for (std::uint32_t f = 0; f < m.faces.size(); ++f)
    for (const auto& loop : m.faces[f])
      for (std::size_t i = 0; i < loop.size() && !needed[f]; ++i)
        needed[f] = needs(f, faces_at[key(loop[i], loop[(i + 1) % loop.size()])]);
  return needed;
}

/// How many faces of the truth no edge needs (outer faces count too, unlike count_unforced,
/// which counts walls between volumes only). O(L), L the total loop length.
inline std::size_t faces_no_edge_needs(const cellforge::samples::sample_model& m) {
  const std::vector<bool> needed = faces_needed(m);
  return static_cast<std::size_t>(std::count(needed.begin(), needed.end(), false));
}

/// Objects of the truth: connected components of its faces through shared vertices (a face's
/// loops are one piece, so a hole stays with its face). O(L α(V)).
inline std::size_t truth_objects(const cellforge::samples::sample_model& m) {
  std::vector<std::uint32_t> up(m.wire.points.size());
  for (std::uint32_t v = 0; v < up.size(); ++v) up[v] = v;
  const auto root = [&](std::uint32_t v) {
    while (up[v] != v) v = up[v] = up[up[v]];
    return v;
  };
  std::vector<bool> used(up.size(), false);
  for (const auto& face : m.faces)
    for (const auto& loop : face)
      for (const std::uint32_t v : loop) {
        used[v] = true;
        up[root(v)] = root(face[0][0]);
      }
  std::size_t n = 0;
  for (std::uint32_t v = 0; v < up.size(); ++v) n += used[v] && root(v) == v;
  return n;
}

/// What shuffled() did: new label of each old vertex, new place of each old edge, the edges
/// turned round, and the motion p → rotation · p + shift (identity when there is none).
struct relabelling {
  std::vector<std::uint32_t> vertex, edge;
  std::vector<bool> flipped;
  glm::dmat3 rotation{1.0};
  glm::dvec3 shift{0.0};
};

namespace detail {

/// A uniformly random permutation of 0..n-1 (Fisher–Yates on random_source, not std::shuffle,
/// whose algorithm is the library's choice). O(n).
inline std::vector<std::uint32_t> permutation(std::size_t n, random_source& rng) {
  std::vector<std::uint32_t> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = static_cast<std::uint32_t>(i);
  for (std::size_t i = n; i > 1; --i) std::swap(p[i - 1], p[rng.below(i)]);
  return p;
}

/// A uniformly random rotation (Shoemake's unit quaternion from three uniforms) as a matrix.
/// O(1).
inline glm::dmat3 random_rotation(random_source& rng) {
  const double u = rng.unit(), a = 2 * std::numbers::pi * rng.unit(), b = 2 * std::numbers::pi * rng.unit();
  const double x = std::sqrt(1 - u) * std::sin(a), y = std::sqrt(1 - u) * std::cos(a);
  const double z = std::sqrt(u) * std::sin(b), w = std::sqrt(u) * std::cos(b);
  glm::dmat3 r(1.0);  // r[column][row]
  r[0] = {1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)};
  r[1] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
  r[2] = {2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)};
  return r;
}

/// Length of the diagonal of the points' bounding box.
/// O(V).
inline double diagonal(const std::vector<glm::dvec3>& points) {
  if (points.empty()) return 0.0;
  glm::dvec3 lo = points[0], hi = points[0];
  for (const auto& p : points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  return glm::length(hi - lo);
}

}  // namespace detail

/// The model with its vertices and edges in a random order, about half of the edges turned
/// round and, when `rigid`, moved by a random rotation and a shift of up to 10 model sizes per
/// axis; the truth is relabelled to match. `record` receives what was done. O(model).
inline cellforge::samples::sample_model shuffled(const cellforge::samples::sample_model& m,
                                                 std::uint64_t seed, bool rigid,
                                                 relabelling* record = nullptr) {
  random_source rng(seed);
  relabelling t;
  t.vertex = detail::permutation(m.wire.points.size(), rng);
  t.edge = detail::permutation(m.wire.edges.size(), rng);
  t.flipped.assign(m.wire.edges.size(), false);
  cellforge::samples::sample_model out;
  out.name = m.name;
  out.wire.points.resize(m.wire.points.size());
  for (std::size_t v = 0; v < m.wire.points.size(); ++v) out.wire.points[t.vertex[v]] = m.wire.points[v];
  out.wire.edges.resize(m.wire.edges.size());
  for (std::size_t e = 0; e < m.wire.edges.size(); ++e) {
    std::array<std::uint32_t, 2> ab{t.vertex[m.wire.edges[e][0]], t.vertex[m.wire.edges[e][1]]};
    if (rng.chance(0.5)) {
      std::swap(ab[0], ab[1]);
      t.flipped[e] = true;
    }
    out.wire.edges[t.edge[e]] = ab;
  }
  out.faces = m.faces;
  for (auto& face : out.faces)
    for (auto& loop : face)
      for (auto& v : loop) v = t.vertex[v];
  out.volumes = m.volumes;
  out.unforced_faces = m.unforced_faces;
  if (rigid) {
    t.rotation = detail::random_rotation(rng);
    const double size = detail::diagonal(m.wire.points);
    for (int a = 0; a < 3; ++a) t.shift[a] = rng.between(-10.0, 10.0) * size;
    out = cellforge::samples::transformed(std::move(out), t.rotation, t.shift);
  }
  if (record) *record = std::move(t);
  return out;
}

namespace detail {

/// A model built face by face: every side of a face loop becomes a wire edge (once), so every
/// edge lies on a face. O(1) amortised per point, O(log E) per face side.
class model_builder {
 public:
  /// Adds a point and returns its label.
  /// O(1) amortised.
  std::uint32_t point(const glm::dvec3& p) {
    m_.wire.points.push_back(p);
    return static_cast<std::uint32_t>(m_.wire.points.size() - 1);
  }
  /// Adds a face (outer loop, then holes) and the edges along it; returns its index.
  /// O(size · log E).
  std::uint32_t face(std::vector<std::vector<std::uint32_t>> loops) {
    for (const auto& loop : loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
        if (edges_.insert({std::min(a, b), std::max(a, b)}).second) m_.wire.edges.push_back({a, b});
      }
    m_.faces.push_back(std::move(loops));
    return static_cast<std::uint32_t>(m_.faces.size() - 1);
  }
  /// Where point v is.
  /// O(1).
  glm::dvec3 point_at(std::uint32_t v) const { return m_.wire.points[v]; }
  /// Adds a volume bounded by the given faces.
  /// O(size).
  void volume(std::vector<std::uint32_t> faces) { m_.volumes.push_back(std::move(faces)); }
  /// The finished model (volumes sorted).
  /// O(model).
  cellforge::samples::sample_model done(std::string name) {
    m_.name = std::move(name);
    return cellforge::samples::detail::finish(std::move(m_));
  }

 private:
  cellforge::samples::sample_model m_;
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges_;
};

/// The model with points at exactly the same place made one vertex (solids touching at a
/// point); edges and faces relabelled, repeated edges dropped. O(V log V + model).
inline cellforge::samples::sample_model glued(cellforge::samples::sample_model m) {
  std::map<std::array<double, 3>, std::uint32_t> at;
  std::vector<std::uint32_t> label(m.wire.points.size());
  std::vector<glm::dvec3> points;
  for (std::size_t v = 0; v < m.wire.points.size(); ++v) {
    const glm::dvec3& p = m.wire.points[v];
    const auto [it, fresh] = at.emplace(std::array<double, 3>{p.x, p.y, p.z}, points.size());
    if (fresh) points.push_back(p);
    label[v] = it->second;
  }
  std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
  std::vector<std::array<std::uint32_t, 2>> edges;
  for (const auto& e : m.wire.edges) {
    const std::uint32_t a = label[e[0]], b = label[e[1]];
    if (seen.insert({std::min(a, b), std::max(a, b)}).second) edges.push_back({a, b});
  }
  m.wire.points = std::move(points);
  m.wire.edges = std::move(edges);
  for (auto& face : m.faces)
    for (auto& loop : face)
      for (auto& v : loop) v = label[v];
  return m;
}

/// The model without its walls (faces between two volumes), its volumes merged into one: the
/// reading the truth rule gives a ring stack whose rings no edge needs. O(model).
inline cellforge::samples::sample_model without_walls(const cellforge::samples::sample_model& m,
                                                      std::string name) {
  std::vector<int> volumes_of(m.faces.size(), 0);
  for (const auto& v : m.volumes)
    for (const std::uint32_t f : v) ++volumes_of[f];
  cellforge::samples::sample_model out;
  out.wire = m.wire;
  out.volumes.emplace_back();
  for (std::size_t f = 0; f < m.faces.size(); ++f)
    if (volumes_of[f] == 1) {
      out.volumes[0].push_back(static_cast<std::uint32_t>(out.faces.size()));
      out.faces.push_back(m.faces[f]);
    }
  out.name = std::move(name);
  return cellforge::samples::detail::finish(std::move(out));
}

/// Lattice coordinates 0, w0, w0 + w1, ... from the cell widths.
/// O(n).
inline std::vector<double> from_widths(const std::vector<double>& widths) {
  std::vector<double> c{0.0};
  for (const double w : widths) c.push_back(c.back() + w);
  return c;
}

/// Label of lattice cell (i, j, k); 0 outside the lattice.
/// O(1).
inline int cell(const cellforge::samples::voxel_layout& l, std::ptrdiff_t i, std::ptrdiff_t j,
                std::ptrdiff_t k) {
  const auto nx = static_cast<std::ptrdiff_t>(l.xs.size()) - 1,
             ny = static_cast<std::ptrdiff_t>(l.ys.size()) - 1,
             nz = static_cast<std::ptrdiff_t>(l.zs.size()) - 1;
  if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) return 0;
  return l.labels[static_cast<std::size_t>(i + nx * (j + ny * k))];
}

/// Whether the cells of a 2×2×2 block in `mask` (bit dx + 2dy + 4dz), and the others, are each
/// connected through faces: the block's corner is then a manifold point of the solid. O(1).
inline bool manifold_block(unsigned mask) { return cellforge::samples::detail::manifold_corner(mask); }

/// True when the cells whose label `inside` accepts make a manifold solid (no two of them
/// touching only along an edge or at a vertex). O(lattice points).
template <class Inside>
bool manifold(const cellforge::samples::voxel_layout& l, Inside inside) {
  static const std::array<bool, 256> ok = [] {
    std::array<bool, 256> t{};
    for (unsigned m = 0; m < 256; ++m) t[m] = manifold_block(m);
    return t;
  }();
  for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(l.zs.size()); ++k)
    for (std::ptrdiff_t j = 0; j < static_cast<std::ptrdiff_t>(l.ys.size()); ++j)
      for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(l.xs.size()); ++i) {
        unsigned mask = 0;
        for (unsigned b = 0; b < 8; ++b)
          if (inside(cell(l, i - 1 + (b & 1), j - 1 + (b >> 1 & 1), k - 1 + (b >> 2 & 1)))) mask |= 1u << b;
        if (!ok[mask]) return false;
      }
  return true;
}

/// True when every empty cell can be reached from outside the lattice through empty cells
/// (a cavity would be read as a volume of its own). O(cells).
inline bool no_cavity(const cellforge::samples::voxel_layout& l) {
  const std::array<std::ptrdiff_t, 3> n{static_cast<std::ptrdiff_t>(l.xs.size()) + 1,
                                        static_cast<std::ptrdiff_t>(l.ys.size()) + 1,
                                        static_cast<std::ptrdiff_t>(l.zs.size()) + 1};
  const auto index = [&](std::ptrdiff_t i, std::ptrdiff_t j, std::ptrdiff_t k) {
    return static_cast<std::size_t>(i + n[0] * (j + n[1] * k));
  };
  std::vector<char> seen(static_cast<std::size_t>(n[0] * n[1] * n[2]), 0);
  std::vector<std::array<std::ptrdiff_t, 3>> todo{{0, 0, 0}};
  seen[0] = 1;
  std::size_t reached = 0;
  while (!todo.empty()) {
    const auto c = todo.back();
    todo.pop_back();
    ++reached;
    for (int a = 0; a < 3; ++a)
      for (const std::ptrdiff_t s : {-1, 1}) {
        auto d = c;
        d[static_cast<std::size_t>(a)] += s;
        if (d[0] < 0 || d[1] < 0 || d[2] < 0 || d[0] >= n[0] || d[1] >= n[1] || d[2] >= n[2]) continue;
        if (seen[index(d[0], d[1], d[2])] || cell(l, d[0] - 1, d[1] - 1, d[2] - 1) != 0) continue;
        seen[index(d[0], d[1], d[2])] = 1;
        todo.push_back(d);
      }
  }
  const auto empty = static_cast<std::size_t>(std::count(l.labels.begin(), l.labels.end(), 0));
  return reached == static_cast<std::size_t>(n[0] * n[1] * n[2]) - l.labels.size() + empty;
}

/// Appends the model's copies to the sweep: in the full sweep the shuffled model and
/// `rigid_copies` rigidly moved ones ("rot#k"); in the sample one copy, moved when `odd`.
/// Without s.shuffle the copies keep the model's labels and place. O(model).
inline void add_copies(sweep_set& s, const std::string& family, const cellforge::samples::sample_model& base,
                       bool full, int rigid_copies, bool odd) {
  const auto add = [&](bool rigid, int k) {
    const std::string name = rigid ? base.name + " rot#" + std::to_string(k) : base.name;
    cellforge::samples::sample_model copy = s.shuffle ? shuffled(base, name_seed(name), rigid) : base;
    copy.name = name;
    s.models.push_back({family, std::move(copy)});
  };
  if (!full) return add(odd, 1);
  add(false, 0);
  for (int k = 1; k <= rigid_copies; ++k) add(true, k);
}

/// Adds a deterministic family: every base must satisfy the truth rule (a fault otherwise);
/// unforced_faces is 0. O(total size).
inline void add_family(sweep_set& s, const std::string& family,
                       std::vector<cellforge::samples::sample_model> bases, bool full, int rigid_copies = 1) {
  for (std::size_t i = 0; i < bases.size(); ++i) {
    cellforge::samples::sample_model& m = bases[i];
    if (const std::size_t n = faces_no_edge_needs(m); n != 0) {
      s.faults.push_back(family + ": '" + m.name + "' has " + std::to_string(n) + " faces no edge needs");
      continue;
    }
    m.unforced_faces = 0;
    add_copies(s, family, m, full, rigid_copies, i % 2 == 1);
  }
}

// ---- the families --------------------------------------------------------------------------

/// A frame (thin bars, big holes) or plate (wide, small holes) with `holes` through-holes in
/// a grid (or a row), one volume or split into bands of cells by walls. O(holes).
inline cellforge::samples::sample_model holed_slab(bool frame, std::size_t holes, bool row, bool cells) {
  std::size_t rows = 1, cols = holes;
  if (!row && holes == 4) rows = 2, cols = 2;
  if (!row && (holes == 5 || holes == 6)) rows = 2, cols = 3;
  if (!row && holes >= 7) rows = 3, cols = 3;
  const double bar = frame ? 0.3 : 1.0, hole = frame ? 1.0 : 0.375, thick = frame ? 0.4 : 0.2;
  const auto widths = [&](std::size_t n) {
    std::vector<double> w;
    for (std::size_t c = 0; c <= 2 * n; ++c)
      w.push_back((c % 2 == 0 ? bar : hole) * (1.0 + 0.125 * double(c % 3)));
    return w;
  };
  cellforge::samples::voxel_layout l =
      cellforge::samples::empty_layout(from_widths(widths(cols)), from_widths(widths(rows)), {0.0, thick});
  for (std::size_t j = 0; j <= 2 * rows; ++j)
    for (std::size_t i = 0; i <= 2 * cols; ++i) l.at(i, j, 0) = cells ? 1 + static_cast<int>((i + 1) / 2) : 1;
  for (std::size_t h = 0; h < holes; ++h) l.at(2 * (h % cols) + 1, 2 * (h / cols) + 1, 0) = 0;
  const std::string name = std::string(frame ? "frame" : "plate") + " holes=" + std::to_string(holes) +
                           (row && holes > 3 ? " row" : "") + (cells ? " cells" : " one");
  return cellforge::samples::make_voxel_model(l, name);
}

/// A ring of n box-like sectors (annular sectors, straight-sided) around a hole, each its own
/// volume, one layer high. O(n).
inline cellforge::samples::sample_model sector_ring(std::size_t n, double inner, double outer,
                                                    double height) {
  model_builder b;
  std::vector<std::array<std::uint32_t, 4>> p(n);  // inner bottom, outer bottom, inner top, outer top
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * double(i) / double(n) + 0.3;
    const glm::dvec3 d(std::cos(t), std::sin(t), 0.0);
    p[i] = {b.point(inner * d), b.point(outer * d), b.point(inner * d + glm::dvec3(0, 0, height)),
            b.point(outer * d + glm::dvec3(0, 0, height))};
  }
  std::vector<std::uint32_t> wall(n);
  for (std::size_t i = 0; i < n; ++i) wall[i] = b.face({{p[i][0], p[i][1], p[i][3], p[i][2]}});
  for (std::size_t i = 0; i < n; ++i) {
    const auto &a = p[i], &c = p[(i + 1) % n];
    b.volume({b.face({{a[3], c[3], c[2], a[2]}}), b.face({{a[0], c[0], c[1], a[1]}}),
              b.face({{a[1], c[1], c[3], a[3]}}), b.face({{a[0], a[2], c[2], c[0]}}), wall[i],
              wall[(i + 1) % n]});
  }
  return b.done("box ring sectors n=" + std::to_string(n) + " r=" + std::to_string(int(inner * 10)));
}

/// A one-layer ring of boxes on the border of a k × m lattice: every cell its own volume, or
/// four boxes in a pinwheel. O(k · m).
inline cellforge::samples::sample_model lattice_ring(std::size_t k, std::size_t m, bool pinwheel) {
  std::vector<double> wx, wy;
  for (std::size_t i = 0; i < k; ++i) wx.push_back(1.0 + 0.25 * double(i % 2));
  for (std::size_t j = 0; j < m; ++j) wy.push_back(0.75 + 0.5 * double(j % 3 == 1));
  cellforge::samples::voxel_layout l =
      cellforge::samples::empty_layout(from_widths(wx), from_widths(wy), {0.0, 0.5});
  int next = 1;
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t i = 0; i < k; ++i) {
      if (i != 0 && j != 0 && i + 1 != k && j + 1 != m) continue;
      if (!pinwheel)
        l.at(i, j, 0) = next++;
      else
        l.at(i, j, 0) = j == 0 && i + 1 < k ? 1 : i + 1 == k && j + 1 < m ? 2 : j + 1 == m && i > 0 ? 3 : 4;
    }
  return cellforge::samples::make_voxel_model(l, "box ring " + std::string(pinwheel ? "pinwheel " : "") +
                                                     std::to_string(k) + "x" + std::to_string(m));
}

/// A solid of revolution of a closed profile polygon ((r, z) pairs) in n segments: one genus-1
/// volume, or split into n volumes by the profile polygons as walls. O(n · profile).
inline cellforge::samples::sample_model revolved(const std::vector<std::array<double, 2>>& profile,
                                                 std::size_t n, bool walls, std::string name) {
  model_builder b;
  const std::size_t k = profile.size();
  std::vector<std::uint32_t> id(n * k);
  for (std::size_t j = 0; j < n; ++j) {
    const double t = 2 * std::numbers::pi * double(j) / double(n);
    for (std::size_t i = 0; i < k; ++i)
      id[j * k + i] = b.point({profile[i][0] * std::cos(t), profile[i][0] * std::sin(t), profile[i][1]});
  }
  const auto at = [&](std::size_t j, std::size_t i) { return id[(j % n) * k + i % k]; };
  std::vector<std::vector<std::uint32_t>> segment(n);
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t i = 0; i < k; ++i)
      segment[j].push_back(b.face({{at(j, i), at(j + 1, i), at(j + 1, i + 1), at(j, i + 1)}}));
  if (!walls) {
    std::vector<std::uint32_t> all;
    for (const auto& s : segment) all.insert(all.end(), s.begin(), s.end());
    b.volume(std::move(all));
    return b.done(std::move(name));
  }
  std::vector<std::uint32_t> meridian(n);
  for (std::size_t j = 0; j < n; ++j) {
    std::vector<std::uint32_t> loop;
    for (std::size_t i = 0; i < k; ++i) loop.push_back(at(j, i));
    meridian[j] = b.face({loop});
  }
  for (std::size_t j = 0; j < n; ++j) {
    segment[j].push_back(meridian[j]);
    segment[j].push_back(meridian[(j + 1) % n]);
    b.volume(segment[j]);
  }
  return b.done(std::move(name));
}

/// Hexagonal torus profiles about radius R: with a corner on top ("pointy", nothing flat) or
/// with flat top and bottom sides ("flat"). O(1).
inline std::vector<std::array<double, 2>> hexagon(double R, double a, bool flat) {
  const double c = a * std::sqrt(3.0) / 2;
  if (flat) return {{R + a, 0}, {R + a / 2, c}, {R - a / 2, c}, {R - a, 0}, {R - a / 2, -c}, {R + a / 2, -c}};
  return {{R + c, a / 2}, {R, a}, {R - c, a / 2}, {R - c, -a / 2}, {R, -a}, {R + c, -a / 2}};
}

/// A box L × W × H under a pyramid roof with its apex at (ax, ay, H + rise): one volume (the
/// rectangle under the roof is no face). O(1).
inline cellforge::samples::sample_model pyramid_house(double L, double W, double H, glm::dvec3 apex,
                                                      std::string name) {
  model_builder b;
  const glm::dvec3 corner[4] = {{0, 0, 0}, {L, 0, 0}, {L, W, 0}, {0, W, 0}};
  std::array<std::uint32_t, 4> lo{}, hi{};
  for (int i = 0; i < 4; ++i) lo[i] = b.point(corner[i]), hi[i] = b.point(corner[i] + glm::dvec3(0, 0, H));
  const std::uint32_t top = b.point(apex);
  std::vector<std::uint32_t> faces{b.face({{lo[0], lo[1], lo[2], lo[3]}})};
  for (int i = 0; i < 4; ++i) {
    const int j = (i + 1) % 4;
    faces.push_back(b.face({{lo[i], lo[j], hi[j], hi[i]}}));
    faces.push_back(b.face({{hi[i], hi[j], top}}));
  }
  b.volume(faces);
  return b.done(std::move(name));
}

/// A box L × W × H under a hip roof: a ridge at height H + rise, `inset` in from each end,
/// two trapezoids and two triangles; one volume. O(1).
inline cellforge::samples::sample_model hip_house(double L, double W, double H, double rise, double inset) {
  model_builder b;
  const glm::dvec3 corner[4] = {{0, 0, 0}, {L, 0, 0}, {L, W, 0}, {0, W, 0}};
  std::array<std::uint32_t, 4> lo{}, hi{};
  for (int i = 0; i < 4; ++i) lo[i] = b.point(corner[i]), hi[i] = b.point(corner[i] + glm::dvec3(0, 0, H));
  const std::uint32_t r0 = b.point({inset, W / 2, H + rise}), r1 = b.point({L - inset, W / 2, H + rise});
  std::vector<std::uint32_t> faces{b.face({{lo[0], lo[1], lo[2], lo[3]}})};
  for (int i = 0; i < 4; ++i) faces.push_back(b.face({{lo[i], lo[(i + 1) % 4], hi[(i + 1) % 4], hi[i]}}));
  faces.push_back(b.face({{hi[0], hi[1], r1, r0}}));
  faces.push_back(b.face({{hi[2], hi[3], r0, r1}}));
  faces.push_back(b.face({{hi[1], hi[2], r1}}));
  faces.push_back(b.face({{hi[3], hi[0], r0}}));
  b.volume(faces);
  return b.done("house hip " + std::to_string(int(L * 10)) + "x" + std::to_string(int(W * 10)) +
                " inset=" + std::to_string(int(inset * 100)));
}

/// A pyramid pit in a box face: a regular `sides`-gon hole about (cu, cv) in the face's unit
/// square, its sides joined to an apex above (au, av) at `depth` (fraction of the box, inwards;
/// negative: a bump outwards).
struct pit {
  int face;
  std::size_t sides;
  double cu, cv, radius, depth, au, av, turn = 0.0;
};

/// A box with pyramid dents or bumps in its faces: each pitted face has a hole per pit, whose
/// sides go to the pit's apex; one volume. O(pits · sides).
inline cellforge::samples::sample_model pitted_box(glm::dvec3 size, const std::vector<pit>& pits,
                                                   std::string name) {
  model_builder b;
  std::array<std::uint32_t, 8> c{};
  for (int i = 0; i < 8; ++i) c[i] = b.point(size * glm::dvec3(i & 1, i >> 1 & 1, i >> 2 & 1));
  // Faces z=0, z=1, y=0, y=1, x=0, x=1 as corner loops; u = loop[1]-loop[0], v = loop[3]-loop[0].
  const std::array<std::array<int, 4>, 6> loops{
      {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}}};
  const glm::dvec3 centre = size / 2.0;
  std::vector<std::uint32_t> faces;
  for (int f = 0; f < 6; ++f) {
    const auto& L = loops[static_cast<std::size_t>(f)];
    std::vector<std::vector<std::uint32_t>> face{{c[L[0]], c[L[1]], c[L[2]], c[L[3]]}};
    const glm::dvec3 o = size * glm::dvec3(L[0] & 1, L[0] >> 1 & 1, L[0] >> 2 & 1);
    const glm::dvec3 u = size * glm::dvec3(L[1] & 1, L[1] >> 1 & 1, L[1] >> 2 & 1) - o;
    const glm::dvec3 v = size * glm::dvec3(L[3] & 1, L[3] >> 1 & 1, L[3] >> 2 & 1) - o;
    glm::dvec3 in = glm::normalize(glm::cross(u, v));
    if (glm::dot(in, centre - o) < 0) in = -in;
    const double extent = std::abs(glm::dot(size, in));
    for (const pit& p : pits) {
      if (p.face != f) continue;
      std::vector<std::uint32_t> hole;
      for (std::size_t k = 0; k < p.sides; ++k) {
        const double t = 2 * std::numbers::pi * double(k) / double(p.sides) + p.turn;
        hole.push_back(
            b.point(o + (p.cu + p.radius * std::cos(t)) * u + (p.cv + p.radius * std::sin(t)) * v));
      }
      const std::uint32_t apex = b.point(o + p.au * u + p.av * v + p.depth * extent * in);
      for (std::size_t k = 0; k < p.sides; ++k)
        faces.push_back(b.face({{hole[k], hole[(k + 1) % p.sides], apex}}));
      face.push_back(std::move(hole));
    }
    faces.push_back(b.face(std::move(face)));
  }
  b.volume(faces);
  return b.done(std::move(name));
}

/// A subdivided icosahedron (frequency f: 20 f² triangles) projected on the unit sphere; one
/// volume. O(f²).
inline cellforge::samples::sample_model geodesic_sphere(std::size_t f) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<glm::dvec3> ico;
  for (const double s : {-1.0, 1.0})
    for (const double t : {-1.0, 1.0}) {
      ico.push_back({0, s, t * g});
      ico.push_back({s, t * g, 0});
      ico.push_back({t * g, 0, s});
    }
  model_builder b;
  std::map<std::vector<std::pair<std::size_t, std::size_t>>, std::uint32_t> ids;  // weights → point
  const auto point = [&](std::array<std::size_t, 3> corner, std::array<std::size_t, 3> weight) {
    std::vector<std::pair<std::size_t, std::size_t>> key;
    for (int i = 0; i < 3; ++i)
      if (weight[i] > 0) key.push_back({corner[i], weight[i]});
    std::sort(key.begin(), key.end());
    if (const auto it = ids.find(key); it != ids.end()) return it->second;
    glm::dvec3 p(0.0);
    for (const auto& [c, w] : key) p += double(w) * ico[c];
    return ids[key] = b.point(glm::normalize(p));
  };
  std::vector<std::uint32_t> faces;
  for (std::size_t i = 0; i < 12; ++i)
    for (std::size_t j = i + 1; j < 12; ++j)
      for (std::size_t k = j + 1; k < 12; ++k) {
        if (std::abs(glm::length(ico[i] - ico[j]) - 2) > 1e-9 ||
            std::abs(glm::length(ico[j] - ico[k]) - 2) > 1e-9 ||
            std::abs(glm::length(ico[i] - ico[k]) - 2) > 1e-9)
          continue;
        const std::array<std::size_t, 3> tri{i, j, k};
        const auto at = [&](std::size_t a, std::size_t c) { return point(tri, {f - a - c, a, c}); };
        for (std::size_t a = 0; a < f; ++a)
          for (std::size_t c = 0; a + c < f; ++c) {
            faces.push_back(b.face({{at(a, c), at(a + 1, c), at(a, c + 1)}}));
            if (a + c + 2 <= f) faces.push_back(b.face({{at(a + 1, c), at(a + 1, c + 1), at(a, c + 1)}}));
          }
      }
  b.volume(faces);
  return b.done("geodesic f=" + std::to_string(f));
}

/// A 3D cross (or a jack with some arms missing): a centre block of `centre` cells per side
/// with arms `arm` cells long and `width` cells thick out of the middle of its faces (arms in
/// the order +x, -x, +y, -y, +z, -z); one volume, coplanar faces merged. O(cells).
inline cellforge::samples::sample_model voxel_cross(std::size_t arm, std::size_t centre, std::size_t width,
                                                    std::array<bool, 6> arms, bool uneven, std::string name) {
  const std::size_t n = 2 * arm + centre, lo = arm + (centre - width) / 2;
  std::vector<double> w;
  for (std::size_t i = 0; i < n; ++i) w.push_back(uneven ? 0.5 + 0.25 * double(i * 7 % 5) : 1.0);
  cellforge::samples::voxel_layout l =
      cellforge::samples::empty_layout(from_widths(w), from_widths(w), from_widths(w));
  const auto in_centre = [&](std::size_t x) { return x >= arm && x < arm + centre; };
  const auto in_band = [&](std::size_t x) { return x >= lo && x < lo + width; };
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const std::array<std::size_t, 3> q{i, j, k};
        bool filled = in_centre(i) && in_centre(j) && in_centre(k);
        for (std::size_t a = 0; a < 3; ++a) {
          const bool band = in_band(q[(a + 1) % 3]) && in_band(q[(a + 2) % 3]);
          filled = filled || (band && arms[2 * a] && q[a] >= arm + centre) ||
                   (band && arms[2 * a + 1] && q[a] < arm);
        }
        l.at(i, j, k) = filled ? 1 : 0;
      }
  return cellforge::samples::make_voxel_model(l, std::move(name));
}

/// Cells (i, j, k) of a 3 × 3 × 3 block that a notch pattern (by name) cuts away.
/// O(1).
inline std::vector<std::array<std::size_t, 3>> notch_cells(const std::string& pattern) {
  using cells = std::vector<std::array<std::size_t, 3>>;
  if (pattern == "corner") return cells{{0, 0, 0}};
  if (pattern == "two corners") return cells{{0, 0, 0}, {2, 2, 2}};
  if (pattern == "edge slot") return cells{{1, 0, 0}};
  if (pattern == "edge step") return cells{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  if (pattern == "edge step and corner") return cells{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 2, 2}};
  if (pattern == "two edge steps")
    return cells{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 2}, {0, 2, 2}, {0, 0, 2}};
  if (pattern == "pocket") return cells{{1, 1, 2}};
  if (pattern == "corner and pocket") return cells{{0, 0, 0}, {1, 1, 2}};
  if (pattern == "groove") return cells{{1, 0, 2}, {1, 1, 2}, {1, 2, 2}};
  if (pattern == "through hole") return cells{{1, 1, 0}, {1, 1, 1}, {1, 1, 2}};
  if (pattern == "stair")
    return cells{{1, 0, 2}, {1, 1, 2}, {1, 2, 2}, {2, 0, 2}, {2, 1, 2},
                 {2, 2, 2}, {2, 0, 1}, {2, 1, 1}, {2, 2, 1}};
  cells all;  // "eight corners"
  for (std::size_t c = 0; c < 8; ++c) all.push_back({2 * (c & 1), 2 * (c >> 1 & 1), 2 * (c >> 2 & 1)});
  return all;
}

/// A frame model: a square ring of cells (bar, hole, thickness) as one volume or as eight boxes.
/// O(1).
inline cellforge::samples::sample_model ring_frame(double bar, double hole, double thick, bool cells) {
  cellforge::samples::voxel_layout l = cellforge::samples::empty_layout(
      {0, bar, bar + hole, 2 * bar + hole}, {0, bar, bar + hole, 2 * bar + hole}, {0, thick});
  for (std::size_t c = 0; c < 9; ++c)
    if (c != 4) l.labels[c] = cells ? static_cast<int>(c < 4 ? c + 1 : c) : 1;
  return cellforge::samples::make_voxel_model(l, "frame");
}

/// Two linked frames: frame A in the xy plane, frame B upright through A's hole with A's bar
/// through B's hole, touching nowhere. O(1).
inline cellforge::samples::sample_model linked_frames(std::array<double, 3> a, std::array<double, 3> b,
                                                      bool a_cells, bool b_cells, std::string name) {
  const cellforge::samples::sample_model A = ring_frame(a[0], a[1], a[2], a_cells);
  const cellforge::samples::sample_model B = ring_frame(b[0], b[1], b[2], b_cells);
  // B's local (x, y, z) → (x, -z, y): a rotation about x; B's left bar centred in A's hole,
  // B's hole centred on A's mid-plane.
  glm::dmat3 turn(0.0);
  turn[0] = {1, 0, 0};
  turn[1] = {0, 0, 1};
  turn[2] = {0, -1, 0};
  const double centre = a[0] + a[1] / 2;
  const glm::dvec3 offset(a[0] + (a[1] - b[0]) / 2, centre + b[2] / 2, a[2] / 2 - b[0] - b[1] / 2);
  return cellforge::samples::disjoint_union(A, cellforge::samples::transformed(B, turn, offset),
                                            glm::dvec3(0.0), std::move(name));
}

/// A UV sphere of `slices` × `stacks` with no wall: sample_uv_sphere's rings, which no edge
/// needs, taken out when it has them (odd slices). O(slices · stacks).
inline cellforge::samples::sample_model ball(std::size_t slices, std::size_t stacks) {
  const cellforge::samples::sample_model s = cellforge::samples::sample_uv_sphere(slices, stacks);
  return s.volumes.size() == 1 ? s : without_walls(s, s.name);
}

/// A box-union model of the listed (cell, label) pairs on one lattice, the other cells empty.
/// O(cells).
inline cellforge::samples::sample_model labelled_cells(
    std::vector<double> xs, std::vector<double> ys, std::vector<double> zs,
    const std::vector<std::pair<std::array<std::size_t, 3>, int>>& cells, std::string name) {
  cellforge::samples::voxel_layout l =
      cellforge::samples::empty_layout(std::move(xs), std::move(ys), std::move(zs));
  for (const auto& [c, label] : cells) l.at(c[0], c[1], c[2]) = label;
  return cellforge::samples::make_voxel_model(l, std::move(name));
}

// ---- random polycubes ------------------------------------------------------------------------

/// Random lattice coordinates: n cells of widths in [0.5, 1.5).
/// O(n).
inline std::vector<double> random_coords(std::size_t n, random_source& rng) {
  std::vector<double> w;
  for (std::size_t i = 0; i < n; ++i) w.push_back(rng.between(0.5, 1.5));
  return from_widths(w);
}

/// Grows a face-connected set of up to `count` cells labelled `label` from a random free cell,
/// never entering a cell `blocked` marks. Returns the number of cells grown. O(count · tries).
inline std::size_t grow(cellforge::samples::voxel_layout& l, std::size_t count, int label,
                        const std::vector<char>& blocked, random_source& rng) {
  const std::array<std::size_t, 3> n{l.xs.size() - 1, l.ys.size() - 1, l.zs.size() - 1};
  std::vector<std::size_t> free;
  for (std::size_t c = 0; c < l.labels.size(); ++c)
    if (l.labels[c] == 0 && !blocked[c]) free.push_back(c);
  if (free.empty()) return 0;
  std::vector<std::size_t> mine{free[rng.below(free.size())]};
  l.labels[mine[0]] = label;
  for (std::size_t tries = 0; mine.size() < count && tries < 50 * count; ++tries) {
    std::size_t c = mine[rng.below(mine.size())];
    std::array<std::size_t, 3> q{c % n[0], c / n[0] % n[1], c / (n[0] * n[1])};
    const std::size_t a = rng.below(3);
    if (rng.chance(0.5)) {
      if (q[a] == 0) continue;
      --q[a];
    } else if (++q[a] == n[a]) {
      continue;
    }
    c = q[0] + n[0] * (q[1] + n[1] * q[2]);
    if (l.labels[c] != 0 || blocked[c]) continue;
    l.labels[c] = label;
    mine.push_back(c);
  }
  return mine.size();
}

/// Splits the filled cells of a layout into k face-connected cells (labels 1..k) by growing
/// them together from k random seeds. O(cells log cells).
inline void split_cells(cellforge::samples::voxel_layout& l, std::size_t k, random_source& rng) {
  const std::array<std::size_t, 3> n{l.xs.size() - 1, l.ys.size() - 1, l.zs.size() - 1};
  std::vector<std::size_t> filled;
  for (std::size_t c = 0; c < l.labels.size(); ++c)
    if (l.labels[c] != 0) filled.push_back(c), l.labels[c] = -1;
  std::vector<std::pair<std::size_t, int>> frontier;  // (cell, label it would get)
  for (int label = 1; label <= static_cast<int>(k); ++label) {
    const std::size_t i = rng.below(filled.size() - static_cast<std::size_t>(label - 1));
    std::swap(filled[i], filled[filled.size() - static_cast<std::size_t>(label)]);
    frontier.push_back({filled[filled.size() - static_cast<std::size_t>(label)], label});
  }
  while (!frontier.empty()) {
    const std::size_t i = rng.below(frontier.size());
    const auto [c, label] = frontier[i];
    frontier[i] = frontier.back();
    frontier.pop_back();
    if (l.labels[c] != -1) continue;
    l.labels[c] = label;
    const std::array<std::size_t, 3> q{c % n[0], c / n[0] % n[1], c / (n[0] * n[1])};
    for (std::size_t a = 0; a < 3; ++a)
      for (const int s : {-1, 1}) {
        auto r = q;
        if ((s < 0 && r[a] == 0) || (s > 0 && r[a] + 1 == n[a])) continue;
        r[a] = s < 0 ? r[a] - 1 : r[a] + 1;
        const std::size_t d = r[0] + n[0] * (r[1] + n[1] * r[2]);
        if (l.labels[d] == -1) frontier.push_back({d, label});
      }
  }
}

/// Labels the filled cells by k boxes cut from the lattice by random axis-aligned cuts (each
/// cut halves a random box with room); false when no box can be cut further. O(k² + cells).
inline bool split_boxes(cellforge::samples::voxel_layout& l, std::size_t k, random_source& rng) {
  const std::array<std::size_t, 3> n{l.xs.size() - 1, l.ys.size() - 1, l.zs.size() - 1};
  std::vector<std::array<std::size_t, 6>> boxes{{0, n[0], 0, n[1], 0, n[2]}};  // lo, hi per axis
  while (boxes.size() < k) {
    std::vector<std::pair<std::size_t, std::size_t>> cuts;  // (box, axis) with room for a cut
    for (std::size_t b = 0; b < boxes.size(); ++b)
      for (std::size_t a = 0; a < 3; ++a)
        if (boxes[b][2 * a + 1] - boxes[b][2 * a] >= 2) cuts.push_back({b, a});
    if (cuts.empty()) return false;
    const auto [b, a] = cuts[rng.below(cuts.size())];
    std::array<std::size_t, 6> upper = boxes[b];
    const std::size_t at = rng.in(boxes[b][2 * a] + 1, boxes[b][2 * a + 1] - 1);
    boxes[b][2 * a + 1] = at;
    upper[2 * a] = at;
    boxes.push_back(upper);
  }
  for (std::size_t b = 0; b < boxes.size(); ++b)
    for (std::size_t k2 = boxes[b][4]; k2 < boxes[b][5]; ++k2)
      for (std::size_t j = boxes[b][2]; j < boxes[b][3]; ++j)
        for (std::size_t i = boxes[b][0]; i < boxes[b][1]; ++i)
          if (l.at(i, j, k2) != 0) l.at(i, j, k2) = static_cast<int>(b + 1);
  return true;
}

/// True when every label 1..k names at least one cell and its cells are face-connected.
/// O(cells).
inline bool cells_connected(const cellforge::samples::voxel_layout& l, std::size_t k) {
  const std::array<std::size_t, 3> n{l.xs.size() - 1, l.ys.size() - 1, l.zs.size() - 1};
  std::vector<char> seen(l.labels.size(), 0);
  std::vector<int> pieces(k + 1, 0);
  for (std::size_t c0 = 0; c0 < l.labels.size(); ++c0) {
    const int label = l.labels[c0];
    if (label == 0 || seen[c0]) continue;
    ++pieces[static_cast<std::size_t>(label)];
    std::vector<std::size_t> todo{c0};
    seen[c0] = 1;
    while (!todo.empty()) {
      const std::size_t c = todo.back();
      todo.pop_back();
      const std::array<std::size_t, 3> q{c % n[0], c / n[0] % n[1], c / (n[0] * n[1])};
      for (std::size_t a = 0; a < 3; ++a)
        for (const std::size_t step : {std::size_t{0}, std::size_t{2}}) {
          if ((step == 0 && q[a] == 0) || (step == 2 && q[a] + 1 == n[a])) continue;
          auto r = q;
          r[a] = r[a] + step - 1;
          const std::size_t d = r[0] + n[0] * (r[1] + n[1] * r[2]);
          if (!seen[d] && l.labels[d] == label) seen[d] = 1, todo.push_back(d);
        }
    }
  }
  return std::all_of(pieces.begin() + 1, pieces.end(), [](int p) { return p == 1; });
}

/// Judges a random layout: a manifold union and manifold cells, no cavity, an outline
/// make_voxel_model accepts, every face needed; counts the verdict in `draws`. O(layout).
inline std::optional<cellforge::samples::sample_model> accept(const cellforge::samples::voxel_layout& l,
                                                              int labels, std::string name,
                                                              family_draws& draws) {
  bool ok = no_cavity(l) && manifold(l, [](int x) { return x != 0; });
  for (int c = 1; ok && labels > 1 && c <= labels; ++c) ok = manifold(l, [c](int x) { return x == c; });
  if (!ok) return ++draws.not_manifold, std::nullopt;
  std::optional<cellforge::samples::sample_model> m;
  try {
    m = cellforge::samples::make_voxel_model(l, std::move(name));
  } catch (const cellforge::error&) {
    return ++draws.outline, std::nullopt;
  }
  if (faces_no_edge_needs(*m) != 0) return ++draws.unneeded, std::nullopt;
  m->unforced_faces = 0;
  ++draws.kept;
  return m;
}

/// The convex hull of `n` random points (in a ball, or in a box when `box`): its triangles and
/// one volume. Random points are in general position, so the hull's faces are triangles and
/// its 3-cycles that are not faces — separating triangles through the inside — are the
/// planar cycles the reading must not take. O(n log n).
inline cellforge::samples::sample_model random_polytope(std::size_t n, bool box, random_source& rng,
                                                        std::string name) {
  std::vector<glm::dvec3> points;
  while (points.size() < n) {
    const glm::dvec3 p(rng.between(-1, 1), rng.between(-1, 1), rng.between(-1, 1));
    if (box || glm::length(p) <= 1.0) points.push_back(p);
  }
  const auto hull = cellforge::convex_hull(std::span<const glm::dvec3>(points));
  const auto soup = cellforge::to_soup(hull);
  cellforge::samples::sample_model m;
  m.name = std::move(name);
  m.wire.points = soup.points;
  std::vector<std::array<std::uint32_t, 2>> edges;
  for (std::size_t f = 0; f < soup.num_faces(); ++f) {
    const auto face = soup.face(f);
    m.faces.push_back({std::vector<std::uint32_t>(face.begin(), face.end())});
    for (std::size_t k = 0; k < face.size(); ++k)
      edges.push_back(
          {std::min(face[k], face[(k + 1) % face.size()]), std::max(face[k], face[(k + 1) % face.size()])});
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  m.wire.edges = edges;
  m.volumes.emplace_back();
  for (std::uint32_t f = 0; f < m.faces.size(); ++f) m.volumes[0].push_back(f);
  return m;
}

/// Random polycubes, one volume per piece (a quarter of them two pieces apart), coplanar
/// faces merged; `count` kept draws. O(count · draws per kept · layout).
inline void random_polycubes(sweep_set& s, std::size_t count) {
  random_source rng(0x9e3779b97f4a7c15ull);
  family_draws draws{"polycube"};
  for (std::size_t tries = 0; draws.kept < count && tries < 200 * count; ++tries) {
    const std::size_t nx = rng.in(2, 6), ny = rng.in(2, 6), nz = rng.in(1, 5);
    cellforge::samples::voxel_layout l = cellforge::samples::empty_layout(
        random_coords(nx, rng), random_coords(ny, rng), random_coords(nz, rng));
    const std::size_t cells = nx * ny * nz, size = rng.in(2, std::max<std::size_t>(2, cells * 2 / 3));
    const bool two = cells >= 18 && rng.chance(0.25);
    std::vector<char> blocked(cells, 0);
    std::size_t grown = grow(l, two ? size / 2 : size, 1, blocked, rng);
    if (two) {  // keep the second piece a cell away from the first, even diagonally
      for (std::size_t c = 0; c < cells; ++c) {
        if (l.labels[c] != 1) continue;
        const std::ptrdiff_t i = std::ptrdiff_t(c % nx), j = std::ptrdiff_t(c / nx % ny),
                             k = std::ptrdiff_t(c / (nx * ny));
        for (std::ptrdiff_t d = 0; d < 27; ++d) {
          const std::ptrdiff_t a = i + d % 3 - 1, b = j + d / 3 % 3 - 1, e = k + d / 9 - 1;
          if (a >= 0 && b >= 0 && e >= 0 && a < std::ptrdiff_t(nx) && b < std::ptrdiff_t(ny) &&
              e < std::ptrdiff_t(nz))
            blocked[static_cast<std::size_t>(a + std::ptrdiff_t(nx) * (b + std::ptrdiff_t(ny) * e))] = 1;
        }
      }
      const std::size_t second = grow(l, size - size / 2, 2, blocked, rng);
      if (second == 0) continue;
      grown += second;
    }
    const std::string name = "polycube #" + std::to_string(draws.kept + 1) + " " + std::to_string(nx) + "x" +
                             std::to_string(ny) + "x" + std::to_string(nz) + " n=" + std::to_string(grown) +
                             (two ? " two pieces" : "");
    if (auto m = accept(l, 1, name, draws)) add_copies(s, "polycube", *m, false, 0, draws.kept % 2 == 0);
  }
  if (draws.kept < count) s.faults.push_back("polycube: only " + std::to_string(draws.kept) + " draws kept");
  s.draws.push_back(draws);
}

/// Random polycubes split into k = 2..25 face-connected cells (volumes), k taking every value
/// in turn: up to 8 cells grown together from random seeds, more by random box cuts (grown
/// cells of many labels mostly make wall outlines that touch themselves); the more cells, the
/// thinner the lattice, so that every cell reaches the outside (a cell buried inside has faces
/// no edge needs); `count` kept draws. O(count · draws · layout).
inline void random_cell_polycubes(sweep_set& s, std::size_t count) {
  random_source rng(0x2545f4914f6cdd1dull);
  family_draws draws{"polycube cells"};
  for (std::size_t tries = 0; draws.kept < count && tries < 5000 * count; ++tries) {
    const std::size_t k = 2 + draws.kept % 24;
    const bool few = k <= 8, some = k <= 16;
    const std::size_t nx = few ? rng.in(2, 6) : some ? rng.in(4, 10) : rng.in(8, 16);
    const std::size_t ny = few ? rng.in(2, 6) : some ? rng.in(1, 3) : rng.in(1, 2);
    const std::size_t nz = few ? rng.in(1, 3) : rng.in(1, 2);
    const std::size_t cells = nx * ny * nz;
    if (cells < k) continue;
    cellforge::samples::voxel_layout l = cellforge::samples::empty_layout(
        random_coords(nx, rng), random_coords(ny, rng), random_coords(nz, rng));
    const std::size_t size = rng.in(std::max(k, few ? cells / 3 : cells * 2 / 3), cells);
    const std::size_t grown = grow(l, size, 1, std::vector<char>(cells, 0), rng);
    if (grown < k) continue;
    if (few) {
      split_cells(l, k, rng);
    } else if (!split_boxes(l, k, rng) || !cells_connected(l, k)) {
      ++draws.not_manifold;
      continue;
    }
    const std::string name = "polycube cells #" + std::to_string(draws.kept + 1) + " " + std::to_string(nx) +
                             "x" + std::to_string(ny) + "x" + std::to_string(nz) +
                             " n=" + std::to_string(grown) + " cells=" + std::to_string(k);
    if (auto m = accept(l, static_cast<int>(k), name, draws))
      add_copies(s, "polycube cells", *m, false, 0, draws.kept % 2 == 0);
  }
  if (draws.kept < count)
    s.faults.push_back("polycube cells: only " + std::to_string(draws.kept) + " draws kept");
  s.draws.push_back(draws);
}

/// One draw of the bigger cell polycubes: a lattice of 4–9 × 3–7 × 1–3 cells of random widths,
/// a face-connected piece of at least a third of it split into k = 6..25 cells (grown together
/// up to 8, by box cuts beyond), from its own seed `draw` (k = 6 + draw % 20); nullopt when the
/// draw is rejected (counted in `draws`). Such lattices have an empty cell beside a filled one
/// with every lattice line drawn either way: wireframes two solids share. O(layout).
inline std::optional<cellforge::samples::sample_model> big_cell_polycube(std::uint64_t draw,
                                                                         family_draws& draws) {
  random_source rng(0x6a09e667f3bcc909ull ^ (draw * 0x9e3779b97f4a7c15ull));
  const std::size_t k = 6 + draw % 20;
  const std::size_t nx = rng.in(4, 9), ny = rng.in(3, 7), nz = rng.in(1, 3), cells = nx * ny * nz;
  if (cells < k) return ++draws.not_manifold, std::nullopt;
  cellforge::samples::voxel_layout l = cellforge::samples::empty_layout(
      random_coords(nx, rng), random_coords(ny, rng), random_coords(nz, rng));
  const std::size_t grown =
      grow(l, rng.in(std::max(k, cells / 3), cells), 1, std::vector<char>(cells, 0), rng);
  if (grown < k) return ++draws.not_manifold, std::nullopt;
  if (k <= 8)
    split_cells(l, k, rng);
  else if (!split_boxes(l, k, rng) || !cells_connected(l, k))
    return ++draws.not_manifold, std::nullopt;
  return accept(l, static_cast<int>(k),
                "big polycube draw " + std::to_string(draw) + " " + std::to_string(nx) + "x" +
                    std::to_string(ny) + "x" + std::to_string(nz) + " n=" + std::to_string(grown) +
                    " cells=" + std::to_string(k),
                draws);
}

/// Draws of big_cell_polycube the sweep builds, so that it spends no time on rejected ones
/// (each is judged again when built; a draw rejected then is a fault). Of draws 0..119 999,
/// 2 455 are kept (most others touch themselves at an edge or a vertex); these are the 27 whose
/// answer is ambiguous (22 of them not the truth, 5 exact) and every 60th of the others.
inline const std::vector<std::uint64_t>& big_polycube_draws() {
  static const std::vector<std::uint64_t> draws{
      8,      2303,   3645,   5385,   7163,   10224,  13683,  13727, 16587,  16921,  19907,  21927,
      22863,  23063,  25468,  26381,  28708,  31124,  31965,  33066, 33169,  33840,  36700,  38847,
      39900,  41266,  43340,  43344,  46325,  48968,  51380,  51867, 54042,  56425,  57580,  60445,
      62441,  63185,  65324,  68663,  71665,  74363,  77564,  79509, 80683,  80860,  84183,  84220,
      86823,  87023,  88350,  89460,  92483,  94942,  97730,  98880, 100385, 100725, 103404, 105587,
      105624, 105701, 106840, 109287, 109883, 112705, 115580, 118920};
  return draws;
}

/// The bigger cell polycubes: the listed draws (the sample: every third).
/// O(count · layout).
inline void big_cell_polycubes(sweep_set& s, bool full) {
  family_draws draws{"big polycube"};
  const auto& list = big_polycube_draws();
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!full && i % 3 != 0) continue;
    if (auto m = big_cell_polycube(list[i], draws))
      add_copies(s, "big polycube", *m, full, 0, i % 2 == 0);
    else
      s.faults.push_back("big polycube: draw " + std::to_string(list[i]) + " is rejected now");
  }
}

// ---- families of the exact reading (issue 38): ambiguous groups decided face by face ---------

/// A plate (wide bars, small holes) or frame (thin bars, big holes) with a rows × cols grid of
/// square through-holes, every box of its lattice its own volume except the boxes where four
/// bars cross, each joined to the bar after it: the mouth of each hole is bounded by the tops
/// of four boxes, and the boxes between two holes have no outer edge (their tops are needed
/// only once the mouths beside them are open). O(rows · cols).
inline cellforge::samples::sample_model hole_grid(std::size_t rows, std::size_t cols, bool frame) {
  const double bar = frame ? 0.3 : 1.0, hole = frame ? 1.0 : 0.5, thick = frame ? 0.4 : 0.25;
  const auto widths = [&](std::size_t n) {
    std::vector<double> w;
    for (std::size_t c = 0; c <= 2 * n; ++c)
      w.push_back((c % 2 == 0 ? bar : hole) * (1.0 + 0.125 * double(c % 3)));
    return w;
  };
  cellforge::samples::voxel_layout l =
      cellforge::samples::empty_layout(from_widths(widths(cols)), from_widths(widths(rows)), {0.0, thick});
  const auto crossing = [&](std::size_t i, std::size_t j) {
    return i % 2 == 0 && j % 2 == 0 && i > 0 && j > 0 && i < 2 * cols && j < 2 * rows;
  };
  int next = 1;
  for (std::size_t j = 0; j <= 2 * rows; ++j)
    for (std::size_t i = 0; i <= 2 * cols; ++i)
      if (!(i % 2 == 1 && j % 2 == 1) && !crossing(i, j)) l.at(i, j, 0) = next++;
  for (std::size_t j = 0; j <= 2 * rows; ++j)
    for (std::size_t i = 0; i <= 2 * cols; ++i)
      if (crossing(i, j)) l.at(i, j, 0) = l.at(i + 1, j, 0);
  return cellforge::samples::make_voxel_model(l, std::string(frame ? "frame" : "plate") + " hole grid " +
                                                     std::to_string(rows) + "x" + std::to_string(cols));
}

/// Two frames side by side sharing a side: every box its own volume (the two boxes between the
/// holes have no outer edge), one volume per frame, or bands (the rows without holes, and each
/// piece of the row with them). O(1).
inline cellforge::samples::sample_model double_frame(int labels, bool wide) {
  const double hole = wide ? 1.0 : 0.6;
  const std::vector<double> xs = from_widths({0.3, hole, 0.3, 0.35, hole * 1.1, 0.3});
  const std::vector<double> ys = from_widths({0.3, hole, 0.4});
  cellforge::samples::voxel_layout l = cellforge::samples::empty_layout(xs, ys, {0, 0.4});
  int next = 1;
  for (std::size_t j = 0; j < 3; ++j)
    for (std::size_t i = 0; i < 6; ++i) {
      if (j == 1 && (i == 1 || i == 4)) continue;
      l.at(i, j, 0) = labels == 0   ? next++
                      : labels == 1 ? (i < 3 ? 1 : 2)
                      : j != 1      ? 1 + static_cast<int>(j / 2)
                                    : 3 + static_cast<int>(i < 1   ? 0
                                                           : i < 4 ? 1
                                                                   : 2);
    }
  static const char* const kind[] = {"boxes", "frames", "bands"};
  return cellforge::samples::make_voxel_model(
      l, std::string("double frame ") + kind[labels] + (wide ? " wide" : " narrow"));
}

/// Two linked solid tori (sections: 0 a diamond, 1 a hexagon, 2 an octagon, none with a flat
/// side) of n segments: each passes through the other's hole, where the other's planar n-gon
/// rings (spurious disks across the hole) cross the quads of its band. O(n).
inline cellforge::samples::sample_model linked_tori(std::size_t n, int section) {
  std::vector<std::array<double, 2>> p;
  if (section == 0) p = {{4, 0}, {3, 1}, {2, 0}, {3, -1}};
  if (section == 1) p = hexagon(3, 1, false);
  if (section == 2)
    for (int k = 0; k < 8; ++k) {
      const double t = 2 * std::numbers::pi * k / 8 + 0.3;
      p.push_back({3 + std::cos(t), std::sin(t)});
    }
  static const char* const kind[] = {"diamond", "hexagon", "octagon"};
  const cellforge::samples::sample_model a = revolved(p, n, false, "a"), b = revolved(p, n, false, "b");
  // b upright in the xz plane, turned about its axis, its centre on a's ring.
  glm::dmat3 up(0.0);
  up[0] = {1, 0, 0};
  up[1] = {0, 0, 1};
  up[2] = {0, -1, 0};
  const double t = 0.37;
  const glm::dmat3 spin(glm::dvec3(std::cos(t), std::sin(t), 0), glm::dvec3(-std::sin(t), std::cos(t), 0),
                        glm::dvec3(0, 0, 1));
  return cellforge::samples::disjoint_union(
      a, cellforge::samples::transformed(b, up * spin, glm::dvec3(0.0)), {3, 0, 0},
      "linked tori " + std::string(kind[section]) + " n=" + std::to_string(n));
}

/// A solid of revolution of an axis-parallel (r, z) profile with a bore (r > 0 everywhere), in
/// n segments as a CAD part is drawn: quads on the cylinders, one ring-shaped face (an n-gon
/// with an n-gon hole) per flat step. Where the bore steps, the smaller bore's n-gon lies in the
/// hole of the step face of the same plane: a disc no edge needs. One volume. O(n · profile).
inline cellforge::samples::sample_model stepped_part(const std::vector<std::array<double, 2>>& profile,
                                                     std::size_t n, std::string name) {
  model_builder b;
  std::map<std::array<double, 2>, std::vector<std::uint32_t>> rings;
  const auto ring = [&](double r, double z) -> const std::vector<std::uint32_t>& {
    auto& v = rings[{r, z}];
    for (std::size_t j = 0; v.size() < n; ++j) {
      const double t = 2 * std::numbers::pi * double(j) / double(n) + 0.1;
      v.push_back(b.point({r * std::cos(t), r * std::sin(t), z}));
    }
    return v;
  };
  std::vector<std::uint32_t> faces;
  for (std::size_t i = 0; i < profile.size(); ++i) {
    const auto p = profile[i], q = profile[(i + 1) % profile.size()];
    if (p[0] == q[0]) {
      const std::vector<std::uint32_t> lo = ring(p[0], p[1]), hi = ring(q[0], q[1]);
      for (std::size_t j = 0; j < n; ++j)
        faces.push_back(b.face({{lo[j], lo[(j + 1) % n], hi[(j + 1) % n], hi[j]}}));
    } else {
      faces.push_back(b.face({ring(std::max(p[0], q[0]), p[1]), ring(std::min(p[0], q[0]), p[1])}));
    }
  }
  b.volume(faces);
  return b.done(std::move(name));
}

/// A box with k = 2..5 polygonal holes in its top face: through holes, blind pockets with a
/// flat floor, or both in turn; one volume, the top face one face with k holes. O(k · sides).
inline cellforge::samples::sample_model holed_box(std::size_t k, std::size_t sides, int kind) {
  model_builder b;
  const double L = 1.2 * double(k) + 0.4, W = 1.5, H = 0.6;
  std::array<std::uint32_t, 8> c{};
  for (int i = 0; i < 8; ++i) c[i] = b.point({L * (i & 1), W * (i >> 1 & 1), H * (i >> 2 & 1)});
  std::vector<std::vector<std::uint32_t>> top{{c[4], c[5], c[7], c[6]}}, bottom{{c[0], c[1], c[3], c[2]}};
  std::vector<std::uint32_t> faces;
  for (std::size_t h = 0; h < k; ++h) {
    const double cx = 0.8 + 1.2 * double(h), cy = 0.75 + 0.1 * double(h % 2), r = 0.3 + 0.05 * double(h % 3);
    const std::size_t s = sides + h % 2;
    const bool pocket = kind == 1 || (kind == 2 && h % 2 == 1);
    std::vector<std::uint32_t> up, down;
    for (std::size_t j = 0; j < s; ++j) {
      const double t = 2 * std::numbers::pi * double(j) / double(s) + 0.2 * double(h);
      up.push_back(b.point({cx + r * std::cos(t), cy + r * std::sin(t), H}));
      down.push_back(b.point({cx + r * std::cos(t), cy + r * std::sin(t), pocket ? H * 0.4 : 0.0}));
    }
    for (std::size_t j = 0; j < s; ++j)
      faces.push_back(b.face({{up[j], up[(j + 1) % s], down[(j + 1) % s], down[j]}}));
    top.push_back(up);
    if (pocket)
      faces.push_back(b.face({down}));
    else
      bottom.push_back(down);
  }
  faces.push_back(b.face(top));
  faces.push_back(b.face(bottom));
  for (const auto& q :
       std::array<std::array<int, 4>, 4>{{{0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}}})
    faces.push_back(b.face({{c[q[0]], c[q[1]], c[q[2]], c[q[3]]}}));
  b.volume(faces);
  static const char* const what[] = {"through", "pockets", "mixed"};
  return b.done("holed box k=" + std::to_string(k) + " sides=" + std::to_string(sides) + " " + what[kind]);
}

/// The families of the exact reading: hole grids, double frames, linked tori, stepped bores,
/// faces with several holes (sweep_families names them). Each in its own block, so that other
/// copies of the sweep (noisy ones, say) can take them up. O(total size).
inline void add_reading_families(sweep_set& s, bool full) {
  using cellforge::samples::sample_model;
  {
    std::vector<sample_model> bases;
    for (const bool frame : {false, true})
      for (const auto& [rows, cols] : std::vector<std::array<std::size_t, 2>>{{2, 2}, {3, 3}, {2, 3}, {1, 3}})
        if (full || (rows == 2 && cols == (frame ? 3u : 2u))) bases.push_back(hole_grid(rows, cols, frame));
    add_family(s, "hole grid", std::move(bases), full);
  }
  {
    std::vector<sample_model> bases;
    for (const int labels : {0, 1, 2})
      for (const bool wide : {true, false})
        if (full || (labels == 0 && wide) || (labels == 2 && !wide))
          bases.push_back(double_frame(labels, wide));
    add_family(s, "double frame", std::move(bases), full);
  }
  {
    std::vector<sample_model> bases;
    for (const std::size_t n : {8, 12, 16, 24})
      for (const int section : {0, 1, 2})
        if (full || (n == 8 && section != 1)) bases.push_back(linked_tori(n, section));
    add_family(s, "linked tori", std::move(bases), full);
  }
  {
    using profile = std::vector<std::array<double, 2>>;
    const std::vector<std::pair<std::string, profile>> parts{
        {"bore step", {{1, 0}, {3, 0}, {3, 4}, {1.5, 4}, {1.5, 2}, {1, 2}}},
        {"bore step down", {{1.5, 0}, {3, 0}, {3, 4}, {1, 4}, {1, 2.5}, {1.5, 2.5}}},
        {"rotor", {{1, 0}, {2, 0}, {2, 1}, {3, 1}, {3, 3}, {2, 3}, {2, 4}, {1.5, 4}, {1.5, 2}, {1, 2}}},
        {"coupling",
         {{1, 0},
          {3, 0},
          {3, 1},
          {2.5, 1},
          {2.5, 3},
          {3, 3},
          {3, 4},
          {1, 4},
          {1, 3},
          {1.5, 3},
          {1.5, 1},
          {1, 1}}},
        {"bore two steps", {{0.5, 0}, {2.5, 0}, {2.5, 3}, {1.5, 3}, {1.5, 2}, {1, 2}, {1, 1}, {0.5, 1}}}};
    std::vector<sample_model> bases;
    for (std::size_t p = 0; p < parts.size(); ++p)
      for (const std::size_t n : {8, 12, 24, 32})
        if (full || (n == 12 && (p == 0 || p == 3)))
          bases.push_back(stepped_part(parts[p].second, n, parts[p].first + " n=" + std::to_string(n)));
    add_family(s, "stepped bore", std::move(bases), full);
  }
  {
    std::vector<sample_model> bases;
    for (std::size_t k = 2; k <= 5; ++k)
      for (const int kind : {0, 1, 2})
        for (const std::size_t sides : {3, 4, 6})
          if (full ? sides != 3 || k % 2 == 0 : (k == 3 && sides == 4 && kind != 1))
            bases.push_back(holed_box(k, sides, kind));
    add_family(s, "holed face", std::move(bases), full);
  }
}

}  // namespace detail

/// Builds the sweep: every family's models (see sweep_families), shuffled (unless `shuffle` is
/// false: the same models, names and order with their own labels and place, to tell a miss
/// that depends on the labelling from one that does not), with the draws of the random
/// families. Full: about 800 models, ~0.4 s in Release; sample: about 100, grids up to 5³.
inline sweep_set make_sweep(sweep_size size, bool shuffle = true) {
  using cellforge::samples::sample_model;
  const bool full = size == sweep_size::full;
  sweep_set s;
  s.shuffle = shuffle;

  for (const bool frame : {true, false}) {
    std::vector<sample_model> bases;
    for (std::size_t h = 1; h <= 9; ++h)
      for (const bool cells : {false, true})
        for (const bool row : {false, true}) {
          if (row && h <= 3) continue;  // a row is the grid layout
          if (!full && (row || (h != 1 && h != 4 && h != 9))) continue;
          bases.push_back(detail::holed_slab(frame, h, row, cells));
        }
    detail::add_family(s, frame ? "frame" : "plate", std::move(bases), full);
  }

  {
    std::vector<sample_model> bases;
    for (std::size_t n = 3; n <= 16; ++n)
      if (full || n == 3 || n == 5 || n == 8)
        bases.push_back(detail::sector_ring(n, n < 6 ? 1.0 : 2.0, 3.0, 0.75));
    for (const auto& [k, m] : std::vector<std::array<std::size_t, 2>>{{3, 3}, {3, 4}, {4, 4}, {4, 6}, {5, 5}})
      if (full || k == 4) bases.push_back(detail::lattice_ring(k, m, false));
    for (const auto& [k, m] : std::vector<std::array<std::size_t, 2>>{{3, 3}, {4, 5}})
      if (full || k == 4) bases.push_back(detail::lattice_ring(k, m, true));
    // A hexagonal torus with flat top and bottom: the radial edges there lie between two
    // coplanar faces, so every profile hexagon is a needed wall: n volumes.
    for (const std::size_t n : {6, 8, 12})
      if (full || n == 8)
        bases.push_back(detail::revolved(detail::hexagon(3, 1, true), n, true,
                                         "box ring hexagon flat n=" + std::to_string(n)));
    detail::add_family(s, "box ring", std::move(bases), full);
  }

  {
    std::vector<sample_model> bases;
    for (const std::size_t n : {4, 5, 6, 8, 12, 16, 32}) {
      if (!full && n != 5 && n != 8) continue;
      const std::string ns = " n=" + std::to_string(n);
      bases.push_back(detail::revolved({{4, 0}, {3, 1}, {2, 0}, {3, -1}}, n, false, "torus diamond" + ns));
      bases.push_back(
          detail::revolved({{4.5, 0}, {3, 0.5}, {2.5, 0}, {3, -0.5}}, n, false, "torus flat diamond" + ns));
      bases.push_back(detail::revolved(detail::hexagon(3, 1, false), n, false, "torus hexagon" + ns));
    }
    detail::add_family(s, "torus", std::move(bases), full);
  }

  {
    std::vector<sample_model> bases;
    for (std::size_t n = 3; n <= 12; ++n)
      for (const bool even : {true, false}) {
        if (!full && !((even && (n == 3 || n == 4 || n == 7 || n == 12)) || (!even && n == 5))) continue;
        cellforge::samples::ring_stack r;
        r.n = n;
        r.radius = {1.0};
        r.height = {0.0};
        r.twist = {0.1};
        r.bottom = even ? -1.0 : -0.6;
        r.top = even ? 1.0 : 1.3;
        bases.push_back(cellforge::samples::make_ring_stack(
            r, "bipyramid n=" + std::to_string(n) + (even ? " symmetric" : " skewed")));
      }
    detail::add_family(s, "bipyramid", std::move(bases), full);
  }

  {
    std::vector<sample_model> bases;
    for (std::size_t n = 3; n <= 8; ++n) {
      if (!full && n != 4 && n != 5) continue;
      cellforge::samples::ring_stack r;
      r.n = n;
      r.radius = {1.0, 1.0};
      r.height = {0.0, 1.0};
      r.twist = {0.2, 0.2};
      r.top = 1.7;
      bases.push_back(cellforge::samples::make_ring_stack(r, "house pyramid n=" + std::to_string(n)));
    }
    if (full) {
      bases.push_back(detail::pyramid_house(2, 1, 1, {1, 0.5, 1.5}, "house pyramid 2x1"));
      bases.push_back(detail::pyramid_house(3, 1.5, 0.5, {1.5, 0.75, 2}, "house pyramid tall roof"));
      bases.push_back(detail::pyramid_house(1, 1, 2, {0.5, 0.5, 2.1}, "house pyramid flat roof"));
      bases.push_back(detail::pyramid_house(2, 2, 1, {0.25, 1.5, 1.5}, "house pyramid apex off-centre"));
    }
    bases.push_back(detail::pyramid_house(2, 1.5, 1, {1.5, 0.25, 1.75}, "house pyramid apex near a side"));
    bases.push_back(detail::hip_house(3, 1.5, 1, 0.75, 0.5));
    if (full) {
      bases.push_back(detail::hip_house(2, 1, 1.5, 0.5, 0.5));
      bases.push_back(detail::hip_house(4, 1, 0.5, 1, 0.25));
      bases.push_back(detail::hip_house(1.5, 1.25, 1, 0.25, 0.625));
    }
    detail::add_family(s, "house", std::move(bases), full);
  }

  {
    using detail::pit;
    const glm::dvec3 cube(1.0);
    std::vector<std::pair<std::string, std::vector<pit>>> kinds{
        {"dent square", {{1, 4, 0.5, 0.5, 0.3, 0.4, 0.5, 0.5, std::numbers::pi / 4}}},
        {"dent triangle", {{1, 3, 0.5, 0.5, 0.3, 0.5, 0.5, 0.5}}},
        {"dent all faces", {}},
        {"bump square", {{1, 4, 0.5, 0.5, 0.3, -0.5, 0.5, 0.5, std::numbers::pi / 4}}},
        {"dent square off-centre", {{1, 4, 0.35, 0.6, 0.2, 0.3, 0.45, 0.5, std::numbers::pi / 4}}},
        {"dent hexagon deep", {{1, 6, 0.5, 0.5, 0.35, 0.8, 0.5, 0.5}}},
        {"dent top and bottom", {{1, 4, 0.5, 0.5, 0.3, 0.4, 0.5, 0.5}, {0, 5, 0.5, 0.5, 0.3, 0.4, 0.5, 0.5}}},
        {"dent and bump",
         {{1, 4, 0.5, 0.5, 0.3, 0.4, 0.5, 0.5, 0.3}, {0, 4, 0.5, 0.5, 0.3, -0.4, 0.5, 0.5, 0.3}}},
        {"dent two on top",
         {{1, 4, 0.25, 0.5, 0.15, 0.3, 0.25, 0.5, std::numbers::pi / 4},
          {1, 3, 0.7, 0.5, 0.15, 0.3, 0.7, 0.5}}},
        {"dent side", {{3, 4, 0.5, 0.5, 0.3, 0.4, 0.5, 0.5, std::numbers::pi / 4}}},
        {"bump all faces", {}},
        {"dent pentagon box", {{1, 5, 0.5, 0.5, 0.35, 0.6, 0.4, 0.55}}}};
    std::vector<sample_model> bases;
    for (std::size_t i = 0; i < kinds.size(); ++i) {
      auto& [name, pits] = kinds[i];
      if (!full && i >= 4) break;
      if (name == "dent all faces" || name == "bump all faces")
        for (int f = 0; f < 6; ++f)
          pits.push_back({f, 4, 0.5, 0.5, 0.3, name[0] == 'd' ? 0.3 : -0.4, 0.5, 0.5, 0.1 * f});
      bases.push_back(
          detail::pitted_box(name == "dent pentagon box" ? glm::dvec3(2, 1, 0.75) : cube, pits, name));
    }
    detail::add_family(s, "dent", std::move(bases), full);
  }

  {
    const std::vector<std::string> patterns{"corner",         "edge slot",         "pocket",
                                            "stair",          "through hole",      "two corners",
                                            "eight corners",  "edge step",         "edge step and corner",
                                            "two edge steps", "corner and pocket", "groove"};
    const std::vector<std::vector<double>> coords{{0, 1, 2, 3}, {0, 0.6, 2.2, 3}};
    std::vector<sample_model> bases;
    for (std::size_t p = 0; p < patterns.size(); ++p)
      for (std::size_t c = 0; c < coords.size(); ++c) {
        if (!full && (p >= 5 || c != p % 2)) continue;
        cellforge::samples::voxel_layout l =
            cellforge::samples::empty_layout(coords[c], coords[1 - c], coords[c]);
        l.labels.assign(27, 1);
        for (const auto& q : detail::notch_cells(patterns[p])) l.at(q[0], q[1], q[2]) = 0;
        bases.push_back(
            cellforge::samples::make_voxel_model(l, "notch " + patterns[p] + (c ? " uneven" : "")));
      }
    detail::add_family(s, "notch", std::move(bases), full);
  }

  for (const bool barrel : {true, false}) {
    std::vector<sample_model> bases;
    for (const std::size_t n : {5, 6, 8, 11, 16})
      for (int variant = 0; variant < 4; ++variant) {
        if (!full && !(n == 5 && variant == 0) && !(n == 8 && variant == 3) && !(n == 6 && variant == 1))
          continue;
        const bool cones = variant >= 2, triangles = variant % 2 == 1;
        cellforge::samples::ring_stack r;
        r.n = n;
        const std::size_t rings = 3 + n % 4;
        for (std::size_t i = 0; i < rings; ++i) {
          const double t = double(i) / double(rings - 1);
          r.radius.push_back(1.0 + (barrel ? 0.35 : -0.45) * std::sin(std::numbers::pi * t));
          r.height.push_back(1.5 * t);
          r.twist.push_back(triangles ? std::numbers::pi / double(n) * double(i) : 0.0);
        }
        r.triangles = triangles;
        if (cones) r.bottom = -0.5, r.top = 2.0;
        bases.push_back(cellforge::samples::make_ring_stack(
            r, std::string(barrel ? "barrel" : "hourglass") + " n=" + std::to_string(n) +
                   " rings=" + std::to_string(rings) + (cones ? " cones" : " caps") +
                   (triangles ? " triangles" : " quads")));
      }
    detail::add_family(s, barrel ? "barrel" : "hourglass", std::move(bases), full);
  }

  {
    std::vector<sample_model> bases;
    for (std::size_t f = 1; f <= (full ? 6u : 3u); ++f) bases.push_back(detail::geodesic_sphere(f));
    if (full)
      for (const std::size_t f : {2, 4}) {
        sample_model m = cellforge::samples::transformed(
            detail::geodesic_sphere(f),
            glm::dmat3(glm::dvec3(1.3, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 0.7)), glm::dvec3(0.0));
        m.name += " stretched";
        bases.push_back(std::move(m));
      }
    detail::add_family(s, "geodesic", std::move(bases), full);
  }

  {
    random_source rng(0x5851f42d4c957f2dull);
    std::vector<sample_model> bases;
    for (std::size_t k = 0; k < (full ? 24u : 4u); ++k) {
      const std::size_t n = 8 + 4 * k;
      const bool box = k % 2 == 1;
      bases.push_back(
          detail::random_polytope(n, box, rng, "polytope n=" + std::to_string(n) + (box ? " box" : " ball")));
    }
    detail::add_family(s, "polytope", std::move(bases), full);
  }

  {
    const std::array<bool, 6> all{true, true, true, true, true, true};
    struct cross_kind {
      std::size_t arm, centre, width;
      std::array<bool, 6> arms;
      bool uneven;
      std::string name;
    };
    const std::vector<cross_kind> kinds{
        {1, 1, 1, all, false, "cross arms=1"},
        {2, 3, 1, all, false, "cross arms=2 centre=3"},
        {1, 1, 1, {true, false, true, false, true, false}, false, "jack 3 arms corner"},
        {2, 1, 1, {true, true, true, true, false, false}, true, "jack 4 arms flat uneven"},
        {2, 1, 1, all, false, "cross arms=2"},
        {3, 1, 1, all, true, "cross arms=3 uneven"},
        {1, 3, 1, all, false, "cross arms=1 centre=3"},
        {2, 5, 3, all, false, "cross arms=2 centre=5 width=3"},
        {1, 1, 1, all, true, "cross arms=1 uneven"},
        {2, 1, 1, {true, false, true, false, false, false}, false, "jack 2 arms bent"},
        {1, 1, 1, {true, true, true, false, false, false}, false, "jack 3 arms T"},
        {1, 1, 1, {true, true, true, false, true, false}, false, "jack 4 arms"},
        {1, 1, 1, {true, true, true, true, true, false}, false, "jack 5 arms"},
        {1, 3, 1, {true, false, true, false, true, false}, false, "jack 3 arms corner centre=3"}};
    std::vector<sample_model> bases;
    for (std::size_t i = 0; i < kinds.size() && (full || i < 4); ++i)
      bases.push_back(detail::voxel_cross(kinds[i].arm, kinds[i].centre, kinds[i].width, kinds[i].arms,
                                          kinds[i].uneven, kinds[i].name));
    detail::add_family(s, "cross", std::move(bases), full);
  }

  detail::random_polycubes(s, full ? 80 : 12);
  detail::random_cell_polycubes(s, full ? 80 : 12);

  {
    std::vector<sample_model> bases;
    bases.push_back(detail::linked_frames({1, 2, 0.5}, {0.5, 2.5, 0.5}, false, false, "linked frames"));
    bases.push_back(
        detail::linked_frames({0.5, 1.5, 0.25}, {0.25, 2, 0.25}, false, true, "linked frames thin cells"));
    if (full) {
      bases.push_back(detail::linked_frames({1, 3, 1}, {1, 3, 1}, false, false, "linked frames equal"));
      bases.push_back(
          detail::linked_frames({1, 2, 0.5}, {0.5, 2.5, 0.5}, true, false, "linked frames cells"));
      bases.push_back(detail::linked_frames({1, 3, 1}, {1, 3, 1}, true, true, "linked frames equal cells"));
      bases.push_back(
          detail::linked_frames({0.25, 2, 1.5}, {0.5, 2, 0.25}, false, false, "linked frames deep"));
    }
    detail::add_family(s, "linked frames", std::move(bases), full);
  }

  {
    const sample_model frame = detail::ring_frame(1, 2, 0.5, false),
                       cells = detail::ring_frame(1, 2, 0.5, true);
    const auto box = [](glm::dvec3 size, glm::dvec3 at, const sample_model& f, std::string name) {
      return cellforge::samples::disjoint_union(f, cellforge::samples::sample_cube(size), at,
                                                std::move(name));
    };
    const auto sphere = [](std::size_t slices, double r, double z, std::string name) {
      const sample_model b = detail::ball(slices, 6);
      return cellforge::samples::disjoint_union(
          detail::ring_frame(1, 2, 0.5, false),
          cellforge::samples::transformed(b, glm::dmat3(r), glm::dvec3(0.0)), {2, 2, z}, std::move(name));
    };
    std::vector<sample_model> bases{box({1, 1, 0.25}, {1.5, 1.5, 0.25}, frame, "box in frame flush top"),
                                    box({1, 1, 1.5}, {1.5, 1.5, -0.5}, frame, "box through frame"),
                                    sphere(8, 0.2, 0.25, "sphere in frame")};
    if (full) {
      bases.push_back(box({1, 1, 0.5}, {1.5, 1.5, 0}, frame, "box in frame flush both"));
      bases.push_back(box({1, 1, 0.25}, {1.5, 1.5, 0.125}, frame, "box in frame inside"));
      bases.push_back(box({1, 1, 1}, {1.5, 1.5, 0.25}, frame, "box in frame sticking up"));
      bases.push_back(box({0.5, 1.5, 1.25}, {1.25, 1.25, -0.25}, cells, "box through frame cells"));
      bases.push_back(sphere(8, 0.8, 0.25, "sphere through frame"));
      bases.push_back(sphere(7, 0.6, 0.5, "sphere odd through frame"));
    }
    detail::add_family(s, "solid in frame", std::move(bases), full);
  }

  {
    using detail::labelled_cells;
    std::vector<sample_model> bases{
        labelled_cells({0, 1, 2}, {0, 1, 2}, {0, 1, 2}, {{{0, 0, 0}, 1}, {{1, 1, 1}, 2}},
                       "touching vertex cubes"),
        labelled_cells({0, 1, 2}, {0, 1, 2}, {0, 1}, {{{0, 0, 0}, 1}, {{1, 1, 0}, 2}}, "touching edge cubes"),
        cellforge::samples::disjoint_union(
            cellforge::samples::sample_pyramid(4),
            cellforge::samples::transformed(cellforge::samples::sample_pyramid(4),
                                            glm::dmat3(1, 0, 0, 0, 1, 0, 0, 0, -1), {0, 0, 2}),
            glm::dvec3(0.0), "touching vertex pyramids")};
    bases.back() = detail::glued(bases.back());
    if (full) {
      bases.push_back(labelled_cells({0, 1, 1.5}, {0, 0.75, 2}, {0, 1.25, 1.75},
                                     {{{0, 0, 0}, 1}, {{1, 1, 1}, 2}}, "touching vertex boxes"));
      bases.push_back(labelled_cells({0, 1, 2, 3}, {0, 1, 2, 3}, {0, 1, 2, 3},
                                     {{{0, 0, 0}, 1}, {{1, 1, 1}, 2}, {{2, 2, 2}, 3}},
                                     "touching vertex chain"));
      bases.push_back(labelled_cells({0, 1, 2}, {0, 1, 2}, {0, 0.25, 0.75, 1},
                                     {{{0, 0, 0}, 1}, {{0, 0, 1}, 1}, {{0, 0, 2}, 1}, {{1, 1, 1}, 2}},
                                     "touching edge part"));
      bases.push_back(labelled_cells({0, 1, 2}, {0, 1.5, 2}, {0, 0.25, 0.75, 1},
                                     {{{0, 0, 0}, 1}, {{0, 0, 1}, 1}, {{1, 1, 1}, 2}, {{1, 1, 2}, 2}},
                                     "touching edge offset"));
      bases.push_back(labelled_cells({0, 1, 2}, {0, 1, 2}, {0, 1, 2},
                                     {{{0, 0, 0}, 1}, {{1, 1, 0}, 2}, {{1, 0, 1}, 3}, {{0, 1, 1}, 4}},
                                     "touching edge checkerboard"));
      detail::model_builder b;
      const std::uint32_t shared = b.point({0, 0, 1});
      const std::array<glm::dvec3, 6> others{
          {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.2, 0.3, 2}, {1, 0.1, 1.8}, {-0.5, 0.8, 2.1}}};
      for (int t = 0; t < 2; ++t) {
        const std::uint32_t p = b.point(others[3 * t]), q = b.point(others[3 * t + 1]),
                            r = b.point(others[3 * t + 2]);
        b.volume({b.face({{p, q, r}}), b.face({{p, q, shared}}), b.face({{q, r, shared}}),
                  b.face({{r, p, shared}})});
      }
      bases.push_back(b.done("touching vertex tetrahedra"));
    }
    detail::add_family(s, "touching", std::move(bases), full);
  }

  {
    std::vector<std::array<std::size_t, 3>> sizes{{1, 1, 1}, {2, 1, 1}, {4, 2, 1}, {2, 2, 2},
                                                  {3, 2, 2}, {3, 3, 3}, {4, 3, 3}, {5, 5, 5}};
    if (full)
      for (const std::array<std::size_t, 3> g : std::vector<std::array<std::size_t, 3>>{
               {3, 1, 1},  {5, 1, 1},  {20, 1, 1},  {2, 2, 1},    {7, 2, 1},    {12, 2, 1},  {6, 2, 2},
               {10, 2, 2}, {20, 2, 2}, {4, 4, 3},   {4, 4, 4},    {5, 4, 3},    {6, 5, 4},   {6, 6, 6},
               {7, 7, 7},  {8, 8, 8},  {12, 10, 8}, {10, 10, 10}, {15, 15, 15}, {20, 20, 20}})
        sizes.push_back(g);
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      sample_model m = cellforge::samples::sample_grid(sizes[i][0], sizes[i][1], sizes[i][2]);
      m.unforced_faces = faces_no_edge_needs(m);
      detail::add_copies(s, "grid", m, full, sizes[i][0] * sizes[i][1] * sizes[i][2] <= 1000 ? 1 : 0,
                         i % 2 == 1);
    }
  }

  detail::add_reading_families(s, full);
  detail::big_cell_polycubes(s, full);

  {
    std::vector<sample_model> library = cellforge::samples::all_small_samples();
    for (const std::size_t n : {4, 7, 12}) library.push_back(cellforge::samples::sample_prism(n));
    for (const std::size_t n : {5, 9}) library.push_back(cellforge::samples::sample_pyramid(n));
    library.push_back(cellforge::samples::sample_uv_sphere(12, 9));
    library.push_back(cellforge::samples::sample_uv_sphere(7, 6));
    library.push_back(cellforge::samples::sample_close_edges());
    for (int i = 1; i <= 6; ++i) library.push_back(cellforge::samples::sample_seed(i));
    // Library models whose walls no edge needs, read as the rule reads them.
    for (const sample_model& walled :
         {cellforge::samples::sample_seed(6), cellforge::samples::sample_uv_sphere(7, 6)})
      if (walled.volumes.size() > 1)
        library.push_back(detail::without_walls(walled, walled.name + " without walls"));
    std::vector<sample_model> bases;
    const std::set<std::string> in_sample{"tetrahedron", "L", "stepped block", "seed sample 3",
                                          "split edges"};
    for (auto& m : library) {
      if (m.name.rfind("grid", 0) == 0) {
        s.left_out.push_back(m.name + " (grids are their own family)");
      } else if (const std::size_t n = faces_no_edge_needs(m); n != 0) {
        s.left_out.push_back(m.name + " (" + std::to_string(n) + " faces no edge needs)");
      } else if (full || in_sample.count(m.name) != 0) {
        bases.push_back(std::move(m));
      }
    }
    detail::add_family(s, "library", std::move(bases), full);
  }
  return s;
}

// ---- ordinary solids nobody tuned for (issue 38): terrains, fins, extrusions, turned boxes ----

/// The families of ordinary solids (make_ordinary_sweep), in the order it builds them.
/// O(1).
inline const std::vector<std::string>& ordinary_families() {
  static const std::vector<std::string> names{"height field", "box with fin", "extrusion", "turned boxes"};
  return names;
}

namespace detail {

/// A height field: a k × m grid of columns with random integer heights 1..4, one volume, coplanar
/// faces merged. Draws alternate between random widths and layer heights (k, m up to 5) and unit
/// cubes (square columns, k, m up to 6); every other pair lets heights be 0 (courtyards and
/// notches: the top faces get holes, the outline turns in), kept face-connected. nullopt when
/// `accept` refuses it (columns touching along an edge only, a face no edge needs) or it falls
/// apart (counted as not manifold). O(k · m · 4).
inline std::optional<cellforge::samples::sample_model> height_field(std::uint64_t draw, family_draws& draws) {
  random_source rng(0x3c6ef372fe94f82bull ^ (draw * 0x9e3779b97f4a7c15ull));
  const bool unit = draw % 2 == 1, pits = draw % 4 >= 2;
  const std::size_t k = rng.in(2, unit ? 6 : 5), m = rng.in(2, unit ? 6 : 5);
  const auto coords = [&](std::size_t n) {
    std::vector<double> c;
    for (std::size_t i = 0; i <= n; ++i) c.push_back(double(i));
    return unit ? c : random_coords(n, rng);
  };
  cellforge::samples::voxel_layout l = cellforge::samples::empty_layout(coords(k), coords(m), coords(4));
  std::string heights;
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t i = 0; i < k; ++i) {
      const std::size_t h = rng.in(pits ? 0 : 1, 4);
      heights += static_cast<char>('0' + h);
      for (std::size_t z = 0; z < h; ++z) l.at(i, j, z) = 1;
    }
  if (heights.find_first_not_of('0') == std::string::npos || !cells_connected(l, 1))
    return ++draws.not_manifold, std::nullopt;
  return accept(l, 1,
                "height field draw " + std::to_string(draw) + (unit ? " unit " : " ") + std::to_string(k) +
                    "x" + std::to_string(m) + " " + heights,
                draws);
}

/// A height field as height_field draws it whose columns touch along an edge (two diagonal
/// columns above both others: no 2-manifold solid), of its own seed; nullopt when the draw is
/// manifold or make_voxel_model refuses its outlines. Its answer must be flagged. O(k · m · 4).
inline std::optional<cellforge::samples::sample_model> touching_height_field(std::uint64_t draw) {
  random_source rng(0x510e527fade682d1ull ^ (draw * 0x9e3779b97f4a7c15ull));
  const std::size_t k = rng.in(2, 4), m = rng.in(2, 4);
  cellforge::samples::voxel_layout l =
      cellforge::samples::empty_layout(random_coords(k, rng), random_coords(m, rng), random_coords(4, rng));
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t i = 0; i < k; ++i)
      for (std::size_t z = 0, h = rng.in(1, 4); z < h; ++z) l.at(i, j, z) = 1;
  if (manifold(l, [](int x) { return x != 0; })) return std::nullopt;
  try {
    return cellforge::samples::make_voxel_model(l, "height field touching draw " + std::to_string(draw));
  } catch (const cellforge::error&) {
    return std::nullopt;
  }
}

/// A box L × W × H with planar flaps: `kind` 0 a rectangle along a whole edge of the top, at
/// `angle` (radians) above the top's plane (0: the top continued; pi/2: the side continued up); 1
/// a triangle there; 2 a rectangle or (odd `variant`) triangle standing on the top across it,
/// from one side to the other (the top then two faces); 3 a rectangle along the middle half of a
/// top edge (the edge in three); 4 two rectangles on opposite top edges. Truth: the box's
/// volume, each flap a face in no volume. O(1).
inline cellforge::samples::sample_model box_with_fin(int kind, double angle, int variant, glm::dvec3 size) {
  model_builder b;
  const double L = size.x, W = size.y, H = size.z;
  std::array<std::uint32_t, 8> c{};
  for (int i = 0; i < 8; ++i) c[i] = b.point({L * (i & 1), W * (i >> 1 & 1), H * (i >> 2 & 1)});
  // Top corners 4 (0,0) 5 (L,0) 7 (L,W) 6 (0,W); the flaps hang on the top edge y = 0 (4-5).
  const glm::dvec3 out(0, -std::cos(angle), std::sin(angle));  // away from the box, tilted up
  const double reach = 0.6 * W;
  std::vector<std::uint32_t> box;
  const auto quad = [&](int p, int q, int r, int s) { return b.face({{c[p], c[q], c[r], c[s]}}); };
  box.push_back(quad(0, 1, 3, 2));  // bottom
  box.push_back(quad(0, 2, 6, 4));  // x = 0
  box.push_back(quad(1, 3, 7, 5));  // x = L
  std::string name = "box with fin ";
  if (kind == 0 || kind == 1 || kind == 4) {
    box.push_back(quad(2, 3, 7, 6));  // y = W
    box.push_back(quad(0, 1, 5, 4));  // y = 0
    box.push_back(quad(4, 5, 7, 6));  // top
    const glm::dvec3 p4 = b.point_at(c[4]), p5 = b.point_at(c[5]);
    if (kind == 1) {
      b.face({{c[4], c[5], b.point(p4 + glm::dvec3(0.3 * L, 0, 0) + reach * out)}});
      name += "triangle";
    } else {
      b.face({{c[4], c[5], b.point(p5 + reach * out), b.point(p4 + reach * out)}});
      name += kind == 0 ? "rectangle" : "two rectangles";
    }
    if (kind == 4) {
      const glm::dvec3 back(0, std::cos(angle), std::sin(angle));
      const glm::dvec3 p6 = b.point_at(c[6]), p7 = b.point_at(c[7]);
      b.face({{c[6], c[7], b.point(p7 + reach * back), b.point(p6 + reach * back)}});
    }
  } else if (kind == 2) {
    // A fin across the top from (x0, 0, H) to (x1, W, H), standing up.
    const double x0 = L * (0.3 + 0.1 * variant), x1 = L * (0.6 - 0.05 * variant);
    const std::uint32_t a = b.point({x0, 0, H}), d = b.point({x1, W, H});
    box.push_back(b.face({{c[0], c[1], c[5], a, c[4]}}));  // y = 0, split at a
    box.push_back(b.face({{c[2], c[3], c[7], d, c[6]}}));  // y = W, split at d
    box.push_back(b.face({{c[4], a, d, c[6]}}));           // top, left of the fin
    box.push_back(b.face({{a, c[5], c[7], d}}));           // top, right of the fin
    const double up = 0.5 * H + 0.2;
    if (variant % 2 == 1)
      b.face({{a, d, b.point({0.5 * (x0 + x1), 0.5 * W, H + up})}});
    else
      b.face({{a, d, b.point({x1, W, H + up}), b.point({x0, 0, H + up})}});
    name += variant % 2 == 1 ? "standing triangle" : "standing rectangle";
  } else {  // kind 3: along the middle half of the edge 4-5
    const std::uint32_t a = b.point({0.25 * L, 0, H}), d = b.point({0.75 * L, 0, H});
    box.push_back(quad(2, 3, 7, 6));                          // y = W
    box.push_back(b.face({{c[0], c[1], c[5], d, a, c[4]}}));  // y = 0
    box.push_back(b.face({{c[4], a, d, c[5], c[7], c[6]}}));  // top
    b.face({{a, d, b.point(b.point_at(d) + reach * out), b.point(b.point_at(a) + reach * out)}});
    name += "on part of an edge";
  }
  b.volume(box);
  name += " angle=" + std::to_string(static_cast<int>(std::lround(angle * 180 / std::numbers::pi))) + " " +
          std::to_string(static_cast<int>(L * 10)) + "x" + std::to_string(static_cast<int>(W * 10)) + "x" +
          std::to_string(static_cast<int>(H * 10)) + (variant > 1 ? " v" + std::to_string(variant) : "");
  return b.done(std::move(name));
}

/// A random simple polygon with `n` corners: star-shaped about the origin (sorted random angles,
/// no gap below a third of the mean, radii in [0.45, 1]), so non-convex in general. O(n log n).
inline std::vector<glm::dvec2> star_polygon(std::size_t n, random_source& rng) {
  const double mean = 2 * std::numbers::pi / double(n);
  std::vector<double> t(n);
  for (;;) {
    for (auto& x : t) x = rng.between(0, 2 * std::numbers::pi);
    std::sort(t.begin(), t.end());
    bool ok = true;
    for (std::size_t i = 0; i < n; ++i)
      ok = ok && (i + 1 < n ? t[i + 1] - t[i] : t[0] + 2 * std::numbers::pi - t[i]) > mean / 3;
    if (ok) break;
  }
  std::vector<glm::dvec2> p;
  for (const double a : t) {
    const double r = rng.between(0.45, 1.0);
    p.push_back({r * std::cos(a), r * std::sin(a)});
  }
  return p;
}

/// Distance from q to the segment a-b. O(1).
inline double segment_distance(glm::dvec2 q, glm::dvec2 a, glm::dvec2 b) {
  const glm::dvec2 d = b - a;
  const double t = std::clamp(glm::dot(q - a, d) / glm::dot(d, d), 0.0, 1.0);
  return glm::length(q - (a + t * d));
}

/// Whether q lies inside the polygon (crossing number). O(n).
inline bool inside_polygon(glm::dvec2 q, const std::vector<glm::dvec2>& p) {
  bool in = false;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    if ((p[i].y > q.y) != (p[j].y > q.y) &&
        q.x < p[j].x + (q.y - p[j].y) * (p[i].x - p[j].x) / (p[i].y - p[j].y))
      in = !in;
  return in;
}

/// The prism over a simple polygon (any orientation) with polygonal bores through it, each a
/// convex polygon given by its corners: bottom and top faces with the bores as holes, a quad per
/// side; one volume. O(total corners).
inline cellforge::samples::sample_model extrude(const std::vector<glm::dvec2>& outline,
                                                const std::vector<std::vector<glm::dvec2>>& bores,
                                                double height, std::string name) {
  model_builder b;
  std::vector<std::vector<std::uint32_t>> bottom, top;
  std::vector<std::uint32_t> faces;
  const auto ring = [&](const std::vector<glm::dvec2>& poly) {
    std::vector<std::uint32_t> lo, hi;
    for (const auto& q : poly)
      lo.push_back(b.point({q.x, q.y, 0.0})), hi.push_back(b.point({q.x, q.y, height}));
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const std::size_t j = (i + 1) % poly.size();
      faces.push_back(b.face({{lo[i], lo[j], hi[j], hi[i]}}));
    }
    bottom.push_back(lo);
    top.push_back(hi);
  };
  ring(outline);
  for (const auto& bore : bores) ring(bore);
  faces.push_back(b.face(bottom));
  faces.push_back(b.face(top));
  b.volume(faces);
  return b.done(std::move(name));
}

/// An extrusion of a random simple polygon of 5..20 sides with 0..3 bores (3..6-gons, kept clear
/// of the outline and of each other), of its own seed `draw`. O(sides · bores · tries).
inline cellforge::samples::sample_model random_extrusion(std::uint64_t draw) {
  random_source rng(0xbb67ae8584caa73bull ^ (draw * 0x9e3779b97f4a7c15ull));
  const std::size_t n = rng.in(5, 20), want = rng.in(0, 3);
  const std::vector<glm::dvec2> outline = star_polygon(n, rng);
  std::vector<std::vector<glm::dvec2>> bores;
  std::vector<std::pair<glm::dvec2, double>> placed;  // centre, radius
  for (std::size_t tries = 0; bores.size() < want && tries < 400; ++tries) {
    const glm::dvec2 c(rng.between(-1, 1), rng.between(-1, 1));
    const double r = rng.between(0.06, 0.2);
    if (!inside_polygon(c, outline)) continue;
    bool clear = true;
    for (std::size_t i = 0; i < n && clear; ++i)
      clear = segment_distance(c, outline[i], outline[(i + 1) % n]) > r * 1.3;
    for (const auto& [d, s] : placed) clear = clear && glm::length(c - d) > (r + s) * 1.3;
    if (!clear) continue;
    placed.push_back({c, r});
    const std::size_t k = rng.in(3, 6);
    const double turn = rng.between(0, 1);
    std::vector<glm::dvec2> bore;
    for (std::size_t j = 0; j < k; ++j) {
      const double t = 2 * std::numbers::pi * double(j) / double(k) + turn;
      bore.push_back(c + r * glm::dvec2(std::cos(t), std::sin(t)));
    }
    bores.push_back(std::move(bore));
  }
  const double height = rng.between(0.2, 1.5);
  return extrude(outline, bores, height,
                 "extrusion draw " + std::to_string(draw) + " sides=" + std::to_string(n) +
                     " bores=" + std::to_string(bores.size()));
}

/// Crossing of segments a-b and c-d at a-b's parameter s and c-d's t, both strictly inside.
/// O(1).
inline bool segments_cross(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d, double& s, double& t) {
  const glm::dvec2 r = b - a, q = d - c;
  const double den = r.x * q.y - r.y * q.x;
  if (std::abs(den) < 1e-12) return false;
  const glm::dvec2 w = c - a;
  s = (w.x * q.y - w.y * q.x) / den;
  t = (w.x * r.y - w.y * r.x) / den;
  return s > 0 && s < 1 && t > 0 && t < 1;
}

/// A box on top of a bigger box, turned about the vertical: the lower box's top rectangle T
/// (0..L × 0..W at z = h1) and the upper box's footprint R (a rectangle turned by `turn` about
/// `centre`) cross or nest; faces in the plane z = h1: the pieces of T outside R (facing up) and
/// of R outside T (facing down, an overhang), found by walking the two boundaries split at their
/// crossings; the side faces carry the crossings on their edges in that plane. One volume;
/// nullopt when R is not inside T and does not cross it (apart). O(1).
inline std::optional<cellforge::samples::sample_model> turned_boxes(glm::dvec2 lower, double h1,
                                                                    glm::dvec2 upper, glm::dvec2 centre,
                                                                    double turn, double h2,
                                                                    std::string name) {
  const std::vector<glm::dvec2> T{{0, 0}, {lower.x, 0}, lower, {0, lower.y}};  // counter-clockwise
  std::vector<glm::dvec2> R;
  for (const auto& [u, v] : std::array<std::array<double, 2>, 4>{{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}}) {
    const glm::dvec2 p(u * upper.x / 2, v * upper.y / 2);
    R.push_back(centre + glm::dvec2(std::cos(turn) * p.x - std::sin(turn) * p.y,
                                    std::sin(turn) * p.x + std::cos(turn) * p.y));
  }
  model_builder b;
  // Boundary points of each polygon in order: corners and crossings, each with its vertex label.
  struct at {
    double s;  // corner index + parameter along the side
    std::uint32_t v;
    int cross;  // index of the crossing, -1 at a corner
  };
  std::array<std::vector<at>, 2> walk;
  std::array<std::vector<std::uint32_t>, 2> corner;
  for (std::size_t i = 0; i < 4; ++i) {
    corner[0].push_back(b.point({T[i].x, T[i].y, h1}));
    walk[0].push_back({double(i), corner[0].back(), -1});
    corner[1].push_back(b.point({R[i].x, R[i].y, h1}));
    walk[1].push_back({double(i), corner[1].back(), -1});
  }
  int crossings = 0;
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = 0; j < 4; ++j) {
      double s = 0, t = 0;
      if (!segments_cross(T[i], T[(i + 1) % 4], R[j], R[(j + 1) % 4], s, t)) continue;
      if (s < 1e-3 || s > 1 - 1e-3 || t < 1e-3 || t > 1 - 1e-3) return std::nullopt;  // too near a corner
      const glm::dvec2 p = T[i] + s * (T[(i + 1) % 4] - T[i]);
      const std::uint32_t v = b.point({p.x, p.y, h1});
      walk[0].push_back({double(i) + s, v, crossings});
      walk[1].push_back({double(j) + t, v, crossings});
      ++crossings;
    }
  for (auto& w : walk) std::sort(w.begin(), w.end(), [](const at& x, const at& y) { return x.s < y.s; });
  const auto inside_T = [&](glm::dvec2 q) { return q.x > 0 && q.x < lower.x && q.y > 0 && q.y < lower.y; };
  const auto inside_R = [&](glm::dvec2 q) { return inside_polygon(q, R); };
  std::vector<std::uint32_t> faces;
  // Side faces: the lower box's go up to z = h1 (its top edge through T's boundary points), the
  // upper box's down to it.
  std::array<std::uint32_t, 4> base{}, roof{};
  for (std::size_t i = 0; i < 4; ++i)
    base[i] = b.point({T[i].x, T[i].y, 0.0}), roof[i] = b.point({R[i].x, R[i].y, h1 + h2});
  for (int p = 0; p < 2; ++p)
    for (std::size_t i = 0; i < 4; ++i) {
      std::vector<std::uint32_t> loop;  // along the side at z = h1 from corner i to i + 1, then back
      for (const at& x : walk[p])
        if (x.s >= double(i) && x.s < double(i + 1)) loop.push_back(x.v);
      loop.push_back(corner[p][(i + 1) % 4]);
      const auto& far = p == 0 ? base : roof;
      loop.push_back(far[(i + 1) % 4]);
      loop.push_back(far[i]);
      faces.push_back(b.face({loop}));
    }
  faces.push_back(b.face({{base[0], base[1], base[2], base[3]}}));
  faces.push_back(b.face({{roof[0], roof[1], roof[2], roof[3]}}));
  if (crossings == 0) {
    if (std::all_of(R.begin(), R.end(), inside_T))
      faces.push_back(b.face({corner[0], corner[1]}));  // T with R as a hole
    else if (std::all_of(T.begin(), T.end(), inside_R))
      faces.push_back(b.face({corner[1], corner[0]}));  // an overhang all round
    else
      return std::nullopt;
  } else {
    // A piece of P outside Q: P's boundary outside Q forwards, Q's inside P backwards, switching at
    // the crossings; one piece from each crossing where P's boundary leaves Q.
    for (int p = 0; p < 2; ++p) {
      const auto& P = walk[p];
      const auto& Q = walk[1 - p];
      const auto in_other = [&](glm::dvec2 q) { return p == 0 ? inside_R(q) : inside_T(q); };
      const auto& poly = p == 0 ? T : R;
      const auto where = [&](const std::vector<at>& w, int cross) {
        for (std::size_t k = 0; k < w.size(); ++k)
          if (w[k].cross == cross) return k;
        return w.size();
      };
      std::vector<char> used(static_cast<std::size_t>(crossings), 0);
      for (std::size_t k0 = 0; k0 < P.size(); ++k0) {
        if (P[k0].cross < 0 || used[static_cast<std::size_t>(P[k0].cross)]) continue;
        // Leaving Q here: the point just after along P is outside Q.
        const double s = P[k0].s, next = k0 + 1 < P.size() ? P[k0 + 1].s : 4.0;
        const double mid = 0.5 * (s + next);
        const auto side = static_cast<std::size_t>(mid);
        const glm::dvec2 q = poly[side % 4] + (mid - double(side)) * (poly[(side + 1) % 4] - poly[side % 4]);
        if (in_other(q)) continue;
        std::vector<std::uint32_t> loop;
        std::size_t k = k0;
        bool on_p = true;
        for (std::size_t guard = 0; guard < 64; ++guard) {
          const auto& w = on_p ? P : Q;
          loop.push_back(w[k].v);
          if (w[k].cross >= 0 && guard > 0) {
            // Switch polygons at a crossing.
            if (on_p) used[static_cast<std::size_t>(w[k].cross)] = 1;
            const std::size_t other = where(on_p ? Q : P, w[k].cross);
            loop.pop_back();
            on_p = !on_p;
            k = other;
            loop.push_back((on_p ? P : Q)[k].v);
            if (on_p && k == k0) break;
          } else if (guard == 0) {
            used[static_cast<std::size_t>(w[k].cross)] = 1;
          }
          k = on_p ? (k + 1) % P.size() : (k + Q.size() - 1) % Q.size();
        }
        if (!loop.empty() && loop.front() == loop.back()) loop.pop_back();
        faces.push_back(b.face({loop}));
      }
    }
  }
  b.volume(faces);
  return b.done(name + (crossings == 0 ? " nested" : " crossings=" + std::to_string(crossings)));
}

/// Random turned boxes of their own seed `draw`: sizes, heights, where the upper box stands (over
/// a corner, a side, or inside) and its turn. nullopt when the two are apart. O(1).
inline std::optional<cellforge::samples::sample_model> random_turned_boxes(std::uint64_t draw) {
  random_source rng(0xa54ff53a5f1d36f1ull ^ (draw * 0x9e3779b97f4a7c15ull));
  const glm::dvec2 lower(rng.between(1.5, 3), rng.between(1.5, 3));
  const double h1 = rng.between(0.3, 1.5), h2 = rng.between(0.3, 1.5);
  // Every third draw a box of about the lower one's size on its middle (up to 8 crossings, four
  // pieces each way touching at corners), every third one over a corner, the others anywhere.
  const std::uint64_t where = draw % 3;
  const glm::dvec2 upper = where == 1 ? lower * glm::dvec2(rng.between(0.75, 1.1), rng.between(0.75, 1.1))
                                      : glm::dvec2(rng.between(0.5, 1.5), rng.between(0.5, 1.5));
  const glm::dvec2 centre =
      where == 1   ? lower / 2.0 + glm::dvec2(rng.between(-0.1, 0.1), rng.between(-0.1, 0.1))
      : where == 2 ? lower * glm::dvec2(double(draw / 3 % 2), double(draw / 6 % 2))
                   : glm::dvec2(rng.between(-0.3, lower.x + 0.3), rng.between(-0.3, lower.y + 0.3));
  const double turn = rng.between(0.05, std::numbers::pi / 2 - 0.05);
  return turned_boxes(lower, h1, upper, centre, turn, h2,
                      "turned boxes draw " + std::to_string(draw) + " turn=" +
                          std::to_string(static_cast<int>(std::lround(turn * 180 / std::numbers::pi))));
}

/// Adds models whose truth may have faces in no volume (a fin): each needed by an edge, or a
/// fault. O(total size).
inline void add_ordinary(sweep_set& s, const std::string& family, cellforge::samples::sample_model m,
                         bool full, bool odd) {
  if (const std::size_t n = faces_no_edge_needs(m); n != 0) {
    s.faults.push_back(family + ": '" + m.name + "' has " + std::to_string(n) + " faces no edge needs");
    return;
  }
  m.unforced_faces = 0;
  add_copies(s, family, m, full, full ? 1 : 0, odd);
}

}  // namespace detail

/// The sweep of ordinary solids nobody tuned the reading for (ordinary_families): height fields
/// (k × m columns of heights 1..4), boxes with fins (flaps in no volume), extrusions of random
/// non-convex polygons with 0..3 bores, boxes turned on boxes. Shuffled as make_sweep's models;
/// full: about 400 models, sample: about 30. O(total size).
inline sweep_set make_ordinary_sweep(sweep_size size, bool shuffle = true) {
  const bool full = size == sweep_size::full;
  sweep_set s;
  s.shuffle = shuffle;
  {
    family_draws draws{"height field"};
    const std::size_t want = full ? 80 : 6;
    for (std::uint64_t d = 0; draws.kept < want && d < 40 * want; ++d)
      if (auto m = detail::height_field(d, draws))
        detail::add_copies(s, "height field", *m, false, 0, d % 2 == 0);
    if (draws.kept < want)
      s.faults.push_back("height field: only " + std::to_string(draws.kept) + " draws kept");
    s.draws.push_back(draws);
  }
  {
    std::size_t i = 0;
    const double pi = std::numbers::pi;
    for (const int kind : {0, 1, 2, 3, 4})
      for (const double angle : {0.0, pi / 6, pi / 4, pi / 2, 2 * pi / 3})
        for (int variant = 0; variant < 2; ++variant, ++i) {
          if (kind == 2 && angle != 0.0) continue;  // a standing fin has no angle; variants instead
          const glm::dvec3 size = variant == 0 ? glm::dvec3(1, 1, 1) : glm::dvec3(2, 1.25, 0.5);
          if (!full && i % 5 != 0) continue;
          detail::add_ordinary(s, "box with fin",
                               detail::box_with_fin(kind, angle, kind == 2 ? variant : 0, size), full,
                               i % 2 == 1);
        }
    if (full)
      for (int variant = 2; variant < 4; ++variant)
        detail::add_ordinary(s, "box with fin", detail::box_with_fin(2, 0.0, variant, {1.5, 1, 0.75}), full,
                             false);
  }
  for (std::uint64_t d = 0; d < (full ? 80u : 6u); ++d)
    detail::add_ordinary(s, "extrusion", detail::random_extrusion(d), false, d % 2 == 0);
  {
    std::size_t kept = 0;
    for (std::uint64_t d = 0; kept < (full ? 60u : 6u) && d < 1000; ++d)
      if (auto m = detail::random_turned_boxes(d))
        detail::add_ordinary(s, "turned boxes", *m, false, kept++ % 2 == 0);
  }
  return s;
}

/// The models of the sweep (make_sweep without the draw counts).
/// O(make_sweep).
inline std::vector<sweep_model> sweep_models(sweep_size size) { return make_sweep(size).models; }

/// Face lists as the truth and the comparisons use: per face its loops.
using faces_t = std::vector<std::vector<std::vector<std::uint32_t>>>;

/// The result's faces in the caller's vertex labels, which the truth uses.
/// O(total loop length).
inline faces_t result_faces(const cellforge::wireframe_result<glm::dvec3>& r) {
  faces_t out;
  for (const auto& f : r.input.faces) {
    out.push_back(f.loops);
    for (auto& loop : out.back())
      for (auto& v : loop) v = r.input_vertex[v];
  }
  return out;
}

/// The faces of `a` that `b` lacks (multisets of canonical faces), each as its corner count
/// and holes: "4" a quadrilateral, "8h1" an octagon with one hole. O(F log F · face size).
inline std::string unmatched(const faces_t& a, const faces_t& b) {
  std::multiset<faces_t::value_type> rest;
  for (const auto& f : b) rest.insert(cellforge::samples::detail::canonical_face(f));
  std::map<std::string, int> shapes;
  for (const auto& f : a) {
    const auto it = rest.find(cellforge::samples::detail::canonical_face(f));
    if (it != rest.end()) {
      rest.erase(it);
      continue;
    }
    ++shapes[std::to_string(f[0].size()) + (f.size() > 1 ? "h" + std::to_string(f.size() - 1) : "")];
  }
  std::string out;
  for (const auto& [shape, n] : shapes) {
    // Appended piece by piece: `"" + std::string(...)` trips g++ 12's false -Wrestrict at -O3.
    if (!out.empty()) out += ' ';
    if (n > 1) out += std::to_string(n) + 'x';
    out += shape;
  }
  return out.empty() ? "-" : out;
}

/// Why a result is not the truth, in one line; empty when it is exact.
/// O(F log F · face size).
inline std::string miss_reason(const cellforge::samples::sample_model& m,
                               const cellforge::wireframe_result<glm::dvec3>& r,
                               const cellforge::cells_validation_options& check = {}) {
  std::vector<std::string> why;
  const faces_t faces = result_faces(r);
  const bool faces_ok = cellforge::samples::same_faces(m.faces, faces);
  if (!faces_ok)
    why.push_back("faces " + std::to_string(faces.size()) + " vs " + std::to_string(m.faces.size()) +
                  " expected (extra " + unmatched(faces, m.faces) + "; missing " + unmatched(m.faces, faces) +
                  ")");
  if (r.input.volumes.size() != m.volumes.size())
    why.push_back("volumes " + std::to_string(r.input.volumes.size()) + " vs " +
                  std::to_string(m.volumes.size()) + " expected");
  else if (faces_ok && !cellforge::samples::same_volumes(m.faces, m.volumes, faces, r.input.volumes))
    why.push_back("volumes differ (" + std::to_string(m.volumes.size()) + " each)");
  if (const std::size_t want = truth_objects(m); r.cells.num_objects() != want)
    why.push_back("objects " + std::to_string(r.cells.num_objects()) + " vs " + std::to_string(want) +
                  " expected");
  if (r.unforced.size() != m.unforced_faces)
    why.push_back("unforced " + std::to_string(r.unforced.size()) + " vs " +
                  std::to_string(m.unforced_faces) + " expected");
  if (const auto v = cellforge::validate(r.cells, check); !v.ok())
    why.push_back("invalid complex: " + v.message);
  std::string out;
  for (const auto& w : why) out += (out.empty() ? "" : "; ") + w;
  return out;
}

/// For a model whose wireframe two solids share: empty when the result is exact, or says it is
/// ambiguous (faces in `unforced`, or an undecided alternative) and the truth is among the
/// readings it reports — the answer without some of its unforced faces, or the answer with one
/// undecided alternative taken (its cycles added, its faces removed); else why not.
/// O(alternatives · F log F · face size).
inline std::string ambiguous_miss(const cellforge::samples::sample_model& m,
                                  const cellforge::wireframe_result<glm::dvec3>& r,
                                  const cellforge::cells_validation_options& check = {}) {
  std::string why = miss_reason(m, r, check);
  if (why.empty()) return why;
  const bool undecided = std::any_of(r.alternatives.begin(), r.alternatives.end(),
                                     [](const cellforge::reading_note& a) { return a.undecided; });
  if (r.unforced.empty() && !undecided) return why + "; reported as certain";
  const faces_t faces = result_faces(r);
  std::multiset<faces_t::value_type> truth;
  for (const auto& f : m.faces) truth.insert(cellforge::samples::detail::canonical_face(f));
  // The answer without some of its unforced faces: every other face in the truth, and the truth
  // no bigger than the answer.
  {
    std::vector<char> loose(faces.size(), 0);
    for (const auto i : r.unforced) loose[i] = 1;
    std::multiset<faces_t::value_type> rest = truth;
    bool ok = true;
    std::size_t found = 0;
    for (std::size_t i = 0; i < faces.size() && ok; ++i) {
      const auto it = rest.find(cellforge::samples::detail::canonical_face(faces[i]));
      if (it != rest.end())
        rest.erase(it), ++found;
      else
        ok = loose[i] != 0;
    }
    if (ok && rest.empty() && found == m.faces.size()) return {};
  }
  for (const auto& a : r.alternatives) {
    if (!a.undecided) continue;
    std::vector<char> gone(faces.size(), 0);
    for (const auto i : a.remove) gone[i] = 1;
    faces_t reading;
    for (std::size_t i = 0; i < faces.size(); ++i)
      if (!gone[i]) reading.push_back(faces[i]);
    for (const auto& n : a.add) reading.push_back(n.loops);
    if (cellforge::samples::same_faces(m.faces, reading)) return {};
  }
  return why + "; ambiguous, but the truth is not among the readings reported";
}

// ---- Noisy copies (tests/test_wireframe_noise.cpp): the same models with every vertex moved.

/// The model with every vertex moved in a random direction (uniform on the sphere) by a random
/// distance up to `eps` of its bounding-box diagonal (uniform in [0, eps]; seeded); the truth is
/// unchanged. O(V).
inline cellforge::samples::sample_model noisy(const cellforge::samples::sample_model& m, double eps,
                                              std::uint64_t seed) {
  random_source rng(seed);
  cellforge::samples::sample_model out = m;
  const double reach = eps * detail::diagonal(m.wire.points);
  for (auto& p : out.wire.points) {
    glm::dvec3 u;
    do u = {rng.between(-1, 1), rng.between(-1, 1), rng.between(-1, 1)};
    while (glm::length(u) > 1.0 || glm::length(u) < 1e-3);
    p += (reach * rng.unit() / glm::length(u)) * u;
  }
  return out;
}

/// How a noisy copy came out: exact, a miss the result flags (its status is not `solid`:
/// tolerance.ambiguous, or the certificate's verdict) or an error (both honest), or a wrong
/// answer passed as good (status `solid`).
enum class noisy_outcome { exact, flagged, error, wrong };

/// Converts a noisy copy with default options and judges it against the truth as the sweep
/// does (`ambiguous`: a model two solids share, judged by ambiguous_miss), its complex checked
/// with the options the pipeline used (wireframe_result::check); `why` gets the reason of a
/// miss. O(one conversion).
inline noisy_outcome judge_noisy(const cellforge::samples::sample_model& m, std::string& why,
                                 bool ambiguous = false) {
  try {
    const auto r = cellforge::wireframe_to_cells(m.wire);
    why = ambiguous ? ambiguous_miss(m, r, r.check) : miss_reason(m, r, r.check);
    if (why.empty()) return noisy_outcome::exact;
    return r.status != cellforge::solid_status::solid ? noisy_outcome::flagged : noisy_outcome::wrong;
  } catch (const cellforge::error& e) {
    why = std::string("error: ") + e.what();
    return noisy_outcome::error;
  }
}

/// Whether some fixed planarity tolerance (1e-8 … 3e-2 of the diagonal, all stages) reads the
/// model exactly: a miss no tolerance mends is information-theoretic for this pipeline (the
/// noise is as large as the shape), one some tolerance mends is the estimator's. O(14 conversions).
inline bool some_tolerance_reads(const cellforge::samples::sample_model& m) {
  for (const double t :
       {1e-8, 3e-8, 1e-7, 3e-7, 1e-6, 3e-6, 1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 3e-3, 1e-2, 3e-2}) {
    cellforge::wireframe_options o;
    o.tolerance.automatic = false;
    o.trace.planarity.relative = o.reduction.planarity.relative = t;
    o.arrangement.planarity.relative = o.extra.retrace.planarity.relative = t;
    try {
      const auto r = cellforge::wireframe_to_cells(m.wire, o);
      if (miss_reason(m, r, r.check).empty()) return true;
    } catch (const cellforge::error&) {
    }
  }
  return false;
}

}  // namespace wireframe_sweep
