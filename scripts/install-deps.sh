#!/usr/bin/env bash
# Installs the Debian/Ubuntu packages cellforge needs, and only those that are missing.
#   bash scripts/install-deps.sh [--bench] [--compare] [--fuzz] [--occt]
#     (none)     compiler, CMake, make, GLM, doctest, Eigen: enough to build the tests and examples;
#                node and npm (only when the commands are missing) for scripts/fetch-bunny.sh;
#                libcgal-demo (CGAL's demo meshes) for scripts/fetch-cgal-data.sh;
#                python3-ezdxf (a third-party DXF writer) for the DXF test data (scripts/make-dxf-data.py);
#                clang-format-14 for the format check (scripts/check-format.sh)
#     --bench    Google Benchmark as well
#     --compare  CGAL (with Eigen), OpenMesh and Qhull, the baselines the benchmarks compare against (implies --bench)
#     --fuzz     clang and its compiler-rt (libFuzzer, ASan/UBSan runtimes for clang)
#     --occt     OpenCASCADE's STEP reader and checks, for the STEP writer's test (tests/occt)
#     --only P.. just the packages P.. (the data fetchers' way to install what they read)
# `apt-get update` runs once, and only when something must be installed; sudo is used only
# when not running as root. Nothing is installed when everything is present already.
set -euo pipefail

packages=(g++ cmake make libglm-dev doctest-dev libeigen3-dev)
# The real-mesh sweep's data: CGAL's demo meshes, unpacked by scripts/fetch-cgal-data.sh.
packages+=(libcgal-demo)
packages+=(python3-ezdxf)
# The format check (scripts/check-format.sh, ctest clang_format) wants this exact version.
packages+=(clang-format-14)
# The bunny test data comes through npm (scripts/fetch-bunny.sh). Checked by command rather
# than by package, since node from another source (e.g. a nodejs build bundling npm) will do.
command -v node >/dev/null 2>&1 || packages+=(nodejs)
command -v npm >/dev/null 2>&1 || packages+=(npm)
if [[ "${1-}" == --only ]]; then
  shift
  packages=("$@")
  set --
fi
for arg in "$@"; do
  case "$arg" in
    --bench) packages+=(libbenchmark-dev) ;;
    --compare) packages+=(libbenchmark-dev libcgal-dev libopenmesh-dev libeigen3-dev libqhull-dev) ;;
    # Debian 12's clang 14 needs libclang-rt-14-dev for -fsanitize=fuzzer (libclang_rt.fuzzer).
    --fuzz) packages+=(clang libclang-rt-14-dev) ;;
    # A test dependency only: test_step_occt reads io/step.hpp's files back with OpenCASCADE.
    --occt) packages+=(libocct-data-exchange-dev libocct-modeling-algorithms-dev) ;;
    -h | --help)
      sed -n '2,15p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
      exit 0
      ;;
    *)
      echo "install-deps.sh: unknown option '$arg' (try --help)" >&2
      exit 2
      ;;
  esac
done

if ! command -v dpkg-query >/dev/null 2>&1; then
  echo "install-deps.sh: not a Debian-like system (no dpkg-query); please install the equivalents of:" >&2
  echo "  ${packages[*]}" >&2
  echo "install-deps.sh: continuing, assuming they are present" >&2
  exit 0
fi

missing=()
for pkg in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  if [[ "$status" != "install ok installed" ]]; then
    # The same package may be requested twice (--bench --compare); list it once.
    [[ " ${missing[*]-} " == *" $pkg "* ]] || missing+=("$pkg")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "install-deps.sh: all required packages are installed"
  exit 0
fi

sudo_cmd=()
if [[ "$(id -u)" -ne 0 ]]; then
  if ! command -v sudo >/dev/null 2>&1; then
    echo "install-deps.sh: need root to install: ${missing[*]} (and sudo is not available)" >&2
    exit 1
  fi
  sudo_cmd=(sudo)
fi

echo "install-deps.sh: installing ${missing[*]}"
"${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${sudo_cmd[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
