#!/usr/bin/env bash
# Moved to scripts/install-deps.sh in 0.6.0; this forwarder is removed in 0.8.
echo "cellforge: cmake/install-deps.sh moved to scripts/install-deps.sh (the old path goes in 0.8)" >&2
exec bash "$(dirname "${BASH_SOURCE[0]}")/../scripts/install-deps.sh" "$@"
