#!/usr/bin/env bash
# Moved to scripts/test-all.sh in 0.6.0; this forwarder is removed in 0.8.
echo "cellforge: cmake/test-all.sh moved to scripts/test-all.sh (the old path goes in 0.8)" >&2
exec bash "$(dirname "${BASH_SOURCE[0]}")/../scripts/test-all.sh" "$@"
