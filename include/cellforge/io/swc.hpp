// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// SWC, the neuron-morphology format, as a skeleton graph: one sample per line,
/// `id type x y z radius parent`, `#` comments, parent -1 for a root. The single-point and
/// the three-point (NeuroMorpho) soma conventions are understood. A graph with cycles (vessels
/// that join again) keeps its extra edges as `# LINK from to` comment lines, which other SWC
/// readers skip. See docs/formats.md ("SWC").

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/detail/union_find.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/core/point_traits.hpp"
#include "cellforge/core/stage_report.hpp"
#include "cellforge/io/detail/output_buffer.hpp"
#include "cellforge/io/detail/read_file.hpp"
#include "cellforge/io/detail/text_cursor.hpp"
#include "cellforge/io/file_path.hpp"
#include "cellforge/tubes/skeleton.hpp"

namespace cellforge::io {

/// A skeleton read from SWC, with what SWC says about each node beyond position and radius.
/// Edges run from a sample's parent to the sample (away from the root), in file order, then
/// one per `# LINK from to` line, in file order. stage_report: milliseconds the parse, a
/// diagnostic per collapsed soma count.
template <Point3 P>
struct swc_result : stage_report {
  cellforge::skeleton<P> skeleton;  ///< nodes in file order (less the collapsed soma points)
  std::vector<std::int32_t> types;  ///< the SWC structure type of each node (1 soma, 2 axon, ...)
  std::vector<std::int64_t> ids;    ///< the sample id of each node in the file
  std::size_t collapsed_somas = 0;  ///< three-point somas read as one node
};

/// How SWC files are read.
struct swc_read_options {
  /// Read a three-point soma (NeuroMorpho) as the one node at its centre, its radius that of the
  /// soma, with the outer points' children attached to it. Off: three nodes and two edges.
  bool collapse_three_point_soma = true;
};

/// How SWC files are written.
struct swc_write_options {
  /// Written as '#' comment lines at the top when not empty.
  std::string comment{};
  /// The type written for every node of a skeleton that has none (0: undefined).
  std::int32_t type = 0;
};

namespace detail {

/// The name of SWC field k (0-based) of a sample, for messages: "the radius of sample 3". O(1).
template <class = void>
std::string swc_field(std::int64_t id, int k) {
  constexpr const char* names[] = {"id",           "type",   "x coordinate", "y coordinate",
                                   "z coordinate", "radius", "parent"};
  return cellforge::detail::cat(std::string("the "), names[k], " of sample ", std::to_string(id), " (field ",
                                std::to_string(k + 1), " of 7: id type x y z radius parent)");
}

/// Each sample's index in the file (of `n`) by id; fails on the first id used twice. O(n log n).
template <class = void>
std::vector<std::pair<std::int64_t, std::uint32_t>> swc_index_by_id(text_cursor& c,
                                                                    const std::vector<std::int64_t>& ids,
                                                                    const std::vector<const char*>& lines) {
  std::vector<std::pair<std::int64_t, std::uint32_t>> by_id(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) by_id[i] = {ids[i], static_cast<std::uint32_t>(i)};
  if (!std::is_sorted(by_id.begin(), by_id.end())) std::sort(by_id.begin(), by_id.end());
  std::uint32_t later = std::numeric_limits<std::uint32_t>::max(), earlier = later;
  for (std::size_t k = 1; k < by_id.size(); ++k)
    if (by_id[k].first == by_id[k - 1].first && by_id[k].second < later) {
      later = by_id[k].second;
      earlier = by_id[k - 1].second;
    }
  if (later != std::numeric_limits<std::uint32_t>::max())
    c.fail_at(lines[later], cellforge::detail::cat(
                                "sample id ", std::to_string(ids[later]), " is used twice (first on line ",
                                std::to_string(line_of({c.begin, static_cast<std::size_t>(c.end - c.begin)},
                                                       static_cast<std::size_t>(lines[earlier] - c.begin))),
                                ")"));
  return by_id;
}

/// Fails at a cycle of parents (samples that reach no root), naming its samples. O(n).
template <class = void>
void swc_check_cycles(text_cursor& c, const std::vector<std::uint32_t>& parent,
                      const std::vector<std::int64_t>& ids, const std::vector<const char*>& lines) {
  constexpr std::uint32_t root = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint8_t> state(parent.size(), 0);  // 0 unseen, 1 on the current walk, 2 reaches a root
  std::vector<std::uint32_t> walk;
  for (std::size_t start = 0; start < parent.size(); ++start) {
    walk.clear();
    std::uint32_t v = static_cast<std::uint32_t>(start);
    while (v != root && state[v] == 0) {
      state[v] = 1;
      walk.push_back(v);
      v = parent[v];
    }
    if (v != root && state[v] == 1) {
      // v is on this walk: the cycle is the walk from v on. Name it from its earliest line.
      const auto from = std::find(walk.begin(), walk.end(), v);
      const auto first = std::min_element(from, walk.end());
      std::string text = std::to_string(ids[*first]);
      std::uint32_t u = parent[*first];
      for (int shown = 0; u != *first && shown < 8; ++shown, u = parent[u])
        text += cellforge::detail::cat(" -> ", std::to_string(ids[u]));
      text += u == *first ? cellforge::detail::cat(" -> ", std::to_string(ids[u])) : std::string(" -> ...");
      c.fail_at(lines[*first],
                cellforge::detail::cat("the parents form a cycle with no root: ", text,
                                       " (each arrow leads to the parent; a tree starts at a parent -1)"));
    }
    for (const std::uint32_t w : walk) state[w] = 2;
  }
}

/// Marks the outer points of each three-point soma (NeuroMorpho: a type-1 centre with exactly
/// two type-1 children at ±r along y, radius r, within 1 % of r) as folded into their centre:
/// `into[i]` is the centre for them, i otherwise. Returns the number of somas. O(n).
template <class = void>
std::size_t swc_three_point_somas(const std::vector<std::array<double, 4>>& xyzr,
                                  const std::vector<std::int32_t>& types,
                                  const std::vector<std::uint32_t>& parent,
                                  std::vector<std::uint32_t>& into) {
  constexpr std::uint32_t root = std::numeric_limits<std::uint32_t>::max();
  const std::size_t n = parent.size();
  // The first two type-1 children of each type-1 sample, and how many it has.
  std::vector<std::array<std::uint32_t, 2>> soma_children(n, {root, root});
  std::vector<std::uint8_t> count(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t p = parent[i];
    if (p == root || types[i] != 1 || types[p] != 1) continue;
    if (count[p] < 2) soma_children[p][count[p]] = static_cast<std::uint32_t>(i);
    if (count[p] < 3) ++count[p];
  }
  std::vector<std::uint8_t> role(n, 0);  // 1 centre, 2 outer point
  std::size_t somas = 0;
  for (std::size_t a = 0; a < n; ++a) {
    if (count[a] != 2 || role[a] != 0) continue;
    const auto [b, c] = soma_children[a];
    if (role[b] != 0 || role[c] != 0) continue;
    const double r = xyzr[a][3], tol = 0.01 * r;
    const auto offset = [&](std::uint32_t q) {  // +1 / -1 when q is at the centre ± r along y, else 0
      if (std::fabs(xyzr[q][0] - xyzr[a][0]) > tol || std::fabs(xyzr[q][2] - xyzr[a][2]) > tol ||
          std::fabs(xyzr[q][3] - r) > tol)
        return 0;
      const double dy = xyzr[q][1] - xyzr[a][1];
      return std::fabs(dy - r) <= tol ? 1 : std::fabs(dy + r) <= tol ? -1 : 0;
    };
    const int ob = offset(b), oc = offset(c);
    if (ob == 0 || ob + oc != 0) continue;
    role[a] = 1;
    role[b] = role[c] = 2;
    into[b] = into[c] = static_cast<std::uint32_t>(a);
    ++somas;
  }
  return somas;
}

/// Reads a comment line that is a LINK (`# LINK from to`: an edge beyond the tree, from sample
/// `from` to sample `to`) into `ids` / `at`; any other comment is left alone. The cursor is on
/// the '#'. Throws at the line when it starts as a LINK (a number after the word) but is not
/// one. O(line).
template <class = void>
void swc_link_line(text_cursor& c, std::vector<std::array<std::int64_t, 2>>& ids,
                   std::vector<const char*>& at) {
  const char* line = c.pos;
  const char* q = c.pos + 1;
  while (q != c.end && is_blank(*q)) ++q;
  if (c.end - q < 5 || std::string_view(q, 4) != "LINK" || !is_blank(q[4])) return;
  q += 4;
  while (q != c.end && is_blank(*q)) ++q;
  if (q == c.end || !((*q >= '0' && *q <= '9') || *q == '-' || *q == '+')) return;  // prose
  const char* const saved = c.pos;
  const char comment = c.comment;
  c.comment = '\0';  // the rest of the line is the LINK's
  c.pos = q;
  const auto field = [](const char* which) {
    return cellforge::detail::cat(std::string("the "), which, " sample of a LINK line (# LINK from to)");
  };
  const std::int64_t from = c.integer([&] { return field("first"); });
  const std::int64_t to = c.integer([&] { return field("second"); });
  c.skip_blanks();
  if (!c.at_line_end())
    c.fail(cellforge::detail::cat("unexpected ", c.token(),
                                  " after the two samples of a LINK line (# LINK from to)"));
  c.comment = comment;
  c.pos = saved;
  ids.push_back({from, to});
  at.push_back(line);
}

/// Appends the edges of the LINK lines (ids resolved through `by_id`, samples folded into a
/// soma through `into`, nodes through `node`) to `edges`; throws at a LINK's line when a sample
/// is not in the file, when it joins a node to itself, or when it repeats an edge. O(E + L log n)
/// expected.
template <class = void>
void swc_add_links(text_cursor& c, const std::vector<std::pair<std::int64_t, std::uint32_t>>& by_id,
                   const std::vector<std::uint32_t>& into, const std::vector<std::uint32_t>& node,
                   const std::vector<std::array<std::int64_t, 2>>& link_ids,
                   const std::vector<const char*>& link_lines,
                   std::vector<std::array<std::uint32_t, 2>>& edges) {
  if (link_ids.empty()) return;
  const std::size_t tree_edges = edges.size();
  for (std::size_t k = 0; k < link_ids.size(); ++k) {
    std::array<std::uint32_t, 2> e{};
    for (std::size_t end = 0; end < 2; ++end) {
      const std::int64_t id = link_ids[k][end];
      const auto it = std::lower_bound(by_id.begin(), by_id.end(), std::pair{id, std::uint32_t{0}});
      if (it == by_id.end() || it->first != id)
        c.fail_at(link_lines[k],
                  cellforge::detail::cat("the LINK's sample ", std::to_string(id), " is not in the file"));
      e[end] = node[into[it->second]];
    }
    const std::string text = std::to_string(link_ids[k][0]) + " " + std::to_string(link_ids[k][1]);
    if (e[0] == e[1])
      c.fail_at(link_lines[k], cellforge::detail::cat("the LINK ", text,
                                                      (link_ids[k][0] == link_ids[k][1]
                                                           ? " joins a sample to itself"
                                                           : " joins two samples read as one soma node")));
    edges.push_back(e);
  }
  // A LINK may not repeat an edge (the tree's or another LINK's), either way round; the tree
  // edges repeat none among themselves, so the first repeat is a LINK.
  const std::size_t repeat = cellforge::detail::first_repeated_edge(edges.size(), [&](std::size_t j) {
    return std::array<std::size_t, 2>{edges[j][0], edges[j][1]};
  })[0];
  if (repeat < edges.size()) {
    const std::size_t k = repeat - tree_edges;
    c.fail_at(link_lines[k], cellforge::detail::cat("the LINK ", std::to_string(link_ids[k][0]), " ",
                                                    std::to_string(link_ids[k][1]),
                                                    " repeats an edge between the same two samples"));
  }
}

}  // namespace detail

/// Parses SWC text held in memory; `name` is used in error messages. Throws an io error with
/// file and line on malformed input (fields, numbers, radii, ids, parents, cycles). O(n log n)
/// for n samples (the ids are sorted to find parents; O(n) when they are already in order).
template <Point3 P>
swc_result<P> parse_swc(std::string_view bytes, std::string_view name = "<memory>",
                        const swc_read_options& options = {}) {
  using S = scalar_t<P>;
  constexpr std::uint32_t root = std::numeric_limits<std::uint32_t>::max();
  const cellforge::detail::stopwatch clock;
  detail::text_cursor c(bytes, name, '#');
  if (bytes.starts_with("\xEF\xBB\xBF")) c.pos += 3;
  std::vector<std::int64_t> ids, parent_ids;
  std::vector<std::int32_t> types;
  std::vector<P> points;
  std::vector<std::array<double, 4>> xyzr;  // positions as read (in S) and radii, for the soma test
  std::vector<const char*> lines;
  std::vector<std::array<std::int64_t, 2>> link_ids;  // `# LINK from to` lines, and where they are
  std::vector<const char*> link_lines;
  for (;;) {
    c.skip_blanks();
    if (c.at_end()) break;
    if (c.at_line_end()) {  // a blank or comment line; a comment may be a LINK
      if (*c.pos == '#') detail::swc_link_line(c, link_ids, link_lines);
      c.next_line();
      continue;
    }
    const char* line = c.pos;
    const std::int64_t id =
        c.integer([] { return std::string("the sample id (field 1 of 7: id type x y z radius parent)"); });
    if (id <= 0)
      c.fail_at(line, cellforge::detail::cat("sample id ", std::to_string(id),
                                             " must be positive (SWC ids start at 1)"));
    if (ids.size() >= root - 1) c.fail_at(line, "too many samples for 32-bit indices");
    c.skip_blanks();
    const char* at = c.pos;
    const std::int64_t type = c.integer([&] { return detail::swc_field(id, 1); });
    if (type < 0 || type > std::numeric_limits<std::int32_t>::max())
      c.fail_at(at,
                cellforge::detail::cat("the type ", std::to_string(type), " of sample ", std::to_string(id),
                                       (type < 0 ? " must not be negative" : " is too large")));
    const S x = c.coordinate<S>([&] { return detail::swc_field(id, 2); });
    const S y = c.coordinate<S>([&] { return detail::swc_field(id, 3); });
    const S z = c.coordinate<S>([&] { return detail::swc_field(id, 4); });
    c.skip_blanks();
    at = c.pos;
    const double radius = c.number<double>([&] { return detail::swc_field(id, 5); });
    if (!std::isfinite(radius) || !(radius > 0))
      c.fail_at(at, cellforge::detail::cat(
                        "the radius of sample ", std::to_string(id), ", ", detail::quote_token(at, c.end),
                        (std::isfinite(radius) ? ", must be positive" : ", is not finite")));
    c.skip_blanks();
    at = c.pos;
    const std::int64_t parent = c.integer([&] { return detail::swc_field(id, 6); });
    if (parent == id)
      c.fail_at(at, cellforge::detail::cat("sample ", std::to_string(id), " is its own parent"));
    if (parent < -1 || parent == 0)
      c.fail_at(
          at, cellforge::detail::cat("the parent ", std::to_string(parent), " of sample ", std::to_string(id),
                                     " is neither -1 (a root) nor a sample id (ids are positive)"));
    c.skip_blanks();
    if (!c.at_line_end())
      c.fail(cellforge::detail::cat("unexpected ", c.token(), " after the 7 fields of sample ",
                                    std::to_string(id), " (id type x y z radius parent)"));
    ids.push_back(id);
    parent_ids.push_back(parent);
    types.push_back(static_cast<std::int32_t>(type));
    points.push_back(point_traits<P>::make(x, y, z));
    xyzr.push_back({static_cast<double>(x), static_cast<double>(y), static_cast<double>(z), radius});
    lines.push_back(line);
    c.next_line();
  }
  const std::size_t n = ids.size();
  const auto by_id = detail::swc_index_by_id(c, ids, lines);
  std::vector<std::uint32_t> parent(n, root);
  for (std::size_t i = 0; i < n; ++i) {
    if (parent_ids[i] == -1) continue;
    const auto it = std::lower_bound(by_id.begin(), by_id.end(), std::pair{parent_ids[i], std::uint32_t{0}});
    if (it == by_id.end() || it->first != parent_ids[i])
      c.fail_at(lines[i], cellforge::detail::cat("the parent ", std::to_string(parent_ids[i]), " of sample ",
                                                 std::to_string(ids[i]), " is not in the file"));
    parent[i] = it->second;
  }
  detail::swc_check_cycles(c, parent, ids, lines);

  swc_result<P> out;
  std::vector<std::uint32_t> into(n);
  for (std::size_t i = 0; i < n; ++i) into[i] = static_cast<std::uint32_t>(i);
  if (options.collapse_three_point_soma)
    out.collapsed_somas = detail::swc_three_point_somas(xyzr, types, parent, into);
  std::vector<std::uint32_t> node(n, root);  // file index -> node index
  auto& s = out.skeleton;
  const std::size_t kept = n - 2 * out.collapsed_somas;
  s.points.reserve(kept);
  s.radii.reserve(kept);
  out.types.reserve(kept);
  out.ids.reserve(kept);
  for (std::size_t i = 0; i < n; ++i) {
    if (into[i] != i) continue;
    node[i] = static_cast<std::uint32_t>(s.points.size());
    s.points.push_back(points[i]);
    s.radii.push_back(xyzr[i][3]);
    out.types.push_back(types[i]);
    out.ids.push_back(ids[i]);
  }
  s.edges.reserve(kept + link_ids.size());
  for (std::size_t i = 0; i < n; ++i)
    if (into[i] == i && parent[i] != root) s.edges.push_back({node[into[parent[i]]], node[i]});
  detail::swc_add_links(c, by_id, into, node, link_ids, link_lines, s.edges);
  if (out.collapsed_somas > 0)
    out.diagnostics.push_back(cellforge::detail::cat(
        std::to_string(out.collapsed_somas),
        " three-point somas read as one node each (swc_read_options::collapse_three_point_soma)"));
  out.milliseconds = clock.ms();
  return out;
}

/// Reads an SWC file. Throws an io error naming the path when it cannot be read, or with file
/// and line when it is malformed. O(file size + n log n).
template <Point3 P>
swc_result<P> read_swc(const file_path& path, const swc_read_options& options = {}) {
  return detail::read_and_parse(path, [&](std::string_view bytes, const std::string& name) {
    return parse_swc<P>(bytes, name, options);
  });
}

namespace detail {

/// What an SWC writer writes, worked out before the first byte: the nodes parents first
/// (the smallest index first among those ready, so a skeleton already in that order keeps
/// it), each node's parent, its id and type, and the edges beyond the forest (LINK lines).
struct swc_plan {
  std::vector<std::uint32_t> order;
  std::vector<std::uint32_t> parent;
  std::vector<std::int64_t> ids;
  std::vector<std::int32_t> types;
  std::vector<std::array<std::uint32_t, 2>> links;
};

/// Checks that g has no defect but coincident nodes and plans its lines: in edge order, an
/// edge a -> b makes a the parent of b when b has none yet and the edge closes no cycle;
/// every other edge is a LINK (so a forest whose edges point away from its roots has none).
/// `ids`/`types` empty: ids are 1, 2, ... in written order and every type is `type`.
/// Throws invalid_input naming the node or edge otherwise. O(V log V + E α(V)).
template <Skeleton G>
swc_plan make_swc_plan(const G& g, std::vector<std::int64_t> ids, std::vector<std::int32_t> types,
                       std::int32_t type) {
  using T = skeleton_traits<G>;
  constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  const auto fail = [](const std::string& m) {
    throw error(error_category::invalid_input, cellforge::detail::cat("write_swc: ", m));
  };
  const std::size_t nv = T::num_nodes(g), ne = T::num_edges(g);
  if (nv >= none) fail("more than 2^32 - 2 nodes");
  if ((!ids.empty() && ids.size() != nv) || (!types.empty() && types.size() != nv))
    fail(cellforge::detail::cat("the ids and types must have one entry per node (", std::to_string(nv), ")"));
  swc_plan plan;
  plan.parent.assign(nv, none);
  // Positions, radii, endpoints, self loops and duplicates as the tube mesher checks them;
  // coincident nodes are no reason to refuse a file.
  cellforge::detail::check_skeleton_writable(g, "write_swc");
  cellforge::detail::union_find trees(nv);
  std::size_t tree_edges = 0;
  for (std::size_t j = 0; j < ne; ++j) {
    const std::array<std::size_t, 2> ab = T::endpoints(g, j);
    const auto a = static_cast<std::uint32_t>(ab[0]), b = static_cast<std::uint32_t>(ab[1]);
    if (plan.parent[b] == none && trees.unite(a, b)) {
      plan.parent[b] = a;
      ++tree_edges;
    } else {
      plan.links.push_back({a, b});
    }
  }
  // Parents first: children lists (CSR), then a min-heap of the nodes whose parent is written.
  std::vector<std::uint32_t> first(nv + 1, 0), child(tree_edges);
  for (std::size_t i = 0; i < nv; ++i)
    if (plan.parent[i] != none) ++first[plan.parent[i] + 1];
  for (std::size_t i = 0; i < nv; ++i) first[i + 1] += first[i];
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  for (std::size_t i = 0; i < nv; ++i)
    if (plan.parent[i] != none) child[fill[plan.parent[i]]++] = static_cast<std::uint32_t>(i);
  const auto later = [](std::uint32_t a, std::uint32_t b) { return a > b; };
  std::vector<std::uint32_t> ready;
  for (std::size_t i = 0; i < nv; ++i)
    if (plan.parent[i] == none) ready.push_back(static_cast<std::uint32_t>(i));  // already a heap
  plan.order.reserve(nv);
  while (!ready.empty()) {
    std::pop_heap(ready.begin(), ready.end(), later);
    const std::uint32_t v = ready.back();
    ready.pop_back();
    plan.order.push_back(v);
    for (std::uint32_t k = first[v]; k < first[v + 1]; ++k) {
      ready.push_back(child[k]);
      std::push_heap(ready.begin(), ready.end(), later);
    }
  }
  if (ids.empty()) {
    ids.resize(nv);
    for (std::size_t k = 0; k < nv; ++k) ids[plan.order[k]] = static_cast<std::int64_t>(k + 1);
  } else {
    std::vector<std::int64_t> sorted = ids;
    std::sort(sorted.begin(), sorted.end());
    if (sorted.front() <= 0)
      fail(cellforge::detail::cat("sample id ", std::to_string(sorted.front()), " is not positive"));
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      fail(cellforge::detail::cat(
          "sample id ", std::to_string(*std::adjacent_find(sorted.begin(), sorted.end())), " is used twice"));
  }
  if (types.empty()) types.assign(nv, type);
  for (std::size_t i = 0; i < nv; ++i)
    if (types[i] < 0)
      fail(cellforge::detail::cat("node ", std::to_string(i), " has the negative type ",
                                  std::to_string(types[i])));
  plan.ids = std::move(ids);
  plan.types = std::move(types);
  return plan;
}

/// Writes the planned lines. O(V).
template <Skeleton G>
void put_swc(std::ostream& os, const G& g, const swc_plan& plan, const swc_write_options& options) {
  using T = skeleton_traits<G>;
  output_buffer out(os);
  put_comment_lines(out, options.comment, "# ");
  for (const std::uint32_t v : plan.order) {
    const auto p = skeleton_point_t<G>(T::position(g, v));
    out.number(plan.ids[v]);
    out.put(' ');
    out.number(plan.types[v]);
    for (std::size_t k = 0; k < 3; ++k) {
      out.put(' ');
      out.number(coord(p, k));
    }
    out.put(' ');
    out.number(static_cast<double>(T::radius(g, v)));
    out.put(' ');
    out.number(plan.parent[v] == std::numeric_limits<std::uint32_t>::max() ? std::int64_t{-1}
                                                                           : plan.ids[plan.parent[v]]);
    out.put('\n');
  }
  for (const std::array<std::uint32_t, 2>& l : plan.links) {
    out.put("# LINK ");
    out.number(plan.ids[l[0]]);
    out.put(' ');
    out.number(plan.ids[l[1]]);
    out.put('\n');
  }
  out.finish("SWC");
}

}  // namespace detail

/// Writes any Skeleton as SWC: a spanning forest of its edges as the samples' parents (ids 1, 2,
/// ... with parents before children, every type `options.type`, numbers in shortest round-trip
/// form), every other edge as a `# LINK from to` line at the end (read back by parse_swc;
/// skipped as a comment by other readers). Throws invalid_input, before writing anything, on
/// what SWC cannot hold (a bad radius or position, a self-loop, a repeated edge). O(V log V + E α(V)).
template <Skeleton G>
void write_swc(std::ostream& os, const G& g, const swc_write_options& options = {}) {
  detail::put_swc(os, g, detail::make_swc_plan(g, {}, {}, options.type), options);
}

/// Writes what parse_swc read, with its own ids and types (parents first). O(V log V + E).
template <Point3 P>
void write_swc(std::ostream& os, const swc_result<P>& swc, const swc_write_options& options = {}) {
  detail::put_swc(os, swc.skeleton, detail::make_swc_plan(swc.skeleton, swc.ids, swc.types, options.type),
                  options);
}

/// Writes an SWC file. A skeleton SWC cannot hold is refused before the file is opened, so an
/// existing file is never truncated by a failed write; io errors name the path. O(V log V + E).
template <Skeleton G>
void write_swc(const file_path& path, const G& g, const swc_write_options& options = {}) {
  const detail::swc_plan plan = detail::make_swc_plan(g, {}, {}, options.type);
  detail::write_file(path, [&](std::ostream& os) { detail::put_swc(os, g, plan, options); });
}

/// Writes an swc_result to a file (see the stream overload); refused before the file is opened. O(V log V +
/// E).
template <Point3 P>
void write_swc(const file_path& path, const swc_result<P>& swc, const swc_write_options& options = {}) {
  const detail::swc_plan plan = detail::make_swc_plan(swc.skeleton, swc.ids, swc.types, options.type);
  detail::write_file(path, [&](std::ostream& os) { detail::put_swc(os, swc.skeleton, plan, options); });
}

}  // namespace cellforge::io
