#!/bin/sh
# Test tier: urdfdom's own check_urdf (Debian's liburdfdom-tools) on every URDF robodesc writes for
# ROS, over the examples, the compositions of tests/compose, the fuzz seeds, tests/urdfdom/fixtures
# and the real-robot corpus (../shared/corpus and the PyPI corpora of the test extra).
# Usage: tests/urdfdom/run.sh [--targets urdf,ros2,isaac]   (run from anywhere; needs root for apt)
# Exit 0 when urdfdom loads every output written for ROS; a faithful -t urdf round trip of a URDF
# that ROS already refuses (pybullet's capsules) is listed but does not fail the tier.
#
# HoloScript's own robot files (not part of robodesc): put them in a folder and name it in
# ROBODESC_HOLOSCRIPT_DIR; the tier then checks them too, with check_urdf and through Pinocchio
# (tests/urdfdom/test_holoscript.py). To get them:
#   git clone https://github.com/brianonbased-dev/HoloScript && cd HoloScript
#   git grep -lE '@joint|behavior "[A-Za-z]*Joint"|joint_(type|parent)' -- '*.holo' \
#       | xargs -I{} cp --parents {} /work/holoscript-robots/
#   ROBODESC_HOLOSCRIPT_DIR=/work/holoscript-robots tests/urdfdom/run.sh
# (benchmarks/results/holoscript_robots.md names the HoloScript commit measured.)
set -eu
cd "$(dirname "$0")/../.."
if ! command -v check_urdf >/dev/null 2>&1 || [ ! -x /usr/bin/check_urdf ]; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq liburdfdom-tools >/dev/null
fi
if [ -n "${ROBODESC_HOLOSCRIPT_DIR:-}" ]; then
    PYTHONPATH="$PWD/src:$PWD${PYTHONPATH:+:$PYTHONPATH}" python -m pytest -q tests/urdfdom/test_holoscript.py
fi
exec python tests/urdfdom/check_outputs.py --corpus "$@"
