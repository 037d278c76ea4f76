"""Named option sets, one per target. ``PRESETS`` lists the passes each one runs (in pipeline
order); ``PRESET_OPTIONS`` holds the option values behind it."""

from __future__ import annotations

from robodesc.ir.diagnostics import ConfigError
from robodesc.passes.options import (
    STRIP_KINDS,
    ArmatureRule,
    PassOptions,
    RenameRule,
    RepairPolicy,
    closest,
    options_from_mapping,
)

# Quad-SDK's leg joints (leg 0 front-left, 1 back-left, 2 front-right, 3 back-right).
QUAD_SDK_RENAME: tuple[RenameRule, ...] = (
    *(RenameRule(str(8 + leg), f"j_abad_{leg}") for leg in range(4)),
    *(RenameRule(str(2 * leg), f"j_hip_{leg}") for leg in range(4)),
    *(RenameRule(str(2 * leg + 1), f"j_knee_{leg}") for leg in range(4)),
)

# J_rotor 1.231e-4 kg·m², gear ratio 6 (abad, hip) and 12 (knee); values as Quad-SDK's bridge set them.
SPIRIT_ARMATURE: tuple[ArmatureRule, ...] = (
    ArmatureRule(r"^j_abad_[0-3]$", 4.4316e-3),
    ArmatureRule(r"^j_hip_[0-3]$", 4.4316e-3),
    ArmatureRule(r"^j_knee_[0-3]$", 1.77264e-2),
)

# Non-URDF leftovers no consumer of the target reads.
_LEFTOVERS = frozenset({"contact", "surface"})

PRESET_OPTIONS: dict[str, dict[str, object]] = {
    "isaac_sim": {
        "sanitize_names": True,
        "unique_materials": True,
        "fill_inertia": True,
        "repair_inertia": RepairPolicy.GEOMETRY,
        # A UsdPhysics reader cannot be told "no mass" (docs/passes.md, massless).
        "mass_from_colliders": True,
        "placeholder_masses": True,
        # dont_collapse is read by Isaac: kept.
        "strip": frozenset({"gazebo", "transmission", "ros2_control"}) | _LEFTOVERS,
        "isaac_limits": True,
        "keep_bodies": True,
        "default_armature": True,
    },
    "ros2": {
        "unique_materials": True,
        "fill_inertia": True,
        "strip": _LEFTOVERS,
    },
    "gazebo": {
        "unique_materials": True,
        "fill_inertia": True,
        "repair_inertia": RepairPolicy.GEOMETRY,
        "mass_from_colliders": True,
        "strip": _LEFTOVERS | {"dont_collapse"},
    },
    "mujoco": {
        "unique_materials": True,
        "fill_inertia": True,
        "repair_inertia": RepairPolicy.GEOMETRY,
        "mass_from_colliders": True,
        "strip": frozenset(STRIP_KINDS),
        "convert_meshes": {".dae": ".obj"},
    },
    # The MJCF target's implied preset: MuJoCo refuses an invalid inertia on a moving body, so invalid
    # ones are repaired from geometry (as for Isaac); a moving link with no mass in its fixed group
    # gets its geometry's (a dead body otherwise); other links without an inertial are left to the
    # emitter (a massless welded body is fine in MuJoCo), so no mass is invented for frame links.
    "mjcf": {
        "fill_inertia": True,
        "mass_from_colliders": True,
        "repair_inertia": RepairPolicy.GEOMETRY,
        "repair_missing": False,
        "default_armature": True,
        # Fixed links fused into their parents (kept as sites): fewer bodies, as menagerie's models
        # (ANYmal C ran 13% slower than menagerie's with its fixed links as bodies, issue 35).
        "merge_fixed": True,
    },
    "quad_sdk": {
        "rename": QUAD_SDK_RENAME,
        "strip": frozenset(STRIP_KINDS),
        "repair_inertia": RepairPolicy.QUAD_SDK,
        "repair_missing": True,
        "unique_materials": True,
        "armature_by_robot": {"spirit": SPIRIT_ARMATURE},
    },
}

# Presets that go on top of the target's own (a workflow rather than a target): their pass options
# are added to the target preset's, and their target options fill what the user did not give. A
# target takes only the options its options class has (docs/contact.md: one choice per cause).
OVERLAYS: dict[str, dict[str, object]] = {
    "gazebo_parity": {
        # Cause 6: an unspecified URDF damping is 0 in ODE, about 0.1 through Isaac's importer.
        "explicit_damping": True,
    },
}
OVERLAY_TARGET_OPTIONS: dict[str, dict[str, object]] = {
    "gazebo_parity": {
        # Cause 8: ODE takes the smaller of two friction coefficients; PhysX averages them.
        "friction_combine": "min",
        # Gazebo's default surface: mu 1 where the source gives none.
        "default_friction": 1.0,
        # Cause 3: ODE iterates 300 times; PhysX's maximum is 255 (costly: lower it when it holds).
        "solver_position_iterations": 255,
        "solver_velocity_iterations": 16,
        # Cause 5: ODE has no contact skin; PhysX's default is about 2 cm.
        "contact_offset": 0.001,
        "rest_offset": 0.0,
        # Cause 1: a dynamic mesh collider is a convex hull in ODE's fallback and in PhysX.
        "collision_approximation": "convexHull",
    },
}
PRESET_OPTIONS.update(OVERLAYS)

PRESETS: dict[str, tuple[str, ...]] = {
    "isaac_sim": (
        "sanitize_names",
        "unique_materials",
        "geometric_inertia",
        "massless",
        "repair_inertia",
        "strip_tags",
        "default_armature",
        "isaac_limits",
        "flat_colliders",
        "keep_bodies",
        "zero_pose",
    ),
    "ros2": ("unique_materials", "geometric_inertia", "strip_tags", "zero_pose"),
    "gazebo": ("unique_materials", "geometric_inertia", "massless", "repair_inertia", "strip_tags", "zero_pose"),
    "mujoco": ("unique_materials", "geometric_inertia", "massless", "repair_inertia", "strip_tags", "zero_pose"),
    "mjcf": ("geometric_inertia", "massless", "repair_inertia", "merge_fixed", "default_armature", "zero_pose"),
    "quad_sdk": ("rename", "unique_materials", "repair_inertia", "strip_tags", "armature", "zero_pose"),
    # An overlay: these on top of the target's own preset's passes.
    "gazebo_parity": ("explicit_damping", "zero_pose"),
}


def preset_options(name: str, **overrides: object) -> PassOptions:
    """The options a preset implies, with ``overrides`` (option names checked) on top."""
    if name not in PRESET_OPTIONS:
        raise ConfigError(
            f"unknown preset {name!r}{closest(name, PRESET_OPTIONS)}; presets are {', '.join(PRESET_OPTIONS)}",
            element="option 'preset'",
        )
    return options_from_mapping(overrides, options_from_mapping(PRESET_OPTIONS[name]))
