// SPDX-License-Identifier: MIT
#pragma once
// The engine of the SVG drawing readers (included by io/svg_drawing.hpp).

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <numbers>
#include <string>
#include <string_view>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point2_traits.hpp"
#include "cellforge/io/detail/arc_io.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/stroke_snapping.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/svg_drawing.hpp"
#include "cellforge/sketch/detail/drawing_grid.hpp"
#include "cellforge/sketch/elliptical_arc.hpp"
#include "cellforge/sketch/line_drawing.hpp"

namespace cellforge::io {

namespace detail {

/// SVG's matrix(a b c d e f).
using svg_affine = affine2;

template <class = void>
struct basic_svg_reader;
using svg_reader = basic_svg_reader<>;

/// The SVG scanner: tags, attributes, number lists, paths and transforms over one buffer.
template <class>
struct basic_svg_reader {
  std::string_view text;
  std::string_view name;
  const svg_drawing_options& options;
  // Segments in SVG user space after transforms, y not yet flipped, with their element.
  std::vector<std::pair<glm::dvec2, glm::dvec2>> segs;
  /// An A command in the root's user space after transforms (y still down), in endpoint form.
  struct arc_piece {
    glm::dvec2 from, to;
    double rx, ry, rotation;  // rotation in radians, in the y-down frame
    bool large, sweep;        // SVG's flags in the y-down frame
    const char* at;
  };
  bool read_arcs = false;  // A commands become arc_pieces (else curves as options.curves says)
  std::vector<arc_piece> arcs;
  std::size_t elements = 0, skipped_curves = 0, skipped_elements = 0;
  std::vector<std::string> diagnostics;
  // Incremental line counting for diagnostics (positions only move forward).
  std::size_t counted_to = 0;
  std::uint64_t counted_line = 1;

  [[noreturn]] void fail(const char* at, const std::string& message) const {
    throw error(
        error_category::io, message,
        source_location{std::string(name), line_of(text, static_cast<std::size_t>(at - text.data()))});
  }

  std::uint64_t line(const char* at) {
    const std::size_t to = static_cast<std::size_t>(at - text.data());
    if (to < counted_to) return line_of(text, to);
    // The tail from the last position on: a "\r\n" across the cut still counts once.
    counted_line += line_of(text.substr(counted_to), to - counted_to) - 1;
    counted_to = to;
    return counted_line;
  }

  void note(const char* at, const std::string& message) {
    constexpr std::size_t shown = 50;
    if (diagnostics.size() < shown)
      diagnostics.push_back(
          cellforge::detail::cat(std::string(name), ":", std::to_string(line(at)), ": ", message));
    else if (diagnostics.size() == shown)
      diagnostics.push_back("(further diagnostics left out)");
  }

  static bool space(char ch) { return ch == ' ' || ch == '\t' || ch == '\n' || ch == '\r' || ch == '\f'; }
  static bool name_char(char ch) {
    return !space(ch) && ch != '/' && ch != '>' && ch != '=' && ch != '<' && ch != '"' && ch != '\'';
  }

  // ---- numbers -------------------------------------------------------------------------

  /// Skips blanks and at most one comma between them.
  static const char* skip_separators(const char* p, const char* end) {
    while (p != end && space(*p)) ++p;
    if (p != end && *p == ',') {
      ++p;
      while (p != end && space(*p)) ++p;
    }
    return p;
  }

  static bool starts_number(const char* p, const char* end) {
    if (p == end) return false;
    if (*p == '+' || *p == '-') ++p;
    if (p != end && *p == '.') ++p;
    return p != end && *p >= '0' && *p <= '9';
  }

  /// Reads an SVG number at p ("10", "-.5", "1e-3"; "10-5" is two numbers), advancing p.
  /// False when there is none; fails on a number too large for a double.
  bool number(const char*& p, const char* end, double& out) const {
    if (!starts_number(p, end)) return false;
    const char* q = p;
    if (*q == '+') ++q;
    const char* start = q;
    if (*q == '-') ++q;
    while (q != end && *q >= '0' && *q <= '9') ++q;
    if (q != end && *q == '.') {
      ++q;
      while (q != end && *q >= '0' && *q <= '9') ++q;
    }
    if (q != end && (*q == 'e' || *q == 'E')) {
      const char* x = q + 1;
      if (x != end && (*x == '+' || *x == '-')) ++x;
      if (x != end && *x >= '0' && *x <= '9') {
        while (x != end && *x >= '0' && *x <= '9') ++x;
        q = x;
      }
    }
    // from_chars refuses a leading '+' (skipped above) but takes the rest of the grammar.
    const auto r = std::from_chars(start, q, out, std::chars_format::general);
    if (r.ec == std::errc::result_out_of_range) {
      long double wide = 0;
      const auto w = std::from_chars(start, q, wide, std::chars_format::general);
      if (w.ec != std::errc{} ||
          std::fabs(wide) > static_cast<long double>(std::numeric_limits<double>::max()))
        fail(p, cellforge::detail::cat("the number ", quote_token(p, end), " is out of range"));
      out = static_cast<double>(wide);
    } else if (r.ec != std::errc{} || r.ptr != q) {
      fail(p, cellforge::detail::cat("expected a number, found ", quote_token(p, end)));
    }
    p = q;
    return true;
  }

  /// Reads `n` numbers separated by blanks or commas into out; fails naming `what`.
  void numbers(const char*& p, const char* end, double* out, int n, const std::string& what) const {
    for (int k = 0; k < n; ++k) {
      if (k > 0) p = skip_separators(p, end);
      while (p != end && space(*p)) ++p;
      if (!number(p, end, out[k]))
        fail(p, what + " expects " + std::to_string(n) + " numbers, found " +
                    (p == end ? std::string("the end of the value") : quote_token(p, end)));
    }
  }

  /// A length attribute: a number, optionally in px (user units); "" is `fallback`.
  double length(std::string_view value, double fallback, std::string_view attr) const {
    const char* p = value.data();
    const char* end = p + value.size();
    while (p != end && space(*p)) ++p;
    if (p == end) return fallback;
    double v = 0;
    const char* at = p;
    if (!number(p, end, v))
      fail(at, cellforge::detail::cat("attribute ", std::string(attr), ": expected a number, found ",
                                      quote_token(at, end)));
    if (end - p >= 2 && p[0] == 'p' && p[1] == 'x') p += 2;
    while (p != end && space(*p)) ++p;
    if (p != end)
      fail(p, cellforge::detail::cat("attribute ", std::string(attr), ": unexpected ", quote_token(p, end),
                                     " after the number (only user units and px are read)"));
    return v;
  }

  // ---- transforms -------------------------------------------------------------------------

  /// Parses a transform list (translate, scale, rotate, matrix, skewX, skewY), composed left to
  /// right as SVG says: the rightmost applies first. O(length).
  svg_affine transform(std::string_view value) const {
    svg_affine m;
    const char* p = value.data();
    const char* end = p + value.size();
    for (;;) {
      while (p != end && (space(*p) || *p == ',')) ++p;
      if (p == end) return m;
      const char* at = p;
      while (p != end && ((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z'))) ++p;
      const std::string_view fn(at, static_cast<std::size_t>(p - at));
      while (p != end && space(*p)) ++p;
      if (fn.empty() || p == end || *p != '(')
        fail(at,
             cellforge::detail::cat(
                 "transform: expected translate(...), scale(...), rotate(...), matrix(...), skewX(...) or "
                 "skewY(...), found ",
                 quote_token(at, end)));
      ++p;
      double v[6] = {0, 0, 0, 0, 0, 0};
      int n = 0;
      for (;;) {
        p = skip_separators(p, end);
        if (p != end && *p == ')') break;
        if (n == 6 || !number(p, end, v[n]))
          fail(p, cellforge::detail::cat(
                      "transform ", std::string(fn), ": expected a number or ')', found ",
                      (p == end ? std::string("the end of the value") : quote_token(p, end))));
        ++n;
      }
      ++p;
      const auto args = [&](std::initializer_list<int> ok) {
        if (std::find(ok.begin(), ok.end(), n) == ok.end()) {
          std::string counts;
          for (const int k : ok) counts += (counts.empty() ? "" : " or ") + std::to_string(k);
          fail(at, cellforge::detail::cat("transform ", std::string(fn), " takes ", counts,
                                          " numbers, found ", std::to_string(n)));
        }
      };
      const double rad = v[0] * std::numbers::pi / 180;
      svg_affine t;
      if (fn == "matrix") {
        args({6});
        t = {v[0], v[1], v[2], v[3], v[4], v[5]};
      } else if (fn == "translate") {
        args({1, 2});
        t.e = v[0];
        t.f = n == 2 ? v[1] : 0;
      } else if (fn == "scale") {
        args({1, 2});
        t.a = v[0];
        t.d = n == 2 ? v[1] : v[0];
      } else if (fn == "rotate") {
        args({1, 3});
        const double cs = std::cos(rad), sn = std::sin(rad);
        t = {cs, sn, -sn, cs, 0, 0};
        if (n == 3) t = svg_affine{1, 0, 0, 1, v[1], v[2]}.then(t).then(svg_affine{1, 0, 0, 1, -v[1], -v[2]});
      } else if (fn == "skewX") {
        args({1});
        t.c = std::tan(rad);
      } else if (fn == "skewY") {
        args({1});
        t.b = std::tan(rad);
      } else {
        fail(at, cellforge::detail::cat("transform: unknown function ", quote_token(at, end),
                                        " (translate, scale, rotate, matrix, skewX and skewY are read)"));
      }
      m = m.then(t);
    }
  }

  // ---- geometry -------------------------------------------------------------------------

  void segment(const svg_affine& m, glm::dvec2 a, glm::dvec2 b, const char* at) {
    const glm::dvec2 p = m(a), q = m(b);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(q.x) || !std::isfinite(q.y))
      fail(at, "a point overflows to infinity under its transforms");
    segs.push_back({p, q});
  }

  [[noreturn]] void refuse_curve(const char* at, const std::string& what) const {
    if (read_arcs)
      fail(at, cellforge::detail::cat(
                   "only straight strokes and elliptical arcs (path command A) are read: ", what,
                   (what.starts_with("<circle") || what.starts_with("<ellipse")
                        ? " is a closed curve, no round or fillet (draw it as arcs between junctions)"
                        : " (draw it as arcs or straight segments, or read with svg_drawing_options::curves "
                          "= skip)")));
    fail(at, cellforge::detail::cat(
                 "curves are not read yet: ", what,
                 " (elliptical arcs are read by parse_svg_arc_drawing / read_svg_arc_drawing; draw straight "
                 "segments, or read with svg_drawing_options::curves = skip)"));
  }

  /// An A command from `a` to `b` in the element's frame: transformed by m into an arc_piece,
  /// or a segment where SVG draws a straight line (a zero radius), or nothing (equal ends). O(1).
  void arc(const svg_affine& m, glm::dvec2 a, glm::dvec2 b, const double* v, const char* at) {
    if (a == b) {
      note(at, "an arc command ending where it starts draws nothing (SVG): left out");
      return;
    }
    if (v[0] == 0 || v[1] == 0) {
      note(at, "an arc command with a zero radius is a straight line (SVG): read as one");
      segment(m, a, b, at);
      return;
    }
    const glm::dvec2 p = m(a), q = m(b);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(q.x) || !std::isfinite(q.y))
      fail(at, "a point overflows to infinity under its transforms");
    arc_piece out{p, q, std::abs(v[0]), std::abs(v[1]), arc_radians(v[2]), v[3] != 0, v[4] != 0, at};
    if (!map_ellipse(m, out.rx, out.ry, out.rotation, out.sweep))
      fail(at, "an arc command's transforms flatten its ellipse or overflow");
    arcs.push_back(out);
  }

  /// Reads the `points` of a polyline or polygon (closed: back to the first point).
  void points(std::string_view value, const svg_affine& m, bool closed, const char* element) {
    const char* p = value.data();
    const char* end = p + value.size();
    std::vector<glm::dvec2> pts;
    for (;;) {
      p = pts.empty() ? p : skip_separators(p, end);
      while (p != end && space(*p)) ++p;
      if (p == end) break;
      double xy[2];
      const char* at = p;
      if (!number(p, end, xy[0]))
        fail(at, cellforge::detail::cat("points: expected a number, found ", quote_token(at, end)));
      p = skip_separators(p, end);
      if (!number(p, end, xy[1]))
        fail(p == end ? at : p,
             cellforge::detail::cat("points: an odd number of coordinates (x without y) at ",
                                    (p == end ? std::string("the end of the value") : quote_token(p, end))));
      pts.push_back({xy[0], xy[1]});
    }
    if (pts.size() < 2) {
      note(element, "a polyline or polygon with fewer than 2 points draws nothing");
      return;
    }
    for (std::size_t k = 1; k < pts.size(); ++k) segment(m, pts[k - 1], pts[k], element);
    if (closed && pts.size() > 2) segment(m, pts.back(), pts.front(), element);
  }

  /// Reads path data: M/L/H/V/Z and their relative forms; curves refused or skipped.
  void path(std::string_view value, const svg_affine& m) {
    const char* p = value.data();
    const char* end = p + value.size();
    glm::dvec2 cur{0, 0}, start{0, 0};
    char cmd = 0;
    bool after_close = false;
    for (;;) {
      while (p != end && (space(*p) || *p == ',')) ++p;
      if (p == end) return;
      const char* at = p;
      if ((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z')) {
        cmd = *p++;
      } else if (starts_number(p, end) && cmd != 0 && !after_close) {
        if (cmd == 'M') cmd = 'L';
        if (cmd == 'm') cmd = 'l';
      } else {
        fail(at,
             after_close
                 ? cellforge::detail::cat("path: expected a command after 'z', found ", quote_token(at, end))
                 : cellforge::detail::cat("path: expected a command letter, found ", quote_token(at, end)));
      }
      static constexpr std::string_view known = "MmLlHhVvZzCcSsQqTtAa";
      if (known.find(cmd) == std::string_view::npos)
        fail(at, cellforge::detail::cat("path: unknown command ", quote_token(at, end),
                                        " (M L H V Z and their relative forms are read)"));
      const bool first = segs_in_path == 0 && moves_in_path == 0;
      if (first && cmd != 'M' && cmd != 'm')
        fail(at,
             cellforge::detail::cat("path: the data must start with M or m, found ", quote_token(at, end)));
      const bool rel = cmd >= 'a';
      const std::string what = cellforge::detail::cat(std::string("path command '"), cmd, "'");
      double v[7];
      after_close = false;
      switch (cmd) {
        case 'M':
        case 'm':
          numbers(p, end, v, 2, what);
          // A leading m is absolute (SVG): it moves from the origin.
          cur = rel ? cur + glm::dvec2{v[0], v[1]} : glm::dvec2{v[0], v[1]};
          start = cur;
          ++moves_in_path;
          break;
        case 'L':
        case 'l': {
          numbers(p, end, v, 2, what);
          const glm::dvec2 next = rel ? cur + glm::dvec2{v[0], v[1]} : glm::dvec2{v[0], v[1]};
          segment(m, cur, next, at);
          ++segs_in_path;
          cur = next;
          break;
        }
        case 'H':
        case 'h':
        case 'V':
        case 'v': {
          numbers(p, end, v, 1, what);
          glm::dvec2 next = cur;
          double& c = (cmd == 'H' || cmd == 'h') ? next.x : next.y;
          c = rel ? c + v[0] : v[0];
          segment(m, cur, next, at);
          ++segs_in_path;
          cur = next;
          break;
        }
        case 'Z':
        case 'z':
          if (cur != start) segment(m, cur, start, at);
          ++segs_in_path;
          cur = start;
          after_close = true;
          break;
        case 'A':
        case 'a':
          if (read_arcs) {
            arc_numbers(p, end, v, at, what);
            const glm::dvec2 next = rel ? cur + glm::dvec2{v[5], v[6]} : glm::dvec2{v[5], v[6]};
            arc(m, cur, next, v, at);
            ++segs_in_path;
            cur = next;
            break;
          }
          [[fallthrough]];
        default: {
          if (options.curves == svg_curves::refuse) refuse_curve(at, what);
          const int n = (cmd == 'C' || cmd == 'c')                               ? 6
                        : (cmd == 'S' || cmd == 's' || cmd == 'Q' || cmd == 'q') ? 4
                        : (cmd == 'T' || cmd == 't')                             ? 2
                                                                                 : 7;
          if (n == 7) {
            arc_numbers(p, end, v, at, what);
          } else {
            numbers(p, end, v, n, what);
          }
          cur = rel ? cur + glm::dvec2{v[n - 2], v[n - 1]} : glm::dvec2{v[n - 2], v[n - 1]};
          ++skipped_curves;
          ++segs_in_path;
        }
      }
    }
  }
  std::size_t segs_in_path = 0, moves_in_path = 0;

  /// The 7 values of an arc command: rx ry rotation large-arc sweep x y. Flags may be single
  /// digits with no separator ("a1 1 0 011 1").
  void arc_numbers(const char*& p, const char* end, double* v, const char* at,
                   const std::string& what) const {
    numbers(p, end, v, 3, what);
    for (int k = 3; k < 5; ++k) {
      p = skip_separators(p, end);
      if (p == end || (*p != '0' && *p != '1'))
        fail(p == end ? at : p, what + ": expected an arc flag 0 or 1");
      v[k] = *p++ - '0';
    }
    p = skip_separators(p, end);
    numbers(p, end, v + 5, 2, what);
  }

  // ---- the document ---------------------------------------------------------------------

  struct attribute {
    std::string_view name, value;
  };

  struct open_element {
    std::string_view name;
    const char* at;
    svg_affine ctm;
    bool skip;
  };

  static std::string_view find(const std::vector<attribute>& attrs, std::string_view key) {
    for (const auto& a : attrs)
      if (a.name == key) return a.value;
    return {};
  }

  static bool has(const std::vector<attribute>& attrs, std::string_view key) {
    return std::any_of(attrs.begin(), attrs.end(), [&](const attribute& a) { return a.name == key; });
  }

  /// display="none", or display:none in the style attribute.
  static bool hidden(const std::vector<attribute>& attrs) {
    const auto trim = [](std::string_view s) {
      while (!s.empty() && space(s.front())) s.remove_prefix(1);
      while (!s.empty() && space(s.back())) s.remove_suffix(1);
      return s;
    };
    if (trim(find(attrs, "display")) == "none") return true;
    std::string_view style = find(attrs, "style");
    while (!style.empty()) {
      const std::size_t semi = std::min(style.find(';'), style.size());
      const std::string_view decl = style.substr(0, semi);
      const std::size_t colon = decl.find(':');
      if (colon != std::string_view::npos && trim(decl.substr(0, colon)) == "display" &&
          trim(decl.substr(colon + 1)) == "none")
        return true;
      style.remove_prefix(std::min(semi + 1, style.size()));
    }
    return false;
  }

  /// Skips past `close` from p; fails naming `what` when the file ends first.
  const char* skip_past(const char* p, std::string_view close, const char* at, const char* what) const {
    const std::size_t from = static_cast<std::size_t>(p - text.data());
    const std::size_t k = text.find(close, from);
    if (k == std::string_view::npos)
      fail(at, cellforge::detail::cat(std::string("the file ends inside "), what));
    return text.data() + k + close.size();
  }

  /// Reads a stroke element's geometry (the element is not skipped). O(its size).
  void shape(std::string_view tag, const std::vector<attribute>& attrs, const svg_affine& m, const char* at) {
    const auto len = [&](std::string_view key, double fallback = 0) {
      return length(find(attrs, key), fallback, key);
    };
    if (tag == "line") {
      ++elements;
      segment(m, {len("x1"), len("y1")}, {len("x2"), len("y2")}, at);
    } else if (tag == "polyline" || tag == "polygon") {
      ++elements;
      points(find(attrs, "points"), m, tag == "polygon", at);
    } else if (tag == "rect") {
      const double x = len("x"), y = len("y"), w = len("width"), h = len("height");
      if (w < 0 || h < 0) fail(at, "<rect>: a negative width or height");
      if (len("rx") > 0 || len("ry") > 0) {
        if (options.curves == svg_curves::refuse) refuse_curve(at, "<rect> with rounded corners (rx, ry)");
        ++skipped_curves;
        note(at, "<rect> with rounded corners left out (curves)");
        return;
      }
      if (w == 0 || h == 0) {
        note(at, "<rect> of zero width or height draws nothing");
        return;
      }
      ++elements;
      const glm::dvec2 c[4] = {{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}};
      for (int k = 0; k < 4; ++k) segment(m, c[k], c[(k + 1) % 4], at);
    } else if (tag == "path") {
      ++elements;
      segs_in_path = moves_in_path = 0;
      path(find(attrs, "d"), m);
    } else {  // circle, ellipse
      if (options.curves == svg_curves::refuse)
        refuse_curve(at, cellforge::detail::cat("<", std::string(tag), ">"));
      ++skipped_curves;
      note(at, cellforge::detail::cat("<", std::string(tag), "> left out (curves)"));
    }
  }

  /// Reads the whole document. O(size).
  void document() {
    const char* p = text.data();
    const char* end = p + text.size();
    std::vector<open_element> stack;
    std::vector<attribute> attrs;
    bool seen_root = false;
    for (;;) {
      while (p != end && *p != '<') ++p;
      if (p == end) break;
      const char* at = p;
      const std::string_view rest(p, static_cast<std::size_t>(end - p));
      if (rest.starts_with("<!--")) {
        p = skip_past(p + 4, "-->", at, "a comment <!-- ... -->");
        continue;
      }
      if (rest.starts_with("<![CDATA[")) {
        p = skip_past(p + 9, "]]>", at, "a <![CDATA[ ... ]]> section");
        continue;
      }
      if (rest.starts_with("<?")) {
        p = skip_past(p + 2, "?>", at, "a processing instruction <? ... ?>");
        continue;
      }
      if (rest.starts_with("<!")) {  // DOCTYPE and its internal subset
        int depth = 0;
        for (++p; p != end && (*p != '>' || depth > 0); ++p) depth += *p == '[' ? 1 : *p == ']' ? -1 : 0;
        if (p == end) fail(at, "the file ends inside a <!DOCTYPE ...> declaration");
        ++p;
        continue;
      }
      if (rest.starts_with("</")) {
        p += 2;
        const char* n0 = p;
        while (p != end && name_char(*p)) ++p;
        const std::string_view tag(n0, static_cast<std::size_t>(p - n0));
        while (p != end && space(*p)) ++p;
        if (p == end || *p != '>')
          fail(at, cellforge::detail::cat("expected '>' to end the closing tag </", std::string(tag), ">"));
        ++p;
        if (stack.empty())
          fail(at, cellforge::detail::cat("closing tag </", std::string(tag), "> without an open element"));
        if (stack.back().name != tag)
          fail(at, cellforge::detail::cat(
                       "expected </", std::string(stack.back().name), "> closing <",
                       std::string(stack.back().name), "> of line ",
                       std::to_string(line_of(text, static_cast<std::size_t>(stack.back().at - text.data()))),
                       ", found </", std::string(tag), ">"));
        stack.pop_back();
        continue;
      }
      // A start tag: name, attributes, '>' or '/>'.
      ++p;
      const char* n0 = p;
      while (p != end && name_char(*p)) ++p;
      const std::string_view tag(n0, static_cast<std::size_t>(p - n0));
      if (tag.empty())
        fail(at, cellforge::detail::cat("expected an element name after '<', found ", quote_token(p, end)));
      attrs.clear();
      bool self_closing = false;
      for (;;) {
        while (p != end && space(*p)) ++p;
        if (p == end)
          fail(at, cellforge::detail::cat("the file ends inside the tag <", std::string(tag), ">"));
        if (*p == '>') {
          ++p;
          break;
        }
        if (*p == '/') {
          if (p + 1 == end || p[1] != '>')
            fail(p, cellforge::detail::cat("expected '/>' in the tag <", std::string(tag), ">"));
          p += 2;
          self_closing = true;
          break;
        }
        const char* a0 = p;
        while (p != end && name_char(*p)) ++p;
        const std::string_view key(a0, static_cast<std::size_t>(p - a0));
        if (key.empty())
          fail(p, cellforge::detail::cat("expected an attribute in the tag <", std::string(tag), ">, found ",
                                         quote_token(p, end)));
        while (p != end && space(*p)) ++p;
        if (p == end || *p != '=')
          fail(p == end ? a0 : p,
               cellforge::detail::cat("expected '=' after the attribute ", std::string(key)));
        ++p;
        while (p != end && space(*p)) ++p;
        if (p == end || (*p != '"' && *p != '\''))
          fail(p == end ? a0 : p,
               cellforge::detail::cat("expected the value of ", std::string(key), " in quotes"));
        const char quote = *p++;
        const char* v0 = p;
        while (p != end && *p != quote) ++p;
        if (p == end)
          fail(v0, cellforge::detail::cat("the file ends inside the value of ", std::string(key)));
        if (!has(attrs, key)) attrs.push_back({key, std::string_view(v0, static_cast<std::size_t>(p - v0))});
        ++p;
      }
      if (!seen_root) {
        if (tag != "svg")
          fail(at, cellforge::detail::cat("expected the root element <svg>, found <", std::string(tag), ">"));
        seen_root = true;
      } else if (stack.empty()) {
        fail(at, cellforge::detail::cat("content after the root element ends: <", std::string(tag), ">"));
      }
      const bool parent_skip = !stack.empty() && stack.back().skip;
      bool skip = parent_skip;
      svg_affine ctm = stack.empty() ? svg_affine{} : stack.back().ctm;
      if (!skip) {
        static constexpr std::string_view silent[] = {"defs", "style",    "text",   "title",
                                                      "desc", "metadata", "script", "tspan"};
        static constexpr std::string_view containers[] = {"svg", "g", "a", "switch"};
        static constexpr std::string_view strokes[] = {"line", "polyline", "polygon", "rect",
                                                       "path", "circle",   "ellipse"};
        const auto in = [&](const auto& list) {
          return std::find(std::begin(list), std::end(list), tag) != std::end(list);
        };
        const std::string_view marker = find(attrs, "data-cellforge");
        if (tag.find(':') != std::string_view::npos || in(silent)) {
          skip = true;
        } else if (options.skip_annotations && has(attrs, "data-cellforge") && marker != "edges") {
          skip = true;
        } else if (options.skip_hidden && hidden(attrs)) {
          skip = true;
          note(at, cellforge::detail::cat("<", std::string(tag), "> is hidden (display none): left out"));
        } else if (in(containers) || in(strokes)) {
          ctm = ctm.then(transform(find(attrs, "transform")));
          if (tag == "svg" && !stack.empty())
            ctm = ctm.then(
                svg_affine{1, 0, 0, 1, length(find(attrs, "x"), 0, "x"), length(find(attrs, "y"), 0, "y")});
          if (in(strokes)) shape(tag, attrs, ctm, at);
        } else {
          skip = true;
          note(at, cellforge::detail::cat("<", std::string(tag), "> is not a stroke or a group: left out"));
        }
        if (skip) ++skipped_elements;
      }
      if (!self_closing) {
        if (tag == "style" || tag == "script") {
          // Raw text that may hold '<': skip to the closing tag.
          const std::string close = cellforge::detail::cat("</", std::string(tag));
          p = skip_past(p, close, at, (cellforge::detail::cat("<", std::string(tag), ">")).c_str()) -
              close.size();
        }
        stack.push_back({tag, at, ctm, skip});
      }
    }
    if (!seen_root) fail(text.data() + text.size(), "no <svg> element: not an SVG file");
    if (!stack.empty())
      fail(text.data() + text.size(),
           cellforge::detail::cat(
               "the file ends inside <", std::string(stack.back().name), "> of line ",
               std::to_string(line_of(text, static_cast<std::size_t>(stack.back().at - text.data())))));
  }
};

/// The SVG stroke reader of parse_svg_drawing (arcs = false: A commands as options.curves says)
/// and parse_svg_arc_drawing (arcs = true). O(size + S log S + K).
template <Point2 P2>
svg_arc_drawing_result<P2> parse_svg_strokes(std::string_view text, std::string_view name,
                                             const svg_drawing_options& options, bool arcs) {
  const cellforge::detail::stopwatch clock;
  if (!std::isfinite(options.snap_tolerance) || options.snap_tolerance < 0 || options.snap_tolerance >= 0.5)
    throw error(error_category::invalid_input,
                "parse_svg_drawing: snap_tolerance must be a finite number in [0, 0.5)");
  svg_reader r{text, name, options, {}, arcs, {}, 0, 0, 0, {}, 0, 1};
  if (text.starts_with("\xEF\xBB\xBF")) r.text.remove_prefix(3);
  r.document();
  svg_arc_drawing_result<P2> out;
  out.arcs = r.arcs.size();
  out.elements = r.elements;
  out.segments = r.segs.size();
  out.skipped_curves = r.skipped_curves;
  out.skipped_elements = r.skipped_elements;
  out.diagnostics = std::move(r.diagnostics);
  if (r.segs.empty() && r.arcs.empty()) {
    out.diagnostics.push_back(cellforge::detail::cat(
        std::string(name), (arcs ? ": no straight stroke or arc found" : ": no straight stroke found")));
    out.milliseconds = clock.ms();
    return out;
  }
  // Strokes in the drawing's frame, y up: the rotation and the sweep's sense flip with y.
  std::vector<std::pair<glm::dvec2, glm::dvec2>> segs(r.segs.size());
  for (std::size_t s = 0; s < segs.size(); ++s)
    segs[s] = {{r.segs[s].first.x, -r.segs[s].first.y}, {r.segs[s].second.x, -r.segs[s].second.y}};
  std::vector<stroke_arc> arc_strokes(r.arcs.size());
  for (std::size_t k = 0; k < arc_strokes.size(); ++k) {
    const auto& a = r.arcs[k];
    arc_strokes[k] = {{a.from.x, -a.from.y}, {a.to.x, -a.to.y}, a.rx, a.ry, -a.rotation, a.large, !a.sweep};
  }
  stroke_snap_counts counts;
  out.drawing = snap_strokes<P2>(
      segs, arc_strokes, options.snap_tolerance, options.split_at_junctions, name,
      [&](std::size_t k) { return r.line(r.arcs[k].at); }, counts, out.diagnostics);
  out.snapped = counts.snapped;
  out.dropped_zero_length = counts.dropped_zero_length;
  out.merged_duplicates = counts.merged_duplicates;
  out.split_at_junctions = counts.split_at_junctions;
  out.milliseconds = clock.ms();
  return out;
}

}  // namespace detail

template <Point2 P2>
svg_drawing_result<P2> parse_svg_drawing(std::string_view text, std::string_view name,
                                         const svg_drawing_options& options) {
  svg_arc_drawing_result<P2> r = detail::parse_svg_strokes<P2>(text, name, options, false);
  svg_drawing_result<P2> out;
  static_cast<svg_reading_counts&>(out) = std::move(static_cast<svg_reading_counts&>(r));
  out.drawing = std::move(r.drawing.lines);
  return out;
}

template <Point2 P2>
svg_arc_drawing_result<P2> parse_svg_arc_drawing(std::string_view text, std::string_view name,
                                                 const svg_drawing_options& options) {
  return detail::parse_svg_strokes<P2>(text, name, options, true);
}

template <Point2 P2>
svg_arc_drawing_result<P2> read_svg_arc_drawing(const file_path& path, const svg_drawing_options& options) {
  return detail::read_and_parse(path, [&](std::string_view bytes, const std::string& name) {
    return parse_svg_arc_drawing<P2>(bytes, name, options);
  });
}

template <Point2 P2>
svg_drawing_result<P2> read_svg_drawing(const file_path& path, const svg_drawing_options& options) {
  return detail::read_and_parse(path, [&](std::string_view bytes, const std::string& name) {
    return parse_svg_drawing<P2>(bytes, name, options);
  });
}

}  // namespace cellforge::io
