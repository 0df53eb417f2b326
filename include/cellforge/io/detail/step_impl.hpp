// SPDX-License-Identifier: MIT
#pragma once
// The engine of write step (included by io/step.hpp).

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/newell.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/rounded_solid.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/step.hpp"
#include "cellforge/version.hpp"

namespace cellforge::io {

namespace detail {

/// Appends a STEP REAL: shortest round-trip digits, always with a decimal point ("1.", "2.5E-07").
template <class = void>
void step_real(std::string& out, double v) {
  char buf[40];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  std::string_view s(buf, static_cast<std::size_t>(r.ptr - buf));
  const std::size_t e = s.find('e');
  const std::string_view mantissa = s.substr(0, e);
  out += mantissa;
  if (mantissa.find('.') == std::string_view::npos) out += '.';
  if (e != std::string_view::npos) {
    out += 'E';
    out += s.substr(e + 1);
  }
}

/// Appends text as a STEP string literal: quotes and backslashes doubled, other characters
/// than printable ASCII as \X2\hhhh\X0\ (UTF-16, from the UTF-8 input; bad bytes as U+FFFD).
template <class = void>
void step_string(std::string& out, std::string_view text) {
  static constexpr char hex[] = "0123456789ABCDEF";
  out += '\'';
  std::vector<std::uint32_t> units;  // UTF-16 code units of a run of non-ASCII characters
  const auto flush = [&] {
    if (units.empty()) return;
    out += "\\X2\\";
    for (std::uint32_t u : units)
      for (int shift = 12; shift >= 0; shift -= 4) out += hex[(u >> shift) & 0xF];
    out += "\\X0\\";
    units.clear();
  };
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7F) {
      flush();
      if (c == '\'' || c == '\\') out += static_cast<char>(c);
      out += static_cast<char>(c);
      ++i;
      continue;
    }
    // One UTF-8 sequence; anything malformed becomes U+FFFD.
    const int len = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    std::uint32_t cp = 0xFFFD;
    std::size_t used = 1;
    if (len == 1) {
      cp = c;
    } else if (len > 1 && i + static_cast<std::size_t>(len) <= text.size()) {
      std::uint32_t v = c & (0xFFu >> (len + 1));
      bool ok = true;
      for (int k = 1; k < len; ++k) {
        const auto b = static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]);
        ok = ok && (b >> 6) == 0x2;
        v = (v << 6) | (b & 0x3Fu);
      }
      if (ok) cp = v, used = static_cast<std::size_t>(len);
    }
    if (cp >= 0x10000 && cp <= 0x10FFFF) {
      units.push_back(0xD800 + ((cp - 0x10000) >> 10));
      units.push_back(0xDC00 + ((cp - 0x10000) & 0x3FF));
    } else {
      units.push_back(cp > 0x10FFFF ? 0xFFFD : cp);
    }
    i += used;
  }
  flush();
  out += '\'';
}

/// Builds the DATA section one numbered entity at a time.
struct step_data {
  std::string text;
  std::size_t next = 1;
  /// Starts entity #n ("#n="), returns n; the caller appends the rest and calls end().
  std::size_t begin() {
    text += '#';
    put_number(next);
    text += '=';
    return next++;
  }
  void end() { text += ";\n"; }
  void put_number(std::size_t n) {
    char buf[24];
    const auto r = std::to_chars(buf, buf + sizeof buf, n);
    text.append(buf, r.ptr);
  }
  void ref(std::size_t n) {
    text += '#';
    put_number(n);
  }
  /// "(#a,#b,...)".
  void refs(std::span<const std::size_t> ns) {
    text += '(';
    for (std::size_t i = 0; i < ns.size(); ++i) {
      if (i) text += ',';
      ref(ns[i]);
    }
    text += ')';
  }
  std::size_t point(const glm::dvec3& p) {
    const std::size_t n = begin();
    text += "CARTESIAN_POINT('',(";
    for (int k = 0; k < 3; ++k) {
      if (k) text += ',';
      step_real(text, p[k]);
    }
    text += "))";
    end();
    return n;
  }
  std::size_t direction(const glm::dvec3& d) {
    const std::size_t n = begin();
    text += "DIRECTION('',(";
    for (int k = 0; k < 3; ++k) {
      if (k) text += ',';
      step_real(text, d[k]);
    }
    text += "))";
    end();
    return n;
  }
  /// "NAME('',#a,#b,...)" as entity #n; returns n.
  std::size_t entity(std::string_view name, std::initializer_list<std::size_t> args,
                     std::string_view tail = {}) {
    const std::size_t n = begin();
    text += name;
    text += "(''";
    for (const std::size_t a : args) {
      text += ',';
      ref(a);
    }
    text += tail;
    text += ')';
    end();
    return n;
  }
  /// A VERTEX_POINT on point entity p.
  std::size_t vertex(std::size_t p) { return entity("VERTEX_POINT", {p}); }
  /// An AXIS2_PLACEMENT_3D at point entity `origin`, its z along axis, its x along ref (unit).
  std::size_t placement(std::size_t origin, const glm::dvec3& axis, const glm::dvec3& ref) {
    const std::size_t z = direction(axis), x = direction(ref);
    return entity("AXIS2_PLACEMENT_3D", {origin, z, x});
  }
  /// A LINE from point entity p along the unit direction dir, its VECTOR `length` long.
  std::size_t line(std::size_t p, const glm::dvec3& dir, double length) {
    const std::size_t u = direction(dir);
    const std::size_t vec = begin();
    text += "VECTOR('',";
    ref(u);
    text += ',';
    step_real(text, length);
    text += ')';
    end();
    return entity("LINE", {p, vec});
  }
  /// An EDGE_CURVE from vertex va to vb on `curve`, running with it.
  std::size_t edge_curve(std::size_t va, std::size_t vb, std::size_t curve) {
    return entity("EDGE_CURVE", {va, vb, curve}, ",.T.");
  }
  /// An EDGE_LOOP of (EDGE_CURVE, forward) uses, each an ORIENTED_EDGE.
  std::size_t edge_loop(std::span<const std::pair<std::size_t, bool>> uses) {
    std::vector<std::size_t> oriented;
    for (const auto& [e, forward] : uses) {
      oriented.push_back(begin());
      text += "ORIENTED_EDGE('',*,*,";
      ref(e);
      text += forward ? ",.T.)" : ",.F.)";
      end();
    }
    const std::size_t n = begin();
    text += "EDGE_LOOP('',";
    refs(oriented);
    text += ')';
    end();
    return n;
  }
};

/// The check that every point is finite, and the distance accuracy written: options.uncertainty,
/// or 1e-9 of the points' bounding-box diagonal (1e-9 with no points). O(points).
template <class = void>
bounding_box step_bounds(std::span<const glm::dvec3> pts, const step_write_options& options,
                         step_result& result) {
  bounding_box box;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(pts[i][k]))
        throw error(
            error_category::invalid_input,
            cellforge::detail::cat("write_step: point ", std::to_string(i), " has a non-finite coordinate"));
    box.add(pts[i]);
  }
  const double diagonal = pts.empty() ? 0.0 : box.diagonal();
  if (!(options.uncertainty >= 0) || !std::isfinite(options.uncertainty))
    throw error(error_category::invalid_input, "write_step: the uncertainty must be a finite number >= 0");
  result.uncertainty = options.uncertainty > 0 ? options.uncertainty : diagonal > 0 ? 1e-9 * diagonal : 1e-9;
  return box;
}

/// Signed faces split into sets connected through shared edges (a volume's shells, the open
/// shells of faces in no volume). O(size · log).
template <class = void>
std::vector<std::vector<oriented<cell_face>>> edge_connected(const cell_topology& cc,
                                                             std::span<const oriented<cell_face>> faces) {
  std::vector<std::uint32_t> parent(faces.size());
  for (std::uint32_t i = 0; i < parent.size(); ++i) parent[i] = i;
  const auto root = [&](std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edge_face;  // (edge, face slot)
  for (std::uint32_t i = 0; i < faces.size(); ++i)
    for (std::size_t l = 0; l < cc.num_loops(faces[i].handle); ++l)
      for (const auto& ue : cc.loop_edges(faces[i].handle, l)) edge_face.emplace_back(ue.handle.idx(), i);
  std::sort(edge_face.begin(), edge_face.end());
  for (std::size_t k = 1; k < edge_face.size(); ++k)
    if (edge_face[k].first == edge_face[k - 1].first)
      parent[root(edge_face[k].second)] = root(edge_face[k - 1].second);
  std::vector<std::vector<oriented<cell_face>>> sets;
  std::vector<std::uint32_t> set_of(faces.size(), 0xFFFFFFFFu);
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    std::uint32_t& s = set_of[root(i)];
    if (s == 0xFFFFFFFFu) s = static_cast<std::uint32_t>(sets.size()), sets.emplace_back();
    sets[s].push_back(faces[i]);
  }
  return sets;
}

/// Signed volume enclosed by signed faces (fans from each loop's first vertex, about `origin`).
/// O(size).
template <class = void>
double shell_volume(const cell_topology& cc, std::span<const glm::dvec3> pts,
                    std::span<const oriented<cell_face>> faces, const glm::dvec3& origin) {
  double sum = 0;
  for (const auto& [f, s] : faces) {
    double face_sum = 0;
    for (std::size_t l = 0; l < cc.num_loops(f); ++l) {
      const auto loop = cc.loop_vertices(f, l);
      const glm::dvec3 a = pts[loop[0].idx()] - origin;
      for (std::size_t i = 1; i + 1 < loop.size(); ++i)
        face_sum += glm::dot(a, glm::cross(pts[loop[i].idx()] - origin, pts[loop[i + 1].idx()] - origin));
    }
    sum += s * face_sum;
  }
  return sum / 6.0;
}

/// The entities every file starts with, numbered from #1: the product (an AP214 part), its
/// units and geometric context (uncertainty in model units), the world placement. O(1).
struct step_context {
  std::size_t context = 0, shape = 0, placement = 0;
};
template <class = void>
step_context step_preamble(step_data& d, const step_write_options& options, double uncertainty) {
  using std::size_t;
  // Product structure (AP214 part), units and the geometric context.
  const size_t app = d.begin();
  d.text += "APPLICATION_CONTEXT('automotive design')";
  d.end();
  d.begin();
  d.text += "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,";
  d.ref(app);
  d.text += ')';
  d.end();
  const size_t pc = d.begin();
  d.text += "PRODUCT_CONTEXT('',";
  d.ref(app);
  d.text += ",'mechanical')";
  d.end();
  const size_t pdc = d.begin();
  d.text += "PRODUCT_DEFINITION_CONTEXT('part definition',";
  d.ref(app);
  d.text += ",'design')";
  d.end();
  const size_t product = d.begin();
  d.text += "PRODUCT(";
  step_string(d.text, options.name);
  d.text += ',';
  step_string(d.text, options.name);
  d.text += ",'',(";
  d.ref(pc);
  d.text += "))";
  d.end();
  d.begin();
  d.text += "PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(";
  d.ref(product);
  d.text += "))";
  d.end();
  const size_t pdf = d.begin();
  d.text += "PRODUCT_DEFINITION_FORMATION('','',";
  d.ref(product);
  d.text += ')';
  d.end();
  const size_t pd = d.begin();
  d.text += "PRODUCT_DEFINITION('design','',";
  d.ref(pdf);
  d.text += ',';
  d.ref(pdc);
  d.text += ')';
  d.end();
  const size_t pds = d.begin();
  d.text += "PRODUCT_DEFINITION_SHAPE('','',";
  d.ref(pd);
  d.text += ')';
  d.end();
  const size_t length_unit = d.begin();
  d.text += options.unit == step_length_unit::metre ? "(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT($,.METRE.))"
            : options.unit == step_length_unit::centimetre
                ? "(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.CENTI.,.METRE.))"
                : "(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))";
  d.end();
  const size_t angle_unit = d.begin();
  d.text += "(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))";
  d.end();
  const size_t solid_angle_unit = d.begin();
  d.text += "(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())";
  d.end();
  const size_t accuracy = d.begin();
  d.text += "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(";
  step_real(d.text, uncertainty);
  d.text += "),";
  d.ref(length_unit);
  d.text += ",'distance_accuracy_value','confusion accuracy')";
  d.end();
  const size_t context = d.begin();
  d.text += "(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((";
  d.ref(accuracy);
  d.text += "))GLOBAL_UNIT_ASSIGNED_CONTEXT((";
  d.ref(length_unit);
  d.text += ',';
  d.ref(angle_unit);
  d.text += ',';
  d.ref(solid_angle_unit);
  d.text += "))REPRESENTATION_CONTEXT('',''))";
  d.end();
  const size_t origin_point = d.point(glm::dvec3(0.0));
  const size_t placement = d.begin();
  d.text += "AXIS2_PLACEMENT_3D('',";
  d.ref(origin_point);
  d.text += ",$,$)";
  d.end();

  return {context, pds, placement};
}

/// The ADVANCED_BREP_SHAPE_REPRESENTATION of `solids` (with the world placement) as the
/// product's shape; returns its number. O(solids).
template <class = void>
std::size_t step_brep_shape(step_data& d, const step_write_options& options, const step_context& ctx,
                            std::span<const std::size_t> solids) {
  std::vector<std::size_t> items{ctx.placement};
  items.insert(items.end(), solids.begin(), solids.end());
  const std::size_t brep = d.begin();
  d.text += "ADVANCED_BREP_SHAPE_REPRESENTATION(";
  step_string(d.text, options.name);
  d.text += ',';
  d.refs(items);
  d.text += ',';
  d.ref(ctx.context);
  d.text += ')';
  d.end();
  d.begin();
  d.text += "SHAPE_DEFINITION_REPRESENTATION(";
  d.ref(ctx.shape);
  d.text += ',';
  d.ref(brep);
  d.text += ')';
  d.end();
  return brep;
}

/// The whole file: header (description, name, time stamp, schema) and the DATA section d. O(size).
template <class = void>
std::string step_file(const step_data& d, const step_write_options& options, std::string_view description) {
  std::string out = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((";
  step_string(out, description);
  out += "),'2;1');\nFILE_NAME(";
  step_string(out, options.name);
  out += ',';
  step_string(out, options.timestamp);
  out += ",(''),(''),'cellforge " CELLFORGE_VERSION_STRING "','cellforge','');\n";
  out += "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";
  out += d.text;
  out += "ENDSEC;\nEND-ISO-10303-21;\n";
  return out;
}

/// The whole STEP file of cc. O(size of cc · log).
template <class = void>
std::string step_text(const cell_topology& cc, std::span<const glm::dvec3> pts,
                      const step_write_options& options, step_result& result) {
  using std::size_t;
  const bounding_box box = step_bounds(pts, options, result);
  const glm::dvec3 centre = pts.empty() ? glm::dvec3(0.0) : box.center();

  step_data d;
  const step_context ctx = step_preamble(d, options, result.uncertainty);
  const size_t placement = ctx.placement;

  // Vertices and edges, written once and shared by every face that uses them.
  const size_t nv = cc.num_vertices(), ne = cc.num_edges(), nf = cc.num_faces();
  std::vector<size_t> vertex_point(nv), vertex_entity(nv);
  for (cell_vertex v : cc.vertices()) {
    vertex_point[v.idx()] = d.point(pts[v.idx()]);
    vertex_entity[v.idx()] = d.vertex(vertex_point[v.idx()]);
  }
  // Only edges on faces: dangling edges bound nothing a solid or shell can hold.
  std::vector<char> edge_used(ne, 0);
  for (cell_face f : cc.faces())
    for (size_t l = 0; l < cc.num_loops(f); ++l)
      for (const auto& ue : cc.loop_edges(f, l)) edge_used[ue.handle.idx()] = 1;
  std::vector<size_t> edge_entity(ne, 0);
  for (cell_edge e : cc.edges()) {
    if (!edge_used[e.idx()]) continue;
    const glm::dvec3 a = pts[cc.source(e).idx()], b = pts[cc.target(e).idx()];
    const double length = glm::length(b - a);
    if (!(length > 0))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_step: edge ", std::to_string(e.idx()),
                                         " has length zero (a LINE needs a direction)"));
    const size_t line = d.line(vertex_point[cc.source(e).idx()], (b - a) / length, length);
    edge_entity[e.idx()] =
        d.edge_curve(vertex_entity[cc.source(e).idx()], vertex_entity[cc.target(e).idx()], line);
    ++result.edges;
  }
  result.vertices = nv;

  // Per face: its plane (normal = the face's normal) and one EDGE_LOOP per loop, shared by
  // both sides; the ADVANCED_FACEs are made per use, since a side flips the loops' sense.
  std::size_t off_plane = 0;  // faces not flat to the uncertainty (the first 10 are named)
  std::vector<size_t> face_plane(nf);
  std::vector<std::vector<size_t>> face_loops(nf);
  for (cell_face f : cc.faces()) {
    const glm::dvec3 n = cellforge::detail::cells::access::unit_normal(cc, f);
    if (!(glm::length(n) > 0.5))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_step: face ", std::to_string(f.idx()),
                                         " has no normal (its outer loop has no area)"));
    const auto outer = cc.loop_vertices(f, 0);
    // The reference direction: the longest outer edge, made perpendicular to the normal.
    glm::dvec3 ref(0.0);
    for (size_t i = 0; i < outer.size(); ++i) {
      const glm::dvec3 t = pts[outer[(i + 1) % outer.size()].idx()] - pts[outer[i].idx()];
      const glm::dvec3 u = t - glm::dot(t, n) * n;
      if (glm::length(u) > glm::length(ref)) ref = u;
    }
    if (!(glm::length(ref) > 0))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_step: face ", std::to_string(f.idx()),
                                         " has no edge across its normal"));
    // The check of the answer: every vertex of the face on its PLANE to the uncertainty.
    double off = 0;
    for (size_t l = 0; l < cc.num_loops(f); ++l)
      for (cell_vertex v : cc.loop_vertices(f, l))
        off = std::max(off, std::abs(glm::dot(pts[v.idx()] - pts[outer[0].idx()], n)));
    if (off > result.uncertainty) {
      if (++off_plane <= 10)
        result.diagnostics.push_back(cellforge::detail::cat(
            "face ", std::to_string(f.idx()), ": a vertex is ", std::to_string(off),
            " from the face's plane, more than the uncertainty ", std::to_string(result.uncertainty)));
    }
    const size_t place = d.placement(vertex_point[outer[0].idx()], n, glm::normalize(ref));
    face_plane[f.idx()] = d.entity("PLANE", {place});
    ++result.planes;
    for (size_t l = 0; l < cc.num_loops(f); ++l) {
      std::vector<std::pair<size_t, bool>> uses;
      for (const auto& [e, s] : cc.loop_edges(f, l)) uses.emplace_back(edge_entity[e.idx()], s > 0);
      face_loops[f.idx()].push_back(d.edge_loop(uses));
    }
  }
  if (off_plane > 10)
    result.diagnostics.push_back(std::to_string(off_plane) + " faces in all are not flat to the uncertainty");
  // One use of face f with its topological normal along (sign +1) or against (-1) f's normal.
  const auto advanced_face = [&](cell_face f, int sign) {
    std::vector<size_t> bounds;
    for (size_t l = 0; l < face_loops[f.idx()].size(); ++l) {
      bounds.push_back(d.begin());
      d.text += l == 0 ? "FACE_OUTER_BOUND(''," : "FACE_BOUND('',";
      d.ref(face_loops[f.idx()][l]);
      d.text += sign > 0 ? ",.T.)" : ",.F.)";
      d.end();
    }
    const size_t n = d.begin();
    d.text += "ADVANCED_FACE('',";
    d.refs(bounds);
    d.text += ',';
    d.ref(face_plane[f.idx()]);
    d.text += sign > 0 ? ",.T.)" : ",.F.)";
    d.end();
    ++result.faces;
    return n;
  };
  const auto shell = [&](const char* kind, std::span<const oriented<cell_face>> faces, int flip) {
    std::vector<size_t> fs;
    for (const auto& [f, s] : faces) fs.push_back(advanced_face(f, s * flip));
    const size_t n = d.begin();
    d.text += kind;
    d.text += "('',";
    d.refs(fs);
    d.text += ')';
    d.end();
    return n;
  };

  // Volumes: the shell of largest enclosed volume is the outside, the others are cavities.
  std::vector<size_t> solids;
  for (cell_volume c : cc.volumes()) {
    const auto shells = edge_connected(cc, cc.volume_faces(c));
    std::vector<double> vol;
    for (const auto& s : shells) vol.push_back(shell_volume(cc, pts, s, centre));
    const size_t outer = static_cast<size_t>(std::max_element(vol.begin(), vol.end()) - vol.begin());
    if (!(vol[outer] > 0))
      result.diagnostics.push_back(
          cellforge::detail::cat("volume ", std::to_string(c.idx()),
                                 ": its outer shell encloses no positive volume (written as given)"));
    for (size_t i = 0; i < shells.size(); ++i)
      if (i != outer && !(vol[i] < 0))
        result.diagnostics.push_back(
            cellforge::detail::cat("volume ", std::to_string(c.idx()), ": shell ", std::to_string(i),
                                   " is neither its outside nor a cavity (written as a cavity)"));
    const size_t outer_shell = shell("CLOSED_SHELL", shells[outer], +1);
    std::vector<size_t> voids;
    for (size_t i = 0; i < shells.size(); ++i) {
      if (i == outer) continue;
      // A cavity is a closed shell facing out of the cavity, used reversed (ISO 10303-42).
      const size_t cs = shell("CLOSED_SHELL", shells[i], -1);
      voids.push_back(d.begin());
      d.text += "ORIENTED_CLOSED_SHELL('',*,";
      d.ref(cs);
      d.text += ",.F.)";
      d.end();
    }
    solids.push_back(d.begin());
    d.text += voids.empty() ? "MANIFOLD_SOLID_BREP(" : "BREP_WITH_VOIDS(";
    step_string(d.text, cellforge::detail::cat("volume ", std::to_string(c.idx())));
    d.text += ',';
    d.ref(outer_shell);
    if (!voids.empty()) {
      d.text += ',';
      d.refs(voids);
    }
    d.text += ')';
    d.end();
    ++result.solids;
    result.voids += voids.size();
  }
  // Faces in no volume: one OPEN_SHELL per set of them connected through edges.
  std::vector<oriented<cell_face>> loose;
  for (cell_face f : cc.faces())
    if (cc.face_volumes(f).empty()) loose.push_back({f, +1});
  std::vector<size_t> open_shells;
  if (!loose.empty()) {
    const auto groups = edge_connected(cc, loose);
    for (const auto& g : groups) open_shells.push_back(shell("OPEN_SHELL", g, +1));
    result.open_shells = open_shells.size();
  }

  // The representations: solids in an ADVANCED_BREP_SHAPE_REPRESENTATION (the product's
  // shape), open shells in a MANIFOLD_SURFACE_SHAPE_REPRESENTATION related to it.
  const size_t brep = step_brep_shape(d, options, ctx, solids);
  if (!open_shells.empty()) {
    const size_t model = d.begin();
    d.text += "SHELL_BASED_SURFACE_MODEL('',";
    d.refs(open_shells);
    d.text += ')';
    d.end();
    const size_t surfaces = d.begin();
    d.text += "MANIFOLD_SURFACE_SHAPE_REPRESENTATION(";
    step_string(d.text, options.name);
    d.text += ",(";
    d.ref(placement);
    d.text += ',';
    d.ref(model);
    d.text += "),";
    d.ref(ctx.context);
    d.text += ')';
    d.end();
    d.begin();
    d.text += "SHAPE_REPRESENTATION_RELATIONSHIP('','open surfaces',";
    d.ref(brep);
    d.text += ',';
    d.ref(surfaces);
    d.text += ')';
    d.end();
  }
  result.entities = d.next - 1;
  return step_file(d, options, "cellforge cell complex");
}

/// A half-edge mesh as a cell complex for STEP: its faces, those not flat to 1e-9 of the
/// diagonal split into triangle fans (a PLANE must hold every vertex); one volume when the mesh
/// is closed and consistently oriented, signed so that it encloses positive volume. O(size of m).
template <Point3 P>
cell_complex<P> mesh_step_cells(const surface_mesh<P>& m) {
  cell_complex_input<P> in;
  std::vector<std::uint32_t> index(m.vertices_size(), 0xFFFFFFFFu);
  std::vector<glm::dvec3> pos;
  bounding_box box;
  for (vertex_handle v : m.vertices()) {
    index[v.idx()] = static_cast<std::uint32_t>(in.points.size());
    in.points.push_back(m.position(v));
    pos.push_back(to_dvec3(m.position(v)));
    box.add(pos.back());
  }
  for (edge_handle e : m.edges())
    in.edges.push_back({index[m.vertex(e, 0).idx()], index[m.vertex(e, 1).idx()]});
  const double flat = 1e-9 * box.diagonal();
  for (face_handle f : m.faces()) {
    std::vector<std::uint32_t> loop;
    for (vertex_handle v : m.vertices_around(f)) loop.push_back(index[v.idx()]);
    const glm::dvec3 n = cellforge::detail::newell(loop, [&](std::uint32_t i) { return pos[i]; });
    bool planar = loop.size() == 3;
    if (!planar && glm::length(n) > 0) {
      const glm::dvec3 u = glm::normalize(n);
      glm::dvec3 c(0.0);
      for (std::uint32_t i : loop) c += pos[i];
      c /= static_cast<double>(loop.size());
      planar = true;
      for (std::uint32_t i : loop) planar = planar && std::abs(glm::dot(pos[i] - c, u)) <= flat;
    }
    if (planar) {
      in.faces.push_back({{std::move(loop)}});
      continue;
    }
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
      in.faces.push_back({{{loop[0], loop[i], loop[i + 1]}}});
      if (i > 1) in.edges.push_back({loop[0], loop[i]});
    }
  }
  if (m.is_closed() && m.is_consistently_oriented() && !in.faces.empty()) {
    double six_volume = 0;
    for (const auto& f : in.faces) {
      const auto& l = f.loops[0];
      for (std::size_t i = 1; i + 1 < l.size(); ++i)
        six_volume += glm::dot(pos[l[0]] - box.center(),
                               glm::cross(pos[l[i]] - box.center(), pos[l[i + 1]] - box.center()));
    }
    cell_input_volume c;
    for (std::uint32_t f = 0; f < in.faces.size(); ++f) c.faces.emplace_back(f, six_volume < 0 ? -1 : +1);
    in.volumes.push_back(std::move(c));
  }
  return make_cell_complex(std::move(in));
}

/// The STEP file of a rounded solid: one MANIFOLD_SOLID_BREP, planar faces and a
/// CYLINDRICAL_SURFACE per blend, LINE edges and the blends' end arcs (CIRCLE when the end
/// plane is square to the axis, else ELLIPSE), each with its sense. O(size of s).
template <class = void>
std::string step_rounded_text(const rounded_solid& s, const step_write_options& options,
                              step_result& result) {
  using std::size_t;
  constexpr std::uint32_t none = rounded_solid::npos;
  step_bounds(s.points, options, result);
  if (s.faces.empty())
    throw error(error_category::invalid_input, "write_step: the rounded solid has no faces");
  for (const auto& e : s.edges)
    if (e.a >= s.points.size() || e.b >= s.points.size() || (e.blend != none && e.blend >= s.blends.size()))
      throw error(error_category::invalid_input,
                  "write_step: a rounded solid's edge names a missing point or blend");
  for (const auto& f : s.faces) {
    if (f.loop.empty() || (f.blend != none && f.blend >= s.blends.size()))
      throw error(error_category::invalid_input,
                  "write_step: a rounded solid's face has no loop or a missing blend");
    for (const auto& [e, forward] : f.loop)
      if (e >= s.edges.size())
        throw error(error_category::invalid_input, "write_step: a face names a missing edge");
  }
  double off = 0;  // the check: vertices on their curves and surfaces, within the uncertainty
  const auto radial = [&](const rounded_solid::cylinder& c, const glm::dvec3& x) {
    glm::dvec3 q = x - c.point;
    q -= glm::dot(q, c.axis) * c.axis;
    off = std::max(off, std::abs(glm::length(q) - c.radius));
    return glm::normalize(q);
  };

  step_data d;
  const step_context ctx = step_preamble(d, options, result.uncertainty);
  std::vector<size_t> vertex_point(s.points.size()), vertex_entity(s.points.size());
  for (size_t v = 0; v < s.points.size(); ++v) {
    vertex_point[v] = d.point(s.points[v]);
    vertex_entity[v] = d.vertex(vertex_point[v]);
  }
  result.vertices = s.points.size();
  std::vector<size_t> edge_entity(s.edges.size());
  for (size_t i = 0; i < s.edges.size(); ++i) {
    const rounded_solid::edge& e = s.edges[i];
    const glm::dvec3 a = s.points[e.a], b = s.points[e.b];
    size_t curve = 0;
    if (e.blend == none) {
      const double length = glm::length(b - a);
      if (!(length > 0))
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("write_step: edge ", std::to_string(i),
                                           " has length zero (a LINE needs a direction)"));
      curve = d.line(vertex_point[e.a], (b - a) / length, length);
    } else {
      // The cylinder cut by the end plane: centred where the axis meets it, oriented so that
      // the curve runs from a to b the short way, through the blend's middle.
      const rounded_solid::cylinder& c = s.blends[e.blend];
      const double gl = glm::length(e.plane_normal);
      const glm::dvec3 g = gl > 0 ? e.plane_normal / gl : e.plane_normal;
      const double gd = glm::dot(g, c.axis);
      if (!(std::abs(gd) > 1e-9))
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("write_step: edge ", std::to_string(i),
                                           ": its plane holds its cylinder's axis"));
      const glm::dvec3 centre = c.point + c.axis * (glm::dot(g, a - c.point) / gd);
      const glm::dvec3 ra = radial(c, a);
      radial(c, b);
      off = std::max(off, std::abs(glm::dot(b - a, g)));
      const double turn = glm::dot(glm::cross(ra, c.middle), c.axis);
      const glm::dvec3 normal = g * ((gd > 0) == (turn > 0) ? 1.0 : -1.0);
      const size_t centre_point = d.point(centre);
      if (1 - std::abs(gd) <= 1e-12) {
        glm::dvec3 ref = -c.middle - glm::dot(-c.middle, normal) * normal;  // the seam opposite the arc
        const size_t place = d.placement(centre_point, normal, glm::normalize(ref));
        curve = d.begin();
        d.text += "CIRCLE('',";
        d.ref(place);
        d.text += ',';
        step_real(d.text, c.radius);
        d.text += ')';
        d.end();
      } else {
        // The major axis (radius / |cos|) is the axis's direction in the plane; its sign puts
        // parameter 0 opposite the arc.
        glm::dvec3 x = glm::normalize(c.axis - gd * g);
        if (glm::dot(x, c.middle) > 0) x = -x;
        const size_t place = d.placement(centre_point, normal, x);
        curve = d.begin();
        d.text += "ELLIPSE('',";
        d.ref(place);
        d.text += ',';
        step_real(d.text, c.radius / std::abs(gd));
        d.text += ',';
        step_real(d.text, c.radius);
        d.text += ')';
        d.end();
      }
      ++result.conics;
    }
    edge_entity[i] = d.edge_curve(vertex_entity[e.a], vertex_entity[e.b], curve);
    ++result.edges;
  }
  std::vector<size_t> surface_of_blend(s.blends.size());
  for (size_t i = 0; i < s.blends.size(); ++i) {
    const rounded_solid::cylinder& c = s.blends[i];
    if (!(c.radius > 0) || !(glm::length(c.axis) > 0.5))
      throw error(error_category::invalid_input,
                  cellforge::detail::cat("write_step: blend ", std::to_string(i), " has no radius or axis"));
    const size_t origin = d.point(c.point);
    const size_t place = d.placement(origin, c.axis, -c.middle);  // the seam opposite the blend
    surface_of_blend[i] = d.begin();
    d.text += "CYLINDRICAL_SURFACE('',";
    d.ref(place);
    d.text += ',';
    step_real(d.text, c.radius);
    d.text += ')';
    d.end();
    ++result.cylinders;
  }
  std::vector<size_t> faces;
  for (size_t fi = 0; fi < s.faces.size(); ++fi) {
    const rounded_solid::face& f = s.faces[fi];
    size_t surface = 0;
    bool same_sense = true;
    if (f.blend == none) {
      const glm::dvec3 n = glm::normalize(f.normal);
      const glm::dvec3 x0 = s.points[s.edges[f.loop[0].first].a];
      glm::dvec3 ref(0.0);  // the longest edge chord across the normal
      for (const auto& [e, forward] : f.loop) {
        const glm::dvec3 p = s.points[s.edges[e].a], q = s.points[s.edges[e].b];
        off = std::max({off, std::abs(glm::dot(p - x0, n)), std::abs(glm::dot(q - x0, n))});
        const glm::dvec3 t = (q - p) - glm::dot(q - p, n) * n;
        if (glm::length(t) > glm::length(ref)) ref = t;
      }
      if (!(glm::length(ref) > 0))
        throw error(error_category::invalid_input,
                    cellforge::detail::cat("write_step: face ", std::to_string(fi), " has no extent"));
      const size_t place = d.placement(vertex_point[s.edges[f.loop[0].first].a], n, glm::normalize(ref));
      surface = d.entity("PLANE", {place});
      ++result.planes;
    } else {
      surface = surface_of_blend[f.blend];
      same_sense = s.blends[f.blend].convex;  // a fillet's solid lies outside its cylinder
      for (const auto& [e, forward] : f.loop)
        for (const std::uint32_t p : {s.edges[e].a, s.edges[e].b}) radial(s.blends[f.blend], s.points[p]);
    }
    std::vector<std::pair<size_t, bool>> uses;
    for (const auto& [e, forward] : f.loop) uses.emplace_back(edge_entity[e], forward);
    const size_t bound = d.entity("FACE_OUTER_BOUND", {d.edge_loop(uses)}, ",.T.");
    faces.push_back(d.begin());
    d.text += "ADVANCED_FACE('',(";
    d.ref(bound);
    d.text += "),";
    d.ref(surface);
    d.text += same_sense ? ",.T.)" : ",.F.)";
    d.end();
    ++result.faces;
  }
  if (off > result.uncertainty)
    result.diagnostics.push_back(cellforge::detail::cat(
        "a vertex is ", std::to_string(off), " from a curve or surface it bounds, more than the uncertainty ",
        std::to_string(result.uncertainty)));
  const size_t shell = d.begin();
  d.text += "CLOSED_SHELL('',";
  d.refs(faces);
  d.text += ')';
  d.end();
  const size_t solid = d.begin();
  d.text += "MANIFOLD_SOLID_BREP(";
  step_string(d.text, options.name);
  d.text += ',';
  d.ref(shell);
  d.text += ')';
  d.end();
  result.solids = 1;
  step_brep_shape(d, options, ctx, std::span<const size_t>(&solid, 1));
  result.entities = d.next - 1;
  return step_file(d, options, "cellforge rounded solid");
}

}  // namespace detail

template <Point3 P>
step_result write_step(std::ostream& os, const cell_complex<P>& cc, const step_write_options& options) {
  const cellforge::detail::stopwatch clock;
  step_result result;
  const cellforge::detail::cells::dvec3_points<P> pts(cc.points());
  const std::string text = detail::step_text(cc, pts.span(), options, result);
  os.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!os) throw error(error_category::io, "step: writing to the stream failed");
  result.milliseconds = clock.ms();
  return result;
}

template <Point3 P>
step_result write_step(const file_path& path, const cell_complex<P>& cc, const step_write_options& options) {
  step_result result;
  detail::write_file(path, [&](std::ostream& os) { result = write_step(os, cc, options); });
  return result;
}

template <Point3 P>
step_result write_step(std::ostream& os, const surface_mesh<P>& m, const step_write_options& options) {
  return write_step(os, detail::mesh_step_cells(m), options);
}
template <Point3 P>
step_result write_step(const file_path& path, const surface_mesh<P>& m, const step_write_options& options) {
  return write_step(path, detail::mesh_step_cells(m), options);
}

template <class>
step_result write_step(std::ostream& os, const rounded_solid& s, const step_write_options& options) {
  const cellforge::detail::stopwatch clock;
  step_result result;
  const std::string text = detail::step_rounded_text(s, options, result);
  os.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!os) throw error(error_category::io, "step: writing to the stream failed");
  result.milliseconds = clock.ms();
  return result;
}
template <class>
step_result write_step(const file_path& path, const rounded_solid& s, const step_write_options& options) {
  step_result result;
  detail::write_file(path, [&](std::ostream& os) { result = write_step(os, s, options); });
  return result;
}

}  // namespace cellforge::io
