#!/usr/bin/env bash
# Moved to scripts/fuzz-long.sh in 0.6.0; this forwarder is removed in 0.8.
echo "cellforge: cmake/fuzz-long.sh moved to scripts/fuzz-long.sh (the old path goes in 0.8)" >&2
exec bash "$(dirname "${BASH_SOURCE[0]}")/../scripts/fuzz-long.sh" "$@"
