"""Tolerances and switches of the validation pass."""

from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass, field

# MuJoCo refuses a moving body without mass: a converter gives it this much (kg), which validation
# then reads as a token, not as a changed mass (emit/mjcf writes it; validation/mujoco_mjcf knows it).
TOKEN_MASS = 1e-3


@dataclass(slots=True)
class ValidateOptions:
    # Give the root a free joint (a floating base). MuJoCo welds a URDF root to the world; the
    # comparisons are relative to the root either way, so this only changes the simulation check.
    floating_base: bool = False
    # Forward kinematics at this many random configurations within the joint limits (plus q = 0).
    fk_samples: int = 8
    seed: int = 0
    # Tolerances. Emitted numbers round-trip exactly and independent parsers agree to ~1e-15, so
    # these are tight: anything above them is a real difference, not noise.
    mass_rel_tol: float = 1e-6
    inertia_rel_tol: float = 1e-6  # relative to the largest principal moment of the link
    position_tol: float = 1e-6  # m: centre of mass and FK positions
    # FK positions may also differ by this much relative to the link's distance from the root: the
    # rounding of the numbers compared (a prismatic joint at q = 6.2e29 m puts a link where doubles
    # are 1e14 m apart). Float32 consumers (USD) use FLOAT32_REL_TOL.
    position_rel_tol: float = 1e-12
    rotation_tol: float = 1e-6  # rad: FK orientations
    axis_tol: float = 1e-9  # unit-vector difference
    limit_tol: float = 1e-9  # rad or m
    gain_rel_tol: float = 1e-9  # MJCF actuator kp/kv, relative: written at full precision
    # Simulation: hold every joint at its start position and step under gravity.
    simulate: bool = True
    sim_duration: float = 0.5  # s
    sim_timestep: float = 0.002  # s
    max_speed: float = 100.0  # rad/s or m/s in any degree of freedom counts as an explosion
    penetration_tol: float = 1e-3  # m: deeper contacts between robot geoms at rest are reported
    # Load USD outputs in PhysX too (validation/physx_usd.py) when a PhysX interpreter exists: a
    # worker process, about 5 s a robot. ROBODESC_VALIDATE_PHYSX=0 turns the default off (the test
    # suite does, outside the PhysX consumer's own tests: hundreds of USD compiles would each pay it).
    physx: bool = field(default_factory=lambda: os.environ.get("ROBODESC_VALIDATE_PHYSX", "1") != "0")
    # Meshes MuJoCo cannot read (DAE ...) are converted to STL here (default: a folder in the temp dir).
    mesh_cache_dir: str | None = None
    # Package roots for ``package://`` URIs left in the text under validation.
    package_paths: Mapping[str, str] = field(default_factory=dict)
