"""The ROS 2 URDF: a copy of the IR with one ``<ros2_control>`` for Gazebo, emitted as URDF.

The block names every actuated joint (``robot.actuated_joints()``: mimic joints are never
commanded) with the chosen command interface and position + velocity state interfaces, uses the
``gz_ros2_control/GazeboSimSystem`` hardware, and is followed by the ``<gazebo>`` plugin that starts
the controller manager with ``controllers.yaml``. Sensors get ``<gazebo reference>`` blocks so that
Gazebo's URDF converter creates them.
"""

from __future__ import annotations

import copy

from lxml import etree

from robodesc.emit.sdf import SdfFlavour, sensor_element
from robodesc.emit.urdf import UrdfOptions, emit_urdf
from robodesc.ir.diagnostics import Findings
from robodesc.ir.geometry import Extension
from robodesc.ir.model import ControlInterface, ControlJoint, Robot, Ros2Control, SensorType

STAGE = "emit:ros2"
HARDWARE_PLUGIN = "gz_ros2_control/GazeboSimSystem"
GZ_PLUGIN_FILE = "gz_ros2_control-system"
GZ_PLUGIN_NAME = "gz_ros2_control::GazeboSimROS2ControlPlugin"
# What <parameters> says in the URDF; the launch file swaps in the absolute path at launch time.
CONTROLLERS_PLACEHOLDER = "controllers.yaml"


def ros2_control_node(robot: Robot, command: str) -> Ros2Control:
    joints = [
        ControlJoint(
            name=j.name,
            command_interfaces=[ControlInterface(command)],
            state_interfaces=[ControlInterface("position"), ControlInterface("velocity")],
        )
        for j in robot.actuated_joints()
        if j.type.dof == 1
    ]
    return Ros2Control(name="GazeboSimSystem", type="system", plugin=HARDWARE_PLUGIN, joints=joints)


def _xml(el: etree._Element) -> str:
    return etree.tostring(el, encoding="unicode")


def ros2_robot(robot: Robot, command: str, findings: Findings) -> Robot:
    """A copy of ``robot`` ready for ``emit_urdf``; ``robot`` itself is not touched."""
    out = copy.deepcopy(robot)
    if out.ros2_controls:
        findings.warn(
            "ros2-control-replaced",
            f"the input's {len(out.ros2_controls)} <ros2_control> block(s) are replaced by one for Gazebo",
            element=f"robot {robot.name!r}",
            stage=STAGE,
        )
    for j in out.actuated_joints():
        if j.type.dof != 1:
            findings.warn(
                "ros2-joint-skipped",
                f"a {j.type.value} joint has no single command interface; not in ros2_control",
                element=f"joint {j.name!r}",
                stage=STAGE,
            )
    rc = ros2_control_node(out, command)
    out.ros2_controls = [rc]
    gazebo = etree.Element("gazebo")
    plugin = etree.SubElement(gazebo, "plugin", filename=GZ_PLUGIN_FILE, name=GZ_PLUGIN_NAME)
    etree.SubElement(plugin, "parameters").text = CONTROLLERS_PLACEHOLDER
    out.extensions.append(Extension(tag="gazebo", xml=_xml(gazebo), anchor=("ros2_control", rc.name)))
    parent_joint = out.parent_joint()
    for sensor in out.sensors:
        if sensor.type is SensorType.FORCE_TORQUE:
            ref = sensor.parent_joint or (parent_joint[sensor.parent].name if sensor.parent in parent_joint else None)
        else:
            ref = sensor.parent
        if ref is None:
            continue
        block = etree.Element("gazebo", reference=ref)
        link = out.link(sensor.parent)
        collisions = [c.name or f"collision_{i}" for i, c in enumerate(link.collisions)]
        sensor_element(
            block,
            out,
            sensor,
            name=sensor.name,
            link=sensor.parent,
            flavour=SdfFlavour.HARMONIC,
            version="1.10",
            contact_collisions=collisions,
            anchored=False,
        )
        out.extensions.append(Extension(tag="gazebo", xml=_xml(block), anchor=("ros2_control", rc.name)))
    # The <gazebo reference> blocks now carry the sensors; Isaac-style top-level <sensor> tags would
    # only confuse ROS tools.
    out.sensors = []
    return out


def emit_ros2_urdf(robot: Robot, command: str, options: UrdfOptions, findings: Findings) -> str:
    return emit_urdf(ros2_robot(robot, command, findings), options, findings)
