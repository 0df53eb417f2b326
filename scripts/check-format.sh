#!/usr/bin/env bash
# Checks that every C++ file under include/, tests/, examples/ and bench/ is formatted as
# .clang-format says, with clang-format 14 (the version Debian 12 and CI have; another version
# formats some lines differently). Lists the files that are not, and fails.
#   bash scripts/check-format.sh          check (the ctest case `clang_format` runs this)
#   bash scripts/check-format.sh --fix    format those files in place instead
# Environment: CLANG_FORMAT (default clang-format-14). Costs about 4 CPU-seconds.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
fmt="${CLANG_FORMAT:-clang-format-14}"
if ! command -v "$fmt" >/dev/null 2>&1; then
  echo "check-format: $fmt not found (bash scripts/install-deps.sh installs clang-format-14)" >&2
  exit 1
fi

mapfile -t files < <(find include tests examples bench -type f \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) | sort)
if [[ "${1:-}" == "--fix" ]]; then
  "$fmt" -i "${files[@]}"
  echo "check-format: formatted ${#files[@]} files"
  exit 0
elif [[ $# -gt 0 ]]; then
  echo "check-format: unknown option '$1' (use --fix or nothing)" >&2
  exit 2
fi

# One run over all files; every violation is a diagnostic naming its file.
out=$("$fmt" --dry-run --Werror "${files[@]}" 2>&1) && status=0 || status=$?
if [[ $status -eq 0 ]]; then
  echo "check-format: ${#files[@]} files formatted as .clang-format says"
  exit 0
fi
mapfile -t bad < <(grep -oE '^[^ :]+:[0-9]+:[0-9]+: (error|warning): code should be clang-formatted' <<<"$out" |
  cut -d: -f1 | sort -u)
if [[ ${#bad[@]} -eq 0 ]]; then
  echo "$out" >&2  # clang-format itself failed
  exit "$status"
fi
head -n 20 <<<"$out" >&2
echo "check-format: ${#bad[@]} of ${#files[@]} files are not formatted; bash scripts/check-format.sh --fix formats them:" >&2
printf '  %s\n' "${bad[@]}" >&2
exit 1
