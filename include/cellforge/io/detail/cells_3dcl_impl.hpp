// SPDX-License-Identifier: MIT
#pragma once
// The 3DCL writer and reader (included by io/cells_3dcl.hpp).

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "cellforge/cells/cell_complex.hpp"
#include "cellforge/cells/conversion.hpp"
#include "cellforge/core/detail/span_of.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/io/cells_3dcl.hpp"
#include "cellforge/io/detail/cells_writing.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/file_path.hpp"

namespace cellforge::io {

namespace detail {

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

template <Point3 P>
void write_3dcl(std::ostream& os, const cell_complex<P>& cc, const cells_write_options& options) {
  const cellforge::detail::cells::dvec3_points<P> pts(cc.points());
  const std::string text = detail::cells_text(cc, pts.span(), options);
  os.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!os) throw error(error_category::io, "3dcl: writing to the stream failed");
}

template <Point3 P>
void write_3dcl(const file_path& path, const cell_complex<P>& cc, const cells_write_options& options) {
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

template <Point3 P>
cell_complex<P> parse_3dcl(std::string_view text, std::string_view name) {
  if constexpr (std::is_same_v<P, glm::dvec3>)
    return detail::parse_3dcl_dvec3(text, name);
  else
    return convert_points<P>(detail::parse_3dcl_dvec3(text, name));
}

template <Point3 P>
cell_complex<P> read_3dcl(const file_path& path) {
  const std::string bytes = detail::read_file(path);
  return parse_3dcl<P>(bytes, detail::display_name(path));
}

}  // namespace cellforge::io
