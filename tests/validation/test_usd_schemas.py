"""Every physics attribute robodesc writes is one a registered schema defines (issue 38).

usd-core defines ``Physics*``; physx-usd-schemas ``Physx*``; newton-usd-schemas ``Newton*``. The
golden USD files and every example compiled through ``-t usd`` and ``--isaac-sim`` carry no API
schema and no ``physics:*``/``physx*``/``newton:*`` attribute that none of them defines; a file
that does is reported, by prim and name.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import robodesc
from robodesc.validation.report import Status, ValidationReport
from robodesc.validation.usd_schemas import CHECK, census, check_schemas, is_physics_attribute, register_schemas

pytest.importorskip("physx_usd_schemas")
pytest.importorskip("newton_usd_schemas")
register_schemas()
from pxr import Usd  # noqa: E402  (after the schema packages registered)

ROOT = Path(__file__).resolve().parents[2]
GOLDEN = sorted(p for p in (ROOT / "tests").glob("*/golden/**/*.usda"))
EXAMPLES = sorted(
    [
        *(ROOT / "examples").glob("*.yaml"),
        *(ROOT / "examples" / "urdf").glob("*.urdf*"),
        ROOT / "examples" / "four_bar.py",
    ]
)


def _unknown(path: Path) -> list[tuple[str, str, str]]:
    stage = Usd.Stage.Open(str(path))
    assert stage is not None, path
    seen = census(stage)
    assert seen.api_schemas > 0 and seen.attributes > 0, f"{path}: nothing physical was found"
    return seen.unknown_schemas + seen.unknown_attributes


def test_goldens_exist() -> None:
    assert len(GOLDEN) >= 8


@pytest.mark.parametrize("path", GOLDEN, ids=lambda p: str(p.relative_to(ROOT / "tests")))
def test_golden_usd_has_only_schema_defined_physics(path: Path) -> None:
    assert _unknown(path) == []


@pytest.mark.parametrize("isaac", [False, True], ids=["usd", "isaac"])
@pytest.mark.parametrize("source", EXAMPLES, ids=lambda p: p.name)
def test_examples_have_only_schema_defined_physics(source: Path, isaac: bool, tmp_path: Path) -> None:
    if isaac:
        result = robodesc.compile_for_isaac_sim(str(source), str(tmp_path / "isaac"), validate=False)
        usd = Path(result.files["usd"])
    else:
        usd = tmp_path / "robot.usda"
        robodesc.compile_to(str(source), "usd", str(usd), validate=False)
    assert _unknown(usd) == []


def test_unknown_schema_attribute_and_type_are_reported(tmp_path: Path) -> None:
    path = tmp_path / "bad.usda"
    path.write_text(
        """#usda 1.0
def Xform "robot" (prepend apiSchemas = ["PhysicsArticulationRootAPI"])
{
    def PhysicsRevoluteJoint "hinge" (
        prepend apiSchemas = ["PhysxJointAPI", "NewtonJointAPI", "PhysxJointAxisAPI:angular", "IsaacJointAPI"]
    )
    {
        float physxJoint:armature = 0.5
        float newton:maxJointVelocity = 10
        double newton:armature = 0.5
        float physxJointAxis:angular:armature = 0.5
        float physxJointAxis:linear:armature = 0.5
        float physics:lowerLimit = -90
        float drive:angular:physics:stiffness = 10
    }
}
"""
    )
    stage = Usd.Stage.Open(str(path))
    seen = census(stage)
    assert [name for _, name, _ in seen.unknown_schemas] == ["PhysxJointAPI"]
    assert seen.unchecked == {"IsaacJointAPI"}
    unknown = {name: why for _, name, why in seen.unknown_attributes}
    # No PhysicsDriveAPI:angular is applied, so its stiffness is no schema's either.
    assert set(unknown) == {
        "physxJoint:armature",
        "newton:maxJointVelocity",
        "newton:armature",
        "physxJointAxis:linear:armature",
        "drive:angular:physics:stiffness",
    }
    assert "the schema declares float" in unknown["newton:armature"]
    assert seen.attributes == 7
    report = ValidationReport(robot="bad", target="usd", consumer="test")
    check_schemas(stage, report)
    rows = report.by_name(CHECK)
    assert {row.status for row in rows} == {Status.WARN, Status.SKIP}
    assert sum(row.status is Status.WARN for row in rows) == 6
    assert any(row.element == "/robot/hinge" and "physxJoint:armature" in row.message for row in rows)


@pytest.mark.parametrize(
    ("name", "physics"),
    [
        ("physics:mass", True),
        ("physxJointAxis:angular:armature", True),
        ("newton:armature", True),
        ("drive:angular:physics:stiffness", True),
        ("limit:rotX:physics:low", True),
        ("xformOp:translate", False),
        ("isaac:physics:robotJoints", False),
        ("drive:angular:foo", False),
    ],
)
def test_physics_namespaces(name: str, physics: bool) -> None:
    assert is_physics_attribute(name) is physics


def test_validate_reports_the_legacy_spelling_by_joint(tmp_path: Path) -> None:
    # The check runs in every -t usd compile: --isaac-version 5 writes PhysxJointAPI, which the
    # current schemas do not define; the default writes nothing unknown.
    source = str(ROOT / "tests" / "usd" / "data" / "arm.urdf")
    legacy = robodesc.compile_to(source, "usd", str(tmp_path / "legacy.usda"), isaac_version="5")
    current = robodesc.compile_to(source, "usd", str(tmp_path / "current.usda"))
    assert legacy.validation is not None and current.validation is not None
    rows = legacy.validation.by_name(CHECK)
    elbow = [row.message for row in rows if row.status is Status.WARN and row.element == "/arm/joints/elbow"]
    assert any(m.startswith("API schema PhysxJointAPI:") for m in elbow)
    assert any(m.startswith("attribute physxJoint:maxJointVelocity:") for m in elbow)
    assert legacy.validation.ok  # a warning: the file stays loadable
    assert [row.status for row in current.validation.by_name(CHECK)] == [Status.PASS]
