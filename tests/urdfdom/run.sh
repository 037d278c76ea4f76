#!/bin/sh
# Test tier: urdfdom's own check_urdf (Debian's liburdfdom-tools) on every URDF robodesc writes for
# ROS, over the examples, the compositions of tests/compose, the fuzz seeds, tests/urdfdom/fixtures
# and the real-robot corpus (../shared/corpus and the PyPI corpora of the test extra).
# Usage: tests/urdfdom/run.sh [--targets urdf,ros2,isaac]   (run from anywhere; needs root for apt)
# Exit 0 when urdfdom loads every output written for ROS; a faithful -t urdf round trip of a URDF
# that ROS already refuses (pybullet's capsules) is listed but does not fail the tier.
set -eu
cd "$(dirname "$0")/../.."
if ! command -v check_urdf >/dev/null 2>&1; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq liburdfdom-tools >/dev/null
fi
exec python tests/urdfdom/check_outputs.py --corpus "$@"
