"""Behaviour checked by simulation, on CPU: hold, drop and slide in MuJoCo, Drake, Newton and PhysX.

``run_dynamics(robot, {"urdf": path, ...})`` returns a :class:`DynamicsReport`; docs/dynamics.md
describes the scenarios and thresholds. Light to import: each engine loads when it runs.
"""

from robodesc.validation.dynamics.result import DynamicsReport, Run
from robodesc.validation.dynamics.run import READERS, engine_for, kind_of, run_dynamics
from robodesc.validation.dynamics.scenarios import DynamicsOptions, Thresholds, home_pose

__all__ = [
    "READERS",
    "DynamicsOptions",
    "DynamicsReport",
    "Run",
    "Thresholds",
    "engine_for",
    "home_pose",
    "kind_of",
    "run_dynamics",
]
