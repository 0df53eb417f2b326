#!/usr/bin/env bash
# Moved to scripts/check-format.sh in 0.6.0; this forwarder is removed in 0.8.
echo "cellforge: cmake/check-format.sh moved to scripts/check-format.sh (the old path goes in 0.8)" >&2
exec bash "$(dirname "${BASH_SOURCE[0]}")/../scripts/check-format.sh" "$@"
