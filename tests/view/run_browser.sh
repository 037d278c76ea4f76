#!/bin/sh
# The browser tier of the view tests: installs Debian's Chromium (no browser is downloaded from
# anywhere else) and the DevTools client, then runs the tests marked `browser` and the render
# goldens. Usage: tests/view/run_browser.sh [pytest args]
set -eu
cd "$(dirname "$0")/../.."
if ! command -v chromium >/dev/null 2>&1; then
    apt-get update
    apt-get install -y --no-install-recommends chromium
fi
# MuJoCo's software renderer for the render goldens, where EGL is missing.
if ! ldconfig -p | grep -q libOSMesa; then
    apt-get install -y --no-install-recommends libosmesa6 || true
fi
python -c "import websocket" 2>/dev/null || python -m pip install -q "websocket-client>=1.6"
exec python -m pytest -q tests/view -m "browser or not browser" "$@"
