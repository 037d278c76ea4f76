"""The verifier passes after every pass, on every robot of the corpora, for every preset.

Robots whose source already fails verification are excluded from the per-pass check, except that
robots failing only the physical checks (bad mass / bad inertia) must pass everything after the
repair pass. Robots with structural errors in their source are reported as skipped.
"""

from __future__ import annotations

import copy

import pytest

from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir import Robot
from robodesc.ir.verify import PHYSICAL_CODES, check, verify
from robodesc.passes import PRESETS, PassOptions, run_passes
from robodesc.passes.options import STRIP_KINDS, ArmatureRule, RepairPolicy
from robodesc.validation.corpora import CorpusRobot, all_robots
from tests.conftest import CORPUS

ROBOTS = all_robots(str(CORPUS))

EVERYTHING = PassOptions(
    sanitize_names=True,
    unique_materials=True,
    fill_inertia=True,
    repair_inertia=RepairPolicy.GEOMETRY,
    merge_fixed=True,
    strip=frozenset(STRIP_KINDS),
    armature=(ArmatureRule(".*", 0.01),),
    isaac_limits=True,
)
CONFIGS: list[tuple[str | None, PassOptions | None]] = [(p, None) for p in sorted(PRESETS)] + [(None, EVERYTHING)]


def _load(entry: CorpusRobot) -> Robot:
    opts = LoadOptions(package_paths=entry.packages, xacro_args=entry.xacro_args, missing_mesh=MissingMesh.WARN)
    return load_path(entry.path, opts).robot


@pytest.mark.slow
@pytest.mark.parametrize("entry", ROBOTS, ids=[f"{r.corpus}:{r.name}" for r in ROBOTS])
def test_every_pass_keeps_the_ir_valid(entry: CorpusRobot) -> None:
    source = _load(entry)
    errors = verify(source).errors
    structural = sorted({f.code for f in errors} - PHYSICAL_CODES)
    if structural:
        pytest.skip(f"source fails structural verification: {', '.join(structural)}")
    for preset, options in CONFIGS:
        robot = copy.deepcopy(source)
        if not errors:
            run_passes(robot, preset=preset, options=options, verify_each=True)
            continue
        opts = options or PassOptions()
        run_passes(robot, preset=preset, options=opts)
        physical = [f for f in verify(robot).errors if f.code in PHYSICAL_CODES]
        repaired = preset in ("isaac_sim", "gazebo", "mujoco", "quad_sdk") or opts.repair_inertia is not None
        if repaired:
            assert physical == [], f"{preset}: {[f.render() for f in physical][:3]}"
            check(robot)
