"""The ANYmal-like robot through every target: the total mass each consumer reads is the source's.

Newton and PhysX are read through ``benchmarks/{newton,physx}_masses.py`` in their own interpreters,
when those exist on the machine (``~/.cache/robodesc-consumers``)."""

from __future__ import annotations

import glob
import json
import os
import subprocess
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

import robodesc
from robodesc.validation.physx_python import physx_python
from tests.passes.test_massless import SOURCE_TOTAL, anymal_like

ROOT = Path(__file__).resolve().parents[2]
NEWTON = os.path.expanduser("~/.cache/robodesc-consumers/newton/bin/python")


def _usd_masses(path: str) -> dict[str, float | None]:
    from pxr import Usd, UsdPhysics

    stage = Usd.Stage.Open(path)
    out: dict[str, float | None] = {}
    for prim in stage.Traverse():
        if prim.HasAPI(UsdPhysics.RigidBodyAPI):
            attr = UsdPhysics.MassAPI(prim).GetMassAttr() if prim.HasAPI(UsdPhysics.MassAPI) else None
            out[str(prim.GetPath())] = float(attr.Get()) if attr is not None and attr.HasAuthoredValue() else None
    return out


@pytest.fixture(scope="module")
def outputs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    out = tmp_path_factory.mktemp("massless")
    files = {}
    for target, name in (("urdf", "r.urdf"), ("sdf", "r.sdf"), ("usd", "r.usda"), ("mjcf", "r.xml")):
        robodesc.compile_to(anymal_like(), target, str(out / name))
        files[target] = str(out / name)
    robodesc.compile_for_isaac_sim(anymal_like(), str(out / "isaac"))
    files["isaac"] = sorted(glob.glob(str(out / "isaac" / "*.usd*")))[0]
    return files


def test_urdf_and_sdf_keep_the_source_total(outputs: dict[str, str]) -> None:
    for target in ("urdf", "sdf"):
        root = ET.parse(outputs[target]).getroot()
        masses = [float(m.get("value") or m.text or 0.0) for m in root.iter("mass")]
        assert sum(masses) == pytest.approx(SOURCE_TOTAL, rel=1e-9), target


def test_mjcf_total_in_mujoco(outputs: dict[str, str]) -> None:
    import mujoco

    model = mujoco.MjModel.from_xml_path(outputs["mjcf"])
    assert float(model.body_mass.sum()) == pytest.approx(SOURCE_TOTAL, rel=1e-9)


@pytest.mark.parametrize("target", ["usd", "isaac"])
def test_usd_authors_every_bodys_mass_and_the_source_total(outputs: dict[str, str], target: str) -> None:
    masses = _usd_masses(outputs[target])
    assert len(masses) == 9
    assert all(m is not None and m > 0 for m in masses.values()), masses
    assert sum(m or 0.0 for m in masses.values()) == pytest.approx(SOURCE_TOTAL, rel=1e-6)  # float32


@pytest.mark.parametrize("consumer", ["newton", "physx"])
def test_newton_and_physx_read_the_source_total(outputs: dict[str, str], consumer: str, tmp_path: Path) -> None:
    python = NEWTON if consumer == "newton" else physx_python()
    if python is None or not os.path.exists(python):
        pytest.skip(f"{consumer}'s interpreter is not installed on this machine")
    answer = tmp_path / "masses.json"
    paths = [outputs["usd"], outputs["isaac"]]
    script = ROOT / "benchmarks" / f"{consumer}_masses.py"
    subprocess.run(
        [python, str(script), str(answer)], input="\n".join(paths), text=True, capture_output=True, check=True
    )
    read = json.loads(answer.read_text())
    for path in paths:
        bodies = read[path]
        assert isinstance(bodies, dict), bodies
        total = sum(v for k, v in bodies.items() if not k.startswith("#"))
        assert total == pytest.approx(SOURCE_TOTAL, rel=1e-5), (consumer, path)
        assert bodies.get("#corrected", 0.0) == 0.0  # Newton changed no body's inertia
