"""ROS 2 package files: they parse, and they name exactly the actuated joints (never a mimic joint)."""

from __future__ import annotations

import ast

import pytest
import yaml
from lxml import etree

from robodesc.emit.common.naming import file_stem
from robodesc.emit.ros2 import CommandInterface, ControllerKind, Ros2Options, build_ros2_package
from robodesc.frontends.load import load_string
from tests.sdf import fixtures as fx

ROBOTS = {"sensor_bot": fx.sensor_bot, "gripper": fx.gripper, "arm": fx.arm, "spirit": fx.spirit}


@pytest.mark.parametrize("robot_name", sorted(ROBOTS))
@pytest.mark.parametrize("controller", list(ControllerKind))
@pytest.mark.parametrize("command", list(CommandInterface))
def test_files_parse_and_name_actuated_joints(
    robot_name: str, controller: ControllerKind, command: CommandInterface
) -> None:
    robot = ROBOTS[robot_name]()
    actuated = [j.name for j in robot.actuated_joints()]
    mimics = [j.name for j in robot.joints if j.mimic is not None]
    files = build_ros2_package(robot, Ros2Options(command_interface=command, controller=controller)).files
    slug = file_stem(robot)  # the files are named after the input file

    controllers = yaml.safe_load(files["controllers.yaml"])
    manager = controllers["controller_manager"]["ros__parameters"]
    assert "joint_state_broadcaster" in manager
    name = (
        "joint_trajectory_controller" if controller is ControllerKind.JOINT_TRAJECTORY else "forward_command_controller"
    )
    assert manager[name]["type"].startswith(name)
    params = controllers[name]["ros__parameters"]
    assert params["joints"] == actuated
    if controller is ControllerKind.JOINT_TRAJECTORY:
        assert params["command_interfaces"] == [command.value]
    else:
        assert params["interface_name"] == command.value

    bridge = yaml.safe_load(files["ros_gz_bridge.yaml"])
    assert all(
        set(e) == {"ros_topic_name", "gz_topic_name", "ros_type_name", "gz_type_name", "direction"} for e in bridge
    )

    launch = files[f"{slug}.launch.py"]
    tree = ast.parse(launch)
    assert any(isinstance(n, ast.FunctionDef) and n.name == "generate_launch_description" for n in tree.body)
    for mimic in mimics:
        assert repr(mimic) not in launch

    urdf = etree.fromstring(files[f"{slug}.urdf"].encode())
    rc = urdf.findall("ros2_control")
    assert len(rc) == 1
    assert rc[0].findtext("hardware/plugin") == "gz_ros2_control/GazeboSimSystem"
    assert [j.get("name") for j in rc[0].findall("joint")] == actuated
    for joint in rc[0].findall("joint"):
        assert [c.get("name") for c in joint.findall("command_interface")] == [command.value]
        assert [s.get("name") for s in joint.findall("state_interface")] == ["position", "velocity"]
    plugin = urdf.find("gazebo/plugin[@filename='gz_ros2_control-system']")
    assert plugin is not None and plugin.get("name") == "gz_ros2_control::GazeboSimROS2ControlPlugin"
    assert plugin.findtext("parameters") == "controllers.yaml"
    # The URDF is still a robot robodesc reads back, with the same joints.
    again = load_string(files[f"{slug}.urdf"]).robot
    assert [j.name for j in again.joints] == [j.name for j in robot.joints]


def test_input_robot_is_not_modified() -> None:
    robot = fx.sensor_bot()
    before = (len(robot.ros2_controls), len(robot.extensions), len(robot.sensors))
    build_ros2_package(robot)
    assert (len(robot.ros2_controls), len(robot.extensions), len(robot.sensors)) == before


def test_bridge_covers_every_sensor_topic() -> None:
    files = build_ros2_package(fx.sensor_bot()).files
    entries = {
        e["gz_topic_name"]: (e["gz_type_name"], e["ros_type_name"]) for e in yaml.safe_load(files["ros_gz_bridge.yaml"])
    }
    assert entries == {
        "clock": ("gz.msgs.Clock", "rosgraph_msgs/msg/Clock"),
        "sensor_bot/front_camera/image": ("gz.msgs.Image", "sensor_msgs/msg/Image"),
        "sensor_bot/front_camera/camera_info": ("gz.msgs.CameraInfo", "sensor_msgs/msg/CameraInfo"),
        "sensor_bot/depth/depth_image": ("gz.msgs.Image", "sensor_msgs/msg/Image"),
        "sensor_bot/depth/camera_info": ("gz.msgs.CameraInfo", "sensor_msgs/msg/CameraInfo"),
        "sensor_bot/depth/depth_image/points": ("gz.msgs.PointCloudPacked", "sensor_msgs/msg/PointCloud2"),
        "sensor_bot/lidar/scan": ("gz.msgs.LaserScan", "sensor_msgs/msg/LaserScan"),
        "sensor_bot/lidar/scan/points": ("gz.msgs.PointCloudPacked", "sensor_msgs/msg/PointCloud2"),
        "sensor_bot/imu": ("gz.msgs.IMU", "sensor_msgs/msg/Imu"),
        "sensor_bot/tilt_ft": ("gz.msgs.Wrench", "geometry_msgs/msg/Wrench"),
        "bumper/contacts": ("gz.msgs.Contacts", "ros_gz_interfaces/msg/Contacts"),
        "sensor_bot/gps": ("gz.msgs.NavSat", "sensor_msgs/msg/NavSatFix"),
    }
    # The SDF sensors publish on exactly these topics.
    sdf = etree.fromstring(files["world.sdf"].encode())
    plugins = {p.get("filename") for p in sdf.iter("plugin")}
    assert {"gz-sim-sensors-system", "gz-sim-imu-system", "gz-sim-forcetorque-system"} <= plugins
    assert {"gz-sim-contact-system", "gz-sim-navsat-system", "gz-sim-physics-system"} <= plugins
    urdf = etree.fromstring(files["sensor_bot.urdf"].encode())
    topics = {s.findtext("topic") for s in urdf.iter("sensor")}
    assert topics <= set(entries)
