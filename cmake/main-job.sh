#!/usr/bin/env bash
# Moved to scripts/main-job.sh in 0.6.0; this forwarder is removed in 0.8.
echo "cellforge: cmake/main-job.sh moved to scripts/main-job.sh (the old path goes in 0.8)" >&2
exec bash "$(dirname "${BASH_SOURCE[0]}")/../scripts/main-job.sh" "$@"
