#!/bin/sh
# Test tier: the fuzzer (tests/fuzz/fuzzer.py) at 2,000 cases over every target (URDF, SDF, USD as
# .usda and .usdc, MJCF, the ROS 2 and Isaac folders) and batch folders (named pipes, Python files
# that must not run without --run-python, symlinks in and out of the folder). Each case runs in a
# child process under a per-case time bound, so a segfault or a hang in native code is counted too.
# Usage: tests/fuzz/run.sh [CASES] [--seed S] [--time-limit SECONDS] [--dir DIR] [--json FILE]
# Prints crashes, hangs, false blames (exit 1 on a mutated source), ok, refused; exit 0 when no case
# failed. CI runs the first 300 cases of the same sequence (tests/fuzz/test_fuzz.py).
set -eu
cd "$(dirname "$0")/../.."
if [ $# -eq 0 ]; then set -- 2000; fi
exec python -m tests.fuzz.tier "$@"
