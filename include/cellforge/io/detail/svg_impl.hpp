// SPDX-License-Identifier: MIT
#pragma once
// The picture engine of basic_svg_scene: projection, hidden lines, edges and the SVG text
// (included by io/svg.hpp).

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <ostream>
#include <ranges>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/bounding_box.hpp"
#include "cellforge/core/detail/edge_table.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/polygon_soup.hpp"
#include "cellforge/core/wireframe.hpp"
#include "cellforge/halfedge/conversion.hpp"
#include "cellforge/halfedge/surface_mesh.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/svg_visibility.hpp"
#include "cellforge/io/detail/xml.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/io/svg.hpp"

namespace cellforge::io {

template <class U>
auto basic_svg_scene<U>::render(const svg_options& o) const -> frame {
  check_options(o);
  frame fr;
  const std::size_t np = points_.size(), nf = face_layer_.size();
  const auto [right, up, toward] = camera(o.view);
  fr.toward = toward;
  bounding_box box;
  for (const auto& p : points_) box.add(p);
  const glm::dvec3 centre = box.center();
  const double diag = box.diagonal();
  if (!std::isfinite(diag)) fail("write: the scene is too large to draw (its extent overflows)");

  // Orthographic projection, then fit to the viewport keeping the aspect ratio, y down.
  fr.screen.resize(np);
  glm::dvec2 lo(0.0), hi(0.0);
  for (std::size_t i = 0; i < np; ++i) {
    const glm::dvec3 d = points_[i] - centre;
    fr.screen[i] = {glm::dot(d, right), glm::dot(d, up), glm::dot(d, toward)};
    const glm::dvec2 s(fr.screen[i]);
    lo = i == 0 ? s : glm::min(lo, s);
    hi = i == 0 ? s : glm::max(hi, s);
  }
  const double aw = o.width - 2.0 * o.margin, ah = o.height - 2.0 * o.margin;
  const double ex = hi.x - lo.x, ey = hi.y - lo.y;
  double scale = 1.0;
  if (ex > 0.0 && ey > 0.0)
    scale = std::min(aw / ex, ah / ey);
  else if (ex > 0.0)
    scale = aw / ex;
  else if (ey > 0.0)
    scale = ah / ey;
  if (!std::isfinite(scale)) scale = 1.0;  // a subnormal extent: the scene is one point
  const glm::dvec2 mid = 0.5 * (lo + hi);
  for (auto& s : fr.screen) {
    s.x = 0.5 * o.width + (s.x - mid.x) * scale;
    s.y = 0.5 * o.height - (s.y - mid.y) * scale;
  }

  // Points at exactly the same place are one vertex, across layers: a soup with split
  // vertices still has shared edges, and a line drawn along a mesh edge is not hidden by it.
  fr.weld.resize(np);
  {
    struct key_hash {
      std::size_t operator()(const std::array<std::uint64_t, 3>& k) const noexcept {
        std::uint64_t h = k[0] * 0x9E3779B97F4A7C15ull;
        h = (h ^ (h >> 29) ^ k[1]) * 0xBF58476D1CE4E5B9ull;
        h = (h ^ (h >> 31) ^ k[2]) * 0x94D049BB133111EBull;
        return static_cast<std::size_t>(h ^ (h >> 32));
      }
    };
    std::unordered_map<std::array<std::uint64_t, 3>, std::uint32_t, key_hash> ids;
    ids.reserve(np);
    for (std::size_t i = 0; i < np; ++i) {
      const glm::dvec3 p = points_[i] + glm::dvec3(0.0);  // -0 and +0 are one place
      const std::array<std::uint64_t, 3> k{std::bit_cast<std::uint64_t>(p.x),
                                           std::bit_cast<std::uint64_t>(p.y),
                                           std::bit_cast<std::uint64_t>(p.z)};
      fr.weld[i] = ids.try_emplace(k, static_cast<std::uint32_t>(i)).first->second;
    }
  }

  // Faces: normal, facing, drawn; painter's order by mean depth, far to near.
  fr.face_normal.resize(nf);
  fr.face_drawn.assign(nf, 0);
  fr.face_facing.assign(nf, 0);
  std::vector<double> depth(nf, 0.0);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto vs = face(f);
    if (vs.size() < 3) continue;
    const glm::dvec3 n = detail::svg_newell(vs.size(), [&](std::size_t i) { return points_[vs[i]]; });
    fr.face_normal[f] = n;
    const double len = glm::length(n);
    if (!(len > 0.0)) continue;
    const bool facing = glm::dot(n, toward) > 0.0;
    if (layers_[face_layer_[f]].style.cull_back_faces && !facing) continue;
    fr.face_drawn[f] = 1;
    fr.face_facing[f] = facing ? 1 : 0;
    for (const auto v : vs) depth[f] += fr.screen[v].z;
    depth[f] /= static_cast<double>(vs.size());
    fr.order.push_back(static_cast<std::uint32_t>(f));
  }
  std::stable_sort(fr.order.begin(), fr.order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return depth[a] < depth[b]; });

  // Occluders: the drawn faces of layers that occlude. A face hides what is behind it by
  // more than eps; one sharing an end with an edge, by more than eps_shared (they meet
  // there exactly, so only rounding needs covering).
  const double eps = o.depth_epsilon * diag;
  const double eps_shared = 1e-3 * eps;
  detail::occlusion_grid grid;
  {
    std::vector<glm::dvec3> poly;
    for (const auto f : fr.order) {
      if (!layers_[face_layer_[f]].style.occludes) continue;
      poly.clear();
      for (const auto v : face(f)) poly.push_back(fr.screen[v]);
      grid.add_face(f, poly);
    }
    grid.build(eps_shared);  // the least margin the tests below ask for
  }

  // Every face side by welded vertex pair, sorted: the faces an edge belongs to.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> sides;
  sides.reserve(face_vertices_.size());
  for (std::size_t f = 0; f < nf; ++f) {
    const auto vs = face(f);
    for (std::size_t i = 0; i < vs.size(); ++i) {
      const std::uint32_t a = fr.weld[vs[i]], b = fr.weld[vs[(i + 1) % vs.size()]];
      if (a != b) sides.emplace_back(detail::svg_edge_key(a, b), static_cast<std::uint32_t>(f));
    }
  }
  std::sort(sides.begin(), sides.end());
  sides.erase(std::unique(sides.begin(), sides.end()), sides.end());
  const auto faces_of = [&](std::uint64_t key) {
    const auto lo_it =
        std::lower_bound(sides.begin(), sides.end(), std::pair<std::uint64_t, std::uint32_t>(key, 0));
    auto hi_it = lo_it;
    while (hi_it != sides.end() && hi_it->first == key) ++hi_it;
    return std::span<const std::pair<std::uint64_t, std::uint32_t>>(lo_it, hi_it);
  };

  collect_edges(fr, faces_of);

  // Whether face f has welded vertex w: a scan of a small face, a binary search for a large
  // one (so a 20 000-gon costs O(log) per test, not 20 000).
  constexpr std::size_t large_face = detail::occlusion_grid::banded_face_size;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> large_corners;  // (face, welded vertex)
  for (std::size_t f = 0; f < nf; ++f)
    if (face(f).size() > large_face)
      for (const auto v : face(f)) large_corners.emplace_back(static_cast<std::uint32_t>(f), fr.weld[v]);
  std::sort(large_corners.begin(), large_corners.end());
  const auto has_vertex = [&](std::uint32_t f, std::uint32_t w) {
    const auto vs = face(f);
    if (vs.size() > large_face)
      return std::binary_search(large_corners.begin(), large_corners.end(), std::make_pair(f, w));
    return std::any_of(vs.begin(), vs.end(), [&](std::uint32_t v) { return fr.weld[v] == w; });
  };

  // Split every edge into hidden and visible parts: exactly while the work budget lasts,
  // then from the midpoint against a few of the nearest faces, then not at all.
  std::size_t num_points = 0;
  for (const auto& l : layers_)
    if (l.kind == layer_kind::points) num_points += l.point_end - l.point_begin;
  const std::uint64_t budget =
      o.work_budget.limit(16'000'000 + 256 * std::uint64_t{fr.edges.size() + num_points});
  const std::uint64_t hard_limit = budget > detail::occlusion_grid::no_limit / 2 ? budget : 2 * budget;
  constexpr std::size_t approximate_faces = 16;  // nearest faces looked at past the budget
  for (auto& e : fr.edges) {
    const std::uint32_t wa = fr.weld[e.a], wb = fr.weld[e.b];
    const auto adjacent = faces_of(detail::svg_edge_key(wa, wb));  // sorted by face
    const auto margin = [&](std::uint32_t f) -> double {
      if (!adjacent.empty() &&
          std::binary_search(adjacent.begin(), adjacent.end(),
                             std::pair<std::uint64_t, std::uint32_t>(adjacent[0].first, f)))
        return -1.0;  // a face the edge belongs to
      return has_vertex(f, wa) || has_vertex(f, wb) ? eps_shared : eps;
    };
    const glm::dvec3 &a = fr.screen[e.a], &b = fr.screen[e.b];
    if (grid.work() <= budget && grid.hidden_intervals(a, b, margin, e.hidden, budget)) {
      const double len = glm::length(glm::dvec2(b) - glm::dvec2(a));
      normalise(e.hidden, len > 0.0 ? o.min_piece_px / len : 0.0);
      continue;
    }
    e.hidden.clear();
    e.quality = 2;
    if (grid.work() > hard_limit) continue;
    const int h = grid.point_test(0.5 * (a + b), margin, hard_limit, approximate_faces);
    if (h < 0) continue;
    e.quality = 1;
    if (h > 0) e.hidden.push_back({0.0, 1.0});
  }

  fr.point_hidden.assign(np, 0);
  for (const auto& l : layers_) {
    if (l.kind != layer_kind::points) continue;
    for (std::uint32_t i = l.point_begin; i < l.point_end; ++i) {
      const std::uint32_t w = fr.weld[i];
      const auto margin = [&](std::uint32_t f) -> double {
        return has_vertex(f, w) ? -1.0 : eps;  // a vertex of the face is on it, not behind it
      };
      const bool exact = grid.work() <= budget;
      const int h = grid.point_test(fr.screen[i], margin, exact ? budget : hard_limit,
                                    exact ? std::numeric_limits<std::size_t>::max() : approximate_faces);
      if (h < 0 || !exact) ++(h < 0 ? fr.untested_points : fr.approximate_points);
      fr.point_hidden[i] = h > 0 ? 1 : 0;
    }
  }
  fr.work = grid.work();
  return fr;
}

template <class U>
template <class FacesOf>
void basic_svg_scene<U>::collect_edges(frame& fr, FacesOf&& faces_of) const {
  for (std::size_t li = 0; li < layers_.size(); ++li) {
    const layer& l = layers_[li];
    if (l.kind == layer_kind::lines) {
      for (std::uint32_t s = l.segment_begin; s < l.segment_end; ++s) {
        const auto [a, b] = segments_[s];
        if (fr.weld[a] != fr.weld[b]) fr.edges.push_back({li, a, b, {}});
      }
    }
    if (l.kind != layer_kind::mesh || !l.style.draw_edges) continue;
    cellforge::detail::edge_table seen;  // welded edges drawn so far
    const double cos_feature = std::cos(l.style.feature_angle_deg * std::numbers::pi / 180.0);
    for (std::uint32_t f = l.face_begin; f < l.face_end; ++f) {
      const auto vs = face(f);
      for (std::size_t i = 0; i < vs.size(); ++i) {
        const std::uint32_t a = vs[i], b = vs[(i + 1) % vs.size()];
        const std::uint32_t wa = fr.weld[a], wb = fr.weld[b];
        if (wa == wb) continue;
        const std::uint64_t key = detail::svg_edge_key(wa, wb);
        if (!seen.try_insert(key, 0)) continue;
        if (l.style.feature_angle_deg > 0.0 && !is_feature(fr, faces_of(key), li, wa, wb, cos_feature))
          continue;
        fr.edges.push_back({li, a, b, {}});
      }
    }
  }
}

template <class U>
bool basic_svg_scene<U>::is_feature(const frame& fr,
                                    std::span<const std::pair<std::uint64_t, std::uint32_t>> sides,
                                    std::size_t li, std::uint32_t wa, std::uint32_t wb,
                                    double cos_feature) const {
  std::array<std::uint32_t, 2> two{};
  std::size_t count = 0;
  for (const auto& s : sides)
    if (face_layer_[s.second] == li) {
      if (count < 2) two[count] = s.second;
      ++count;
    }
  if (count != 2) return true;
  const auto runs_forward = [&](std::uint32_t f) {
    const auto vs = face(f);
    for (std::size_t i = 0; i < vs.size(); ++i)
      if (fr.weld[vs[i]] == wa && fr.weld[vs[(i + 1) % vs.size()]] == wb) return true;
    return false;
  };
  glm::dvec3 n0 = fr.face_normal[two[0]], n1 = fr.face_normal[two[1]];
  const double l0 = glm::length(n0), l1 = glm::length(n1);
  if (!(l0 > 0.0) || !(l1 > 0.0)) return true;
  n0 /= l0;
  n1 /= l1;
  // Consistently oriented neighbours run along their shared edge in opposite directions.
  if (runs_forward(two[0]) == runs_forward(two[1])) n1 = -n1;
  if (glm::dot(n0, fr.toward) * glm::dot(n1, fr.toward) < 0.0) return true;  // silhouette
  return glm::dot(n0, n1) < cos_feature;
}

template <class U>
svg_result basic_svg_scene<U>::write_to(std::string& out, const svg_options& o) const {
  const cellforge::detail::stopwatch clock;
  const frame fr = render(o);
  svg_result r;
  for (const auto& e : fr.edges) {
    r.approximate_edges += e.quality == 1 ? 1 : 0;
    r.untested_edges += e.quality == 2 ? 1 : 0;
  }
  r.approximate_points = fr.approximate_points;
  r.untested_points = fr.untested_points;
  r.work = fr.work;
  const int prec = o.precision;
  const auto num = [&](double v) { detail::svg_number(out, v, prec); };
  const auto attr = [&](std::string_view name, std::string_view value) {
    out += ' ';
    out += name;
    out += "=\"";
    detail::svg_escape(out, value);
    out += '"';
  };
  const auto num_attr = [&](std::string_view name, double v) {
    out += ' ';
    out += name;
    out += "=\"";
    num(v);
    out += '"';
  };

  out += "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"no\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\"";
  out += cellforge::detail::cat(" width=\"", std::to_string(o.width), "\" height=\"",
                                std::to_string(o.height), "\"");
  out += cellforge::detail::cat(" viewBox=\"0 0 ", std::to_string(o.width), " ", std::to_string(o.height),
                                "\">\n");
  if (!o.title.empty()) {
    out += "<title>";
    detail::svg_escape(out, o.title);
    out += "</title>\n";
  }
  if (r.approximate_edges + r.untested_edges + r.approximate_points + r.untested_points > 0) {
    r.complete = false;
    r.diagnostics.push_back(cellforge::detail::cat(
        "the hidden-line work budget ran out: ", std::to_string(r.approximate_edges + r.approximate_points),
        " edges and points judged from one point, ", std::to_string(r.untested_edges + r.untested_points),
        " not tested (drawn visible); raise svg_options::work_budget for exact hidden lines"));
    out += cellforge::detail::cat("<!-- cellforge: ", r.diagnostics.back(), " -->\n");
  }
  if (!o.background.empty() && o.background != "none") {
    out += "<rect width=\"100%\" height=\"100%\"";
    attr("fill", o.background);
    out += "/>\n";
  }

  // Faces, far to near, each filled with its Lambert shade; a hairline of the same colour
  // closes the anti-aliasing cracks between neighbours.
  const glm::dvec3 light = glm::normalize(o.light);
  const auto [right, up, toward] = camera(o.view);
  if (!fr.order.empty()) {
    out += "<g stroke-width=\"0.5\" stroke-linejoin=\"round\">\n";
    std::string colour;
    for (const auto f : fr.order) {
      const svg_style& st = layers_[face_layer_[f]].style;
      const glm::dvec3 n = glm::normalize(fr.face_normal[f]);
      glm::dvec3 nc(glm::dot(n, right), glm::dot(n, up), glm::dot(n, toward));
      if (nc.z < 0.0) nc = -nc;  // two-sided: shade the side the viewer sees
      const double shade = o.ambient + (1.0 - o.ambient) * std::max(0.0, glm::dot(nc, light));
      colour.clear();
      if (const auto rgb = detail::svg_parse_hex(st.fill))
        detail::svg_hex_colour(colour, *rgb * shade);
      else
        colour = st.fill;
      out += "<polygon points=\"";
      bool first = true;
      for (const auto v : face(f)) {
        if (!first) out += ' ';
        first = false;
        num(fr.screen[v].x);
        out += ',';
        num(fr.screen[v].y);
      }
      out += '"';
      attr("fill", colour);
      if (st.opacity < 1.0) {
        num_attr("fill-opacity", st.opacity);
        out += " stroke=\"none\"";  // a hairline would double the opacity at shared sides
      } else {
        attr("stroke", colour);
      }
      out += "/>\n";
      ++r.faces_drawn;
      if (fr.face_facing[f]) ++r.faces_facing_viewer;
    }
    out += "</g>\n";
  }

  // Edge counts, then hidden parts (dashed, see-through, over the faces), then visible parts.
  for (const auto& e : fr.edges) {
    ++r.edges;
    if (e.hidden.empty())
      ++r.visible_edges;
    else if (e.hidden.size() == 1 && e.hidden[0][0] == 0.0 && e.hidden[0][1] == 1.0)
      ++r.hidden_edges;
    else
      ++r.partly_hidden_edges;
    r.hidden_pieces += e.hidden.size();
    double t = 0.0;
    for (const auto& h : e.hidden) {
      if (h[0] > t) ++r.visible_pieces;
      t = h[1];
    }
    if (t < 1.0) ++r.visible_pieces;
  }
  for (const bool hidden_pass : {true, false}) {
    std::size_t next = 0;
    for (std::size_t li = 0; li < layers_.size(); ++li) {
      const svg_style& st = layers_[li].style;
      std::string d;
      std::string last;  // the pen's position as written: chains pieces that meet
      const auto piece = [&](const glm::dvec3& a, const glm::dvec3& b, double t0, double t1) {
        const glm::dvec2 p = glm::dvec2(a) + t0 * (glm::dvec2(b) - glm::dvec2(a));
        const glm::dvec2 q = glm::dvec2(a) + t1 * (glm::dvec2(b) - glm::dvec2(a));
        std::string start;
        detail::svg_number(start, p.x, prec);
        start += ' ';
        detail::svg_number(start, p.y, prec);
        if (start != last) {
          d += 'M';
          d += start;
        }
        d += 'L';
        last.clear();
        detail::svg_number(last, q.x, prec);
        last += ' ';
        detail::svg_number(last, q.y, prec);
        d += last;
      };
      for (; next < fr.edges.size() && fr.edges[next].layer == li; ++next) {
        const edge& e = fr.edges[next];
        const glm::dvec3 &a = fr.screen[e.a], &b = fr.screen[e.b];
        if (hidden_pass) {
          for (const auto& h : e.hidden) piece(a, b, h[0], h[1]);
        } else {
          double t = 0.0;
          for (const auto& h : e.hidden) {
            if (h[0] > t) piece(a, b, t, h[0]);
            t = h[1];
          }
          if (t < 1.0) piece(a, b, t, 1.0);
        }
      }
      if (d.empty() || (hidden_pass && !st.draw_hidden)) continue;
      out += "<path";
      attr("d", d);
      out += " fill=\"none\"";
      attr("stroke", hidden_pass ? st.hidden_stroke : st.stroke);
      num_attr("stroke-width", st.stroke_width);
      if (hidden_pass) {
        if (st.hidden_dash.empty()) {
          // Dashes grow with the line so that thick hidden lines still read as dashed.
          const double w = std::max(1.0, st.stroke_width);
          std::string dash;
          detail::svg_number(dash, 4.0 * w, prec);
          dash += ' ';
          detail::svg_number(dash, 3.0 * w, prec);
          attr("stroke-dasharray", dash);
        } else {
          attr("stroke-dasharray", st.hidden_dash);
        }
        num_attr("stroke-opacity", st.hidden_opacity);
        out += " stroke-linejoin=\"round\"/>\n";  // butt caps: round ones would fill the gaps
      } else {
        out += " stroke-linecap=\"round\" stroke-linejoin=\"round\"/>\n";
      }
    }
  }

  // Points: hidden ones faint beneath the visible ones; then labels on top of everything.
  for (const auto& l : layers_) {
    if (l.kind != layer_kind::points) continue;
    for (const bool hidden_pass : {true, false}) {
      std::string body;
      for (std::uint32_t i = l.point_begin; i < l.point_end; ++i) {
        if (static_cast<bool>(fr.point_hidden[i]) != hidden_pass) continue;
        ++(hidden_pass ? r.points_hidden : r.points_visible);
        if (hidden_pass && !l.style.draw_hidden) continue;
        body += "<circle cx=\"";
        detail::svg_number(body, fr.screen[i].x, prec);
        body += "\" cy=\"";
        detail::svg_number(body, fr.screen[i].y, prec);
        body += "\" r=\"";
        detail::svg_number(body, l.radius, prec);
        body += "\"/>\n";
      }
      if (body.empty()) continue;
      // Hidden points are hollow rings in the hidden colour: they must not read as visible.
      out += "<g";
      attr("fill", hidden_pass ? std::string_view("none") : std::string_view(l.style.fill));
      attr("stroke", hidden_pass ? l.style.hidden_stroke : l.style.stroke);
      num_attr("stroke-width", l.style.stroke_width);
      if (hidden_pass) num_attr("opacity", l.style.hidden_opacity);
      out += ">\n";
      out += body;
      out += "</g>\n";
    }
  }
  for (const auto& l : layers_) {
    if (l.kind != layer_kind::label) continue;
    const glm::dvec3& p = fr.screen[l.point_begin];
    out += "<text";
    num_attr("x", p.x + 0.3 * l.style.font_size);
    num_attr("y", p.y - 0.3 * l.style.font_size);
    num_attr("font-size", l.style.font_size);
    out += " font-family=\"sans-serif\"";
    attr("fill", l.style.stroke);
    out += '>';
    detail::svg_escape(out, l.text);
    out += "</text>\n";
    ++r.labels;
  }
  out += "</svg>\n";
  r.milliseconds = clock.ms();
  return r;
}

}  // namespace cellforge::io
