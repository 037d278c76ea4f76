"""Golden SDF and ROS 2 files for representative robots (regenerate with ``pytest --update-golden``)."""

from __future__ import annotations

import pytest

from robodesc.emit.common.paths import PathMode
from robodesc.emit.ros2 import Ros2Options, build_ros2_package
from robodesc.emit.sdf import PoseFrames, SdfFlavour, SdfOptions, SdfProp, emit_sdf
from tests.conftest import Golden
from tests.sdf import fixtures as fx

OUT = str(fx.GOLDEN)

CASES = {
    "arm_fixed.sdf": (fx.arm, SdfOptions(fix_base=True, out_dir=OUT)),
    "arm_model_frame.sdf": (
        fx.arm,
        SdfOptions(fix_base=True, pose_frames=PoseFrames.MODEL, version="1.9", out_dir=OUT),
    ),
    "spirit.sdf": (fx.spirit, SdfOptions(out_dir=OUT)),
    "gripper_1_11.sdf": (fx.gripper, SdfOptions(version="1.11", fix_base=True)),
    "gripper_1_10.sdf": (fx.gripper, SdfOptions(fix_base=True)),
    "sensor_bot.sdf": (fx.sensor_bot, SdfOptions(version="1.11")),
    "sensor_bot_classic.sdf": (fx.sensor_bot, SdfOptions(flavour=SdfFlavour.CLASSIC)),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_sdf_golden(name: str, golden: Golden) -> None:
    make, options = CASES[name]
    text, findings = emit_sdf(make(), options)
    # Without file locations, which depend on where the checkout lives.
    report = "".join(f"<!-- {f.severity.value}: {f.code}: {f.element}: {f.message} -->\n" for f in findings)
    golden.check(name, text + report)


def test_world_golden(golden: Golden) -> None:
    prop = fx.gripper()
    prop.name = "cube_prop"
    prop.links = prop.links[:1]
    prop.joints = []
    text, _ = emit_sdf(fx.sensor_bot(), SdfOptions(world=True, version="1.11", props=[SdfProp(prop)]))
    golden.check("sensor_bot_world.sdf", text)


def test_ros2_golden(golden: Golden) -> None:
    package = build_ros2_package(fx.sensor_bot(), Ros2Options(path_mode=PathMode.RELATIVE))
    assert sorted(package.files) == [
        "controllers.yaml",
        "ros_gz_bridge.yaml",
        "sensor_bot.launch.py",
        "sensor_bot.urdf",
        "world.sdf",
    ]
    for name, text in package.files.items():
        golden.check(f"ros2/{name}", text)
