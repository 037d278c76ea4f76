"""HoloScript's own robot files: every URDF robodesc writes for ROS from them loads in urdfdom.

HoloScript's files are not part of robodesc. Put them in a folder and name it in
``ROBODESC_HOLOSCRIPT_DIR`` (every ``*.holo`` below it is compiled); without it the test is skipped.
How to get them (the commit measured is in ``benchmarks/results/holoscript_robots.md``)::

    git clone https://github.com/brianonbased-dev/HoloScript && cd HoloScript
    mkdir -p /work/holoscript-robots
    git grep -lE '@joint|behavior "[A-Za-z]*Joint"|joint_(type|parent)' -- '*.holo' \\
        | xargs -I{} cp --parents {} /work/holoscript-robots/
    ROBODESC_HOLOSCRIPT_DIR=/work/holoscript-robots tests/urdfdom/run.sh

For each file: ``-t urdf`` (a composition's URDF is written for ROS), the ROS 2 folder's URDF and the
Isaac folder's URDF, each loaded by urdfdom through Pinocchio (``pin.buildModelFromXML``) and by
every ``check_urdf`` installed (Debian's ``liburdfdom-tools``, and the one on PATH).
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

import robodesc
from robodesc.ir.diagnostics import RobodescError
from tests.urdfdom.check_outputs import check_urdf

ENV = "ROBODESC_HOLOSCRIPT_DIR"
FOLDER = os.environ.get(ENV)
FILES = sorted(Path(FOLDER).rglob("*.holo")) if FOLDER else []
SKIP = (
    f"set {ENV} to a folder of HoloScript's robot files (.holo) to run this test; "
    "tests/urdfdom/test_holoscript.py's docstring says how to get them"
)


def _checkers() -> list[str]:
    """Every check_urdf binary here, once each (the one on PATH, Debian's)."""
    found = [shutil.which("check_urdf"), "/usr/bin/check_urdf"]
    out: list[str] = []
    for binary in found:
        if binary and os.path.isfile(binary) and os.path.realpath(binary) not in map(os.path.realpath, out):
            out.append(binary)
    return out


def _accepts(urdf: Path) -> None:
    pin = pytest.importorskip("pinocchio")
    try:
        pin.buildModelFromXML(urdf.read_text(encoding="utf-8"))
    except (ValueError, RuntimeError) as exc:  # urdfdom's refusal
        raise AssertionError(f"urdfdom (Pinocchio) refuses {urdf.name}: {exc}") from None
    for binary in _checkers():
        ok, message = check_urdf(str(urdf), binary)
        assert ok, f"{binary} refuses {urdf.name}: {message}"


def _params() -> list[object]:
    if not FILES:
        return [pytest.param(None, marks=pytest.mark.skip(reason=SKIP if not FOLDER else f"no .holo file in {FOLDER}"))]
    return [pytest.param(p, id=str(p.relative_to(FOLDER or "."))) for p in FILES]


@pytest.mark.parametrize("source", _params())
def test_holoscript_robot_urdfs_load_in_urdfdom(source: Path, tmp_path: Path) -> None:
    try:
        robodesc.compile_to_urdf(str(source), tmp_path / "robot.urdf", validate=False)
        robodesc.compile_for_ros2(str(source), tmp_path / "ros2", validate=False)
        isaac = robodesc.compile_for_isaac_sim(str(source), tmp_path / "isaac", validate=False)
    except RobodescError as exc:
        pytest.fail(f"robodesc refused {source.name}, so there is no URDF to load: {exc}")
    urdfs = [tmp_path / "robot.urdf", *sorted((tmp_path / "ros2").glob("*.urdf")), Path(isaac.files["urdf"])]
    assert len(urdfs) == 3, urdfs
    for urdf in urdfs:
        _accepts(urdf)
