"""Drake (libsdformat) loads what the SDF emitter writes, and the plant matches the IR numerically."""

from __future__ import annotations

import pytest

from robodesc.emit.sdf import PoseFrames, SdfOptions, SdfProp, build_sdf
from robodesc.ir.verify import verify
from tests.sdf import fixtures as fx
from tests.sdf.drake_compare import compare_with_drake

pytest.importorskip("pydrake")

ROBOTS = {"arm": fx.arm, "gripper": fx.gripper, "sensor_bot": fx.sensor_bot, "spirit": fx.spirit}
OPTIONS = {
    "default": SdfOptions(),
    "fixed-1.11": SdfOptions(version="1.11", fix_base=True),
    "model-frame-1.9": SdfOptions(version="1.9", pose_frames=PoseFrames.MODEL),
    "world": SdfOptions(world=True, version="1.11"),
}


@pytest.mark.parametrize("robot_name", sorted(ROBOTS))
@pytest.mark.parametrize("option_name", sorted(OPTIONS))
def test_drake_matches_ir(robot_name: str, option_name: str) -> None:
    robot = ROBOTS[robot_name]()
    assert not verify(robot).errors
    result = build_sdf(robot, OPTIONS[option_name])
    comparison = compare_with_drake(robot, result, samples=5)
    assert comparison.ok, comparison.problems
    assert comparison.max_fk_error <= 1e-9


def test_fix_base_welds_root_to_world() -> None:
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    for fix in (False, True):
        plant = MultibodyPlant(0.0)
        Parser(plant).AddModelsFromString(build_sdf(fx.arm(), SdfOptions(fix_base=fix)).text, "sdf")
        plant.Finalize()
        # A floating base adds 7 positions (quaternion + translation) to the 3 joints.
        assert plant.num_positions() == (3 if fix else 10)


def test_mimic_written_only_for_1_11() -> None:
    from lxml import etree
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    for version, expected in (("1.10", 0), ("1.11", 2)):
        result = build_sdf(fx.gripper(), SdfOptions(version=version))
        mimics = etree.fromstring(result.text.encode()).findall(".//joint/axis/mimic")
        assert len(mimics) == expected
        dropped = [f for f in result.findings if f.code == "sdf-mimic-dropped"]
        assert len(dropped) == 2 - expected
        # libsdformat accepts the 1.11 element under strict parsing. (Drake 1.51 then ignores SDF's
        # <mimic>: it builds coupler constraints only from URDF mimic / drake:mimic.)
        plant = MultibodyPlant(0.001)
        parser = Parser(plant)
        parser.SetStrictParsing()
        parser.AddModelsFromString(result.text, "sdf")
    tip = next(m for m in mimics if m.get("joint") == "finger_joint" and m.findtext("offset") == "0.1")
    assert tip.findtext("multiplier") == "-0.5"
    assert tip.findtext("reference") == "0"


def test_world_with_props_loads() -> None:
    from pydrake.multibody.parsing import Parser
    from pydrake.multibody.plant import MultibodyPlant

    prop = fx.gripper()
    prop.name = "block"
    prop.links = prop.links[:1]
    prop.joints = []
    text = build_sdf(fx.arm(), SdfOptions(world=True, props=[SdfProp(prop), SdfProp(fx.gripper(), static=True)])).text
    plant = MultibodyPlant(0.0)
    Parser(plant).AddModelsFromString(text, "sdf")
    plant.Finalize()
    names = {plant.GetModelInstanceName(plant.GetModelInstanceByName(n)) for n in ("arm", "block", "gripper")}
    assert names == {"arm", "block", "gripper"}
