// SPDX-License-Identifier: MIT
#pragma once
// The engine of the DXF readers (included by io/dxf_drawing.hpp).

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/io/detail/numbers.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/stroke_snapping.hpp"
#include "cellforge/io/dxf_drawing.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::io {

namespace detail {

/// One group of a DXF file: the code, the value (trimmed) and the line of the code.
struct dxf_group {
  int code = 0;
  std::string_view value;
  std::uint64_t line = 0;
};

/// ASCII case-insensitive equality of DXF names.
template <class = void>
bool dxf_same_name(std::string_view a, std::string_view b) noexcept {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const auto lower = [](char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c; };
    if (lower(a[i]) != lower(b[i])) return false;
  }
  return true;
}

/// The DXF reader: groups, sections, tables, blocks and entities over one buffer.
template <class = void>
struct basic_dxf_reader {
  std::string_view name;
  const dxf_drawing_options& options;
  bool read_arcs;
  std::vector<dxf_group> groups;
  std::vector<std::pair<glm::dvec2, glm::dvec2>> segs;
  std::vector<stroke_arc> arcs;
  std::vector<std::uint64_t> arc_lines;
  dxf_reading_counts counts;
  /// Block definitions: name -> [first, last) group range of its entities, and base point.
  struct block {
    std::string name;
    std::size_t first = 0, last = 0;
    glm::dvec2 base{0, 0};
    std::uint64_t line = 0;
  };
  std::vector<block> blocks;
  std::vector<std::string> hidden_layers;
  std::vector<std::size_t> insert_stack;  // blocks being expanded, against self-insertion
  struct skipped_kind {
    std::string type;
    std::size_t count = 0;
    std::uint64_t first_line = 0;
  };
  std::vector<skipped_kind> skipped;
  std::map<std::string, bool> layer_decided;  // lower-case layer name -> read
  std::size_t work = 0;
  static constexpr std::size_t max_depth = 32;

  [[noreturn]] void fail(std::uint64_t line, const std::string& message) const {
    throw error(error_category::io, message, source_location{std::string(name), line});
  }

  // ---- groups -------------------------------------------------------------------------------

  static std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
  }

  static std::string shown(std::string_view s) {
    std::string out = "'";
    for (const char c : s.substr(0, 40)) {
      const auto u = static_cast<unsigned char>(c);
      out += u >= 32 && u < 127 ? c : '?';
    }
    return out + (s.size() > 40 ? "...'" : "'");
  }

  /// Splits the text into (code, value) line pairs; 999 comments dropped. O(size).
  void split_groups(std::string_view text) {
    if (text.starts_with("AutoCAD Binary DXF"))
      fail(1, "a binary DXF file: only ASCII DXF is read (save it as ASCII DXF)");
    std::size_t pos = 0;
    std::uint64_t line = 0;
    const auto next_line = [&](std::string_view& out) {
      if (pos >= text.size()) return false;
      std::size_t end = pos;
      while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
      out = text.substr(pos, end - pos);
      if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') ++end;
      pos = end + 1;
      ++line;
      return true;
    };
    std::string_view code_text, value;
    while (next_line(code_text)) {
      const std::uint64_t at = line;
      const std::string_view c = trim(code_text);
      if (c.empty() && pos >= text.size()) break;  // a blank last line
      if (c.empty())
        fail(at,
             "a group code expected, found an empty line (group codes and values alternate line by line)");
      int code = 0;
      const char* p = c.data();
      if (parse_number(p, c.data() + c.size(), code) != parse_status::ok || p != c.data() + c.size() ||
          code < 0 || code > 1071)
        fail(at,
             cellforge::detail::cat(
                 "a group code (an integer 0 to 1071) expected, found ", shown(c),
                 " (group codes and values alternate line by line: a value line missing or doubled above?)"));
      if (!next_line(value))
        fail(at, cellforge::detail::cat("the file ends after group code ", std::to_string(code),
                                        " with no value line (truncated, or an odd number of lines)"));
      if (code == 999) continue;
      groups.push_back({code, trim(value), at});
    }
  }

  // ---- values -------------------------------------------------------------------------------

  double number(const dxf_group& g, const char* what) const {
    double v = 0;
    const char* p = g.value.data();
    const char* end = p + g.value.size();
    if (g.value.empty() || parse_number(p, end, v) != parse_status::ok || p != end || !std::isfinite(v))
      fail(g.line + 1, cellforge::detail::cat(std::string(what), " (group code ", std::to_string(g.code),
                                              ") is not a finite number: ", shown(g.value)));
    return v;
  }

  std::int64_t integer(const dxf_group& g, const char* what) const {
    std::int64_t v = 0;
    const char* p = g.value.data();
    const char* end = p + g.value.size();
    if (g.value.empty() || parse_number(p, end, v) != parse_status::ok || p != end)
      fail(g.line + 1, cellforge::detail::cat(std::string(what), " (group code ", std::to_string(g.code),
                                              ") is not an integer: ", shown(g.value)));
    return v;
  }

  // ---- structure ----------------------------------------------------------------------------

  /// Index of the next group with code 0 at or after i.
  std::size_t next_zero(std::size_t i) const {
    while (i < groups.size() && groups[i].code != 0) ++i;
    return i;
  }

  /// Reads the section structure; returns the ENTITIES section's [first, last) range. O(groups).
  std::pair<std::size_t, std::size_t> sections() {
    std::pair<std::size_t, std::size_t> entities{0, 0};
    bool seen_entities = false, seen_eof = false;
    std::size_t i = 0;
    if (groups.empty()) fail(1, "an empty file: no DXF sections");
    while (i < groups.size()) {
      const dxf_group& g = groups[i];
      if (g.code == 0 && g.value == "EOF") {
        seen_eof = true;
        break;
      }
      if (g.code != 0 || g.value != "SECTION")
        fail(g.line,
             cellforge::detail::cat("0 SECTION expected, found ", std::to_string(g.code), " ", shown(g.value),
                                    (g.code == 0 && g.value == "ENDSEC" ? " (an ENDSEC with no SECTION open)"
                                                                        : " (outside any section)")));
      if (i + 1 >= groups.size() || groups[i + 1].code != 2)
        fail(g.line, "a SECTION with no name (2 HEADER, TABLES, BLOCKS, ENTITIES, ...) after it");
      const std::string_view section = groups[i + 1].value;
      const std::uint64_t opened = g.line;
      std::size_t j = i + 2;
      while (j < groups.size() &&
             !(groups[j].code == 0 &&
               (groups[j].value == "ENDSEC" || groups[j].value == "SECTION" || groups[j].value == "EOF")))
        ++j;
      if (j >= groups.size())
        fail(groups.back().line, cellforge::detail::cat("the file ends inside section ", std::string(section),
                                                        " (opened at line ", std::to_string(opened),
                                                        "): no 0 ENDSEC (truncated?)"));
      if (groups[j].value != "ENDSEC")
        fail(groups[j].line, cellforge::detail::cat("0 ", std::string(groups[j].value), " inside section ",
                                                    std::string(section), " (opened at line ",
                                                    std::to_string(opened), "): its 0 ENDSEC is missing"));
      if (section == "HEADER") header(i + 2, j);
      if (section == "TABLES") tables(i + 2, j);
      if (section == "BLOCKS") block_section(i + 2, j);
      if (section == "ENTITIES") {
        if (seen_entities) fail(opened, "a second ENTITIES section");
        seen_entities = true;
        entities = {i + 2, j};
      }
      i = j + 1;
    }
    if (!seen_eof)
      fail(groups.back().line + 1, "the file ends without 0 EOF after its last section (truncated?)");
    if (!seen_entities)
      counts.diagnostics.push_back(cellforge::detail::cat(std::string(name), ": no ENTITIES section"));
    return entities;
  }

  void header(std::size_t first, std::size_t last) {
    for (std::size_t i = first; i + 1 < last; ++i)
      if (groups[i].code == 9 && groups[i].value == "$ACADVER" && groups[i + 1].code == 1)
        counts.version = std::string(groups[i + 1].value);
  }

  /// The LAYER table: layers off (negative colour) or frozen (flag 1). O(groups).
  void tables(std::size_t first, std::size_t last) {
    for (std::size_t i = next_zero(first); i < last;) {
      const std::size_t end = std::min(next_zero(i + 1), last);
      if (groups[i].value == "LAYER") {
        std::string_view layer;
        bool hidden = false, named = false;
        for (std::size_t k = i + 1; k < end; ++k) {
          if (groups[k].code == 2) layer = groups[k].value, named = true;
          if (groups[k].code == 62 && integer(groups[k], "a layer's colour") < 0) hidden = true;
          if (groups[k].code == 70 && (integer(groups[k], "a layer's flags") & 1) != 0) hidden = true;
        }
        if (named && hidden) hidden_layers.emplace_back(layer);
      }
      i = end;
    }
  }

  /// The BLOCKS section: BLOCK ... ENDBLK ranges. O(groups).
  void block_section(std::size_t first, std::size_t last) {
    std::size_t i = next_zero(first);
    while (i < last) {
      const dxf_group& g = groups[i];
      if (g.value != "BLOCK")
        fail(g.line,
             cellforge::detail::cat("0 BLOCK expected in the BLOCKS section, found 0 ", shown(g.value)));
      block b;
      b.line = g.line;
      const std::size_t head_end = std::min(next_zero(i + 1), last);
      bool has_name = false;
      for (std::size_t k = i + 1; k < head_end; ++k) {
        if (groups[k].code == 2) b.name = std::string(groups[k].value), has_name = true;
        if (groups[k].code == 10) b.base.x = number(groups[k], "a block's base point x");
        if (groups[k].code == 20) b.base.y = number(groups[k], "a block's base point y");
      }
      if (!has_name) fail(g.line, "a BLOCK with no name (group code 2)");
      std::size_t k = head_end;
      while (k < last && groups[k].value != "ENDBLK") k = std::min(next_zero(k + 1), last);
      if (k >= last)
        fail(g.line, cellforge::detail::cat("block ", shown(b.name),
                                            " has no 0 ENDBLK before the end of the BLOCKS section"));
      b.first = head_end;
      b.last = k;
      blocks.push_back(std::move(b));
      i = std::min(next_zero(k + 1), last);
    }
  }

  // ---- entities -----------------------------------------------------------------------------

  struct placement {
    affine2 m;                 // block frame to world
    std::string_view layer{};  // the INSERT's layer, for entities on layer "0"
  };

  void skip_note(std::string_view type, std::uint64_t line) {
    ++counts.skipped_entities;
    for (skipped_kind& s : skipped)
      if (s.type == type) {
        ++s.count;
        return;
      }
    skipped.push_back({std::string(type), 1, line});
  }

  static std::string lower(std::string_view s) {
    std::string out(s);
    for (char& c : out)
      if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
    return out;
  }

  /// Whether entities on `layer` are read; each layer decided once. O(log L) after the first.
  bool layer_chosen(std::string_view layer) {
    std::string key = lower(layer);
    if (const auto at = layer_decided.find(key); at != layer_decided.end()) return at->second;
    counts.layers.emplace_back(layer);
    bool chosen = options.layers.empty();
    for (const std::string& l : options.layers) chosen = chosen || dxf_same_name(l, layer);
    if (options.skip_hidden_layers)
      for (const std::string& h : hidden_layers) chosen = chosen && !dxf_same_name(h, layer);
    layer_decided.emplace(std::move(key), chosen);
    return chosen;
  }

  /// Counts one stroke, entity or block placement against options.max_strokes.
  void budget(std::uint64_t line) {
    if (++work > options.max_strokes)
      fail(line,
           cellforge::detail::cat(
               "more than ", std::to_string(options.max_strokes),
               " strokes, entities and block placements (dxf_drawing_options::max_strokes): blocks inserted "
               "too often?"));
  }

  void segment(const affine2& m, glm::dvec2 a, glm::dvec2 b, std::uint64_t line) {
    budget(line);
    const glm::dvec2 p = m(a), q = m(b);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(q.x) || !std::isfinite(q.y))
      fail(line, "a point overflows to infinity under its block's placement");
    segs.push_back({p, q});
    ++counts.segments;
  }

  /// Refused or skipped curve in the line reader; true when it is to be read.
  bool curve_wanted(std::string_view what, std::uint64_t line) {
    if (read_arcs) return true;
    if (options.curves == dxf_curves::refuse)
      fail(line,
           cellforge::detail::cat(
               std::string(what),
               ": curves are read by parse_dxf_arc_drawing / read_dxf_arc_drawing; draw straight lines, or "
               "read with dxf_drawing_options::curves = skip"));
    ++counts.skipped_curves;
    return false;
  }

  /// An elliptical arc in the entity's frame (ends, radii, rotation, sense) placed by m.
  void arc(const affine2& m, glm::dvec2 from, glm::dvec2 to, double rx, double ry, double rotation,
           bool large, bool ccw, std::uint64_t line) {
    budget(line);
    stroke_arc a{m(from), m(to), rx, ry, rotation, large, ccw};
    if (!std::isfinite(a.from.x) || !std::isfinite(a.from.y) || !std::isfinite(a.to.x) ||
        !std::isfinite(a.to.y) || !map_ellipse(m, a.rx, a.ry, a.rotation, a.ccw))
      fail(line, "an arc's placement flattens it or overflows");
    arcs.push_back(a);
    arc_lines.push_back(line);
  }

  /// A full ellipse (or circle) as two half arcs, so that each has distinct ends.
  void closed_ellipse(const affine2& m, glm::dvec2 c, glm::dvec2 major, double ratio, bool ccw,
                      std::uint64_t line) {
    const double rx = glm::length(major), rotation = std::atan2(major.y, major.x);
    arc(m, c + major, c - major, rx, rx * ratio, rotation, false, ccw, line);
    arc(m, c - major, c + major, rx, rx * ratio, rotation, false, ccw, line);
  }

  /// The entity's extrusion direction as the OCS x sign: +1 for (0,0,1), -1 for (0,0,-1)
  /// (OCS x = -world x, a mirror); other directions are refused.
  double ocs_sign(glm::dvec3 n, std::uint64_t line, std::string_view type) const {
    const double len = glm::length(n);
    if (!(len > 0) || !std::isfinite(len))
      fail(line, cellforge::detail::cat(std::string(type), " has a zero extrusion direction (210/220/230)"));
    n /= len;
    if (std::abs(n.x) < 1e-12 && std::abs(n.y) < 1e-12) return n.z > 0 ? 1.0 : -1.0;
    fail(line,
         cellforge::detail::cat(
             std::string(type),
             " lies in a plane tilted out of the drawing (extrusion direction not ±z): only 2D drawings "
             "are read"));
  }

  /// A bulged polyline segment from a to b (bulge = tan(sweep / 4), > 0 counter-clockwise).
  void bulge_arc(const affine2& m, glm::dvec2 a, glm::dvec2 b, double bulge, std::uint64_t line,
                 std::string_view type) {
    if (!curve_wanted(cellforge::detail::cat(std::string(type), " with a bulged (arc) segment"), line))
      return;
    const double chord = glm::length(b - a);
    const double r = chord * (1 + bulge * bulge) / (4 * std::abs(bulge));
    if (!std::isfinite(r))
      fail(line, cellforge::detail::cat(std::string(type), ": a bulge too large for its segment"));
    arc(m, a, b, r, r, 0, std::abs(bulge) > 1, bulge > 0, line);
  }

  /// A polyline's vertices (with bulges) as segments and arcs.
  void polyline(const affine2& m, const std::vector<std::pair<glm::dvec2, double>>& v,
                const std::vector<std::uint64_t>& lines, bool closed, std::uint64_t line,
                std::string_view type) {
    const std::size_t n = v.size();
    if (n < 2) {
      counts.diagnostics.push_back(cellforge::detail::cat(std::string(name), ":", std::to_string(line), ": ",
                                                          std::string(type), " with ", std::to_string(n),
                                                          " vertex: nothing drawn"));
      return;
    }
    for (std::size_t k = 0; k < (closed ? n : n - 1); ++k) {
      const glm::dvec2 a = v[k].first, b = v[(k + 1) % n].first;
      if (a == b) continue;
      // A bulge below 1e-9 bows the segment by less than 1e-9 of its length: straight.
      if (std::abs(v[k].second) > 1e-9)
        bulge_arc(m, a, b, v[k].second, lines[k], type);
      else
        segment(m, a, b, lines[k]);
    }
  }

  /// Reads entities in [first, last) placed by p. O(groups in range).
  void entities(std::size_t first, std::size_t last, const placement& p) {
    std::size_t i = next_zero(first);
    if (i != first)
      fail(groups[first].line, cellforge::detail::cat("an entity (0 TYPE) expected, found group code ",
                                                      std::to_string(groups[first].code)));
    while (i < last) {
      const dxf_group& g = groups[i];
      const std::size_t end = std::min(next_zero(i + 1), last);
      const std::string_view type = g.value;
      // Sequences: POLYLINE's VERTEXes and an INSERT's ATTRIBs run to SEQEND.
      std::size_t after = end;
      if (type == "POLYLINE" || type == "INSERT") {
        bool attribs = type == "POLYLINE";
        if (type == "INSERT")
          for (std::size_t k = i + 1; k < end; ++k)
            if (groups[k].code == 66 && integer(groups[k], "INSERT's attributes-follow flag") != 0)
              attribs = true;
        if (attribs) {
          std::size_t k = end;
          while (k < last && groups[k].value != "SEQEND") {
            const std::string_view t = groups[k].value;
            if (t != (type == "POLYLINE" ? "VERTEX" : "ATTRIB"))
              fail(groups[k].line,
                   cellforge::detail::cat("0 ", shown(t), " inside the ", std::string(type), " of line ",
                                          std::to_string(g.line), ": ",
                                          (type == "POLYLINE" ? "VERTEX" : "ATTRIB"), " or SEQEND expected"));
            k = std::min(next_zero(k + 1), last);
          }
          if (k >= last)
            fail(g.line,
                 cellforge::detail::cat(std::string(type), " with no 0 SEQEND after its ",
                                        (type == "POLYLINE" ? "vertices" : "attributes"), " (truncated?)"));
          after = std::min(next_zero(k + 1), last);
        }
      }
      budget(g.line);
      entity(i, end, after, p);
      i = after;
    }
  }

  void entity(std::size_t i, std::size_t end, std::size_t after, const placement& p) {
    const dxf_group& g = groups[i];
    const std::string_view type = g.value;
    const bool known = type == "LINE" || type == "LWPOLYLINE" || type == "POLYLINE" || type == "ARC" ||
                       type == "CIRCLE" || type == "ELLIPSE" || type == "INSERT";
    if (!known) {
      if (type == "VERTEX" || type == "SEQEND" || type == "ATTRIB")
        fail(g.line,
             cellforge::detail::cat("0 ", std::string(type), " outside a POLYLINE or INSERT sequence"));
      skip_note(type, g.line);
      return;
    }
    std::string_view layer = "0";
    glm::dvec3 normal{0, 0, 1};
    for (std::size_t k = i + 1; k < end; ++k) {
      if (groups[k].code == 8) layer = groups[k].value;
      if (groups[k].code == 210) normal.x = number(groups[k], "the extrusion direction x");
      if (groups[k].code == 220) normal.y = number(groups[k], "the extrusion direction y");
      if (groups[k].code == 230) normal.z = number(groups[k], "the extrusion direction z");
    }
    if (layer == "0" && !p.layer.empty()) layer = p.layer;
    if (!layer_chosen(layer)) {
      ++counts.skipped_by_layer;
      return;
    }
    const auto value = [&](int code, double fallback, const char* what) {
      double v = fallback;
      for (std::size_t k = i + 1; k < end; ++k)
        if (groups[k].code == code) v = number(groups[k], what);
      return v;
    };
    const auto flags_of = [&] {
      std::int64_t v = 0;
      for (std::size_t k = i + 1; k < end; ++k)
        if (groups[k].code == 70) v = integer(groups[k], "the flags");
      return v;
    };
    const auto required = [&](int code, const char* what) {
      for (std::size_t k = i + 1; k < end; ++k)
        if (groups[k].code == code) return number(groups[k], what);
      fail(g.line, cellforge::detail::cat(std::string(type), " without ", what, " (group code ",
                                          std::to_string(code), ")"));
    };
    // The OCS of 2D entities: (0,0,-1) mirrors x; LINE, ELLIPSE are in world coordinates but
    // their z is ignored (a view of the x-y plane).
    const bool ocs = type != "LINE" && type != "ELLIPSE";
    const double sx = type == "LINE" ? 1.0 : ocs_sign(normal, g.line, type);
    const affine2 m = ocs ? p.m.then(affine2{sx, 0, 0, 1, 0, 0}) : p.m;
    if (type == "LINE") {
      ++counts.entities;
      const glm::dvec2 a{required(10, "a start point x"), required(20, "a start point y")};
      const glm::dvec2 b{required(11, "an end point x"), required(21, "an end point y")};
      if (a == b) {
        ++counts.dropped_zero_length;
        return;
      }
      segment(m, a, b, g.line);
    } else if (type == "LWPOLYLINE") {
      ++counts.entities;
      const bool closed = (flags_of() & 1) != 0;
      std::int64_t declared = -1;
      std::vector<std::pair<glm::dvec2, double>> v;
      std::vector<std::uint64_t> lines;
      bool has_y = true;
      for (std::size_t k = i + 1; k < end; ++k) {
        const dxf_group& q = groups[k];
        if (q.code == 10) {
          if (!has_y) fail(q.line, "LWPOLYLINE vertex without its y (group code 20)");
          v.push_back({{number(q, "a vertex x"), 0}, 0});
          lines.push_back(q.line);
          has_y = false;
        } else if (q.code == 20) {
          if (v.empty() || has_y) fail(q.line, "a y (group code 20) with no vertex x (10) before it");
          v.back().first.y = number(q, "a vertex y");
          has_y = true;
        } else if (q.code == 42) {
          if (v.empty()) fail(q.line, "a bulge (group code 42) before the first vertex");
          v.back().second = number(q, "a bulge");
        } else if (q.code == 90) {
          declared = integer(q, "LWPOLYLINE's vertex count");
        }
      }
      if (!has_y) fail(lines.back(), "LWPOLYLINE vertex without its y (group code 20)");
      if (declared >= 0 && static_cast<std::size_t>(declared) != v.size())
        counts.diagnostics.push_back(
            cellforge::detail::cat(std::string(name), ":", std::to_string(g.line), ": LWPOLYLINE says ",
                                   std::to_string(declared), " vertices (group code 90) but has ",
                                   std::to_string(v.size()), ": the vertices present are read"));
      polyline(m, v, lines, closed, g.line, type);
    } else if (type == "POLYLINE") {
      const std::int64_t flags = flags_of();
      if ((flags & (16 | 64)) != 0) {  // polygon or polyface meshes are surfaces, not strokes
        skip_note("POLYLINE (mesh)", g.line);
        return;
      }
      ++counts.entities;
      std::vector<std::pair<glm::dvec2, double>> v;
      std::vector<std::uint64_t> lines;
      for (std::size_t k = end; k < after;) {
        const std::size_t vend = next_zero(k + 1);
        if (groups[k].value == "VERTEX") {
          glm::dvec2 at{0, 0};
          double bulge = 0;
          std::int64_t vflags = 0;
          bool hx = false, hy = false;
          for (std::size_t q = k + 1; q < vend; ++q) {
            if (groups[q].code == 10) at.x = number(groups[q], "a vertex x"), hx = true;
            if (groups[q].code == 20) at.y = number(groups[q], "a vertex y"), hy = true;
            if (groups[q].code == 42) bulge = number(groups[q], "a bulge");
            if (groups[q].code == 70) vflags = integer(groups[q], "a vertex's flags");
          }
          if (!hx || !hy) fail(groups[k].line, "VERTEX without its point (group codes 10 and 20)");
          if ((vflags & 16) == 0) {  // spline frame control points are not on the curve
            v.push_back({at, (flags & 8) != 0 ? 0.0 : bulge});
            lines.push_back(groups[k].line);
          }
        }
        k = vend;
      }
      const affine2 pm = (flags & 8) != 0 ? p.m : m;  // a 3D polyline is in world coordinates
      polyline(pm, v, lines, (flags & 1) != 0, g.line, type);
    } else if (type == "ARC" || type == "CIRCLE") {
      ++counts.entities;
      const glm::dvec2 c{required(10, "a centre x"), required(20, "a centre y")};
      const double r = required(40, "a radius");
      if (!(r > 0))
        fail(g.line, cellforge::detail::cat(std::string(type), " with radius ", shown(std::to_string(r)),
                                            ": not positive"));
      if (!curve_wanted(type, g.line)) return;
      if (type == "CIRCLE") {
        closed_ellipse(m, c, {r, 0}, 1.0, true, g.line);
        return;
      }
      const double a0 = required(50, "a start angle"), a1 = required(51, "an end angle");
      double sweep = std::fmod(a1 - a0, 360.0);
      if (sweep <= 0) sweep += 360;
      const double t0 = a0 * std::numbers::pi / 180, t1 = a1 * std::numbers::pi / 180;
      const glm::dvec2 from = c + r * glm::dvec2(std::cos(t0), std::sin(t0));
      const glm::dvec2 to = c + r * glm::dvec2(std::cos(t1), std::sin(t1));
      if (sweep >= 360 || from == to) {
        closed_ellipse(m, c, r * glm::dvec2(std::cos(t0), std::sin(t0)), 1.0, true, g.line);
        return;
      }
      arc(m, from, to, r, r, 0, sweep > 180, true, g.line);
    } else if (type == "ELLIPSE") {
      ++counts.entities;
      const glm::dvec2 c{required(10, "a centre x"), required(20, "a centre y")};
      const glm::dvec2 major{required(11, "a major axis end x"), required(21, "a major axis end y")};
      const double ratio = required(40, "an axis ratio");
      if (!(glm::length(major) > 0)) fail(g.line, "ELLIPSE with a zero major axis");
      if (!(ratio > 0) || ratio > 1 + 1e-9)
        fail(g.line,
             cellforge::detail::cat("ELLIPSE with axis ratio ", std::to_string(ratio), ": not in (0, 1]"));
      if (!curve_wanted(type, g.line)) return;
      // The minor axis is normal × major: with the normal -z the parameter runs clockwise.
      const bool ccw = sx > 0;
      const double t0 = value(41, 0, "a start parameter"),
                   t1 = value(42, 2 * std::numbers::pi, "an end parameter");
      double sweep = std::fmod(t1 - t0, 2 * std::numbers::pi);
      if (sweep <= 0) sweep += 2 * std::numbers::pi;
      const glm::dvec2 minor = ratio * glm::dvec2(-major.y, major.x) * sx;
      const auto at = [&](double t) { return c + std::cos(t) * major + std::sin(t) * minor; };
      const glm::dvec2 from = at(t0), to = at(t1);
      if (sweep >= 2 * std::numbers::pi - 1e-12 || from == to) {
        closed_ellipse(m, c, major, ratio, ccw, g.line);
        return;
      }
      const double rx = glm::length(major);
      arc(m, from, to, rx, rx * ratio, std::atan2(major.y, major.x), sweep > std::numbers::pi, ccw, g.line);
    } else {  // INSERT
      insert(i, end, m, layer);
    }
  }

  void insert(std::size_t i, std::size_t end, const affine2& m, std::string_view layer) {
    const dxf_group& g = groups[i];
    if (!options.expand_inserts)
      fail(g.line,
           "INSERT of a block: block references are not read (dxf_drawing_options::expand_inserts is "
           "false; explode the block in the CAD program, or read with expand_inserts = true)");
    std::string_view block_name;
    double x = 0, y = 0, scale_x = 1, scale_y = 1, degrees = 0, dx = 0, dy = 0;
    std::int64_t columns = 1, rows = 1;
    for (std::size_t k = i + 1; k < end; ++k) {
      const dxf_group& q = groups[k];
      switch (q.code) {
        case 2:
          block_name = q.value;
          break;
        case 10:
          x = number(q, "an insertion point x");
          break;
        case 20:
          y = number(q, "an insertion point y");
          break;
        case 41:
          scale_x = number(q, "a scale x");
          break;
        case 42:
          scale_y = number(q, "a scale y");
          break;
        case 50:
          degrees = number(q, "a rotation");
          break;
        case 44:
          dx = number(q, "a column spacing");
          break;
        case 45:
          dy = number(q, "a row spacing");
          break;
        case 70:
          columns = integer(q, "a column count");
          break;
        case 71:
          rows = integer(q, "a row count");
          break;
        default:
          break;
      }
    }
    if (columns < 1 || rows < 1 || columns > 100000 || rows > 100000)
      fail(g.line, cellforge::detail::cat("INSERT with ", std::to_string(columns), " columns and ",
                                          std::to_string(rows), " rows: each must be 1 to 100000"));
    if (scale_x == 0 || scale_y == 0) fail(g.line, "INSERT with a zero scale: the block is flattened");
    std::size_t b = blocks.size();
    for (std::size_t k = 0; k < blocks.size() && b == blocks.size(); ++k)
      if (dxf_same_name(blocks[k].name, block_name)) b = k;
    if (b == blocks.size())
      fail(g.line, cellforge::detail::cat("INSERT of block ", shown(block_name), ", which is not defined"));
    for (const std::size_t open : insert_stack)
      if (open == b)
        fail(g.line, cellforge::detail::cat("block ", shown(block_name),
                                            " inserts itself (directly or through others)"));
    if (insert_stack.size() >= max_depth)
      fail(g.line, cellforge::detail::cat("blocks nested more than ", std::to_string(max_depth), " deep"));
    const double rad = degrees * std::numbers::pi / 180, cs = std::cos(rad), sn = std::sin(rad);
    insert_stack.push_back(b);
    for (std::int64_t r = 0; r < rows; ++r)
      for (std::int64_t c = 0; c < columns; ++c) {
        budget(g.line);
        // Block frame -> insert frame: minus the base point, scaled, rotated, moved (array
        // offsets along the rotated axes).
        const double ox = x + cs * (static_cast<double>(c) * dx) - sn * (static_cast<double>(r) * dy);
        const double oy = y + sn * (static_cast<double>(c) * dx) + cs * (static_cast<double>(r) * dy);
        const affine2 place = affine2{cs, sn, -sn, cs, ox, oy}
                                  .then(affine2{scale_x, 0, 0, scale_y, 0, 0})
                                  .then(affine2{1, 0, 0, 1, -blocks[b].base.x, -blocks[b].base.y});
        ++counts.inserts;
        if (blocks[b].first < blocks[b].last)
          entities(blocks[b].first, blocks[b].last, {m.then(place), layer});
      }
    insert_stack.pop_back();
  }

  void finish_notes() {
    for (const skipped_kind& s : skipped)
      counts.diagnostics.push_back(cellforge::detail::cat(
          std::string(name), ":", std::to_string(s.first_line), ": ", std::to_string(s.count), " ", s.type,
          (s.count == 1 ? " entity" : " entities"), " left out (not a line, polyline or arc)"));
    if (counts.skipped_curves > 0)
      counts.diagnostics.push_back(
          cellforge::detail::cat(std::string(name), ": ", std::to_string(counts.skipped_curves),
                                 " curves left out (dxf_drawing_options::curves = skip)"));
  }
};

using dxf_reader = basic_dxf_reader<>;

/// The DXF reader of parse_dxf_drawing (arcs = false) and parse_dxf_arc_drawing (arcs = true).
template <Point2 P2>
dxf_arc_drawing_result<P2> parse_dxf_strokes(std::string_view text, std::string_view name,
                                             const dxf_drawing_options& options, bool arcs) {
  const cellforge::detail::stopwatch clock;
  if (!std::isfinite(options.snap_tolerance) || options.snap_tolerance < 0 || options.snap_tolerance >= 0.5)
    throw error(error_category::invalid_input,
                "parse_dxf_drawing: snap_tolerance must be a finite number in [0, 0.5)");
  dxf_reader r{name, options, arcs, {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  r.split_groups(text);
  const auto [first, last] = r.sections();
  if (first < last) r.entities(first, last, {});
  r.finish_notes();
  dxf_arc_drawing_result<P2> out;
  static_cast<dxf_reading_counts&>(out) = std::move(r.counts);
  out.arcs = r.arcs.size();
  if (r.segs.empty() && r.arcs.empty()) {
    out.diagnostics.push_back(cellforge::detail::cat(
        std::string(name), (arcs ? ": no line or arc found" : ": no straight line found")));
    out.milliseconds = clock.ms();
    return out;
  }
  stroke_snap_counts counts;
  out.drawing = snap_strokes<P2>(
      r.segs, r.arcs, options.snap_tolerance, options.split_at_junctions, name,
      [&](std::size_t k) { return r.arc_lines[k]; }, counts, out.diagnostics);
  out.snapped = counts.snapped;
  out.dropped_zero_length += counts.dropped_zero_length;
  out.merged_duplicates = counts.merged_duplicates;
  out.split_at_junctions = counts.split_at_junctions;
  out.milliseconds = clock.ms();
  return out;
}

}  // namespace detail

template <Point2 P2>
dxf_drawing_result<P2> parse_dxf_drawing(std::string_view text, std::string_view name,
                                         const dxf_drawing_options& options) {
  dxf_arc_drawing_result<P2> r = detail::parse_dxf_strokes<P2>(text, name, options, false);
  dxf_drawing_result<P2> out;
  static_cast<dxf_reading_counts&>(out) = std::move(static_cast<dxf_reading_counts&>(r));
  out.drawing = std::move(r.drawing.lines);
  return out;
}

template <Point2 P2>
dxf_arc_drawing_result<P2> parse_dxf_arc_drawing(std::string_view text, std::string_view name,
                                                 const dxf_drawing_options& options) {
  return detail::parse_dxf_strokes<P2>(text, name, options, true);
}

template <Point2 P2>
dxf_drawing_result<P2> read_dxf_drawing(const file_path& path, const dxf_drawing_options& options) {
  return detail::read_and_parse(path, [&](std::string_view bytes, const std::string& name) {
    return parse_dxf_drawing<P2>(bytes, name, options);
  });
}

template <Point2 P2>
dxf_arc_drawing_result<P2> read_dxf_arc_drawing(const file_path& path, const dxf_drawing_options& options) {
  return detail::read_and_parse(path, [&](std::string_view bytes, const std::string& name) {
    return parse_dxf_arc_drawing<P2>(bytes, name, options);
  });
}

}  // namespace cellforge::io
