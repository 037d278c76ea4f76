#!/usr/bin/env bash
# The engine tier of validate --dynamics: MuJoCo, Drake and Newton (if its venv exists; build it
# with tests/consumers/run.sh) on the example arm, the example quadruped and Quad-SDK's Spirit.
#   tests/dynamics/run.sh [pytest args]
set -euo pipefail
cd "$(dirname "$0")/../.."
ROBODESC_DYNAMICS_TIER=1 PYTHONPATH=src "${PYTHON:-python}" -m pytest -q tests/dynamics "$@"
