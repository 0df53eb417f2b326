// SPDX-License-Identifier: MIT
#pragma once
/// \file
/// Shared helpers for the benchmark binaries: timing, heap measurement, a Google Benchmark
/// reporter that keeps the results, a scratch directory and the side-by-side table printer
/// ("row | seed ms | ours ms | ratio | OpenMesh ms | CGAL ms"). Each binary runs Google
/// Benchmark through run_benchmarks() and then prints its tables from the kept results.
///
/// Allocation peaks need the counting operator new/delete: define
/// CELLFORGE_BENCH_ALLOCATION_HOOKS before including this header in exactly one source
/// file of the binary. They count only inside measure_heap(); without them measure_heap()
/// reports the retained heap (glibc mallinfo2) and no peak.

#include <benchmark/benchmark.h>
#include <malloc.h>
#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cellforge::bench {

/// Which comparison baselines this binary was built with (bench/CMakeLists.txt defines
/// the macros when it finds the libraries).
#ifdef CELLFORGE_HAVE_OPENMESH
inline constexpr bool have_openmesh = true;
#else
inline constexpr bool have_openmesh = false;
#endif
#ifdef CELLFORGE_HAVE_CGAL
inline constexpr bool have_cgal = true;
#else
inline constexpr bool have_cgal = false;
#endif
#ifdef CELLFORGE_HAVE_QHULL
inline constexpr bool have_qhull = true;
#else
inline constexpr bool have_qhull = false;
#endif

// ------------------------------------------------------------------------------ timing
//
// The tables use the CPU time of the benchmarking thread (user + system, so page faults
// and reading the file from the page cache count), best of the iterations: on a shared
// machine other processes stretch wall time by up to 2x while CPU time stays put. Wall
// times are kept next to it (best_wall_us) for a quiet machine, where the two agree.

using clock = std::chrono::steady_clock;

/// Milliseconds from t0 to now. O(1).
inline double ms_since(clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(clock::now() - t0).count();
}

/// CPU time this thread has used, in ms. O(1).
inline double thread_cpu_ms() noexcept {
  timespec ts{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

/// Best CPU time in ms of `repeats` calls of f (its result is destroyed outside the timed
/// span, so freeing the structure is not charged). O(repeats × cost of f).
template <class F>
double time_ms(F&& f, int repeats = 3) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < repeats; ++i) {
    const double t0 = thread_cpu_ms();
    auto result = f();
    const double ms = thread_cpu_ms() - t0;
    benchmark::DoNotOptimize(result);
    best = std::min(best, ms);
  }
  return best;
}

/// Runs one Google Benchmark iteration loop timing only `make()` (register with
/// ->UseManualTime(): the manual time is the thread's CPU time); the made object is
/// destroyed outside the timed span. `check(object)` runs once, on the first result, and
/// may call state.SkipWithError. Sets the counters best_cpu_us and best_wall_us.
template <class Make, class Check>
void timed_loop(benchmark::State& state, Make&& make, Check&& check) {
  bool checked = false;
  double best_cpu = std::numeric_limits<double>::infinity(), best_wall = best_cpu;
  for (auto _ : state) {
    const clock::time_point w0 = clock::now();
    const double c0 = thread_cpu_ms();
    auto made = make();
    const double cpu = thread_cpu_ms() - c0;
    const double wall = ms_since(w0);
    state.SetIterationTime(cpu * 1e-3);
    best_cpu = std::min(best_cpu, cpu);
    best_wall = std::min(best_wall, wall);
    benchmark::DoNotOptimize(made);
    if (!checked) {
      checked = true;
      check(made);
    }
  }
  state.counters["best_cpu_us"] = best_cpu * 1e3;
  state.counters["best_wall_us"] = best_wall * 1e3;
}

/// The glibc settings a series runs under. mallopt is process-wide and an explicit
/// M_MMAP_THRESHOLD switches off glibc's dynamic threshold for good, so the default series
/// (and the seed tables) run first and each other series sets its own settings on entry.
enum class heap { default_glibc, cold, warm };

/// Whether any benchmark has called mallopt yet (after that, glibc's defaults are gone).
inline bool& mallopt_called() {
  static bool called = false;
  return called;
}

/// Puts glibc in the state `h` needs; returns an error message, or nullptr. Cheap.
inline const char* set_heap(heap h) {
  switch (h) {
    case heap::default_glibc:
      return mallopt_called() ? "glibc defaults already changed by mallopt: run this series first" : nullptr;
    case heap::cold:
      // Every block of 64 KiB or more is its own mmap, unmapped on free, and free memory at
      // the heap's top is returned at once: each run gets new zero-filled pages at any size.
      mallopt_called() = true;
      if (mallopt(M_MMAP_THRESHOLD, 64 * 1024) != 1 || mallopt(M_TRIM_THRESHOLD, 0) != 1 ||
          mallopt(M_TOP_PAD, 0) != 1)
        return "mallopt refused the cold settings";
      malloc_trim(0);  // drop what an earlier warm series kept, so it cannot be reused
      return nullptr;
    case heap::warm:
      // glibc keeps freed memory and serves large blocks from the heap: a repeated run
      // reuses pages instead of faulting in fresh zeroed ones.
      mallopt_called() = true;
      if (mallopt(M_MMAP_THRESHOLD, 1 << 30) != 1 || mallopt(M_TRIM_THRESHOLD, 1 << 30) != 1 ||
          mallopt(M_TOP_PAD, 128 * 1024) != 1)
        return "mallopt refused the warm-heap settings";
      return nullptr;
  }
  return nullptr;
}

/// Minor page faults of the process so far (each a page the kernel mapped, zero-filled
/// when it is new anonymous memory).
inline long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

/// Transparent-huge-page faults so far, system-wide (/proc/vmstat thp_fault_alloc; 0 where
/// it is missing): each of our minor faults that is one maps and zeroes 2 MiB, not 4 KiB.
inline long huge_faults() {
  std::ifstream vmstat("/proc/vmstat");
  std::string key;
  long value = 0;
  while (vmstat >> key >> value)
    if (key == "thp_fault_alloc") return value;
  return 0;
}

/// The median of v (the mean of the middle two for an even count; 0 when empty). O(n log n).
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  if (v.empty()) return 0.0;
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// Like timed_loop, but keeps every iteration's CPU and wall time and sets the counters
/// median_cpu_us and median_wall_us as well as best_cpu_us and best_wall_us (register with
/// ->Iterations(n) for the median of n runs, and ->UseManualTime()). `check(object)` runs once,
/// on the first result. O(iterations × cost of make).
template <class Make, class Check>
void median_loop(benchmark::State& state, Make&& make, Check&& check) {
  std::vector<double> cpu, wall;
  for (auto _ : state) {
    const clock::time_point w0 = clock::now();
    const double c0 = thread_cpu_ms();
    auto made = make();
    cpu.push_back(thread_cpu_ms() - c0);
    wall.push_back(ms_since(w0));
    state.SetIterationTime(cpu.back() * 1e-3);
    benchmark::DoNotOptimize(made);
    if (cpu.size() == 1) check(made);
  }
  if (cpu.empty()) return;
  state.counters["median_cpu_us"] = median(cpu) * 1e3;
  state.counters["median_wall_us"] = median(wall) * 1e3;
  state.counters["best_cpu_us"] = *std::min_element(cpu.begin(), cpu.end()) * 1e3;
  state.counters["best_wall_us"] = *std::min_element(wall.begin(), wall.end()) * 1e3;
}
template <class Make>
void median_loop(benchmark::State& state, Make&& make) {
  median_loop(state, std::forward<Make>(make), [](const auto&) {});
}

/// The 1-minute load average (from /proc/loadavg), to print next to the results. O(1).
inline std::string load_average() {
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if (!f) return "unknown";
  char buf[64] = {};
  const bool ok = std::fgets(buf, sizeof buf, f) != nullptr;
  std::fclose(f);
  if (!ok) return "unknown";
  std::string s(buf);
  return s.substr(0, s.find(' '));
}

// ------------------------------------------------------------------------------ heap

/// Bytes the C heap has handed out and not taken back: small blocks (uordblks) plus the
/// large ones glibc maps directly (hblkhd) — a million-element vector is one of those.
/// O(number of arenas).
inline std::size_t heap_in_use() noexcept {
  const struct mallinfo2 mi = ::mallinfo2();
  return mi.uordblks + mi.hblkhd;
}

/// Counters fed by the counting operator new/delete while `on` (so that the timed runs pay
/// one relaxed load per allocation, not the bookkeeping). Net bytes are signed: freeing a
/// block allocated before counting began lowers them.
struct allocation_counters {
  std::atomic<bool> on{false};
  std::atomic<std::int64_t> net{0};   ///< bytes allocated minus bytes freed (usable sizes)
  std::atomic<std::int64_t> peak{0};  ///< highest `net` since counting began
  std::atomic<std::size_t> calls{0};  ///< allocations made
};
inline allocation_counters& counters() noexcept {
  static allocation_counters c;
  return c;
}
/// True when the counting operator new is compiled into this binary. O(1).
#ifdef CELLFORGE_BENCH_ALLOCATION_HOOKS
inline constexpr bool hooks_active = true;
#else
inline constexpr bool hooks_active = false;
#endif

/// What building something costs in heap: what stays allocated while it lives, and the
/// highest extra heap on the way (temporaries included); peak is empty without the hooks.
struct heap_cost {
  std::size_t retained = 0;
  std::optional<std::size_t> peak;
  std::size_t allocations = 0;
};

/// Calls make() and, while its result is still alive, reports its heap cost: the mallinfo2
/// delta (retained) and the counted peak of net allocation. O(cost of make).
template <class Make>
heap_cost measure_heap(Make&& make) {
  allocation_counters& c = counters();
  ::malloc_trim(0);  // return free pages so that the snapshot starts from a quiet heap
  const std::size_t before = heap_in_use();
  c.net.store(0, std::memory_order_relaxed);
  c.peak.store(0, std::memory_order_relaxed);
  c.calls.store(0, std::memory_order_relaxed);
  c.on.store(true, std::memory_order_relaxed);
  auto made = make();
  c.on.store(false, std::memory_order_relaxed);
  heap_cost cost;
  const std::size_t after = heap_in_use();
  cost.retained = after > before ? after - before : 0;
  if (hooks_active) {
    cost.peak = static_cast<std::size_t>(std::max<std::int64_t>(0, c.peak.load(std::memory_order_relaxed)));
    cost.allocations = c.calls.load(std::memory_order_relaxed);
  }
  benchmark::DoNotOptimize(made);
  return cost;  // `made` is freed only now, after the measurement
}

// ------------------------------------------------------------------------------ results

/// One benchmark's outcome as the tables need it.
struct run_result {
  double ms = 0;                ///< best CPU ms of an iteration (timed_loop), else the mean time
  std::int64_t iterations = 0;  ///< iterations measured
  std::string error;            ///< non-empty when the benchmark skipped with an error
  std::map<std::string, double> counters;
};

/// A console reporter that also keeps every run by name (the best of repetitions), so
/// that main can print the seed tables after Google Benchmark's own output.
class collecting_reporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration) continue;
      run_result r;
      r.iterations = run.iterations;
      r.ms = run.GetAdjustedRealTime() / benchmark::GetTimeUnitMultiplier(run.time_unit) * 1e3;
      if (run.error_occurred) r.error = run.error_message;
      for (const auto& [name, counter] : run.counters) r.counters[name] = counter.value;
      // The registered name, without the /min_time:…/manual_time decorations.
      const std::string name = run.run_name.function_name;
      if (const auto best = r.counters.find("best_cpu_us"); best != r.counters.end())
        r.ms = best->second * 1e-3;
      const auto it = results_.find(name);
      const bool better =
          it == results_.end() || (r.error.empty() && (!it->second.error.empty() || r.ms < it->second.ms));
      if (better) results_[name] = std::move(r);
    }
    ConsoleReporter::ReportRuns(runs);
  }

  /// The result registered as `name`, if it ran without error.
  std::optional<double> ms(std::string_view name) const {
    const auto it = results_.find(std::string(name));
    if (it == results_.end() || !it->second.error.empty()) return std::nullopt;
    return it->second.ms;
  }
  /// Counter `counter` (in µs, e.g. median_cpu_us) of the result `name` in ms, if it ran
  /// without error and has that counter.
  std::optional<double> counter_ms(std::string_view name, std::string_view counter) const {
    const auto it = results_.find(std::string(name));
    if (it == results_.end() || !it->second.error.empty()) return std::nullopt;
    const auto c = it->second.counters.find(std::string(counter));
    if (c == it->second.counters.end()) return std::nullopt;
    return c->second * 1e-3;
  }
  const run_result* find(std::string_view name) const {
    const auto it = results_.find(std::string(name));
    return it == results_.end() ? nullptr : &it->second;
  }
  const std::map<std::string, run_result>& results() const noexcept { return results_; }

 private:
  std::map<std::string, run_result> results_;
};

/// Initialises Google Benchmark from the command line (rejecting unknown flags) and runs
/// the registered benchmarks into `reporter`. Returns false when the flags were wrong.
inline bool run_benchmarks(int& argc, char** argv, collecting_reporter& reporter) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return false;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return true;
}

/// The whole main() of a table benchmark: registers, runs (Google Benchmark's flags apply),
/// then prints the tables from the kept results. Returns the process exit code.
template <class Register, class Print>
int table_main(int argc, char** argv, Register&& register_all, Print&& print_tables) {
  register_all();
  collecting_reporter reporter;
  if (!run_benchmarks(argc, argv, reporter)) return 1;
  print_tables(reporter, std::cout);
  return 0;
}

// ------------------------------------------------------------------------------ files

/// A private scratch directory under the system temporary directory, removed with
/// everything in it when the object dies.
class scratch_dir {
 public:
  explicit scratch_dir(std::string_view tag) {
    namespace fs = std::filesystem;
    path_ = fs::temp_directory_path() / ("cellforge-" + std::string(tag) + "-" + std::to_string(::getpid()));
    fs::create_directories(path_);
  }
  ~scratch_dir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);  // best effort: a leftover temp dir is harmless
  }
  scratch_dir(const scratch_dir&) = delete;
  scratch_dir& operator=(const scratch_dir&) = delete;
  const std::filesystem::path& path() const noexcept { return path_; }
  std::filesystem::path operator/(std::string_view name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// ------------------------------------------------------------------------------ tables

/// `x` with `digits` decimals, or "—" when absent.
inline std::string fixed(std::optional<double> x, int digits = 2) {
  if (!x || !std::isfinite(*x)) return "—";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, *x);
  return buf;
}
/// A time in ms with precision that suits its size (3 significant digits at least).
inline std::string ms(std::optional<double> x) {
  if (!x || !std::isfinite(*x)) return "—";
  return fixed(x, *x >= 100 ? 0 : *x >= 10 ? 1 : *x >= 1 ? 2 : 3);
}
/// A ratio a/b as "12.3x", or "—" when either is absent (NaN) or b is not positive.
inline std::string ratio(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b) || b <= 0) return "—";
  return fixed(a / b, a / b >= 100 ? 0 : a / b >= 10 ? 1 : 2) + "x";
}
inline std::string ratio(std::optional<double> a, std::optional<double> b) {
  constexpr double none = std::numeric_limits<double>::quiet_NaN();
  return ratio(a.value_or(none), b.value_or(none));
}
/// An integer in groups of three digits, e.g. 1 000 000.
inline std::string count(std::size_t n) {
  // Built front to back (not by insert, which g++ 12 -O3 warns about with -Wrestrict).
  const std::string digits = std::to_string(n);
  std::string s;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) s += ' ';
    s += digits[i];
  }
  return s;
}

/// A Markdown table printed with aligned columns (so it reads in a terminal and pastes
/// into docs unchanged). Columns of numbers are right-aligned, others left-aligned.
class table {
 public:
  table(std::string title, std::vector<std::string> headers)
      : title_(std::move(title)), headers_(std::move(headers)) {}

  /// Appends a row; missing trailing cells print empty, extra ones are dropped. O(columns).
  void add_row(std::vector<std::string> cells) {
    cells.resize(headers_.size());
    rows_.push_back(std::move(cells));
  }
  /// A note printed under the table (one line each).
  void add_note(std::string note) { notes_.push_back(std::move(note)); }

  /// Prints the title, the table and its notes. O(cells).
  void print(std::ostream& os) const {
    std::vector<std::size_t> width(headers_.size());
    auto measure = [](const std::string& s) {  // display width: count UTF-8 lead bytes only
      return static_cast<std::size_t>(std::count_if(
          s.begin(), s.end(), [](char ch) { return (static_cast<unsigned char>(ch) & 0xC0) != 0x80; }));
    };
    for (std::size_t j = 0; j < headers_.size(); ++j) {
      width[j] = std::max<std::size_t>(3, measure(headers_[j]));
      for (const auto& row : rows_) width[j] = std::max(width[j], measure(row[j]));
    }
    auto numeric = [](const std::string& s) {
      return !s.empty() && (std::isdigit(static_cast<unsigned char>(s[0])) || s == "—");
    };
    // A column is right-aligned when every cell in it is a number (or missing).
    std::vector<bool> right(headers_.size(), true);
    for (std::size_t j = 0; j < headers_.size(); ++j)
      for (const auto& row : rows_) right[j] = right[j] && numeric(row[j]);
    auto line = [&](const std::vector<std::string>& cells) {
      os << '|';
      for (std::size_t j = 0; j < cells.size(); ++j) {
        const std::string pad(width[j] - measure(cells[j]), ' ');
        os << ' ' << (right[j] ? pad : "") << cells[j] << (right[j] ? "" : pad) << " |";
      }
      os << '\n';
    };
    os << "\n### " << title_ << "\n\n";
    line(headers_);
    os << '|';
    // Appended, not `":" + std::string(…)` (an insert at the front, which g++ 12 -O3 warns
    // about with -Wrestrict).
    for (std::size_t j = 0; j < headers_.size(); ++j)
      os << (right[j] ? std::string(width[j] + 1, '-') + ":|"
                      : std::string(":").append(width[j] + 1, '-') + "|");
    os << '\n';
    for (const auto& row : rows_) line(row);
    if (!notes_.empty()) os << '\n';
    for (const auto& n : notes_) os << n << '\n';
  }

 private:
  std::string title_;
  std::vector<std::string> headers_;
  std::vector<std::vector<std::string>> rows_;
  std::vector<std::string> notes_;
};

/// One row of a seed comparison: the seed's figures (some may be missing), then ours and
/// the baselines measured in this run (missing when not installed or filtered out).
struct seed_row {
  std::string label;
  std::vector<std::optional<double>> seed_ms;
  std::optional<double> ours, openmesh, cgal;
};

/// The standard seed table "row | seed ms... | ours ms | ratio | OpenMesh ms | CGAL ms";
/// the ratio is the last seed column over ours (how many times faster we are). O(rows).
inline table seed_table(std::string title, std::string row_header,
                        const std::vector<std::string>& seed_headers, const std::vector<seed_row>& rows) {
  std::vector<std::string> headers{std::move(row_header)};
  headers.insert(headers.end(), seed_headers.begin(), seed_headers.end());
  std::string last = seed_headers.empty() ? "seed" : seed_headers.back();
  if (last.ends_with(" ms")) last.resize(last.size() - 3);
  headers.insert(headers.end(), {"ours ms", "ratio (" + last + " / ours)", "OpenMesh ms", "CGAL ms"});
  table t(std::move(title), std::move(headers));
  for (const seed_row& r : rows) {
    std::vector<std::string> cells{r.label};
    for (std::size_t j = 0; j < seed_headers.size(); ++j)
      cells.push_back(j < r.seed_ms.size() ? ms(r.seed_ms[j]) : "—");
    constexpr double none = std::numeric_limits<double>::quiet_NaN();
    const double seed = r.seed_ms.empty() ? none : r.seed_ms.back().value_or(none);
    cells.insert(cells.end(), {ms(r.ours), ratio(seed, r.ours.value_or(none)), ms(r.openmesh), ms(r.cgal)});
    t.add_row(std::move(cells));
  }
  return t;
}

}  // namespace cellforge::bench

// ------------------------------------------------------------------------------ hooks

#ifdef CELLFORGE_BENCH_ALLOCATION_HOOKS
// Counting replacements of the global operator new/delete (the other forms forward to
// these in libstdc++). Usable sizes are counted so new and delete always agree.
void* operator new(std::size_t n) {
  void* p = std::malloc(n == 0 ? 1 : n);
  if (!p) throw std::bad_alloc();
  auto& c = cellforge::bench::counters();
  if (c.on.load(std::memory_order_relaxed)) {
    const auto size = static_cast<std::int64_t>(::malloc_usable_size(p));
    const std::int64_t now = c.net.fetch_add(size, std::memory_order_relaxed) + size;
    c.calls.fetch_add(1, std::memory_order_relaxed);
    std::int64_t peak = c.peak.load(std::memory_order_relaxed);
    while (now > peak && !c.peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
    }
  }
  return p;
}
void operator delete(void* p) noexcept {
  if (!p) return;
  auto& c = cellforge::bench::counters();
  if (c.on.load(std::memory_order_relaxed))
    c.net.fetch_sub(static_cast<std::int64_t>(::malloc_usable_size(p)), std::memory_order_relaxed);
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept { operator delete(p); }
#endif
