"""What each kind of warning means downstream: which consumers refuse or change the element, and
which option repairs it. The CLI prints this once per kind of warning; ``--json`` carries it; the
table in docs/diagnostics.md says the same.

It lives beside the CLI, not in the stage that found the defect, because it speaks about every
target and every option at once.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True, slots=True)
class Advice:
    consumers: str  # what the consumers of the output will do with it
    repair: str = ""  # the option (or the edit) that repairs it
    # The finding's own message says both already, in one line (the README's first command meets
    # one): the CLI prints no "->" line for it; --json still carries both.
    in_message: bool = False


_INERTIA = Advice(
    "MuJoCo refuses a physically invalid inertia; PhysX (Isaac Sim) recomputes mass properties from the "
    "colliders; Gazebo and pybullet simulate it as given, often unstably",
    "--invalid-inertia repair (from geometry)",
)

ADVICE: dict[str, Advice] = {
    "consumer-warning": Advice(
        "the consumer that checked the output printed this while loading it; the output is written as is",
        "the message names the element to edit in the source",
    ),
    "bad-inertia": _INERTIA,
    "bad-mass": _INERTIA,
    "tiny-inertia": Advice(
        "Newton (Isaac Lab 3's kit-less backend) raises the moment, adding about 1e-6 kg·m² to the body; "
        "MuJoCo and PhysX take it as given",
        "--invalid-inertia repair (raises it to the floor)",
    ),
    "massless-link": Advice(
        "MuJoCo refuses a moving body without mass; PhysX gives it a default mass; ROS tools do not mind",
        "--merge-fixed (when it hangs on a fixed joint) or --repair-inertia geometry",
    ),
    "missing-mesh": Advice(
        "URDF and SDF keep the reference (a consumer that cannot find the file either skips the shape "
        "or refuses the model); USD leaves the shape out",
        "--package NAME=DIR where the mesh lives, or --missing-mesh primitive|drop",
    ),
    "usd-missing-mesh": Advice("Isaac Sim and usdview show the link without that shape", "--package NAME=DIR"),
    "unknown-element": Advice(
        "kept verbatim in the URDF output; SDF and USD leave it out (each says so)", "--strip KINDS removes them"
    ),
    "extra-numbers": Advice(
        "urdfdom (ROS) refuses the file; pybullet, Drake and the Isaac importer read the first numbers",
        "edit the source",
    ),
    "number-trailing-dot": Advice(
        "urdfdom (ROS) refuses the file; pybullet reads the number before the dot", "edit the source"
    ),
    "urdf-limit-defaults": Advice(
        "urdfdom (ROS) refuses a revolute/prismatic <limit> without effort and velocity; the values written are "
        "what controllers and simulators will enforce",
        "give effort and velocity in the source (or UrdfOptions.default_effort / default_velocity)",
    ),
    "urdf-capsule-split": Advice(
        "urdfdom (ROS) refuses <capsule>; the cylinder and two spheres are the same solid", "capsules='keep'"
    ),
    "urdf-spherical-split": Advice(
        "urdfdom (ROS) refuses type='spherical'; ros2_control commands the three revolute joints",
        "edit the source",
    ),
    "urdf-not-ros": Advice(
        "pybullet, MuJoCo and Isaac Sim read it; urdfdom (robot_state_publisher, MoveIt, check_urdf) refuses the file",
        "--ros2 (or a composition input) writes the URDF 1.0 equivalent",
        in_message=True,
    ),
    "usd-mesh-not-read": Advice(
        "the USD shows the link without that shape; --copy-meshes refuses the same file",
        "--package NAME=DIR where the mesh lives, or move the mesh inside the robot's folder",
    ),
    "comma-vector": Advice("urdfdom (ROS) refuses the file; pybullet reads commas as separators", "edit the source"),
    "extra-shapes": Advice("urdfdom, pybullet and the Isaac importer use the first shape only", "edit the source"),
    "unmodelled-geometry": Advice(
        "urdfdom refuses the file; pybullet reads planes; the URDF output keeps the element, SDF and USD leave it out",
        "replace it with a box, cylinder, sphere or mesh",
    ),
    "zero-size-shape": Advice(
        "urdfdom keeps it; MuJoCo and PhysX refuse zero-size geometry; robodesc dropped it from every output",
        "edit the source",
    ),
    "bad-geometry": Advice("no consumer can build the shape; robodesc dropped it from every output", "edit the source"),
    "trailing-content": Advice("urdfdom, pybullet and Drake stop at the root element too", "edit the source"),
    "xml-declaration": Advice("urdfdom and pybullet accept it; libxml2-based tools refuse the file", "edit the source"),
    "package-by-folder": Advice(
        "ROS resolves package:// through its package index: without a package.xml the file only loads "
        "where a tool guesses the folder as robodesc did",
        "--package NAME=DIR, or a package.xml in that folder",
    ),
    "env-unset": Advice("xacro would refuse the file", "set the variable, or edit the source"),
    "unreadable-carried": Advice(
        "ros_control reads the text as written; no simulator target uses the element", "edit the source"
    ),
    "dangling-mimic": Advice(
        "urdfdom and Gazebo ignore a mimic of a joint that does not exist; robodesc dropped it", "edit the source"
    ),
    "bad-mimic": Advice("robodesc dropped the <mimic>: the joint moves on its own", "edit the source"),
    "dangling-joint": Advice(
        "ros_control refuses a transmission or ros2_control entry of an unknown joint; robodesc dropped it",
        "edit the source",
    ),
    "dangling-link": Advice("robodesc dropped the element that names no link", "edit the source"),
    "limit-unbounded": Advice(
        "urdfdom (ROS) reads a missing bound as 0 (both missing: a joint that cannot move); MuJoCo, pybullet "
        "and Drake read no limit, as robodesc's SDF and USD do",
        "give lower= and upper=, or make the joint continuous",
    ),
    "zero-outside-limits": Advice(
        "simulators start the joint at 0 and push it into its range on the first step", "--preset with zero_pose"
    ),
    "undefined-material": Advice("every consumer draws the link in its default colour", "define the material"),
    "unnamed-robot": Advice("robodesc names it 'robot'", "name the <robot>"),
    "repeated-element": Advice("urdfdom and pybullet use the first one, as robodesc does", "edit the source"),
    "undeclared-prefix": Advice(
        "urdfdom and pybullet ignore namespaces; libxml2-based tools refuse the file", "declare the prefix (xmlns:...)"
    ),
    "world-link": Advice(
        "Gazebo and Drake read 'world' as the ground; urdfdom refuses an undeclared link",
        'declare <link name="world"/>',
    ),
    "validation": Advice(
        "the consumer named in the message refused or changed this element of the source; robodesc wrote it "
        "as the source has it",
        "the option named for the element's own warning",
    ),
}


def advice_for(code: str) -> Advice | None:
    if code.startswith("validation:"):
        return ADVICE["validation"]
    return ADVICE.get(code)
