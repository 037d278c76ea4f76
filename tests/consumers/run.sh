#!/usr/bin/env bash
# The consumer tier: build one environment per engine, then load what robodesc writes in each.
#
#   tests/consumers/run.sh                      # build what is missing, run every corpus robot
#   tests/consumers/run.sh --robots panda,a1    # a subset (substring match on corpus names)
#   tests/consumers/run.sh --kinds newton_mjcf  # only robodesc's MJCF through Newton's add_mjcf (other columns kept)
#   ROBODESC_CONSUMERS_ISAACLAB=1 tests/consumers/run.sh   # also build Isaac Lab 3.0 (~8 GB, torch)
#                                   and spawn the corpus in it (isaaclab_tier.py; ROBODESC_ISAACLAB_ARGS
#                                   passes it more, e.g. "--robots go1,icub --label after")
#   ROBODESC_ISAAC6_ROBOTS=spirit,go2 tests/consumers/run.sh   # the robots isaac6_layer.py runs (corpus
#                                   names or unique stems, or all; default the two examples)
#
# Environments live outside the repository, in $ROBODESC_CONSUMERS_DIR (default
# ~/.cache/robodesc-consumers), one virtualenv per engine:
#   newton/    Python 3.12, newton[importers,sim] 1.8, warp-lang, newton-usd-schemas (CPU)
#   isaacsim/  Python 3.12, isaacsim-asset-isolated 6.2 (the URDF importer, no Kit, no GPU)
#   physx/     ovphysx 0.7 (PhysX on CPU), physx-usd-schemas, newton-usd-schemas, usd-core
#   isaaclab/  Python 3.12, isaaclab 3.0 (optional)
# PYTHON312 names the interpreter used to create them (default: python3.12 on PATH, then pyenv's).
# robodesc itself runs with the Python that runs this script's driver ($PYTHON, default python).
# Results: benchmarks/results/consumers.json and consumers.md (see docs/usd.md, "Consumer tier").
set -euo pipefail
cd "$(dirname "$0")/../.."
ENVS="${ROBODESC_CONSUMERS_DIR:-$HOME/.cache/robodesc-consumers}"
PYTHON="${PYTHON:-python}"
if [ -z "${PYTHON312:-}" ]; then
  PYTHON312="$(command -v python3.12 || true)"
  if [ -z "$PYTHON312" ] && [ -x "$HOME/.pyenv/versions/3.12.1/bin/python" ]; then
    PYTHON312="$HOME/.pyenv/versions/3.12.1/bin/python"
  fi
fi
[ -n "$PYTHON312" ] || { echo "error: no Python 3.12 (set PYTHON312)" >&2; exit 2; }
mkdir -p "$ENVS"

build() {  # build NAME PACKAGES...: a venv with these packages, once (a marker file records success)
  local name="$1"; shift
  if [ -f "$ENVS/$name/.built" ]; then return; fi
  echo "building $ENVS/$name: $*"
  rm -rf "${ENVS:?}/$name"
  "$PYTHON312" -m venv "$ENVS/$name"
  "$ENVS/$name/bin/pip" install -q "$@"
  touch "$ENVS/$name/.built"
}

build newton "newton[importers,sim]==1.8.0" warp-lang newton-usd-schemas
build isaacsim "isaacsim-asset-isolated==6.2.0.0"
# PhysX (ovphysx, CPU) with the current PhysX and Newton USD schemas; Python 3.11 or 3.12 both work.
build physx "ovphysx==0.7.*" physx-usd-schemas newton-usd-schemas usd-core numpy
if [ "${ROBODESC_CONSUMERS_ISAACLAB:-0}" = "1" ]; then
  build isaaclab "isaaclab==3.0.0"
fi

"$PYTHON" tests/consumers/run_tier.py --envs "$ENVS" "$@"
# The Isaac Sim 6 route: the physics layer over the importer's USD, read in PhysX (docs/isaac.md).
# Each robot's structure in PhysX and its hold, drop and slide on the three routes (~2 min a robot on a
# loaded two-core machine); ROBODESC_ISAAC6_ROBOTS=all runs the whole corpus.
"$PYTHON" tests/consumers/isaac6_layer.py --envs "$ENVS" --robots "${ROBODESC_ISAAC6_ROBOTS:-quadruped,arm6_gripper}" \
  --out /tmp/robodesc-isaac6.json
"$PYTHON" tests/consumers/isaac6_report.py /tmp/robodesc-isaac6.json \
  --json benchmarks/results/isaac6_layer.json --md benchmarks/results/isaac6_layer.md
if [ "${ROBODESC_CONSUMERS_ISAACLAB:-0}" = "1" ]; then
  # shellcheck disable=SC2086  # the extra arguments are words on purpose
  "$PYTHON" tests/consumers/isaaclab_tier.py --envs "$ENVS" ${ROBODESC_ISAACLAB_ARGS:-}
fi
