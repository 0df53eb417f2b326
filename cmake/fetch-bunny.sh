#!/usr/bin/env bash
# Moved to scripts/fetch-bunny.sh in 0.6.0; this forwarder is removed in 0.8.
echo "cellforge: cmake/fetch-bunny.sh moved to scripts/fetch-bunny.sh (the old path goes in 0.8)" >&2
exec bash "$(dirname "${BASH_SOURCE[0]}")/../scripts/fetch-bunny.sh" "$@"
