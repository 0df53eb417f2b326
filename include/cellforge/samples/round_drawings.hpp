// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample drawings of solids with rounded edges and fillets, with their ground truth: prisms
/// over normalon and quasi-normalon footprints (blocks, L, T, U, crosses, chamfered blocks,
/// wedges, ramps, trapezoids, stairs, gable houses) with 1–6 edges blended by a circular arc of random
/// radius (convex edges rounded, concave ones filleted), seen in a generic parallel view: each
/// blend's two end curves are exact elliptical arcs. The truth is the skeleton drawing (the
/// polyhedron's own drawing, what drawing_to_cells reads), which skeleton edges carry a blend,
/// its radius, convex or concave, and the seed's visibility category. See docs/sketch.md,
/// "Rounds and fillets".

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/samples/drawings.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"

namespace cellforge::samples {

/// One blended edge of a sample round drawing.
struct round_truth {
  static constexpr std::uint32_t npos = ~std::uint32_t{0};
  std::uint32_t edge = npos;                ///< the skeleton edge (index into skeleton.drawing.edges)
  std::array<std::uint32_t, 2> vertices{};  ///< its skeleton junctions
  double radius = 0;                        ///< in model units (the view is a rotation: drawing units too)
  bool convex = true;                       ///< a round (convex edge) or a fillet (concave edge)
  blend_category category = blend_category::a;  ///< a, b or c (from the true depths)
  bool oblique = false;                         ///< the edge is parallel to no model axis
  bool perpendicular = true;  ///< the end faces are perpendicular to the edge (the end curves are circles)
  std::vector<std::uint32_t> arcs;  ///< its arcs in the round drawing (2; 4 when a contour line splits them)
  std::uint32_t contour = npos;     ///< its contour line in the round drawing (convex, category b)
};

/// A drawing with rounds and fillets and its truth.
struct sample_round_drawing {
  std::string name, family;
  arc_drawing<glm::dvec2> drawing;  ///< the drawing as the designer draws it
  sample_drawing skeleton;          ///< the polyhedron without its blends, in the same view
  std::vector<round_truth> rounds;
  /// How generic the view is for the blends: the smallest junction–junction or junction–line
  /// distance over the diagonal; the smallest |cos| between the view direction and a blend's
  /// face or end face; the smallest fraction of a split arc's sweep on either side of its
  /// contour point (1 when none is split).
  double spacing = 0, face_cos = 0, rim_gap = 1;
};

/// Options of round_drawing_sweep.
struct round_sweep_options {
  std::uint64_t seed = 1;
  std::size_t drawings = 240;  ///< drawings to make
  std::size_t max_blends = 6;  ///< blends per drawing: 1..max_blends (as many as fit)
  double min_margin = 2e-3;  ///< junction–junction and junction–line distance over the drawing's diagonal
  int view_attempts = 60;    ///< views tried per model before it is dropped
  /// One radius for every blend of a drawing (8–30 % of its shortest side or height), as parts
  /// are often designed; off: each blend its own.
  bool equal_radii = false;
};

/// What round_drawing_sweep made: drawings, blends by kind and category, models dropped.
struct round_sweep_report {
  std::size_t drawings = 0, blends = 0, rounds = 0, fillets = 0, oblique = 0, not_perpendicular = 0;
  std::array<std::size_t, 3> category{};  ///< a, b, c
  std::size_t dropped = 0;                ///< models with no blend that fits or no good view
};

namespace detail::rounds {

/// The end curve of a blend at one end of its edge: X(φ) = c + u cos φ + v sin φ, φ in [0, Φ]
/// (φ = 0 on the first face's tangent line, Φ on the second's).
struct end_curve {
  glm::dvec3 c{0.0}, u{0.0}, v{0.0};
  glm::dvec3 at(double phi) const { return c + u * std::cos(phi) + v * std::sin(phi); }
};

/// A blend's end curves and its normal frame: outward normal n(φ) = cos φ n1 + sin φ m, φ in [0, Phi].
struct blend {
  std::array<end_curve, 2> ends;
  glm::dvec3 n1{0.0}, m{0.0};
  double Phi = 0;
};

/// A circular blend of radius r on the edge A→B between faces of outward unit normals n1, n2
/// (both ⊥ AB), cut by the end planes through A (normal gA) and B (normal gB): the cylinder's
/// axis is at distance r from both face planes, inside the solid for a convex edge, outside for
/// a concave one; its surface point of outward normal n(φ) is swept along the edge to each end
/// plane, which is affine in (cos φ, sin φ). O(1).

template <class = void>
blend make_blend(glm::dvec3 A, glm::dvec3 B, glm::dvec3 n1, glm::dvec3 n2, bool convex, double r,
                 glm::dvec3 gA, glm::dvec3 gB) {
  blend out;
  const glm::dvec3 d = glm::normalize(B - A);
  const double c = std::clamp(glm::dot(n1, n2), -1.0, 1.0);
  out.n1 = n1;
  out.m = glm::normalize(n2 - c * n1);
  out.Phi = std::acos(c);
  const double sigma = convex ? -1.0 : 1.0;
  const glm::dvec3 x = sigma * r / (1 + c) * (n1 + n2);  // axis point − edge point, in the cross-section
  for (int k = 0; k < 2; ++k) {
    const glm::dvec3 P = k == 0 ? A : B, g = k == 0 ? gA : gB;
    const double gd = glm::dot(g, d);
    end_curve& e = out.ends[static_cast<std::size_t>(k)];
    e.c = P + x - d * (glm::dot(g, x) / gd);
    e.u = -sigma * r * n1 + d * (sigma * r * glm::dot(g, n1) / gd);
    e.v = -sigma * r * out.m + d * (sigma * r * glm::dot(g, out.m) / gd);
  }
  return out;
}

/// The elliptical arc c + a cos φ + b sin φ, φ from phi0 to phi1, in centre form (principal
/// axes from the conjugate semi-diameters a, b). O(1).
template <class = void>
elliptical_arc<glm::dvec2> affine_arc(glm::dvec2 c, glm::dvec2 a, glm::dvec2 b, double phi0, double phi1) {
  const double t0 = 0.5 * std::atan2(2 * glm::dot(a, b), glm::dot(a, a) - glm::dot(b, b));
  const glm::dvec2 A = a * std::cos(t0) + b * std::sin(t0), B = -a * std::sin(t0) + b * std::cos(t0);
  const double s = A.x * B.y - A.y * B.x > 0 ? 1.0 : -1.0;
  return {c, glm::length(A), glm::length(B), std::atan2(A.y, A.x), s * (phi0 - t0), s * (phi1 - phi0)};
}

/// Whether two convex polygons (2D) overlap, by separating axes. O(n m).
template <class = void>
bool convex_overlap(const std::vector<glm::dvec2>& p, const std::vector<glm::dvec2>& q) {
  const auto separated = [](const std::vector<glm::dvec2>& a, const std::vector<glm::dvec2>& b) {
    for (std::size_t i = 0; i < a.size(); ++i) {
      const glm::dvec2 e = a[(i + 1) % a.size()] - a[i], n(-e.y, e.x);
      double alo = std::numeric_limits<double>::infinity(), ahi = -alo, blo = alo, bhi = -alo;
      for (const auto& v : a) alo = std::min(alo, glm::dot(n, v)), ahi = std::max(ahi, glm::dot(n, v));
      for (const auto& v : b) blo = std::min(blo, glm::dot(n, v)), bhi = std::max(bhi, glm::dot(n, v));
      if (ahi < blo || bhi < alo) return true;
    }
    return false;
  };
  return !separated(p, q) && !separated(q, p);
}

/// Whether segments ab and cd cross or touch. O(1).
template <class = void>
bool segments_meet(glm::dvec2 a, glm::dvec2 b, glm::dvec2 c, glm::dvec2 d) {
  const auto orient = [](glm::dvec2 p, glm::dvec2 q, glm::dvec2 r) {
    return (q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x);
  };
  const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
  if (((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0))) return true;
  return cellforge::detail::segment_distance(a, c, d) < 1e-12 ||
         cellforge::detail::segment_distance(b, c, d) < 1e-12 ||
         cellforge::detail::segment_distance(c, a, b) < 1e-12 ||
         cellforge::detail::segment_distance(d, a, b) < 1e-12;
}

/// A blended edge of a prism while the sample is built.
struct prism_blend {
  std::uint32_t a = 0, b = 0;  ///< model vertices
  bool convex = true, oblique = false, perpendicular = true;
  double radius = 0;
  glm::dvec3 n1{0.0}, n2{0.0}, gA{0.0}, gB{0.0};
  blend geometry;
  std::array<std::array<std::uint32_t, 2>, 2> cut{};  ///< per end: the model edges in face 1 and face 2
  std::array<std::array<double, 2>, 2> cut_length{};
  int cap = -1;                    ///< 0: bottom, 1: top face of a side edge's blend; -1: a vertical edge
  std::vector<glm::dvec2> region;  ///< its footprint-plane region in a cap face (convex polygon)
};

/// The blendable edges of the prism over the counter-clockwise footprint p (height h) and the
/// blend of radius r on one of them (edge kind 0: vertical at corner i; 1: top side i; 2:
/// bottom side i). Vertex i is p_i at z = 0, n + i at z = h (extruded_polygon's numbering).
/// false when the edge cannot be blended as the seed's rounds are (a side edge whose
/// neighbouring sides are not parallel, or at a reflex corner). O(1).
template <class = void>
bool prism_edge_blend(const std::vector<glm::dvec2>& p, double h, int kind, std::size_t i, double r,
                      prism_blend& out) {
  const std::size_t n = p.size();
  const auto P = [&](std::size_t j) { return p[j % n]; };
  const auto side_normal = [&](std::size_t j) {  // outward normal of side j (p_j → p_{j+1})
    const glm::dvec2 d = glm::normalize(P(j + 1) - P(j));
    return glm::dvec3(d.y, -d.x, 0);
  };
  const auto cross2 = [](glm::dvec2 u, glm::dvec2 v) { return u.x * v.y - u.y * v.x; };
  const auto convex_corner = [&](std::size_t j) { return cross2(P(j) - P(j + n - 1), P(j + 1) - P(j)) > 0; };
  const auto up = glm::dvec3(0, 0, 1);
  out = {};
  out.radius = r;
  const auto n32 = static_cast<std::uint32_t>(n);
  const auto at = [&](std::size_t j, bool top) { return glm::dvec3(P(j), top ? h : 0.0); };
  if (kind == 0) {
    out.a = static_cast<std::uint32_t>(i);
    out.b = static_cast<std::uint32_t>(i) + n32;
    out.convex = convex_corner(i);
    out.n1 = side_normal(i + n - 1);
    out.n2 = side_normal(i);
    out.gA = -up;
    out.gB = up;
    out.geometry = make_blend(at(i, false), at(i, true), out.n1, out.n2, out.convex, r, out.gA, out.gB);
  } else {
    const bool top = kind == 1;
    if (!convex_corner(i) || !convex_corner(i + 1)) return false;
    const glm::dvec2 before = P(i) - P(i + n - 1), after = P(i + 2) - P(i + 1);
    if (std::abs(cross2(before, after)) > 1e-9 * glm::length(before) * glm::length(after)) return false;
    const std::uint32_t off = top ? n32 : 0;
    out.a = static_cast<std::uint32_t>(i % n) + off;
    out.b = static_cast<std::uint32_t>((i + 1) % n) + off;
    out.convex = true;
    out.n1 = side_normal(i);
    out.n2 = top ? up : -up;
    out.gA = side_normal(i + n - 1);
    out.gB = side_normal(i + 1);
    out.cap = top ? 1 : 0;
    const glm::dvec2 d = P(i + 1) - P(i);
    out.oblique = std::abs(d.x) > 1e-9 * glm::length(d) && std::abs(d.y) > 1e-9 * glm::length(d);
    out.perpendicular = std::abs(glm::dot(glm::normalize(before), glm::normalize(d))) < 1e-9;
    out.geometry = make_blend(at(i, top), at(i + 1, top), out.n1, out.n2, true, r, out.gA, out.gB);
  }
  return true;
}

inline constexpr std::uint32_t none32 = ~std::uint32_t{0};

}  // namespace detail::rounds

/// Blends the listed edges of the prism over footprint `p` (counter-clockwise, height h) —
/// `edges[k] = {kind, index, radius}`, kind 0 the vertical edge at corner index, 1 the top edge
/// of side index, 2 the bottom edge — and draws it in the parallel view `view` (model → view
/// rotation). Every sharp edge and every arc is drawn, hidden ones included (the wireframe
/// convention of the sketch stages); smooth tangent lines are not; a round on the contour
/// (category b) has its contour line drawn, splitting both arcs at its ends; fillets have none.
/// Throws invalid_input when an edge cannot be blended or blends do not fit (a shared vertex, a
/// cut longer than 60 % of an edge, regions of two blends meeting in a cap face, a fillet
/// reaching other sides). O(n² + blends²).
template <class = void>
sample_round_drawing round_prism_drawing(const std::vector<glm::dvec2>& p, double h,
                                         const std::vector<std::array<double, 3>>& edges,
                                         const glm::dmat3& view, std::string name, std::string family) {
  const std::size_t n = p.size();
  double area = 0;
  for (std::size_t i = 0; i < n; ++i) area += p[i].x * p[(i + 1) % n].y - p[(i + 1) % n].x * p[i].y;
  if (!(area > 0))
    throw error(error_category::invalid_input, "round_prism_drawing: give the footprint counter-clockwise");
  sample_model model = extruded_polygon(p, h, name);
  const auto fail = [&](const std::string& why) {
    throw error(error_category::invalid_input,
                cellforge::detail::cat("round_prism_drawing: ", name, ": ", why));
  };
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> edge_id;
  for (std::uint32_t e = 0; e < model.wire.edges.size(); ++e)
    edge_id[{model.wire.edges[e][0], model.wire.edges[e][1]}] = e;
  const auto find_edge = [&](std::uint32_t a, std::uint32_t b) {
    const auto it = edge_id.find({std::min(a, b), std::max(a, b)});
    return it == edge_id.end() ? detail::rounds::none32 : it->second;
  };
  const auto& X = model.wire.points;
  std::vector<std::vector<std::uint32_t>> around(X.size());
  for (const auto& e : model.wire.edges) around[e[0]].push_back(e[1]), around[e[1]].push_back(e[0]);

  std::vector<detail::rounds::prism_blend> blends;
  std::vector<bool> used(X.size(), false);
  std::map<std::uint32_t, std::array<double, 2>> cuts;  // edge -> cut at its first, second junction
  for (const auto& spec : edges) {
    detail::rounds::prism_blend b;
    const int kind = static_cast<int>(spec[0]);
    const auto i = static_cast<std::size_t>(spec[1]);
    if (kind < 0 || kind > 2 || i >= n || !(spec[2] > 0)) fail("an edge spec is out of range");
    if (!detail::rounds::prism_edge_blend(p, h, kind, i, spec[2], b))
      fail(cellforge::detail::cat("side edge ", std::to_string(i),
                                  " has neighbouring sides that are not parallel or a reflex corner"));
    if (used[b.a] || used[b.b]) fail("two blends share a vertex");
    used[b.a] = used[b.b] = true;
    // The edges the blend shortens: at each end, the other two edges, matched to the tangent points.
    for (int k = 0; k < 2; ++k) {
      const std::uint32_t v = k == 0 ? b.a : b.b, w = k == 0 ? b.b : b.a;
      for (int side = 0; side < 2; ++side) {
        const glm::dvec3 t =
            b.geometry.ends[static_cast<std::size_t>(k)].at(side == 0 ? 0.0 : b.geometry.Phi);
        std::uint32_t best = detail::rounds::none32;
        double cut = 0;
        for (const std::uint32_t o : around[v]) {
          if (o == w) continue;
          const glm::dvec3 dir = X[o] - X[v], off = t - X[v];
          const double along = glm::dot(off, dir) / glm::dot(dir, dir);
          if (glm::length(off - along * dir) < 1e-9 * glm::length(dir) && along > 0 && along < 1)
            best = find_edge(v, o), cut = along;
        }
        if (best == detail::rounds::none32) fail("a blend's tangent point is on no edge at its end");
        b.cut[static_cast<std::size_t>(k)][static_cast<std::size_t>(side)] = best;
        b.cut_length[static_cast<std::size_t>(k)][static_cast<std::size_t>(side)] = cut;
        auto& c = cuts[best];
        c[model.wire.edges[best][0] == v ? 0 : 1] += cut;
      }
    }
    // Its region in a cap face.
    const auto flat = [](glm::dvec3 q) { return glm::dvec2(q.x, q.y); };
    if (b.cap < 0) {
      const auto& e = b.geometry.ends[1];
      b.region = {p[i], flat(e.at(0)), flat(e.at(b.geometry.Phi))};
      if (!b.convex)  // a fillet adds the corner's outside: no other side may reach it
        for (std::size_t j = 0; j < n; ++j) {
          if (j == i || (j + 1) % n == i) continue;
          const glm::dvec2 a = p[j], c = p[(j + 1) % n];
          if (detail::rounds::segments_meet(a, c, b.region[1], b.region[2]) ||
              detail::rounds::segments_meet(a, c, b.region[0], b.region[1]) ||
              detail::rounds::segments_meet(a, c, b.region[0], b.region[2]))
            fail("a fillet reaches another side");
        }
    } else {
      const auto& e0 = b.geometry.ends[0];
      const auto& e1 = b.geometry.ends[1];
      b.region = {p[i], p[(i + 1) % n], flat(e1.at(b.geometry.Phi)), flat(e0.at(b.geometry.Phi))};
      if (b.radius > 0.35 * h) fail("a side edge's radius exceeds 35 % of the height");
      for (std::size_t j = 0; j < n; ++j) {
        if (j == i || (j + 1) % n == i || j == (i + 1) % n) continue;
        const glm::dvec2 a = p[j], c = p[(j + 1) % n];
        if (std::min({cellforge::detail::segment_distance(a, p[i], p[(i + 1) % n]),
                      cellforge::detail::segment_distance(c, p[i], p[(i + 1) % n]),
                      cellforge::detail::segment_distance(p[i], a, c),
                      cellforge::detail::segment_distance(p[(i + 1) % n], a, c)}) < 2.5 * b.radius)
          fail("a side edge's blend comes near another side");
      }
    }
    for (const auto& o : blends) {
      const bool shares_cap = (b.cap < 0 || o.cap < 0 || b.cap == o.cap);
      if (shares_cap && detail::rounds::convex_overlap(b.region, o.region))
        fail("two blends meet in a cap face");
    }
    blends.push_back(std::move(b));
  }
  for (const auto& [e, c] : cuts)  // cuts are fractions of the edge's length
    if (c[0] + c[1] > 0.6) fail("an edge would be cut by more than 60 % of its length");

  // The drawing. Skeleton first: the polyhedron's own drawing.
  sample_round_drawing out;
  out.name = std::move(name);
  out.family = family;
  out.skeleton = project_model(model, view, out.name, family);
  const auto proj = [&](glm::dvec3 q) {
    const glm::dvec3 v = view * q;
    return glm::dvec2(v.x, v.y);
  };
  const auto projv = [&](glm::dvec3 q) {  // a vector
    const glm::dvec3 v = view * q;
    return glm::dvec2(v.x, v.y);
  };
  const glm::dvec3 toward(view[0][2], view[1][2], view[2][2]);  // the viewer's direction in model axes
  auto& d = out.drawing;
  std::vector<std::uint32_t> id(X.size(), detail::rounds::none32);
  for (std::uint32_t v = 0; v < X.size(); ++v)
    if (!used[v]) {
      id[v] = static_cast<std::uint32_t>(d.lines.points.size());
      d.lines.points.push_back(out.skeleton.drawing.points[v]);
    }
  const auto add_point = [&](glm::dvec3 q) {
    d.lines.points.push_back(proj(q));
    return static_cast<std::uint32_t>(d.lines.points.size() - 1);
  };
  // Each shortened edge's new ends.
  std::vector<std::array<std::uint32_t, 2>> ends(model.wire.edges.size());
  for (std::uint32_t e = 0; e < model.wire.edges.size(); ++e)
    ends[e] = {id[model.wire.edges[e][0]], id[model.wire.edges[e][1]]};
  std::vector<bool> blended(model.wire.edges.size(), false);
  std::vector<std::array<std::uint32_t, 2>> contours;
  double face_cos = 1, rim_gap = 1;
  for (auto& b : blends) {
    round_truth t;
    t.edge = find_edge(b.a, b.b);
    blended[t.edge] = true;
    t.vertices = {b.a, b.b};
    t.radius = b.radius;
    t.convex = b.convex;
    t.oblique = b.oblique;
    t.perpendicular = b.perpendicular;
    const double c1 = glm::dot(b.n1, toward), c2 = glm::dot(b.n2, toward);
    const int front = (c1 > 0) + (c2 > 0);
    t.category = front == 2 ? blend_category::a : front == 1 ? blend_category::b : blend_category::c;
    face_cos = std::min({face_cos, std::abs(c1), std::abs(c2), std::abs(glm::dot(b.gA, toward)),
                         std::abs(glm::dot(b.gB, toward))});
    const detail::rounds::blend& g = b.geometry;
    // The contour generator of a round on the contour: where its normal is square to the view.
    double rim = -1;
    if (b.convex && front == 1) {
      const double two_pi = 2 * std::numbers::pi;
      double s = std::atan2(-c1, glm::dot(g.m, toward));
      for (int k = 0; k < 2 && rim < 0; ++k, s += std::numbers::pi) {
        const double u = std::fmod(s + 2 * two_pi, two_pi);
        if (u > 0 && u < g.Phi) rim = u;
      }
      if (rim < 0) fail("no contour generator on a round whose faces face opposite ways (a generator fault)");
      rim_gap = std::min({rim_gap, rim / g.Phi, 1 - rim / g.Phi});
    }
    std::array<std::uint32_t, 2> split{detail::rounds::none32, detail::rounds::none32};
    for (std::size_t k = 0; k < 2; ++k) {
      const detail::rounds::end_curve& e = g.ends[k];
      const std::uint32_t v = k == 0 ? b.a : b.b;
      const std::uint32_t t0 = add_point(e.at(0)), t1 = add_point(e.at(g.Phi));
      for (std::size_t side = 0; side < 2; ++side) {
        const std::uint32_t edge = b.cut[k][side];
        ends[edge][model.wire.edges[edge][0] == v ? 0 : 1] = side == 0 ? t0 : t1;
      }
      const glm::dvec2 c = proj(e.c), a = projv(e.u), bb = projv(e.v);
      const auto add_arc = [&](std::uint32_t from, std::uint32_t to, double phi0, double phi1) {
        t.arcs.push_back(static_cast<std::uint32_t>(d.arcs.size()));
        d.arcs.push_back({{from, to}, detail::rounds::affine_arc(c, a, bb, phi0, phi1)});
      };
      if (rim > 0) {
        split[k] = add_point(e.at(rim));
        add_arc(t0, split[k], 0, rim);
        add_arc(split[k], t1, rim, g.Phi);
      } else {
        add_arc(t0, t1, 0, g.Phi);
      }
    }
    if (rim > 0) {
      t.contour = static_cast<std::uint32_t>(contours.size());  // made an edge index below
      contours.push_back(split);
    }
    out.rounds.push_back(std::move(t));
  }
  for (std::uint32_t e = 0; e < model.wire.edges.size(); ++e)
    if (!blended[e]) d.lines.edges.push_back(ends[e]);
  for (auto& t : out.rounds)
    if (t.contour != round_truth::npos) t.contour += static_cast<std::uint32_t>(d.lines.edges.size());
  for (const auto& c : contours) d.lines.edges.push_back(c);
  // How generic the view is for the blends.
  const auto& q = d.lines.points;
  glm::dvec2 lo = q[0], hi = q[0];
  for (const auto& v : q) lo = glm::min(lo, v), hi = glm::max(hi, v);
  out.spacing = detail::junction_spacing(q, d.lines.edges, glm::length(hi - lo));
  out.face_cos = face_cos;
  out.rim_gap = rim_gap;
  return out;
}

/// The families of round_drawing_sweep, in its order. O(1).
template <class = void>
std::vector<std::string> round_sweep_families() {
  return {"block",       "L",     "T",    "cross",     "U",      "chamfered block",
          "chamfered L", "wedge", "ramp", "trapezoid", "stairs", "gable"};
}

namespace detail::rounds {

/// The footprint of a family member (counter-clockwise), random sizes from rng. O(1).
template <class = void>
std::vector<glm::dvec2> family_footprint(std::size_t family, cellforge::detail::splitmix& rng) {
  const double a = rng.uniform(1, 3), b = rng.uniform(1, 3);
  std::vector<glm::dvec2> p;
  const auto letter = [&](int kind) {
    std::vector<glm::dvec2> q = letter_footprint(kind, 0.0, rng);
    const double sx = rng.uniform(0.5, 1.0), sy = rng.uniform(0.5, 1.0);
    for (auto& v : q) v = {v.x * sx, v.y * sy};
    return q;
  };
  const auto pick = [&](std::vector<glm::dvec2> q, double size) {
    std::vector<bool> which(q.size(), false);
    const std::size_t n = q.size();
    for (std::size_t i = 0; i < n; ++i) {
      const glm::dvec2 u = q[i] - q[(i + n - 1) % n], v = q[(i + 1) % n] - q[i];
      which[i] = u.x * v.y - u.y * v.x > 0 && rng.uniform(0, 1) < 0.35;
    }
    return chamfered_corners(q, which, size);
  };
  switch (family) {
    case 0:
      p = {{0, 0}, {a, 0}, {a, b}, {0, b}};
      break;
    case 1:
      p = letter(0);
      break;
    case 2:
      p = letter(1);
      break;
    case 3:
      p = letter(2);
      break;
    case 4: {
      const double w = rng.uniform(0.4, 0.8), g = rng.uniform(0.4, 1.0), d = rng.uniform(0.5, 1.5);
      p = {{0, 0},       {2 * w + g, 0}, {2 * w + g, d + 0.6}, {w + g, d + 0.6},
           {w + g, 0.6}, {w, 0.6},       {w, d + 0.6},         {0, d + 0.6}};
      break;
    }
    case 5:
      p = pick({{0, 0}, {a, 0}, {a, b}, {0, b}}, rng.uniform(0.15, 0.4));
      break;
    case 6:
      p = pick(letter(0), rng.uniform(0.15, 0.35));
      break;
    case 7:
      p = {{0, 0}, {a, 0}, {0, b}};
      break;
    case 8:
      p = {{0, 0}, {a + 1, 0}, {a + 1, b}, {rng.uniform(0.3, 0.8) * (a + 1), b}};
      break;
    case 9: {
      const double s1 = rng.uniform(0.2, 0.4) * a, s2 = rng.uniform(0.2, 0.4) * a;
      p = {{0, 0}, {a, 0}, {a - s2, b}, {s1, b}};
      break;
    }
    case 10: {  // a staircase of 1..3 steps, as sample_stairs draws its profile
      const std::size_t steps = 1 + below(3, rng);
      std::vector<double> x{0.0}, z{0.0};
      for (std::size_t k = 0; k < steps; ++k) {
        x.push_back(x.back() + rng.uniform(0.6, 1.4));
        z.push_back(z.back() + rng.uniform(0.4, 1.0));
      }
      p = {{0, 0}, {x[steps], 0}, {x[steps], z[steps]}};
      for (std::size_t k = steps; k-- > 0;) {
        p.push_back({x[k], z[k + 1]});
        if (k > 0) p.push_back({x[k], z[k]});
      }
      break;
    }
    default:
      p = {{0, 0}, {a, 0}, {a, b}, {a / 2, b + rng.uniform(0.3, 1.2)}, {0, b}};
      break;
  }
  double area = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    area += p[i].x * p[(i + 1) % p.size()].y - p[(i + 1) % p.size()].x * p[i].y;
  if (area < 0) std::reverse(p.begin(), p.end());
  return p;
}

}  // namespace detail::rounds

/// The test drawings of the round stages: `options.drawings` prisms of the families of
/// round_sweep_families() in turn, each with 1..max_blends edges blended (vertical edges at
/// convex corners rounded, at reflex corners filleted; top and bottom edges of sides whose
/// neighbouring sides are parallel rounded: the oblique ones of ramps and trapezoids), random
/// radii that fit, in the first random view that keeps every junction and line
/// `min_margin` apart, no blend face within |cos| 0.1 of edge-on and every contour point at
/// least 10 % of its arc's sweep from the arc's ends. Deterministic in the options.
/// O(drawings · (candidates · blends² + attempts · V · E)).
template <class = void>
std::vector<sample_round_drawing> round_drawing_sweep(const round_sweep_options& options = {},
                                                      round_sweep_report* report = nullptr) {
  if (options.max_blends < 1 || options.view_attempts < 1)
    throw error(error_category::invalid_input,
                "round_drawing_sweep: max_blends and view_attempts must be at least 1");
  const std::vector<std::string> families = round_sweep_families();
  std::vector<sample_round_drawing> out;
  round_sweep_report rep;
  for (std::size_t k = 0; out.size() < options.drawings && k < 4 * options.drawings + 20; ++k) {
    const std::size_t family = k % families.size();
    cellforge::detail::splitmix rng{options.seed * 0x9e3779b97f4a7c15u + 0x726f756e64000000u + k};
    const std::vector<glm::dvec2> p = detail::rounds::family_footprint(family, rng);
    const double h = rng.uniform(0.8, 2.5);
    const std::size_t n = p.size();
    const std::string name = families[family] + " #" + std::to_string(k);
    // Candidates in random order, the rarer kinds (fillets at reflex corners, side edges along
    // oblique sides) usually first; each kept when it fits with those kept before.
    std::vector<std::array<double, 3>> cand, kept;
    std::vector<std::pair<double, std::size_t>> order;
    for (int kind = 0; kind < 3; ++kind)
      for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 u = p[i] - p[(i + n - 1) % n], w = p[(i + 1) % n] - p[i];
        const bool rare =
            kind == 0 ? u.x * w.y - u.y * w.x < 0
                      : std::abs(w.x) > 1e-9 * glm::length(w) && std::abs(w.y) > 1e-9 * glm::length(w);
        const double key = rng.uniform(0, 1) - (rare ? 0.6 : 0.0);
        order.push_back({key, cand.size()});
        cand.push_back({static_cast<double>(kind), static_cast<double>(i), 0});
      }
    std::sort(order.begin(), order.end());
    {
      std::vector<std::array<double, 3>> sorted;
      for (const auto& [key, at] : order) sorted.push_back(cand[at]);
      cand = std::move(sorted);
    }
    const std::size_t want = 1 + detail::below(options.max_blends, rng);
    double shortest = h;
    for (std::size_t i = 0; i < n; ++i) shortest = std::min(shortest, glm::length(p[(i + 1) % n] - p[i]));
    const double common = options.equal_radii ? rng.uniform(0.08, 0.3) * shortest : 0.0;
    for (auto& c : cand) {
      if (kept.size() >= want) break;
      const auto i = static_cast<std::size_t>(c[1]);
      const double side =
          std::min(glm::length(p[(i + 1) % n] - p[i]), glm::length(p[i] - p[(i + n - 1) % n]));
      c[2] = options.equal_radii ? common : rng.uniform(0.08, 0.3) * std::min(side, h);
      kept.push_back(c);
      try {
        round_prism_drawing(p, h, kept, glm::dmat3(1.0), name, families[family]);
      } catch (const error&) {
        kept.pop_back();
      }
    }
    if (kept.empty()) {
      ++rep.dropped;
      continue;
    }
    bool found = false;
    for (int attempt = 0; attempt < options.view_attempts && !found; ++attempt) {
      sample_round_drawing s =
          round_prism_drawing(p, h, kept, detail::random_rotation(rng),
                              name + ", view " + std::to_string(attempt + 1), families[family]);
      if (s.spacing < options.min_margin || s.face_cos < 0.1 || s.rim_gap < 0.1 ||
          generic_margin(s.skeleton) < options.min_margin)
        continue;
      found = true;
      for (const auto& t : s.rounds) {
        ++rep.blends;
        ++(t.convex ? rep.rounds : rep.fillets);
        rep.oblique += t.oblique;
        rep.not_perpendicular += !t.perpendicular;
        ++rep.category[static_cast<std::size_t>(t.category)];
      }
      out.push_back(std::move(s));
    }
    if (!found) ++rep.dropped;
  }
  rep.drawings = out.size();
  if (report) *report = rep;
  return out;
}

}  // namespace cellforge::samples
