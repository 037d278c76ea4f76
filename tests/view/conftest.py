"""Fixtures of the view tests: a robot with defects on disk, and a GL backend (or a skip saying why)."""

from __future__ import annotations

import os
import pathlib

import pytest

from tests.view.cases import DEFECTS, gl_backend


@pytest.fixture
def defects_urdf(tmp_path: pathlib.Path) -> str:
    path = tmp_path / "defects.urdf"
    path.write_text(DEFECTS)
    return str(path)


@pytest.fixture
def gl() -> str:
    name, why = gl_backend()
    if name is None:
        pytest.skip(f"no offscreen GL backend: {why}")
    os.environ.setdefault("MUJOCO_GL", name)
    return name
