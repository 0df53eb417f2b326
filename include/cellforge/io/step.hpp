// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// STEP (ISO 10303-21 text, AP214 "automotive_design") of a cell complex: every volume a
/// MANIFOLD_SOLID_BREP (BREP_WITH_VOIDS with cavities) of planar ADVANCED_FACEs, all solids
/// sharing their vertices, edges, loops and planes; faces in no volume as an OPEN_SHELL of a
/// SHELL_BASED_SURFACE_MODEL; half-edge meshes as faceted B-reps. See docs/formats.md "STEP".

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
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
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/version.hpp"

namespace cellforge::io {

/// The length unit a model unit stands for in the STEP file (an SI_UNIT, no conversion).
enum class step_length_unit : std::uint8_t { millimetre, centimetre, metre };

/// How a STEP file is written.
struct step_write_options {
  std::string name = "cellforge";                        ///< the product's name (any UTF-8 text)
  std::string timestamp{};                               ///< FILE_NAME's time stamp (ISO 8601); empty: none
  step_length_unit unit = step_length_unit::millimetre;  ///< what one model unit means
  /// The distance_accuracy_value in the header context, in model units; 0: 1e-9 times the
  /// bounding-box diagonal (the pipeline's merge tolerance), or 1e-9 for an empty model.
  double uncertainty = 0;
};

/// What write_step wrote: solids (one per volume), their cavities, open shells, ADVANCED_FACEs
/// (a face shared by two volumes counts twice), edges, vertices and planes (each once), entities.
struct step_result {
  std::size_t solids = 0;
  std::size_t voids = 0;
  std::size_t open_shells = 0;
  std::size_t faces = 0;
  std::size_t edges = 0;
  std::size_t vertices = 0;
  std::size_t planes = 0;
  std::size_t entities = 0;
  double uncertainty = 0;  ///< the distance accuracy written, in model units
  double milliseconds = 0;
  /// What the file's reader may object to: faces not flat to the uncertainty, volumes whose
  /// outer shell encloses no positive volume (written all the same).
  std::vector<std::string> diagnostics;
};

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
};

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

/// The whole STEP file of cc. O(size of cc · log).
template <class = void>
std::string step_text(const cell_topology& cc, std::span<const glm::dvec3> pts,
                      const step_write_options& options, step_result& result) {
  using std::size_t;
  bounding_box box;
  for (size_t i = 0; i < pts.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(pts[i][k]))
        throw error(error_category::invalid_input,
                    "write_step: point " + std::to_string(i) + " has a non-finite coordinate");
    box.add(pts[i]);
  }
  const double diagonal = pts.empty() ? 0.0 : box.diagonal();
  if (!(options.uncertainty >= 0) || !std::isfinite(options.uncertainty))
    throw error(error_category::invalid_input, "write_step: the uncertainty must be a finite number >= 0");
  result.uncertainty = options.uncertainty > 0 ? options.uncertainty : diagonal > 0 ? 1e-9 * diagonal : 1e-9;
  const glm::dvec3 centre = pts.empty() ? glm::dvec3(0.0) : box.center();

  step_data d;
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
  step_real(d.text, result.uncertainty);
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

  // Vertices and edges, written once and shared by every face that uses them.
  const size_t nv = cc.num_vertices(), ne = cc.num_edges(), nf = cc.num_faces();
  std::vector<size_t> vertex_point(nv), vertex_entity(nv);
  for (cell_vertex v : cc.vertices()) {
    vertex_point[v.idx()] = d.point(pts[v.idx()]);
    vertex_entity[v.idx()] = d.begin();
    d.text += "VERTEX_POINT('',";
    d.ref(vertex_point[v.idx()]);
    d.text += ')';
    d.end();
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
      throw error(error_category::invalid_input, "write_step: edge " + std::to_string(e.idx()) +
                                                     " has length zero (a LINE needs a direction)");
    const size_t dir = d.direction((b - a) / length);
    const size_t vec = d.begin();
    d.text += "VECTOR('',";
    d.ref(dir);
    d.text += ',';
    step_real(d.text, length);
    d.text += ')';
    d.end();
    const size_t line = d.begin();
    d.text += "LINE('',";
    d.ref(vertex_point[cc.source(e).idx()]);
    d.text += ',';
    d.ref(vec);
    d.text += ')';
    d.end();
    edge_entity[e.idx()] = d.begin();
    d.text += "EDGE_CURVE('',";
    d.ref(vertex_entity[cc.source(e).idx()]);
    d.text += ',';
    d.ref(vertex_entity[cc.target(e).idx()]);
    d.text += ',';
    d.ref(line);
    d.text += ",.T.)";
    d.end();
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
      throw error(error_category::invalid_input, "write_step: face " + std::to_string(f.idx()) +
                                                     " has no normal (its outer loop has no area)");
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
                  "write_step: face " + std::to_string(f.idx()) + " has no edge across its normal");
    // The check of the answer: every vertex of the face on its PLANE to the uncertainty.
    double off = 0;
    for (size_t l = 0; l < cc.num_loops(f); ++l)
      for (cell_vertex v : cc.loop_vertices(f, l))
        off = std::max(off, std::abs(glm::dot(pts[v.idx()] - pts[outer[0].idx()], n)));
    if (off > result.uncertainty) {
      if (++off_plane <= 10)
        result.diagnostics.push_back(
            "face " + std::to_string(f.idx()) + ": a vertex is " + std::to_string(off) +
            " from the face's plane, more than the uncertainty " + std::to_string(result.uncertainty));
    }
    const size_t origin = vertex_point[outer[0].idx()];
    const size_t axis = d.direction(n), ref_dir = d.direction(glm::normalize(ref));
    const size_t place = d.begin();
    d.text += "AXIS2_PLACEMENT_3D('',";
    d.ref(origin);
    d.text += ',';
    d.ref(axis);
    d.text += ',';
    d.ref(ref_dir);
    d.text += ')';
    d.end();
    face_plane[f.idx()] = d.begin();
    d.text += "PLANE('',";
    d.ref(place);
    d.text += ')';
    d.end();
    ++result.planes;
    for (size_t l = 0; l < cc.num_loops(f); ++l) {
      std::vector<size_t> oriented_edges;
      for (const auto& [e, s] : cc.loop_edges(f, l)) {
        oriented_edges.push_back(d.begin());
        d.text += "ORIENTED_EDGE('',*,*,";
        d.ref(edge_entity[e.idx()]);
        d.text += s > 0 ? ",.T.)" : ",.F.)";
        d.end();
      }
      face_loops[f.idx()].push_back(d.begin());
      d.text += "EDGE_LOOP('',";
      d.refs(oriented_edges);
      d.text += ')';
      d.end();
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
      result.diagnostics.push_back("volume " + std::to_string(c.idx()) +
                                   ": its outer shell encloses no positive volume (written as given)");
    for (size_t i = 0; i < shells.size(); ++i)
      if (i != outer && !(vol[i] < 0))
        result.diagnostics.push_back("volume " + std::to_string(c.idx()) + ": shell " + std::to_string(i) +
                                     " is neither its outside nor a cavity (written as a cavity)");
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
    step_string(d.text, "volume " + std::to_string(c.idx()));
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
  std::vector<size_t> items{placement};
  items.insert(items.end(), solids.begin(), solids.end());
  const size_t brep = d.begin();
  d.text += "ADVANCED_BREP_SHAPE_REPRESENTATION(";
  step_string(d.text, options.name);
  d.text += ',';
  d.refs(items);
  d.text += ',';
  d.ref(context);
  d.text += ')';
  d.end();
  d.begin();
  d.text += "SHAPE_DEFINITION_REPRESENTATION(";
  d.ref(pds);
  d.text += ',';
  d.ref(brep);
  d.text += ')';
  d.end();
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
    d.ref(context);
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

  std::string out = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('cellforge cell complex'),'2;1');\nFILE_NAME(";
  step_string(out, options.name);
  out += ',';
  step_string(out, options.timestamp);
  out += ",(''),(''),'cellforge " CELLFORGE_VERSION_STRING "','cellforge','');\n";
  out += "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n";
  out += d.text;
  out += "ENDSEC;\nEND-ISO-10303-21;\n";
  return out;
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

}  // namespace detail

/// Writes cc as STEP AP214: one MANIFOLD_SOLID_BREP per volume (BREP_WITH_VOIDS with cavities)
/// sharing vertices, edges and planes, faces in no volume as open shells; see docs/formats.md.
/// O(size of cc · log). Throws invalid_input on a non-finite point, a zero-length edge or a face
/// without area; io when the stream fails.
template <Point3 P>
step_result write_step(std::ostream& os, const cell_complex<P>& cc, const step_write_options& options = {}) {
  const cellforge::detail::stopwatch clock;
  step_result result;
  const cellforge::detail::cells::dvec3_points<P> pts(cc.points());
  const std::string text = detail::step_text(cc, pts.span(), options, result);
  os.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!os) throw error(error_category::io, "step: writing to the stream failed");
  result.milliseconds = clock.ms();
  return result;
}

/// Writes cc to a STEP file (beside it, then renamed over it). O(size of cc · log). Throws
/// as the stream version, and io naming the path.
template <Point3 P>
step_result write_step(const file_path& path, const cell_complex<P>& cc,
                       const step_write_options& options = {}) {
  step_result result;
  detail::write_file(path, [&](std::ostream& os) { result = write_step(os, cc, options); });
  return result;
}

/// Writes a half-edge mesh (a tube, a subdivided surface) as a faceted B-rep: one solid of
/// planar faces when it is closed and consistently oriented, else an open shell. O(size of m).
template <Point3 P>
step_result write_step(std::ostream& os, const surface_mesh<P>& m, const step_write_options& options = {}) {
  return write_step(os, detail::mesh_step_cells(m), options);
}
/// The mesh to a STEP file (beside it, then renamed over it). O(size of m).
template <Point3 P>
step_result write_step(const file_path& path, const surface_mesh<P>& m,
                       const step_write_options& options = {}) {
  return write_step(path, detail::mesh_step_cells(m), options);
}

}  // namespace cellforge::io
