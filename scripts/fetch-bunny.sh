#!/usr/bin/env bash
# Puts the Stanford bunny where the thin-point test and benchmark look for it:
#   bash scripts/fetch-bunny.sh [<dir>]        (default: build/data)
# installs the npm package `bunny` (1839 points, 3674 triangles, closed; Public Domain per
# the package) into <dir>/npm and converts it to <dir>/bunny.off. Both steps are skipped
# when their result is already there, so a second run needs no network. Needs node and npm
# (scripts/install-deps.sh installs them). Configure and build never call this: it runs as a
# separate step (scripts/test-all.sh does it once before its stages).
set -euo pipefail

version="1.0.1" # pinned: the OFF file and the figures in docs/benchmarks.md come from it
dir="${1:-build/data}"
off="$dir/bunny.off"
pkg="$dir/npm/node_modules/bunny"

if [[ -s "$off" ]]; then
  echo "fetch-bunny.sh: $off is present"
  exit 0
fi
for tool in node npm; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "fetch-bunny.sh: '$tool' not found; install node and npm (bash scripts/install-deps.sh)" >&2
    exit 1
  fi
done

mkdir -p "$dir/npm"
# npm keeps its cache under $HOME; a CI shell may have none, then the cache goes beside the package.
[[ -n "${HOME:-}" ]] || export npm_config_cache="$dir/npm/.cache"
if [[ ! -f "$pkg/package.json" ]]; then
  echo "fetch-bunny.sh: npm install bunny@$version into $dir/npm"
  # No prompts, no audit/fund round trips, no update check: runs unattended under CI=true.
  npm install --prefix "$dir/npm" --no-audit --no-fund --no-update-notifier --no-save \
    --loglevel=error "bunny@$version" </dev/null
fi

# Converted by node itself (the package is a CommonJS module exporting {positions, cells});
# checked on the way (finite coordinates, triangles, indices in range) and written to a
# temporary file first, so an interrupted run never leaves a truncated bunny.off behind.
tmp="$off.tmp.$$"
trap 'rm -f "$tmp"' EXIT
node - "$pkg" "$tmp" <<'EOF'
const fs = require('fs');
const path = require('path');
const [pkg, out] = process.argv.slice(2);
const bunny = require(path.resolve(pkg));
const fail = (msg) => { console.error('fetch-bunny.sh: ' + msg); process.exit(1); };
if (!Array.isArray(bunny.positions) || !Array.isArray(bunny.cells)) fail(pkg + ' does not export positions and cells');
const lines = ['OFF', `${bunny.positions.length} ${bunny.cells.length} 0`];
bunny.positions.forEach((p, i) => {
  if (p.length !== 3 || !p.every(Number.isFinite)) fail(`position ${i} is not three finite numbers`);
  lines.push(p.map(String).join(' ')); // shortest text that reads back to the same double
});
bunny.cells.forEach((c, i) => {
  if (c.length !== 3 || !c.every((v) => Number.isInteger(v) && v >= 0 && v < bunny.positions.length))
    fail(`cell ${i} is not a triangle of valid vertex indices`);
  lines.push('3 ' + c.join(' '));
});
fs.writeFileSync(out, lines.join('\n') + '\n');
console.log(`fetch-bunny.sh: ${bunny.positions.length} vertices, ${bunny.cells.length} triangles`);
EOF
mv "$tmp" "$off"
trap - EXIT
echo "fetch-bunny.sh: wrote $off"
