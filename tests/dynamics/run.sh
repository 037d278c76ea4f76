#!/usr/bin/env bash
# The engine tier of validate --dynamics: MuJoCo, Drake, Newton and PhysX (each if its venv exists;
# build them with tests/consumers/run.sh) on the example arm, the example quadruped and Quad-SDK's
# Spirit; PhysX against MuJoCo (test_dynamics_physx.py) also runs in the plain suite when it can.
#   tests/dynamics/run.sh [pytest args]
set -euo pipefail
cd "$(dirname "$0")/../.."
ROBODESC_DYNAMICS_TIER=1 PYTHONPATH=src "${PYTHON:-python}" -m pytest -q tests/dynamics "$@"
