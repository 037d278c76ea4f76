"""A long chain whose bodies sit far from the origin: usd-core hands body poses back in float32,
so the rest-pose tolerance follows their magnitude (issue 26)."""

from __future__ import annotations

from pathlib import Path

import robodesc

LINK = (
    '<link name="l{i}"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" '
    'iyz="0"/></inertial></link>'
)
JOINT = (
    '<joint name="j{i}" type="revolute"><parent link="l{p}"/><child link="l{i}"/><origin xyz="0 0 {dz}"/>'
    '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
)


def _chain(n: int, dz: float) -> str:
    parts = ['<robot name="chain">', *(LINK.format(i=i) for i in range(n))]
    parts += [JOINT.format(i=i, p=i - 1, dz=dz) for i in range(1, n)]
    return "\n".join([*parts, "</robot>"])


def test_bodies_far_from_the_origin_pass_the_rest_pose_check(tmp_path: Path) -> None:
    # 600 links 3.3 m apart: the tip is 2 km out, where float32 keeps ~1.2e-4 m (the fixed 1e-5 failed).
    src = tmp_path / "far.urdf"
    src.write_text(_chain(600, 3.3))
    result = robodesc.compile_to_usd(str(src), tmp_path / "far.usda")
    report = result.validation
    assert report is not None and report.ok, [c.message for c in report.failures][:3]
