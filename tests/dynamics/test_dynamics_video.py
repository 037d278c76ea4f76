"""``validate --dynamics --video`` with PhysX and Newton beside MuJoCo (the engine tier,
tests/dynamics/run.sh; each engine where its interpreter exists, a skip saying why otherwise): every
engine reports the dropped root's pose, and the clip has a panel per engine run. The fast tests of
the clips are tests/view/test_video.py."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import robodesc
from robodesc.view import video
from robodesc.view.video import read_frames, write_dynamics_clips
from tests.view.cases import gl_backend

from ..conftest import EXAMPLES

pytestmark = [
    pytest.mark.slow,
    pytest.mark.skipif(os.environ.get("ROBODESC_DYNAMICS_TIER") != "1", reason="engine tier: tests/dynamics/run.sh"),
]


@pytest.fixture
def gl(monkeypatch: pytest.MonkeyPatch) -> str:
    name, why = gl_backend()
    if name is None:
        pytest.skip(f"no offscreen GL backend: {why}")
    monkeypatch.setenv("MUJOCO_GL", name)
    return name


def test_physx_and_newton_panels_beside_mujoco(tmp_path: Path, gl: str) -> None:
    """The quadruped compiled to USD, run in MuJoCo, PhysX and Newton (where their interpreters
    exist), one clip per scenario with a panel per engine."""
    from robodesc.validation.dynamics.newton_run import newton_python
    from robodesc.validation.physx_python import physx_python

    engines = ["mujoco"] + (["physx"] if physx_python() else []) + (["newton"] if newton_python() else [])
    if len(engines) == 1:
        pytest.skip("neither PhysX nor Newton has an interpreter here (tests/consumers/run.sh builds them)")
    result = robodesc.check(
        str(EXAMPLES / "quadruped.yaml"), "usd", dynamics={"engines": tuple(engines), "record": True}
    )
    assert result.dynamics is not None
    drops = [r for r in result.dynamics.runs if r.scenario == "drop" and r.ok]
    assert {r.engine for r in drops} == set(engines)
    for run in drops:  # every engine reports where the root ended, as its height column says
        assert run.root and run.root[-1][1][2] == pytest.approx(run.height, abs=1e-6)
    clips = write_dynamics_clips(result.dynamics, str(tmp_path))
    drop = next(c for c in clips if c.scenario == "drop")
    assert len(drop.panels) == len(drops)
    frames = read_frames(drop.path)
    assert len(frames) == 51 and frames[0].shape[1] == video.PANEL[0] * min(len(drops), video.PER_ROW)
