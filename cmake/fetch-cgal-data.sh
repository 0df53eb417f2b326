#!/usr/bin/env bash
# Moved to scripts/fetch-cgal-data.sh in 0.6.0; this forwarder is removed in 0.8.
echo "cellforge: cmake/fetch-cgal-data.sh moved to scripts/fetch-cgal-data.sh (the old path goes in 0.8)" >&2
exec bash "$(dirname "${BASH_SOURCE[0]}")/../scripts/fetch-cgal-data.sh" "$@"
