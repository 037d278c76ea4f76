"""The settings of an Isaac Sim import, and the importer-settings file that applies them.

One :class:`IsaacSettings` drives the USD emitter, the importer-settings file (in both the Isaac Sim
5.x ``ImportConfig`` and Isaac Lab ``UrdfConverterCfg`` vocabularies) and the Isaac Lab module, so
the three can never disagree.

Units: ``stiffness``/``damping`` are SI here (N·m/rad and N·m·s/rad for revolute joints; N/m and
N·s/m for prismatic). Isaac Sim's importer and USD drives take angular gains per DEGREE; the
conversion happens in exactly one place, :func:`usd_gain`.
"""

from __future__ import annotations

import json
import math
import re
from dataclasses import asdict, dataclass, field

import robodesc.emit.usd as usd
from robodesc.emit.common import flags as common
from robodesc.emit.common.approximation import Approximation, global_mode
from robodesc.emit.common.flags import flag
from robodesc.ir.model import Joint, Robot
from robodesc.ir.rules import lookup

DEG_PER_RAD = 180.0 / math.pi

Gains = float | dict[str, float]


@dataclass(slots=True)
class IsaacSettings:
    fix_base: bool = field(default=True, metadata=common.FIX_BASE)
    merge_fixed_joints: bool = field(
        default=False,
        metadata=flag(
            "importer setting: merge fixed joints on URDF import (dont_collapse keeps marked bodies)", kind="on"
        ),
    )
    drive_type: str = field(default="force", metadata=common.DRIVE_TYPE)  # force | acceleration
    target_type: str = field(default="position", metadata=common.TARGET_TYPE)  # none | position | velocity
    stiffness: Gains = field(default=100.0, metadata=common.STIFFNESS)
    damping: Gains = field(default=1.0, metadata=common.DAMPING)
    self_collision: bool = field(default=False, metadata=common.SELF_COLLISION)
    # convexHull | convexDecomposition | boundingCube | boundingSphere | none
    collision_approximation: Approximation = field(default="convexHull", metadata=usd.COLLISION_APPROXIMATION)
    solver_position_iterations: int | None = field(default=None, metadata=usd.POSITION_ITERATIONS)
    solver_velocity_iterations: int | None = field(default=None, metadata=usd.VELOCITY_ITERATIONS)
    contact_offset: float | None = field(default=None, metadata=usd.CONTACT_OFFSET)
    rest_offset: float | None = field(default=None, metadata=usd.REST_OFFSET)
    import_inertia_tensor: bool = True
    # One .usda, or an interface layer + payload as NVIDIA's converter writes.
    layered: bool = field(default=False, metadata=usd.LAYERED)
    physics_scene: bool = field(default=False, metadata=usd.PHYSICS_SCENE)
    friction_combine: str | None = field(default=None, metadata=common.FRICTION_COMBINE)
    default_friction: float = field(default=0.5, metadata=common.DEFAULT_FRICTION)
    # The Isaac Sim release the USD's PhysX joint attributes are written for (docs/isaac.md).
    isaac_version: str = field(default="6", metadata=usd.ISAAC_VERSION)
    motor_envelope: bool = field(default=False, metadata=usd.MOTOR_ENVELOPE)
    # The USD Isaac Sim 6's importer made of the folder's URDF: the physics layer's prim paths are
    # read from it instead of computed by the importer's naming rules (docs/isaac.md).
    importer_usd: str | None = field(
        default=None,
        metadata=flag(
            "the USD Isaac Sim 6's URDF importer wrote from this folder's URDF: <robot>_physics.usda addresses "
            "its prims as read from it (default: by the importer's naming rules)",
            metavar="FILE",
        ),
    )
    # Spawn pose for Isaac Lab: base position (m) and the initial joint positions (rad) by regex.
    init_pos: tuple[float, float, float] = field(default=(0.0, 0.0, 0.0), metadata=common.INIT_POS)
    init_joint_pos: dict[str, float] = field(default_factory=dict, metadata=common.INIT_JOINT_POS)
    # The Isaac Lab the generated module targets: "3" (quaternions x, y, z, w) or "2" (w, x, y, z).
    isaac_lab_version: str = field(
        default="3",
        metadata=flag(
            "Isaac Lab the generated module targets (default 3: quaternions x,y,z,w and joint_*_limit; "
            "2: w,x,y,z and *_limit_sim)",
            choices=("3", "2"),
        ),
    )

    def gains(self, joint: Joint) -> tuple[float, float]:
        """SI (stiffness, damping) for ``joint``; 0 where no rule matches."""
        k = lookup(self.stiffness, joint.name, "stiffness") or 0.0
        d = lookup(self.damping, joint.name, "damping") or 0.0
        return k, d


def usd_gain(value: float, joint: Joint) -> float:
    """SI gain → USD drive units: angular gains are per degree (x π/180), linear ones unchanged."""
    return value / DEG_PER_RAD if joint.type.is_angular else value


_APPROX_TO_LAB = {"convexHull": "Convex Hull", "convexDecomposition": "Convex Decomposition"}
_APPROX_TO_SIM6 = {
    **_APPROX_TO_LAB,
    "boundingSphere": "Bounding Sphere",
    "boundingCube": "Bounding Cube",
}


def importer_settings(robot: Robot, settings: IsaacSettings) -> dict[str, object]:
    """The importer-settings document (JSON-ready)."""
    joints = robot.actuated_joints()
    per_joint = {j.name: dict(zip(("stiffness", "damping"), settings.gains(j), strict=True)) for j in joints}
    uniform_k = _uniform([v["stiffness"] for v in per_joint.values()])
    uniform_d = _uniform([v["damping"] for v in per_joint.values()])
    angular = any(j.type.is_angular for j in joints)
    scale = 1.0 / DEG_PER_RAD if angular else 1.0
    sim5: dict[str, object] = {
        "merge_fixed_joints": settings.merge_fixed_joints,
        "replace_cylinders_with_capsules": False,
        "convex_decomp": global_mode(settings.collision_approximation) == "convexDecomposition",
        "import_inertia_tensor": settings.import_inertia_tensor,
        "fix_base": settings.fix_base,
        "self_collision": settings.self_collision,
        "density": 0.0,
        "default_drive_type": settings.target_type,
        "joint_drive_type": settings.drive_type,
        # Isaac Sim 5.x takes angular gains per degree.
        "default_drive_strength": (uniform_k if uniform_k is not None else 0.0) * scale,
        "default_position_drive_damping": (uniform_d if uniform_d is not None else 0.0) * scale,
        "distance_scale": 1.0,
        "up_vector": [0.0, 0.0, 1.0],
        "create_physics_scene": False,
        "make_default_prim": True,
        "collision_from_visuals": False,
        "parse_mimic": True,
        "override_joint_dynamics": False,
    }
    lab: dict[str, object] = {
        "fix_base": settings.fix_base,
        "root_link_name": robot.root.name,
        "link_density": 0.0,
        "merge_fixed_joints": settings.merge_fixed_joints,
        "joint_drive": {
            "drive_type": settings.drive_type,
            "target_type": settings.target_type,
            "gains": {
                "stiffness": settings.stiffness,
                "damping": settings.damping,
            },
        },
        "collision_from_visuals": False,
        "collision_type": _APPROX_TO_LAB.get(global_mode(settings.collision_approximation), "Convex Hull"),
        "self_collision": settings.self_collision,
        "force_usd_conversion": True,
        "make_instanceable": False,
    }

    # Isaac Sim 6.x: the fields of isaacsim.asset.importer.urdf.URDFImporterConfig (6.2). Gains are
    # SI; its joint patterns are re.search patterns, so each name is anchored.
    def anchored(values: dict[str, float]) -> dict[str, float]:
        return {f"^{re.escape(name)}$": value for name, value in values.items()}

    sim6: dict[str, object] = {
        "merge_fixed_joints": settings.merge_fixed_joints,
        "collision_type": _APPROX_TO_SIM6.get(global_mode(settings.collision_approximation), "Convex Hull"),
        "allow_self_collision": settings.self_collision,
        "fix_base": settings.fix_base,
        "joint_drive_type": settings.drive_type,
        "joint_target_type": settings.target_type,
        "override_joint_stiffness": anchored({n: v["stiffness"] for n, v in per_joint.items()}),
        "override_joint_damping": anchored({n: v["damping"] for n, v in per_joint.items()}),
    }
    doc: dict[str, object] = {
        "robot": robot.name,
        "units": {
            "isaac_sim_5_importer": "angular gains per degree (USD drive units), linear per metre",
            "isaaclab_urdf_converter_cfg": "gains in SI: N·m/rad, N·m·s/rad (Isaac Lab converts)",
            "isaac_sim_6_importer": "gains in SI: N·m/rad, N·m·s/rad (URDFImporterConfig converts)",
        },
        "isaac_sim_5_importer": sim5,
        "isaac_sim_6_importer": sim6,
        "isaaclab_urdf_converter_cfg": lab,
        "physx": {
            "solver_position_iteration_count": settings.solver_position_iterations,
            "solver_velocity_iteration_count": settings.solver_velocity_iterations,
            "contact_offset": settings.contact_offset,
            "rest_offset": settings.rest_offset,
        },
        "per_joint_si_gains": per_joint,
        # importer_usd is a path on this machine, read once to address the physics layer: not a setting.
        "robodesc_settings": {k: v for k, v in asdict(settings).items() if k != "importer_usd"},
    }
    if uniform_k is None or uniform_d is None:
        sim5["note"] = "gains differ per joint: the USD asset carries each joint's drive; see per_joint_si_gains"
    return doc


def importer_settings_json(robot: Robot, settings: IsaacSettings) -> str:
    return json.dumps(importer_settings(robot, settings), indent=2, sort_keys=False) + "\n"


def _uniform(values: list[float]) -> float | None:
    if not values:
        return 0.0
    return values[0] if all(v == values[0] for v in values) else None
