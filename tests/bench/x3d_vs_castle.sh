#!/usr/bin/env bash
# Every X3D world of the corpus against castle-model-viewer (issue 20; docs/castle-comparison.md):
#
#   tests/bench/x3d_vs_castle.sh BUILD_DIR [OUT_DIR] [WIDTHxHEIGHT] [TIME]
#
# x3d_vs_peer.sh castle, which says what is compared and how. Needs view3dscene (Debian's
# castle-model-viewer) and xvfb-run. A measurement, not a test.
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR [OUT_DIR] [WIDTHxHEIGHT] [TIME]}
exec "$(dirname "$0")/x3d_vs_peer.sh" castle "$build" "${2:-}" "${3:-300x300}" "${4:-0}"
