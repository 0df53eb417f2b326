// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Sample drawings (samples/drawings.hpp): the hand-made classics of seed 003 and sketch_sweep,
/// the face finder's test drawings: every family of the other drawings_*.hpp pieces drawn in
/// generic random views.

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "cellforge/core/detail/splitmix.hpp"
#include "cellforge/core/detail/stopwatch.hpp"
#include "cellforge/core/detail/text.hpp"
#include "cellforge/core/error.hpp"
#include "cellforge/samples/drawings_compound.hpp"
#include "cellforge/samples/drawings_normalons.hpp"
#include "cellforge/samples/drawings_polytopes.hpp"
#include "cellforge/samples/drawings_views.hpp"
#include "cellforge/samples/wireframe_models.hpp"

namespace cellforge::samples {

/// Hand-made drawings of the kinds seed 003 shows as hard for face
/// finders, each with its genus: internal faces, several circuits in one plane, edge pairs in
/// no face, through-slots, loops shorter than faces that are no faces. O(1).
template <class = void>
std::vector<voxel_solid> sketch_classics() {
  std::vector<voxel_solid> out;
  const auto voxels = [&](std::vector<double> xs, std::vector<double> ys, std::vector<double> zs,
                          const std::vector<std::array<std::size_t, 3>>& cells, std::string name) {
    voxel_layout l = empty_layout(std::move(xs), std::move(ys), std::move(zs));
    for (const auto& c : cells) l.at(c[0], c[1], c[2]) = 1;
    auto s = voxel_solid_model(std::move(l), std::move(name));
    if (!s) throw error(error_category::invalid_input, "sketch_classics: a classic is not a manifold solid");
    out.push_back(std::move(*s));
  };
  std::vector<std::array<std::size_t, 3>> pocket, tower;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 3; ++j) {
      pocket.push_back({i, j, 0});
      tower.push_back({i, j, 0});
      if (i != 1 || j != 1) pocket.push_back({i, j, 1});
    }
  tower.push_back({1, 1, 1});
  voxels({0, 1.2, 2.0, 3.1}, {0, 0.9, 1.8, 2.6}, {0, 0.8, 1.3}, pocket,
         "classic: pocket block (internal faces, a ring face)");
  voxels({0, 1.2, 2.0, 3.1}, {0, 0.9, 1.8, 2.6}, {0, 0.8, 1.5}, tower,
         "classic: cube on a block (two circuits in the top plane)");
  voxels({0, 0.7, 2.0, 2.6}, {0, 2.2}, {0, 0.6, 1.7}, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 1}, {2, 0, 1}},
         "classic: U channel (two faces in one plane)");
  voxels({0, 1.0, 1.8}, {0, 0.9, 2.0}, {0, 0.7, 1.6}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}},
         "classic: corner step (a cube on a slab's corner: three L faces)");
  voxels({0, 1.0, 1.6, 2.7}, {0, 0.8, 1.7, 2.4}, {0, 0.9},
         {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {2, 1, 0}, {0, 2, 0}, {1, 2, 0}, {2, 2, 0}},
         "classic: frame (faces with holes, genus 1)");
  out.push_back({sample_block_with_hole(), 1});
  out.back().model.name = "classic: block with a through-slot";
  out.push_back(through_slot(2, 7));
  out.back().model.name = "classic: block with two through-slots (genus 2)";
  sample_model oct = sample_bipyramid(4, 1.2, 0.9);
  oct.name = "classic: skew octahedron (edge pairs in no face, equator no face)";
  out.push_back({oct, 0});
  sample_model house = sample_house();
  house.name = "classic: house with a pyramid roof (the square under the roof is no face)";
  out.push_back({house, 0});
  sample_model tiny = sample_frustum(3, 0.04, 1.5);
  tiny.name = "classic: triangular frustum with a tiny top";
  out.push_back({tiny, 0});
  ring_stack s = detail::regular_stack(6, {0.0, 9.0}, 0.5);
  sample_model thin = make_ring_stack(s, "classic: long thin hexagonal prism");
  out.push_back({thin, 0});
  sample_model wedge =
      extruded_polygon({{0, 0}, {3, 0}, {0, 0.25}}, 2.0, "classic: thin wedge (a sliver face)");
  out.push_back({wedge, 0});
  cellforge::detail::splitmix rng{0x636c617373696373u};
  out.push_back({extruded_polygon(random_star_polygon(12, rng), 0.7, "classic: star prism 12"), 0});
  sample_model anti = sample_antiprism(8, 0.6);
  anti.name = "classic: flat octagonal antiprism (triangle strips)";
  out.push_back({anti, 0});
  return out;
}

/// What sketch_sweep builds.
struct sketch_sweep_options {
  std::size_t max_edges = 300;  ///< models with more edges are left out
  int views_per_model = 3;  ///< random generic views per model (×4 for the Platonic and Archimedean solids)
  std::uint64_t seed = 1;   ///< seed of the random families and of the views
  std::size_t random_models = 40;  ///< models per random family
  /// 0: every drawing; else a deterministic sample of about `limit` drawings (every k-th of
  /// each family, so every family stays), the same drawings the full sweep has.
  std::size_t limit = 0;
  /// Families to build (names of sketch_sweep_families()); empty: all of them.
  std::vector<std::string> families;
  /// generic_margin a view of a drawing of up to 100 edges must reach; a drawing of E > 100
  /// edges must reach min_margin · 100 / E (sketch_margin_threshold: the junctions of a dense
  /// drawing are closer, the margin per edge spacing is kept).
  double min_margin = 1e-3;
  int view_attempts = 500;  ///< random views tried per drawing before it is dropped
};

/// The generic_margin a sweep drawing of `edges` edges must reach: options.min_margin up to
/// 100 edges, min_margin · 100 / edges beyond. O(1).
template <class = void>
double sketch_margin_threshold(const sketch_sweep_options& options, std::size_t edges) {
  return edges <= 100 ? options.min_margin : options.min_margin * 100.0 / static_cast<double>(edges);
}

/// Per family: models built, drawings planned (models × views: what the sweep without a limit
/// tries), drawings made, random draws rejected (not a manifold solid or over max_edges),
/// drawings dropped for want of a generic view, edge range.
struct sketch_sweep_family {
  std::string family;
  std::size_t models = 0, planned = 0, drawings = 0, rejected = 0, no_view = 0;
  std::size_t min_edges = 0, max_edges = 0;
};

/// What sketch_sweep did: per family counts (in the order of sketch_sweep_families()), total
/// drawings and the time taken.
struct sketch_sweep_report {
  std::vector<sketch_sweep_family> families;
  std::size_t drawings = 0;
  double ms = 0;
};

/// The family names of the sweep, in its order. O(1).
template <class = void>
std::vector<std::string> sketch_sweep_families() {
  return {"prism",          "pyramid",          "antiprism", "platonic",   "archimedean",
          "random convex",  "cut cube",         "normalon",  "stairs",     "through slot",
          "quasi-normalon", "non-convex prism", "classic",   "cell block", "sliced",
          "roof on box",    "bar frame",        "touching",  "revolved"};
}

namespace detail {

/// Whether generic_margin reaches `stop`, with early exits: a value below `stop` when it does
/// not, else one at least `stop` (not the margin: far pairs are skipped).
/// O(V² + V·E + F·L).
template <class = void>
double margin_until(const sample_drawing& s, double stop) {
  const auto& pts = s.drawing.points;
  const double diag = detail::drawing_diagonal(pts);
  if (!(diag > 0)) return 0;
  const double limit = stop * diag;
  double margin = std::numeric_limits<double>::infinity();
  for (const auto& face : s.model.faces) {
    glm::dvec3 n{0.0};
    const auto& loop = face[0];
    for (std::size_t k = 0; k < loop.size(); ++k)
      n += glm::cross(s.points[loop[k]], s.points[loop[(k + 1) % loop.size()]]);
    const double len = glm::length(n);
    if (len > 0) margin = std::min(margin, std::abs(n.z) / len);
    if (margin < stop) return margin;
  }
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t j = i + 1; j < pts.size(); ++j) {
      const glm::dvec2 d = pts[i] - pts[j];
      if (std::abs(d.x) < limit && std::abs(d.y) < limit) margin = std::min(margin, glm::length(d) / diag);
      if (margin < stop) return margin;
    }
  for (const auto& e : s.drawing.edges) {
    const glm::dvec2 a = pts[e[0]], b = pts[e[1]];
    const glm::dvec2 elo = glm::min(a, b) - limit, ehi = glm::max(a, b) + limit;
    for (std::uint32_t v = 0; v < pts.size(); ++v) {
      const glm::dvec2 q = pts[v];
      if (v == e[0] || v == e[1] || q.x < elo.x || q.y < elo.y || q.x > ehi.x || q.y > ehi.y) continue;
      margin = std::min(margin, cellforge::detail::segment_distance(q, a, b) / diag);
      if (margin < stop) return margin;
    }
  }
  return margin;  // at least `stop`; the bounding-box filters skipped the pairs farther apart
}

/// FNV-1a of a string, mixed with a number. O(length).
template <class = void>
std::uint64_t name_hash(const std::string& s, std::uint64_t mix) {
  std::uint64_t h = 0xcbf29ce484222325u ^ mix;
  for (const char c : s) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3u;
  return h;
}

/// A model of the sweep before it is drawn.
struct sweep_item {
  sample_model model;
  std::string family;
  int genus = 0;
  int views = 1;
};

}  // namespace detail

/// The test drawings of the face finder: every family of sketch_sweep_families() (prisms,
/// pyramids with frusta and bipyramids, antiprisms, Platonic and Archimedean solids, random
/// convex polytopes, cut cubes and prisms, normalons, stairs, through-slots, quasi-normalons,
/// non-convex prisms, the classics), each model in several random generic views, with the
/// true faces and the genus; deterministic in the options. `report`, when given, receives the
/// per-family counts. O(Σ views · attempts · (V² + V·E)).
template <class = void>
std::vector<sample_drawing> sketch_sweep(const sketch_sweep_options& options = {},
                                         sketch_sweep_report* report = nullptr) {
  const cellforge::detail::stopwatch start;
  if (options.views_per_model < 1 || options.view_attempts < 1 || !(options.min_margin >= 0))
    throw error(error_category::invalid_input,
                "sketch_sweep: views_per_model and view_attempts must be at least 1, min_margin >= 0");
  const std::vector<std::string> names = sketch_sweep_families();
  for (const auto& f : options.families)
    if (std::find(names.begin(), names.end(), f) == names.end())
      throw error(
          error_category::invalid_input,
          cellforge::detail::cat("sketch_sweep: no family '", f, "'; sketch_sweep_families() lists them"));
  sketch_sweep_report rep;
  for (const auto& f : names) rep.families.push_back({f});
  const auto fam = [&](const std::string& f) -> sketch_sweep_family& {
    return rep.families[static_cast<std::size_t>(std::find(names.begin(), names.end(), f) - names.begin())];
  };
  std::vector<detail::sweep_item> items;
  const int v = options.views_per_model;
  // Adds a model when it is small enough; returns whether it did.
  // Families to build: options.families, or all of them.
  const auto wanted = [&](const char* family) {
    return options.families.empty() ||
           std::find(options.families.begin(), options.families.end(), family) != options.families.end();
  };
  const auto add = [&](sample_model m, const std::string& family, int genus, int views) {
    if (m.wire.edges.size() > options.max_edges) {
      ++fam(family).rejected;
      return false;
    }
    items.push_back({std::move(m), family, genus, views});
    return true;
  };
  const auto seed_of = [&](std::uint64_t family, std::uint64_t k) {
    return options.seed * 0x9e3779b97f4a7c15u + family * 0x100000u + k;
  };
  const std::size_t emax = options.max_edges;
  // Regular families: n from 3 to 20, then every 4th up to what max_edges allows.
  const auto sizes = [](std::size_t most) {
    std::vector<std::size_t> out;
    for (std::size_t n = 3; n <= most; n += n < 20 ? 1 : 4) out.push_back(n);
    return out;
  };
  if (wanted("prism"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 3, 100)))
      add(sample_prism(n), "prism", 0, v);
  if (wanted("pyramid"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 2, 100)))
      add(sample_pyramid(n), "pyramid", 0, v);
  if (wanted("pyramid"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 3, 12)))
      add(sample_frustum(n, 0.25 + 0.05 * static_cast<double>(n)), "pyramid", 0, v);
  if (wanted("pyramid"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 3, 100)))
      if (n < 12 || n % 8 == 0) add(sample_bipyramid(n, 0.8, 1.3), "pyramid", 0, v);
  if (wanted("antiprism"))
    for (const std::size_t n : sizes(std::min<std::size_t>(emax / 4, 75)))
      add(sample_antiprism(n), "antiprism", 0, v);
  if (wanted("platonic"))
    for (auto& m : platonic_solids()) add(std::move(m), "platonic", 0, 4 * v);
  if (wanted("archimedean"))
    for (auto& m : archimedean_solids()) add(std::move(m), "archimedean", 0, 4 * v);
  // Random families: draws until random_models are kept (or 20 times as many draws).
  const std::size_t want = options.random_models, budget = 20 * options.random_models + 20;
  if (wanted("random convex")) {
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(1, k)};
      const bool sphere = k % 2 == 0;
      const std::size_t n = sphere ? 4 + detail::below(97, rng) : 8 + detail::below(143, rng);
      kept += add(random_convex_polytope(n, sphere, rng.next()), "random convex", 0, v);
    }
  }
  if (wanted("cut cube")) {
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(2, k)};
      const std::size_t base = k % 5 < 3 ? 0 : 3 + detail::below(6, rng);
      const std::size_t cuts = 1 + detail::below(6, rng);
      sample_model m = cut_polytope(base, cuts, rng.next());
      // Well shaped: no edge shorter than 2 % of the size (a cut grazing a corner).
      double shortest = std::numeric_limits<double>::infinity();
      for (const auto& e : m.wire.edges)
        shortest = std::min(shortest, glm::length(m.wire.points[e[0]] - m.wire.points[e[1]]));
      if (shortest < 0.02 * detail::diagonal_of(m.wire.points)) {
        ++fam("cut cube").rejected;
        continue;
      }
      kept += add(std::move(m), "cut cube", 0, v);
    }
  }
  if (wanted("normalon")) add(sample_L(), "normalon", 0, v);
  if (wanted("normalon")) add(sample_T(), "normalon", 0, v);
  if (wanted("normalon")) add(sample_U(), "normalon", 0, v);
  if (wanted("normalon")) {
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(3, k)};
      std::optional<voxel_solid> s;
      if (k % 3 == 2) {
        const std::size_t notches = 1 + detail::below(6, rng);
        s = notched_block(notches, rng.next());
      } else if (k % 3 == 1) {
        const std::size_t nx = 3 + detail::below(6, rng), ny = 3 + detail::below(6, rng);
        const std::size_t height = 2 + detail::below(3, rng);
        s = random_skyline(nx, ny, height, rng.next());
      } else {
        const std::size_t nx = 2 + detail::below(4, rng), ny = 2 + detail::below(4, rng),
                          nz = 1 + detail::below(4, rng);
        const std::size_t cells = nx * ny * nz;
        const std::size_t count = 2 + detail::below(cells - 2, rng);
        s = random_normalon(nx, ny, nz, count, rng.next());
      }
      if (!s) {
        ++fam("normalon").rejected;
        continue;
      }
      kept += add(std::move(s->model), "normalon", s->genus, v);
    }
  }
  if (wanted("stairs"))
    for (std::size_t steps = 1; steps <= 20; ++steps)
      add(sample_stairs(steps, seed_of(4, steps)), "stairs", 0, v);
  if (wanted("stairs"))
    for (std::size_t steps = 25; 6 * steps + 6 <= emax; steps += 6)
      add(sample_stairs(steps, seed_of(4, steps)), "stairs", 0, v);
  if (wanted("through slot")) add(sample_block_with_hole(), "through slot", 1, v);
  if (wanted("through slot")) add(sample_frame(), "through slot", 1, v);
  if (wanted("through slot"))
    for (std::size_t k = 0, kept = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(5, k)};
      const std::size_t holes = 1 + detail::below(4, rng);
      voxel_solid s = through_slot(holes, rng.next());
      kept += add(std::move(s.model), "through slot", s.genus, v);
    }
  if (wanted("quasi-normalon"))
    for (std::size_t k = 0, kept = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(6, k)};
      kept += add(random_quasi_normalon(static_cast<int>(k % 6), rng.next()), "quasi-normalon", 0, v);
    }
  if (wanted("non-convex prism"))
    for (std::size_t k = 0, kept = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(7, k)};
      try {
        if (k % 3 == 2) {
          const int kind = static_cast<int>(detail::below(3, rng));
          const double jitter = rng.uniform(0.05, 0.3);
          const std::vector<glm::dvec2> footprint = letter_footprint(kind, jitter, rng);
          kept += add(extruded_polygon(footprint, rng.uniform(0.5, 2),
                                       cellforge::detail::cat(std::string(kind == 0   ? "oblique L"
                                                                          : kind == 1 ? "oblique T"
                                                                                      : "oblique cross"),
                                                              " prism #", std::to_string(k))),
                      "non-convex prism", 0, v);
        } else {
          const std::size_t n = 5 + detail::below(std::min<std::size_t>(emax / 3, 100) - 4, rng);
          const std::vector<glm::dvec2> footprint = random_star_polygon(n, rng);
          kept += add(extruded_polygon(
                          footprint, rng.uniform(0.3, 1.5),
                          cellforge::detail::cat("star prism ", std::to_string(n), " #", std::to_string(k))),
                      "non-convex prism", 0, v);
        }
      } catch (const error&) {
        ++fam("non-convex prism").rejected;  // a footprint that is not simple
      }
    }
  if (wanted("classic"))
    for (auto& c : sketch_classics()) add(std::move(c.model), "classic", c.genus, v);
  // Several volumes, touching solids, solids of revolution.
  if (wanted("cell block")) {
    for (std::size_t k = 2; k <= 6; ++k) {  // rows of k boxes, every box a volume
      voxel_layout l = empty_layout(detail::iota_coords(k), {0, 1}, {0, 1});
      for (std::size_t i = 0; i < k; ++i) l.labels[i] = static_cast<int>(i + 1);
      add(make_voxel_model(l, cellforge::detail::cat("row of ", std::to_string(k), " boxes")), "cell block",
          0, v);
    }
    for (const auto& n :
         std::vector<std::array<std::size_t, 3>>{{2, 2, 1}, {3, 2, 1}, {2, 2, 2}, {4, 2, 1}, {3, 2, 2}})
      add(sample_grid(n[0], n[1], n[2]), "cell block", 0, v);
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(8, k)};
      const std::size_t nx = 1 + detail::below(4, rng), ny = 1 + detail::below(3, rng),
                        nz = 1 + detail::below(3, rng);
      std::optional<sample_model> m;
      if (nx * ny * nz >= 2) {
        try {
          m = cell_block(nx, ny, nz, k % 2 == 1, rng.next());
        } catch (const error&) {
          m.reset();
        }
      }
      // A cell whose walls no edge needs (the middle of 3 x 3 x 1) reads as a hole: ambiguous.
      if (!m || m->unforced_faces > 0) {
        ++fam("cell block").rejected;
        continue;
      }
      kept += add(std::move(*m), "cell block", 0, v);
    }
  }
  if (wanted("sliced")) {
    std::size_t kept = 0;
    for (std::size_t k = 0; kept < want && k < budget; ++k) {
      cellforge::detail::splitmix rng{seed_of(9, k)};
      const std::size_t base = k % 3 == 2 ? 3 + detail::below(8, rng) : 0;
      const bool diagonal = base == 0 && k % 3 == 1;
      const std::size_t cuts = diagonal ? detail::below(3, rng) : 1 + detail::below(3, rng);
      auto m = sliced_polytope(base, cuts, diagonal, rng.next());
      if (!m) {
        ++fam("sliced").rejected;
        continue;
      }
      kept += add(std::move(*m), "sliced", 0, v);
    }
  }
  if (wanted("roof on box"))
    for (std::size_t k = 0; k < want; ++k)
      add(roof_on_box(static_cast<int>(k % 3), seed_of(10, k)), "roof on box", 0, v);
  if (wanted("bar frame"))
    for (std::size_t k = 0; k < want; ++k)  // one hole: wireframe_to_cells fills two (docs/sketch.md)
      add(bar_frame(1, seed_of(11, k)), "bar frame", 1, v);
  if (wanted("touching"))
    for (std::size_t k = 0; k < want; ++k)
      add(touching_solids(static_cast<int>(k % 7), seed_of(12, k)), "touching", 0, v);
  if (wanted("revolved"))
    for (std::size_t k = 0; k < want; ++k)
      add(revolved_solid(static_cast<int>(k % 5), seed_of(13, k)), "revolved", 0, v);

  // The drawings: the sample keeps every stride-th drawing of each family.
  std::size_t total = 0;
  for (const auto& it : items) total += static_cast<std::size_t>(it.views);
  const std::size_t stride =
      options.limit == 0 || options.limit >= total ? 1 : (total + options.limit - 1) / options.limit;
  std::vector<std::size_t> index(names.size(), 0);
  std::vector<sample_drawing> out;
  for (const auto& it : items) {
    auto& f = fam(it.family);
    const auto fi = static_cast<std::size_t>(&f - rep.families.data());
    bool counted = false;
    f.planned += static_cast<std::size_t>(it.views);
    for (int view = 0; view < it.views; ++view) {
      if (index[fi]++ % stride != 0) continue;
      // Classics: fixed views; the others follow options.seed.
      cellforge::detail::splitmix rng{
          detail::name_hash(it.model.name, it.family == "classic" ? 0 : options.seed) +
          0x9e3779b97f4a7c15u * static_cast<std::uint64_t>(view + 1)};
      bool found = false;
      const double threshold = sketch_margin_threshold(options, it.model.wire.edges.size());
      for (int attempt = 0; attempt < options.view_attempts && !found; ++attempt) {
        sample_drawing s = project_model(it.model, detail::random_rotation(rng),
                                         it.model.name + ", view " + std::to_string(view + 1), it.family);
        if (detail::margin_until(s, threshold) < threshold) continue;
        s.genus = it.genus;
        const std::size_t e = s.drawing.edges.size();
        f.min_edges = f.drawings == 0 ? e : std::min(f.min_edges, e);
        f.max_edges = std::max(f.max_edges, e);
        ++f.drawings;
        out.push_back(std::move(s));
        found = true;
      }
      if (!found) ++f.no_view;
      if (!counted) ++f.models, counted = true;
    }
  }
  rep.drawings = out.size();
  rep.ms = start.ms();
  if (report) *report = std::move(rep);
  return out;
}

}  // namespace cellforge::samples
