"""Closed-form, mesh and composite inertia against hand-computed values, and the geometric_inertia pass."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import trimesh

from robodesc.ir import Box, Capsule, Collision, Cylinder, Inertial, Link, Mesh, Pose, Robot, Sphere, Visual
from robodesc.ir.inertia import inertia_problem, tensor
from robodesc.passes.geometric_inertia import geometric_inertia
from robodesc.passes.shape_inertia import inertial_from_props, link_props, mesh_props, primitive_props
from tests.passes.pass_helpers import codes, ctx


def _inertial(shapes: list[tuple[object, Pose | None]], mass: float, origin: Pose | None = None) -> Inertial:
    link = Link("l", collisions=[Collision(geometry=g, origin=o) for g, o in shapes])  # type: ignore[arg-type]
    found = link_props(link)
    assert found is not None
    return inertial_from_props(found[0], mass=mass, origin=origin)


def _diag(inertial: Inertial) -> tuple[float, float, float]:
    assert inertial.inertia is not None
    return (inertial.inertia.ixx, inertial.inertia.iyy, inertial.inertia.izz)


def test_box() -> None:
    i = _inertial([(Box((0.1, 0.2, 0.3)), None)], mass=2.0)
    # m/12 (b² + c²), m/12 (a² + c²), m/12 (a² + b²)
    assert _diag(i) == pytest.approx((2 * 0.13 / 12, 2 * 0.10 / 12, 2 * 0.05 / 12), rel=1e-12)
    assert i.origin is not None and i.origin.xyz == (0.0, 0.0, 0.0)


def test_cylinder() -> None:
    i = _inertial([(Cylinder(radius=0.05, length=0.4), None)], mass=3.0)
    # m (3r² + h²) / 12 = 3 (0.0075 + 0.16) / 12 = 0.041875; m r² / 2 = 0.00375
    assert _diag(i) == pytest.approx((0.041875, 0.041875, 0.00375), rel=1e-12)


def test_cylinder_rotated_onto_x() -> None:
    i = _inertial([(Cylinder(radius=0.05, length=0.4), Pose(rpy=(0.0, math.pi / 2, 0.0)))], mass=3.0)
    assert _diag(i) == pytest.approx((0.00375, 0.041875, 0.041875), rel=1e-9)


def test_sphere() -> None:
    i = _inertial([(Sphere(radius=0.1), None)], mass=5.0)
    assert _diag(i) == pytest.approx((0.02, 0.02, 0.02), rel=1e-12)  # 2/5 m r²


def test_capsule_with_hemispherical_caps() -> None:
    r, length, rho = 0.1, 0.2, 1000.0
    props = primitive_props(Capsule(radius=r, length=length))
    mc = rho * math.pi * r * r * length  # the cylinder part
    ms = rho * 4 / 3 * math.pi * r**3  # both caps
    assert props.volume * rho == pytest.approx(mc + ms, rel=1e-12)
    izz = mc * r * r / 2 + 0.4 * ms * r * r
    ixx = mc * (length**2 / 12 + r * r / 4) + ms * (0.4 * r * r + length**2 / 4 + 3 * length * r / 8)
    # by hand: izz = 1000π (0.002·0.005 + 0.4·(0.004/3)·0.01) = 23π/1500,
    #          ixx = 1000π (0.002·(0.04/12 + 0.0025) + (0.004/3)·0.0215) = 121π/3000
    assert izz == pytest.approx(23 * math.pi / 1500, rel=1e-12)
    assert ixx == pytest.approx(121 * math.pi / 3000, rel=1e-12)
    assert np.diag(props.tensor) * rho == pytest.approx([ixx, ixx, izz], rel=1e-12)
    # Independent check: a finely tessellated capsule through trimesh.
    mesh = trimesh.creation.capsule(height=length, radius=r, count=[96, 96])
    mesh.density = rho
    assert np.diag(mesh.moment_inertia) == pytest.approx([ixx, ixx, izz], rel=5e-3)


def test_composite_parallel_axis_mass_split_by_volume() -> None:
    # 1 m³ cube at the origin, 2 m³ box centred at x = 1.5: 3 kg splits 1 + 2, centre of mass at x = 1.
    i = _inertial([(Box((1.0, 1.0, 1.0)), None), (Box((2.0, 1.0, 1.0)), Pose(xyz=(1.5, 0.0, 0.0)))], mass=3.0)
    assert i.origin is not None and i.origin.xyz == pytest.approx((1.0, 0.0, 0.0))
    # ixx: 1·2/12 + 2·2/12 = 0.5; iyy = izz: (1/6 + 1·1²) + (2·5/12 + 2·0.5²) = 2.5
    assert _diag(i) == pytest.approx((0.5, 2.5, 2.5), rel=1e-12)
    assert i.inertia is not None and i.inertia.ixy == 0.0


def test_given_origin_is_kept_and_tensor_taken_about_it() -> None:
    i = _inertial([(Box((0.1, 0.2, 0.3)), None)], mass=1.0, origin=Pose(xyz=(0.1, 0.0, 0.0)))
    assert i.origin is not None and i.origin.xyz == (0.1, 0.0, 0.0)
    assert _diag(i) == pytest.approx((0.13 / 12, 0.10 / 12 + 0.01, 0.05 / 12 + 0.01), rel=1e-12)


def test_collision_preferred_over_visual() -> None:
    link = Link(
        "l",
        visuals=[Visual(geometry=Sphere(1.0))],
        collisions=[Collision(geometry=Box((1.0, 1.0, 1.0)))],
    )
    found = link_props(link)
    assert found is not None and found[1] == "collision" and found[0].volume == 1.0


def test_mesh_matches_trimesh(tmp_path: Path) -> None:
    box = trimesh.creation.box(extents=(0.1, 0.2, 0.3))
    box.apply_translation((0.5, -0.2, 0.1))
    path = tmp_path / "box.stl"
    box.export(path)
    mesh = Mesh(uri=str(path), path=str(path), scale=(2.0, 1.0, 1.0))
    props = mesh_props(mesh)
    scaled = trimesh.load(path, force="mesh")  # STL stores float32: compare with what trimesh reads
    scaled.apply_transform(np.diag([2.0, 1.0, 1.0, 1.0]))
    assert props.volume == pytest.approx(scaled.volume, rel=1e-12)
    assert props.com == pytest.approx(scaled.center_mass, rel=1e-12)
    i = inertial_from_props(props, mass=2.0)
    scaled.density = 2.0 / scaled.volume
    assert tensor(i.inertia) == pytest.approx(scaled.moment_inertia, rel=1e-9)  # type: ignore[arg-type]
    # and the closed form: a 0.2 x 0.2 x 0.3 box of 2 kg
    assert _diag(i) == pytest.approx((2 * 0.13 / 12, 2 * 0.13 / 12, 2 * 0.08 / 12), rel=1e-6)
    assert i.origin is not None and i.origin.xyz == pytest.approx((1.0, -0.2, 0.1), rel=1e-6)
    assert props.notes == []


def test_open_mesh_uses_convex_hull_with_a_finding(tmp_path: Path) -> None:
    box = trimesh.creation.box(extents=(1.0, 1.0, 1.0))
    box.update_faces(np.arange(len(box.faces)) != 0)  # drop one triangle: not watertight
    path = tmp_path / "open.stl"
    box.export(path)
    robot = Robot(
        "r", links=[Link("l", inertial=Inertial(mass=6.0), visuals=[Visual(Mesh(str(path), path=str(path)))])]
    )
    c = ctx(fill_inertia=True)
    geometric_inertia(robot, c)
    assert "mesh-not-watertight" in codes(c) and "inertia-from-geometry" in codes(c)
    assert _diag(robot.links[0].inertial) == pytest.approx((1.0, 1.0, 1.0), rel=1e-9)  # type: ignore[arg-type]


def test_geometric_inertia_fills_mass_without_tensor() -> None:
    robot = Robot(
        "r",
        links=[
            Link("a", inertial=Inertial(mass=2.0), collisions=[Collision(Box((0.1, 0.2, 0.3)), Pose(xyz=(0, 0, 0.5)))]),
            Link("b", inertial=Inertial(mass=1.0)),  # no geometry: reported, left alone
        ],
    )
    c = ctx(fill_inertia=True)
    geometric_inertia(robot, c)
    a = robot.links[0].inertial
    assert a is not None and a.origin is not None and a.origin.xyz == (0.0, 0.0, 0.5)
    assert _diag(a) == pytest.approx((2 * 0.13 / 12, 2 * 0.10 / 12, 2 * 0.05 / 12), rel=1e-12)
    assert a.inertia is not None and inertia_problem(a.inertia) is None
    assert robot.links[1].inertial is not None and robot.links[1].inertial.inertia is None
    assert codes(c) == ["inertia-from-geometry", "no-geometry"]
    assert all(f.stage == "pass:geometric_inertia" for f in c.findings)
