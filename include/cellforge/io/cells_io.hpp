// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Files of the 3DCL: the "3dcl" text format (seed 000 §4.9: vertices, edges, faces,
/// volumes, each with all its relations; docs/formats.md "3DCL text format") written and read
/// back exactly, plus OBJ with one group per volume, PLY with faces coloured by volume and an
/// exploded, shaded SVG picture.

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <ostream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/obj.hpp"
#include "cellforge/io/svg.hpp"

namespace cellforge::io {

/// How a 3DCL text file is written.
struct cells_write_options {
  std::string comment{};  ///< written as '#' lines after the header when not empty
};

namespace detail {

// Appends the decimal digits of n; appending pieces instead of `" " + std::to_string(n)`
// also keeps g++ 12's false -Wrestrict (PR 105329) out of a user's -O2 -Werror build.
template <class = void>
void put_count(std::string& out, std::uint64_t n) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, n);
  out.append(buf, r.ptr);
}

// Appends a keyword, a space and a count, e.g. "edges 12".
template <class = void>
void put_keyword(std::string& out, std::string_view keyword, std::uint64_t n) {
  out += keyword;
  out += ' ';
  put_count(out, n);
}

template <class = void>
void put_signed(std::string& out, std::uint32_t index, int sign) {
  out += sign < 0 ? " -" : " +";
  put_count(out, index);
}

template <class = void>
void put_double(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

/// The whole 3DCL text of cc. O(size of cc).
template <class = void>
std::string cells_text(const cell_topology& cc, std::span<const glm::dvec3> pts,
                       const cells_write_options& options) {
  std::string out = "3dcl 1\n";
  for (std::string_view text = options.comment; !text.empty();) {
    const std::size_t eol = std::min(text.find_first_of("\r\n"), text.size());
    if (eol > 0) {
      out += "# ";
      out += text.substr(0, eol);
      out += '\n';
    }
    text.remove_prefix(std::min(eol + 1, text.size()));
  }
  put_keyword(out, "vertices", cc.num_vertices());
  out += '\n';
  for (cell_vertex v : cc.vertices()) {
    put_keyword(out, "v", v.idx());
    for (int k = 0; k < 3; ++k) out += ' ', put_double(out, pts[v.idx()][k]);
    out += " edges";
    for (const auto& [e, s] : cc.vertex_edges(v)) put_signed(out, e.idx(), s);
    out += '\n';
  }
  put_keyword(out, "edges", cc.num_edges());
  out += '\n';
  for (cell_edge e : cc.edges()) {
    put_keyword(out, "e", e.idx());
    out += ' ';
    put_count(out, cc.source(e).idx());
    out += ' ';
    put_count(out, cc.target(e).idx());
    out += " faces";
    for (const auto& [f, s] : cc.edge_faces(e)) put_signed(out, f.idx(), s);
    out += " volumes";
    for (cell_volume c : cc.edge_wedges(e)) {
      out += ' ';
      if (c.is_valid())
        put_count(out, c.idx());
      else
        out += '-';
    }
    out += '\n';
  }
  put_keyword(out, "faces", cc.num_faces());
  out += '\n';
  for (cell_face f : cc.faces()) {
    put_keyword(out, "f", f.idx());
    out += " volumes";
    for (const auto& [c, s] : cc.face_volumes(f)) put_signed(out, c.idx(), s);
    for (std::size_t l = 0; l < cc.num_loops(f); ++l) {
      out += " loop";
      for (cell_vertex v : cc.loop_vertices(f, l)) {
        out += ' ';
        put_count(out, v.idx());
      }
      out += " edges";
      for (const auto& [e, s] : cc.loop_edges(f, l)) put_signed(out, e.idx(), s);
    }
    out += '\n';
  }
  put_keyword(out, "volumes", cc.num_volumes());
  out += '\n';
  for (cell_volume c : cc.volumes()) {
    put_keyword(out, "c", c.idx());
    out += " faces";
    for (const auto& [f, s] : cc.volume_faces(c)) put_signed(out, f.idx(), s);
    out += '\n';
  }
  out += "end\n";
  return out;
}

/// A message fragment "text<id>tail<id2>tail2" assembled only when an error needs it, so a
/// clean parse builds no strings.
struct cells_label {
  static constexpr std::uint64_t none = ~std::uint64_t{0};
  std::string_view text;
  std::uint64_t id = none;
  std::string_view tail{};
  std::uint64_t id2 = none;
  std::string_view tail2{};
  cells_label(const char* t) : text(t) {}  // NOLINT: implicit from literals on purpose
  cells_label(std::string_view t, std::uint64_t i = none, std::string_view tl = {}, std::uint64_t i2 = none,
              std::string_view tl2 = {})
      : text(t), id(i), tail(tl), id2(i2), tail2(tl2) {}
  std::string str() const {
    std::string s(text);
    if (id != none) s += std::to_string(id);
    s += tail;
    if (id2 != none) s += std::to_string(id2);
    s += tail2;
    return s;
  }
};

template <class = void>
class basic_cells_line;
using cells_line = basic_cells_line<>;

/// Tokens of one line of a 3DCL file, with errors that name file:line.
template <class>
class basic_cells_line {
 public:
  basic_cells_line(std::string_view text, std::string_view file, std::uint64_t line)
      : file_(file), line_(line) {
    if (const auto hash = text.find('#'); hash != std::string_view::npos) text = text.substr(0, hash);
    std::size_t i = 0;
    while (i < text.size()) {
      while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
      std::size_t j = i;
      while (j < text.size() && text[j] != ' ' && text[j] != '\t') ++j;
      if (j > i) tokens_.push_back(text.substr(i, j - i));
      i = j;
    }
  }
  bool empty() const { return tokens_.empty(); }
  bool done() const { return next_ == tokens_.size(); }
  std::uint64_t line() const { return line_; }
  std::string_view peek() const { return done() ? std::string_view() : tokens_[next_]; }

  [[noreturn]] void fail(const std::string& msg) const {
    throw error(error_category::io, msg, source_location{std::string(file_), line_});
  }
  std::string found() const {
    return done() ? "end of line" : cellforge::detail::cat("'", std::string(tokens_[next_]), "'");
  }

  void keyword(std::string_view k, const cells_label& context) {
    if (peek() != k)
      fail(cellforge::detail::cat("expected '", std::string(k), "' ", context.str(), ", found ", found()));
    ++next_;
  }
  std::uint64_t index(const cells_label& what, std::uint64_t limit) {
    const std::string_view t = peek();
    std::uint64_t v = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(cellforge::detail::cat("expected ", what.str(), " (a non-negative integer), found ", found()));
    if (v >= limit) fail(what.str() + " " + std::string(t) + " " + range(limit));
    ++next_;
    return v;
  }
  double coordinate(const cells_label& what) {
    std::string_view t = peek();
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    double v = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(cellforge::detail::cat("expected ", what.str(), " (a number), found ", found()));
    if (!std::isfinite(v)) fail(what.str() + " '" + std::string(t) + "' is not finite");
    ++next_;
    return v;
  }
  /// "+i" or "-i": an index with an explicit sign.
  std::pair<std::uint32_t, int> signed_index(const cells_label& what, std::uint64_t limit) {
    const std::string_view t = peek();
    if (t.size() < 2 || (t[0] != '+' && t[0] != '-'))
      fail(
          cellforge::detail::cat("expected ", what.str(), " with its sign (like +3 or -3), found ", found()));
    const int sign = t[0] == '+' ? 1 : -1;
    std::uint64_t v = 0;
    const auto r = std::from_chars(t.data() + 1, t.data() + t.size(), v);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(
          cellforge::detail::cat("expected ", what.str(), " with its sign (like +3 or -3), found ", found()));
    if (v >= limit) fail(what.str() + " " + std::string(t) + " " + range(limit));
    ++next_;
    return {static_cast<std::uint32_t>(v), sign};
  }
  /// Signed indices until a keyword (a token starting with a letter) or the end of the line.
  std::vector<std::pair<std::uint32_t, int>> signed_list(const cells_label& what, std::uint64_t limit) {
    std::vector<std::pair<std::uint32_t, int>> out;
    while (!done() && !is_word(peek())) out.push_back(signed_index(what, limit));
    return out;
  }
  std::vector<std::uint32_t> index_list(const cells_label& what, std::uint64_t limit) {
    std::vector<std::uint32_t> out;
    while (!done() && !is_word(peek())) out.push_back(static_cast<std::uint32_t>(index(what, limit)));
    return out;
  }
  void finish(const cells_label& element) const {
    if (!done()) fail(cellforge::detail::cat("unexpected ", found(), " at the end of ", element.str()));
  }

 private:
  static std::string range(std::uint64_t limit) {
    return limit == 0 ? "out of range (there are none)"
                      : cellforge::detail::cat("out of range (0..", std::to_string(limit - 1), ")");
  }
  static bool is_word(std::string_view t) {
    return !t.empty() && ((t[0] >= 'a' && t[0] <= 'z') || (t[0] >= 'A' && t[0] <= 'Z'));
  }
  std::string_view file_;
  std::uint64_t line_;
  std::vector<std::string_view> tokens_;
  std::size_t next_ = 0;
};

template <class = void>
class basic_cells_lines;
using cells_lines = basic_cells_lines<>;

/// Splits text into content lines (comments and blank lines skipped), keeping line numbers.
template <class>
class basic_cells_lines {
 public:
  basic_cells_lines(std::string_view text, std::string_view file) : text_(text), file_(file) {
    if (text_.substr(0, 3) == "\xEF\xBB\xBF") text_.remove_prefix(3);
  }
  /// The next line with content; fails with `expected` at the end of the file.
  cells_line next(const cells_label& expected) {
    while (pos_ < text_.size()) {
      std::size_t eol = text_.find_first_of("\r\n", pos_);
      if (eol == std::string_view::npos) eol = text_.size();
      cells_line l(text_.substr(pos_, eol - pos_), file_, ++line_);
      pos_ = eol;
      if (pos_ < text_.size() && text_[pos_] == '\r') ++pos_;
      if (pos_ < text_.size() && text_[pos_] == '\n') ++pos_;  // "\n" alone or after "\r"
      if (!l.empty()) return l;
    }
    throw error(error_category::io,
                cellforge::detail::cat("expected ", expected.str(), ", found end of file"),
                source_location{std::string(file_), std::max<std::uint64_t>(line_, 1)});
  }
  bool at_end() {
    // True when only blank or comment lines remain.
    std::size_t save_pos = pos_;
    const std::uint64_t save_line = line_;
    try {
      (void)next("");
    } catch (const error&) {
      return true;
    }
    pos_ = save_pos;
    line_ = save_line;
    return false;
  }

 private:
  std::string_view text_, file_;
  std::size_t pos_ = 0;
  std::uint64_t line_ = 0;
};

/// The line of the element a make_cell_complex() message names first ("vertex 3", "edge 7",
/// "face 2", "volume 1"), or 0.
template <class = void>
std::uint64_t line_of_element(const std::string& message,
                              const std::array<std::vector<std::uint64_t>, 4>& lines) {
  static constexpr std::array<std::string_view, 4> names{"vertex ", "edge ", "face ", "volume "};
  std::size_t best = std::string::npos;
  std::uint64_t line = 0;
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t at = message.find(names[k]); at != std::string::npos;
         at = message.find(names[k], at + 1)) {
      if (at > 0 && message[at - 1] != ' ' && message[at - 1] != '(') continue;
      std::uint64_t i = 0;
      const char* first = message.data() + at + names[k].size();
      const auto r = std::from_chars(first, message.data() + message.size(), i);
      if (r.ec != std::errc() || r.ptr == first) continue;
      if (at < best && i < lines[k].size()) best = at, line = lines[k][i];
      break;
    }
  return line;
}

}  // namespace detail

/// Writes cc as 3DCL text (docs/formats.md). O(size of cc). Throws io when the stream fails.
template <Point3 P>
void write_3dcl(std::ostream& os, const cell_complex<P>& cc, const cells_write_options& options = {}) {
  const cellforge::detail::cells::dvec3_points<P> pts(cc.points());
  const std::string text = detail::cells_text(cc, pts.span(), options);
  os.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!os) throw error(error_category::io, "3dcl: writing to the stream failed");
}

/// Writes cc to a 3DCL text file. O(size of cc). Throws io naming the path on failure.
template <Point3 P>
void write_3dcl(const file_path& path, const cell_complex<P>& cc, const cells_write_options& options = {}) {
  detail::write_file(path, [&](std::ostream& os) { write_3dcl(os, cc, options); });
}

namespace detail {
/// parse_3dcl in double precision. O(size of the text + n log n).
template <class = void>
cell_complex<glm::dvec3> parse_3dcl_dvec3(std::string_view text, std::string_view name) {
  detail::cells_lines lines(text, name);
  constexpr std::uint64_t max = 0xFFFFFFFEu;
  {
    auto l = lines.next("the header '3dcl 1'");
    l.keyword("3dcl", "at the start of the file (the header '3dcl 1')");
    if (l.peek() != "1")
      l.fail(cellforge::detail::cat("unsupported 3dcl version ", l.found(), "; this reader knows version 1"));
    (void)l.index("the version", 2);
    l.finish("the header");
  }
  cell_complex_input<glm::dvec3> in;
  std::array<std::vector<std::uint64_t>, 4> at;  // line of each vertex, edge, face, volume
  std::vector<std::vector<std::pair<std::uint32_t, int>>> vertex_edges, edge_faces, face_volumes;
  std::vector<std::vector<std::uint32_t>> edge_wedges;
  std::vector<std::vector<std::vector<std::pair<std::uint32_t, int>>>> loop_edges;

  auto section = [&](std::string_view keyword) {
    const std::string k(keyword);
    auto l = lines.next(detail::cells_label(cellforge::detail::cat("'", k, " <count>'")));
    l.keyword(keyword, detail::cells_label(cellforge::detail::cat("(the section '", k, " <count>')")));
    const std::uint64_t n =
        l.index(detail::cells_label(cellforge::detail::cat("the number of ", k)), max + 1);
    l.finish("the section header");
    return static_cast<std::size_t>(n);
  };
  // `what` ends in a space: "vertex ", "edge ", ...
  auto element = [&](std::string_view tag, std::string_view what, std::size_t i, std::size_t n) {
    auto l = lines.next({what, i, " of ", n});
    l.keyword(tag,
              {cellforge::detail::cat("at the start of ", std::string(what)), i, " (there are ", n, ")"});
    const std::string_view t = l.peek();
    std::uint64_t got = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), got);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size() || got != i)
      l.fail(cellforge::detail::cat("expected ", std::string(what), "number ", std::to_string(i), ", found ",
                                    l.found()));
    (void)l.index(what, max + 1);
    return l;
  };

  const std::size_t nv = section("vertices");
  for (std::size_t i = 0; i < nv; ++i) {
    auto l = element("v", "vertex ", i, nv);
    const double x = l.coordinate({"coordinate x of vertex ", i});
    const double y = l.coordinate({"coordinate y of vertex ", i});
    const double z = l.coordinate({"coordinate z of vertex ", i});
    in.points.push_back({x, y, z});
    l.keyword("edges", {"after the coordinates of vertex ", i});
    vertex_edges.push_back(l.signed_list("an edge", max));
    l.finish({"vertex ", i});
    at[0].push_back(l.line());
  }
  const std::size_t ne = section("edges");
  for (std::size_t i = 0; i < ne; ++i) {
    auto l = element("e", "edge ", i, ne);
    const auto a = static_cast<std::uint32_t>(l.index({"the start vertex of edge ", i}, nv));
    const auto b = static_cast<std::uint32_t>(l.index({"the end vertex of edge ", i}, nv));
    in.edges.push_back({a, b});
    l.keyword("faces", {"after the vertices of edge ", i});
    edge_faces.push_back(l.signed_list("a face", max));
    l.keyword("volumes", {"after the faces of edge ", i});
    std::vector<std::uint32_t> w;
    while (!l.done()) {
      if (l.peek() == "-") {
        l.keyword("-", "");
        w.push_back(0xFFFFFFFFu);
      } else {
        w.push_back(static_cast<std::uint32_t>(l.index("a volume (or '-' for outside)", max)));
      }
    }
    edge_wedges.push_back(std::move(w));
    at[1].push_back(l.line());
  }
  const std::size_t nf = section("faces");
  for (std::size_t i = 0; i < nf; ++i) {
    auto l = element("f", "face ", i, nf);
    l.keyword("volumes", {"after the number of face ", i});
    face_volumes.push_back(l.signed_list("a volume", max));
    cell_input_face face;
    loop_edges.emplace_back();
    while (!l.done()) {
      l.keyword("loop", {"(a vertex loop) in face ", i});
      face.loops.push_back(l.index_list({"a vertex of face ", i}, nv));
      l.keyword("edges", {"after the vertices of a loop of face ", i});
      loop_edges.back().push_back(l.signed_list({"an edge of face ", i}, ne));
    }
    if (face.loops.empty()) l.fail(cellforge::detail::cat("face ", std::to_string(i), " has no 'loop'"));
    in.faces.push_back(std::move(face));
    at[2].push_back(l.line());
  }
  const std::size_t nc = section("volumes");
  for (std::size_t i = 0; i < nc; ++i) {
    auto l = element("c", "volume ", i, nc);
    l.keyword("faces", {"after the number of volume ", i});
    cell_input_volume vol;
    for (const auto& [f, s] : l.signed_list("a face", nf)) vol.faces.emplace_back(f, s);
    l.finish({"volume ", i});
    in.volumes.push_back(std::move(vol));
    at[3].push_back(l.line());
  }
  {
    auto l = lines.next("'end' after the last volume");
    l.keyword("end", "after the last volume");
    l.finish("the file");
    if (!lines.at_end()) lines.next("").fail("unexpected content after 'end'");
  }

  cell_complex<glm::dvec3> cc;
  try {
    cc = make_cell_complex(std::move(in));
  } catch (const error& e) {
    throw error(error_category::io, e.message(),
                source_location{std::string(name), detail::line_of_element(e.message(), at)});
  }
  // The relations the file lists must be the derived ones, in the same order.
  auto mismatch = [&](std::uint64_t line, const std::string& msg) {
    throw error(error_category::io, msg + " (the file's relations disagree with its cells)",
                source_location{std::string(name), line});
  };
  // Same entries, same order: a derived span of oriented handles against the listed pairs.
  auto same = [](const auto& derived, const std::vector<std::pair<std::uint32_t, int>>& listed) {
    return std::equal(
        derived.begin(), derived.end(), listed.begin(), listed.end(),
        [](const auto& d, const auto& l) { return d.handle.idx() == l.first && d.sign == l.second; });
  };
  for (cell_vertex v : cc.vertices())
    if (!same(cc.vertex_edges(v), vertex_edges[v.idx()]))
      mismatch(at[0][v.idx()],
               cellforge::detail::cat("vertex ", std::to_string(v.idx()),
                                      ": the listed edges are not those at it, with their directions"));
  for (cell_edge e : cc.edges()) {
    if (!same(cc.edge_faces(e), edge_faces[e.idx()]))
      mismatch(at[1][e.idx()],
               cellforge::detail::cat("edge ", std::to_string(e.idx()),
                                      ": the listed faces are not those at it in right-hand rotation order"));
    const auto w = cc.edge_wedges(e);
    if (!std::equal(w.begin(), w.end(), edge_wedges[e.idx()].begin(), edge_wedges[e.idx()].end(),
                    [](cell_volume c, std::uint32_t i) { return c.idx() == i; }))
      mismatch(at[1][e.idx()],
               cellforge::detail::cat("edge ", std::to_string(e.idx()),
                                      ": the listed volumes are not those between its faces"));
  }
  for (cell_face f : cc.faces()) {
    if (!same(cc.face_volumes(f), face_volumes[f.idx()]))
      mismatch(at[2][f.idx()],
               cellforge::detail::cat("face ", std::to_string(f.idx()),
                                      ": the listed volumes are not the face's, with their signs"));
    for (std::size_t k = 0; k < cc.num_loops(f); ++k)
      if (!same(cc.loop_edges(f, k), loop_edges[f.idx()][k]))
        mismatch(at[2][f.idx()],
                 cellforge::detail::cat("face ", std::to_string(f.idx()), ": loop ", std::to_string(k),
                                        " lists edges that do not join its vertices in order"));
  }
  return cc;
}
}  // namespace detail

/// Parses 3DCL text into a complex with positions of type P: builds it from its coordinates,
/// edges, face loops and volumes, then checks that every relation the file lists is the one
/// the complex derives. Errors name file:line and what was expected. O(size of the text + n log n).
template <Point3 P>
cell_complex<P> parse_3dcl(std::string_view text, std::string_view name = "<memory>") {
  if constexpr (std::is_same_v<P, glm::dvec3>)
    return detail::parse_3dcl_dvec3(text, name);
  else
    return convert_points<P>(detail::parse_3dcl_dvec3(text, name));
}

/// Reads a 3DCL text file (see parse_3dcl). O(file size + n log n).
template <Point3 P>
cell_complex<P> read_3dcl(const file_path& path) {
  const std::string bytes = detail::read_file(path);
  return parse_3dcl<P>(bytes, detail::display_name(path));
}

namespace detail {
/// cells_obj_data on double positions (one copy of the code for every point type). O(size of cc).
/// cells_obj_data without its points (the caller puts them in, in the type it wants); pts
/// are needed only to triangulate faces with holes. O(size of cc).
template <class = void>
obj_data<glm::dvec3> cells_obj_faces(const cell_topology& cc, std::span<const glm::dvec3> pts) {
  obj_data<glm::dvec3> data;
  std::vector<std::uint32_t> face;
  auto add = [&](cell_face f, int sign) {
    if (cc.num_loops(f) == 1) {
      face.clear();
      for (cell_vertex v : cc.loop_vertices(f, 0)) face.push_back(v.idx());
      if (sign < 0) std::reverse(face.begin(), face.end());
      data.soup.add_face(cellforge::detail::span_of(face));
      return;
    }
    std::vector<std::vector<glm::dvec3>> loops(cc.num_loops(f));
    std::vector<std::uint32_t> flat;
    for (std::size_t l = 0; l < loops.size(); ++l)
      for (cell_vertex v : cc.loop_vertices(f, l)) loops[l].push_back(pts[v.idx()]), flat.push_back(v.idx());
    for (const auto& t : cellforge::detail::cells::triangulate_face(
             loops, cellforge::detail::cells::access::unit_normal(cc, f),
             cellforge::detail::cat("cells obj: face ", std::to_string(f.idx()))))
      data.soup.add_face(sign < 0 ? std::initializer_list<std::uint32_t>{flat[t[0]], flat[t[2]], flat[t[1]]}
                                  : std::initializer_list<std::uint32_t>{flat[t[0]], flat[t[1]], flat[t[2]]});
  };
  for (cell_volume c : cc.volumes()) {
    data.groups.push_back({cellforge::detail::cat("volume_", std::to_string(c.idx())),
                           static_cast<std::uint32_t>(data.soup.num_faces())});
    for (const auto& [f, sign] : cc.volume_faces(c)) add(f, sign);
  }
  // Faces of no volume (an open surface), as they are oriented, in a group of their own.
  bool open_group = false;
  for (cell_face f : cc.faces())
    if (cc.face_volumes(f).empty()) {
      if (!open_group)
        data.groups.push_back({"faces_without_volume", static_cast<std::uint32_t>(data.soup.num_faces())});
      open_group = true;
      add(f, +1);
    }
  for (cell_edge e : cc.edges())
    if (cc.edge_faces(e).empty()) data.lines.push_back({cc.source(e).idx(), cc.target(e).idx()});
  return data;
}

template <Point3 P>
obj_data<glm::dvec3> cells_obj_data_dvec3(const cell_complex<P>& cc) {
  const cellforge::detail::cells::dvec3_points<P> pts(cc.points());
  obj_data<glm::dvec3> data = cells_obj_faces(cc, pts.span());
  data.soup.points.assign(pts.span().begin(), pts.span().end());
  return data;
}
}  // namespace detail

/// The faces of every volume, outward, as an OBJ model in the complex's point type with one
/// group "volume_<i>" per volume (a face between two volumes appears in both), then the faces
/// of no volume in a group "faces_without_volume", faces with holes triangulated, edges in no
/// face as `l` lines. O(size of cc).
template <Point3 P>
obj_data<P> cells_obj_data(const cell_complex<P>& cc) {
  if constexpr (std::is_same_v<P, glm::dvec3>) {
    return detail::cells_obj_data_dvec3(cc);
  } else {
    const cellforge::detail::cells::dvec3_points<P> pts(cc.points());
    obj_data<glm::dvec3> data = detail::cells_obj_faces(cc, pts.span());
    obj_data<P> out;
    out.soup.points.assign(cc.points().begin(), cc.points().end());
    out.soup.face_offsets = std::move(data.soup.face_offsets);
    out.soup.face_vertices = std::move(data.soup.face_vertices);
    out.groups = std::move(data.groups);
    out.lines = std::move(data.lines);
    return out;
  }
}

/// Writes cells_obj_data(cc) with write_obj. O(size of cc).
template <Point3 P>
void write_cells_obj(std::ostream& os, const cell_complex<P>& cc, const obj_write_options& options = {}) {
  write_obj(os, detail::cells_obj_data_dvec3(cc), options);
}
template <Point3 P>
void write_cells_obj(const file_path& path, const cell_complex<P>& cc,
                     const obj_write_options& options = {}) {
  write_obj(path, detail::cells_obj_data_dvec3(cc), options);
}

/// A distinct, saturated colour for volume i (hues spaced by the golden angle). O(1).
template <class = void>
std::array<double, 3> volume_colour(std::size_t i) {
  const double h = std::fmod(0.13 + 0.618033988749895 * static_cast<double>(i), 1.0) * 6.0, s = 0.55,
               v = 0.92;
  const double c = v * s, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = v - c;
  const int k = static_cast<int>(h) % 6;
  const glm::dvec3 rgb = k == 0   ? glm::dvec3(c, x, 0)
                         : k == 1 ? glm::dvec3(x, c, 0)
                         : k == 2 ? glm::dvec3(0, c, x)
                         : k == 3 ? glm::dvec3(0, x, c)
                         : k == 4 ? glm::dvec3(x, 0, c)
                                  : glm::dvec3(c, 0, x);
  return {rgb.x + m, rgb.y + m, rgb.z + m};
}

namespace detail {
template <class = void>
void write_cells_ply(std::ostream& os, const obj_data<glm::dvec3>& data) {
  std::size_t largest = 0;
  for (std::size_t f = 0; f < data.soup.num_faces(); ++f)
    largest = std::max(largest, data.soup.face(f).size());
  const char* count_type = largest <= 0xFF ? "uchar" : largest <= 0xFFFF ? "ushort" : "uint";
  std::string out = cellforge::detail::cat(
      "ply\nformat ascii 1.0\ncomment 3DCL faces coloured by volume (cellforge)\nelement vertex ",
      std::to_string(data.soup.points.size()),
      "\nproperty double x\nproperty double y\nproperty double z\nelement face ",
      std::to_string(data.soup.num_faces()), "\nproperty list ", count_type,
      " int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n");
  for (const glm::dvec3& p : data.soup.points) {
    for (int k = 0; k < 3; ++k) detail::put_double(out, p[k]), out += k < 2 ? ' ' : '\n';
  }
  for (std::size_t g = 0; g < data.groups.size(); ++g) {
    const std::size_t end =
        g + 1 < data.groups.size() ? data.groups[g + 1].first_face : data.soup.num_faces();
    const std::array<double, 3> rgb = volume_colour(g);
    for (std::size_t f = data.groups[g].first_face; f < end; ++f) {
      const auto face = data.soup.face(f);
      out += std::to_string(face.size());
      for (std::uint32_t v : face) out += ' ' + std::to_string(v);
      for (int k = 0; k < 3; ++k) out += ' ' + std::to_string(static_cast<int>(std::lround(rgb[k] * 255.0)));
      out += '\n';
    }
  }
  os.write(out.data(), static_cast<std::streamsize>(out.size()));
  if (!os) throw error(error_category::io, "cells ply: writing to the stream failed");
}
}  // namespace detail

/// Writes an ASCII PLY of every volume's outward faces (then the faces of no volume), each face with the
/// colour of its volume (uchar red, green, blue face properties), faces with holes triangulated; the count
/// type of the vertex lists is the narrowest that holds the largest face. O(size).
template <Point3 P>
void write_cells_ply(std::ostream& os, const cell_complex<P>& cc) {
  detail::write_cells_ply(os, detail::cells_obj_data_dvec3(cc));
}
template <Point3 P>
void write_cells_ply(const file_path& path, const cell_complex<P>& cc) {
  detail::write_file(path, [&](std::ostream& os) { write_cells_ply(os, cc); });
}

/// How the exploded picture of a complex is drawn.
struct cells_svg_options {
  /// Each volume moves away from the model's centre by this fraction of the distance from
  /// the centre to the volume's centre (0: assembled).
  double explode = 0.35;
  svg_options picture{};
  svg_style style{};  ///< fill is replaced by each volume's colour
};

namespace detail {
template <class = void>
svg_scene cells_svg_scene(const obj_data<glm::dvec3>& data, const cells_svg_options& options) {
  if (!(options.explode >= 0.0) || !std::isfinite(options.explode))
    throw error(error_category::invalid_input, "cells svg: explode must be finite and >= 0");
  bounding_box box;
  for (const glm::dvec3& p : data.soup.points) box.add(p);
  svg_scene scene;
  // Each layer gets only the points its volume's faces use, so the scene holds O(size of
  // the volumes' boundaries) points, not (volumes x points).
  constexpr std::uint32_t unused = 0xFFFFFFFFu;
  std::vector<std::uint32_t> local(data.soup.points.size(), unused);
  std::vector<std::uint32_t> face;
  polygon_soup<glm::dvec3> soup;
  for (std::size_t g = 0; g < data.groups.size(); ++g) {
    const std::size_t end =
        g + 1 < data.groups.size() ? data.groups[g + 1].first_face : data.soup.num_faces();
    soup.clear();
    bounding_box vb;
    for (std::size_t f = data.groups[g].first_face; f < end; ++f) {
      face.clear();
      for (std::uint32_t v : data.soup.face(f)) {
        if (local[v] == unused) {
          local[v] = static_cast<std::uint32_t>(soup.points.size());
          soup.points.push_back(data.soup.points[v]);
          vb.add(data.soup.points[v]);
        }
        face.push_back(local[v]);
      }
      soup.add_face(cellforge::detail::span_of(face));
    }
    for (std::size_t f = data.groups[g].first_face; f < end; ++f)
      for (std::uint32_t v : data.soup.face(f)) local[v] = unused;
    svg_style style = options.style;
    const std::array<double, 3> rgb = volume_colour(g);
    char hex[8];
    std::snprintf(hex, sizeof hex, "#%02x%02x%02x", static_cast<int>(std::lround(rgb[0] * 255)),
                  static_cast<int>(std::lround(rgb[1] * 255)), static_cast<int>(std::lround(rgb[2] * 255)));
    style.fill = hex;
    if (style.feature_angle_deg == 0) style.feature_angle_deg = 1;
    style.offset = options.explode * (vb.center() - box.center());
    scene.add_mesh(soup, style);
  }
  return scene;
}
}  // namespace detail

/// The exploded picture as a scene: one shaded mesh layer per volume holding only that
/// volume's points, offset away from the model's centre; edges drawn where faces meet at an
/// angle (not triangulation diagonals). O(size of cc).
template <Point3 P>
svg_scene cells_svg_scene(const cell_complex<P>& cc, const cells_svg_options& options = {}) {
  return detail::cells_svg_scene(detail::cells_obj_data_dvec3(cc), options);
}

/// Writes the exploded, shaded picture of cc (see cells_svg_scene). O(picture).
template <Point3 P>
svg_result write_cells_svg(std::ostream& os, const cell_complex<P>& cc,
                           const cells_svg_options& options = {}) {
  return cells_svg_scene(cc, options).write(os, options.picture);
}
template <Point3 P>
svg_result write_cells_svg(const file_path& path, const cell_complex<P>& cc,
                           const cells_svg_options& options = {}) {
  return cells_svg_scene(cc, options).write(path, options.picture);
}

}  // namespace cellforge::io
