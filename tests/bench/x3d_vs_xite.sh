#!/usr/bin/env bash
# Every X3D world of the corpus against X_ITE 15, the reference for X3D 4 (issue 41), at
# T = 0 and one later time:
#
#   tests/bench/x3d_vs_xite.sh BUILD_DIR [OUT_DIR] [WIDTHxHEIGHT] [TIMES]
#
# x3d_vs_peer.sh xite, which says what is compared and how (TIMES default "0 2", the times
# x3d_vs_xite.known names). Needs the X_ITE peer set up in XITE_PEER (default /tmp/peer/xite):
# cp -r ../shared/peers/xite /tmp/peer/xite && /tmp/peer/xite/setup.sh. A measurement, not a
# test.
set -euo pipefail
build=${1:?usage: $0 BUILD_DIR [OUT_DIR] [WIDTHxHEIGHT] [TIMES]}
exec "$(dirname "$0")/x3d_vs_peer.sh" xite "$build" "${2:-}" "${3:-300x300}" "${4:-0 2}"
