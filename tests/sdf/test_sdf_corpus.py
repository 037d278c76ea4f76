"""Every corpus robot that passes robodesc's verifier loads in Drake from the emitted SDF and matches.

Robots the verifier rejects are source defects (reported, not failures); nothing is repaired.
"""

from __future__ import annotations

import pytest

from robodesc.emit.sdf import PoseFrames, SdfOptions, build_sdf
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir.diagnostics import RobodescError
from robodesc.ir.verify import verify
from robodesc.validation.corpora import all_robots
from tests.conftest import CORPUS
from tests.sdf.drake_compare import compare_with_drake

pytest.importorskip("pydrake")


@pytest.mark.slow
@pytest.mark.parametrize("pose_frames", list(PoseFrames))
def test_corpus_loads_in_drake(pose_frames: PoseFrames) -> None:
    robots = all_robots(str(CORPUS))
    assert robots, "no corpus installed"
    passed: list[str] = []
    defects: dict[str, str] = {}
    failures: dict[str, str] = {}
    for entry in robots:
        label = f"{entry.corpus}/{entry.name}"
        try:
            options = LoadOptions(
                package_paths=entry.packages, xacro_args=entry.xacro_args, missing_mesh=MissingMesh.WARN
            )
            robot = load_path(entry.path, options).robot
        except RobodescError as err:
            defects[label] = f"does not load: {err}"
            continue
        errors = verify(robot).errors
        if errors:
            defects[label] = f"{len(errors)} verifier error(s), first: {errors[0].element}: {errors[0].message}"
            continue
        comparison = compare_with_drake(robot, build_sdf(robot, SdfOptions(pose_frames=pose_frames)), samples=3)
        if comparison.ok:
            passed.append(label)
        else:
            failures[label] = "; ".join(comparison.problems[:2])
    print(
        f"\nSDF corpus ({pose_frames.value} poses): {len(passed)} match Drake, {len(failures)} fail, "
        f"{len(defects)} source defects"
    )
    for label, why in sorted(defects.items()):
        print(f"  source defect {label}: {why[:160]}")
    for label, why in sorted(failures.items()):
        print(f"  FAIL {label}: {why}")
    assert not failures
    assert passed
