"""URDF (and expanded xacro) → IR.

Every modelled element becomes a typed node with its file:line. Elements robodesc does not model
(``<gazebo>``, ``<contact>``, vendor tags) are kept verbatim as :class:`Extension` and reported,
never dropped. Values are parsed strictly: ``"1/12*m"`` is an error naming the attribute.
"""

from __future__ import annotations

import functools
import os
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TypeVar

from lxml import etree

from robodesc.frontends.gazebo_contact import read_gazebo_contact
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.frontends.packages import BY_FOLDER_NAME, PackageResolver
from robodesc.frontends.xml_safety import parse_xml
from robodesc.ir.diagnostics import BrokenReferenceError, Findings, ParseError, PathEscapeError, SourceLoc
from robodesc.ir.geometry import (
    RGBA,
    Box,
    Capsule,
    Cylinder,
    Extension,
    Geometry,
    Inertia,
    Inertial,
    Material,
    Mesh,
    Pose,
    Sphere,
    Vec3,
)
from robodesc.ir.model import (
    Calibration,
    CameraSpec,
    Collision,
    ControlInterface,
    ControlJoint,
    Dynamics,
    FixedFrame,
    Joint,
    JointType,
    Limit,
    Link,
    LoopFrame,
    LoopJoint,
    Mimic,
    RayAxis,
    RaySpec,
    Robot,
    Ros2Control,
    SafetyController,
    Sensor,
    SensorType,
    Transmission,
    TransmissionActuator,
    TransmissionJoint,
    Visual,
)

_TRAILING_DOT = re.compile(r"^([+-]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][+-]?\d+)?)\.+$")
STAGE = "frontend:urdf"
T = TypeVar("T")
# xacro's environment substitutions, sometimes left in a URDF that was never run through xacro.
_ENV_SUBST = re.compile(r"\$\((env|optenv)\s+([A-Za-z_][A-Za-z0-9_]*)(?:\s+([^)]*))?\)")
# What each target does with a geometry robodesc does not model, said once in the warning.
_OTHER_TARGETS = "kept verbatim in the URDF output, left out of SDF and USD"


class _UnmodelledShape(Exception):
    """A <geometry> holds a shape robodesc does not model: its visual/collision is kept verbatim."""

    def __init__(self, tag: str) -> None:
        super().__init__(tag)
        self.tag = tag


class _ZeroShape(Exception):
    """A primitive of zero size: nothing to draw or collide with."""


# Sensor type spellings seen in URDF files, mapped to the IR's.
_SENSOR_TYPES = {
    "camera": SensorType.CAMERA,
    "depth": SensorType.DEPTH,
    "depth_camera": SensorType.DEPTH,
    "ray": SensorType.RAY,
    "lidar": SensorType.RAY,
    "gpu_ray": SensorType.RAY,
    "gpu_lidar": SensorType.RAY,
    "imu": SensorType.IMU,
    "force_torque": SensorType.FORCE_TORQUE,
    "contact": SensorType.CONTACT,
    "gps": SensorType.GPS,
    "navsat": SensorType.GPS,
}


@dataclass
class UrdfReader:
    """Reads one URDF document. ``file`` names it in messages; ``base_dir`` anchors relative paths."""

    file: str | None
    base_dir: str | None
    options: LoadOptions
    resolver: PackageResolver
    findings: Findings
    _last_anchor: tuple[str, str] | None = None
    _folder_packages: set[str] = field(default_factory=set)

    # ---- entry point ---------------------------------------------------------------------
    def read(self, root: etree._Element) -> Robot:
        if _tag(root) != "robot":
            raise ParseError(f"root element is <{_tag(root)}>, expected <robot>", loc=self._loc(root))
        robot = Robot(name=root.get("name") or "", src=self._loc(root), source_file=self.file)
        if not robot.name:
            self.findings.warn("unnamed-robot", "<robot> has no name; using 'robot'", loc=robot.src, stage=STAGE)
            robot.name = "robot"
        self._substitute_env(root)
        anchor: tuple[str, str] | None = None
        handlers: dict[str, Callable[[etree._Element, Robot], tuple[str, str]]] = {
            "link": self._add_link,
            "joint": self._add_joint,
            "material": self._add_material,
            "transmission": self._add_transmission,
            "ros2_control": self._add_ros2_control,
            "loop_joint": self._add_loop_joint,
            "fixed_frame": self._add_fixed_frame,
            "sensor": self._add_sensor,
        }
        for child in root:
            if not isinstance(child.tag, str):
                continue
            tag = _tag(child)
            handler = handlers.get(tag)
            if handler is not None:
                self._last_anchor = anchor
                anchor = handler(child, robot)
                continue
            ext = self._extension(child, anchor)
            if tag != "gazebo":
                self._unknown(child, "robot")
            robot.extensions.append(ext)
        joints = robot.joint_map()
        for sensor in robot.sensors:
            if sensor.parent_joint is not None and sensor.parent_joint in joints:
                sensor.parent = joints[sensor.parent_joint].child
        return robot

    # ---- helpers -------------------------------------------------------------------------
    def _substitute_env(self, root: etree._Element) -> None:
        """Resolve ``$(env VAR)`` and ``$(optenv VAR default)`` as xacro would have: a URDF that
        was written by hand from a xacro template sometimes keeps them (in mesh paths mostly)."""
        for el in root.iter():
            if not isinstance(el.tag, str):
                continue
            for key, raw in el.attrib.items():
                value = str(raw)
                if "$(" not in value:
                    continue
                new = _ENV_SUBST.sub(functools.partial(self._env_value, el=el), value)
                if new != value:
                    el.set(key, new)

    def _env_value(self, match: re.Match[str], el: etree._Element) -> str:
        kind, var, default = match.group(1), match.group(2), match.group(3)
        # As in xacro (docs/security.md): only the variables the user names with --env are read.
        allowed = self.options.trust_xacro or var in self.options.allowed_env
        value = self.resolver.environ.get(var) if allowed else None
        if value is None and kind == "optenv":
            value = (default or "").strip()
        if value is None:
            why = "names an unset environment variable" if allowed else f"was not read (--env {var} allows it)"
            self.findings.warn("env-unset", f"{match.group(0)} {why}; left as written", loc=self._loc(el), stage=STAGE)
            return match.group(0)
        self.findings.info(
            "env-substituted",
            f"{match.group(0)} resolved to {value!r}, as xacro would (this file is plain URDF)",
            loc=self._loc(el),
            stage=STAGE,
        )
        return value

    def _loc(self, el: etree._Element) -> SourceLoc:
        line = el.sourceline
        return SourceLoc(self.file, line if isinstance(line, int) else None)

    def _fail(self, el: etree._Element, message: str, element: str = "") -> ParseError:
        return ParseError(message, element=element, loc=self._loc(el))

    def _extension(self, el: etree._Element, anchor: tuple[str, str] | None = None) -> Extension:
        xml = etree.tostring(el, encoding="unicode", with_tail=False)
        return Extension(tag=_tag(el), xml=xml, anchor=anchor, reference=el.get("reference"), src=self._loc(el))

    def _carried_verbatim(self, el: etree._Element, exc: ParseError) -> Extension:
        """An element robodesc only carries (a transmission's actuator, a joint's calibration or
        safety controller) with a value it cannot read: keep the element as written, with a warning.
        No simulator target uses these; ROS nodes that read them see the original text."""
        if self.options.strict:
            raise exc
        self.findings.warn(
            "unreadable-carried",
            f"{exc.message}; <{_tag(el)}> is only carried through, so it is kept verbatim in the URDF output "
            "(no simulator target reads it)",
            element=exc.element,
            loc=exc.loc,
            stage=STAGE,
        )
        return self._extension(el)

    def _unknown(self, el: etree._Element, where: str) -> None:
        if _tag(el) == "surface" and where.endswith("<collision>"):
            # SDF's spelling of contact parameters: read into the IR (frontends/gazebo_contact.py).
            self.findings.info(
                "contact-surface",
                f"<surface> in {where}: read as its contact parameters (every target writes them); "
                "kept verbatim in the URDF",
                loc=self._loc(el),
                stage=STAGE,
            )
            return
        message = f"unknown element <{_tag(el)}> in {where}: kept verbatim"
        if self.options.strict:
            raise self._fail(el, message.replace(": kept verbatim", ""))
        self.findings.warn("unknown-element", message, loc=self._loc(el), stage=STAGE)

    def _float(self, el: etree._Element, attr: str, element: str, *, required: bool = False) -> float | None:
        raw = el.get(attr)
        if raw is None:
            if required:
                raise self._fail(el, f"<{_tag(el)}> needs attribute {attr!r}", element)
            return None
        try:
            return float(raw.strip())
        except ValueError:
            pass
        # pybullet's humanoid has <limit lower="-1.57.">: pybullet (strtod) reads the number before
        # the stray dot; urdfdom refuses it. Read it as pybullet does, loudly.
        quirk = _TRAILING_DOT.match(raw.strip())
        if quirk is None:
            raise self._fail(el, f"<{_tag(el)} {attr}={raw!r}>: expected a number", element)
        self.findings.warn(
            "number-trailing-dot",
            f"<{_tag(el)} {attr}={raw!r}>: a stray '.' after the number; read as {quirk.group(1)}, as pybullet "
            "does (urdfdom refuses it)",
            element=element,
            loc=self._loc(el),
            stage=STAGE,
        )
        return float(quirk.group(1))

    def _vec(self, el: etree._Element, attr: str, n: int, element: str) -> tuple[float, ...] | None:
        raw = el.get(attr)
        if raw is None:
            return None
        parts = raw.split()
        if "," in raw:
            # pybullet reads "0.07, 0, -0.69"; urdfdom refuses it.
            parts = raw.replace(",", " ").split()
            self.findings.warn(
                "comma-vector",
                f"<{_tag(el)} {attr}={raw!r}>: numbers separated by commas; read as spaces, as pybullet does "
                "(urdfdom refuses them)",
                element=element,
                loc=self._loc(el),
                stage=STAGE,
            )
        try:
            values = tuple(float(p) for p in parts)
        except ValueError:
            raise self._fail(el, f"<{_tag(el)} {attr}={raw!r}>: expected {n} numbers", element) from None
        if len(values) > n:
            # urdfdom refuses these, pybullet and the Isaac importer read the first n: do that, loudly.
            self.findings.warn(
                "extra-numbers",
                f"<{_tag(el)} {attr}={raw!r}>: {len(values)} numbers where {n} are expected; the first {n} are used",
                element=element,
                loc=self._loc(el),
                stage=STAGE,
            )
            return values[:n]
        if len(values) != n:
            raise self._fail(el, f"<{_tag(el)} {attr}={raw!r}>: expected {n} numbers, got {len(values)}", element)
        return values

    def _vec3(self, el: etree._Element, attr: str, element: str) -> Vec3 | None:
        v = self._vec(el, attr, 3, element)
        return (v[0], v[1], v[2]) if v is not None else None

    def _pose(self, el: etree._Element | None, element: str) -> Pose | None:
        if el is None:
            return None
        return Pose(
            xyz=self._vec3(el, "xyz", element) or (0.0, 0.0, 0.0),
            rpy=self._vec3(el, "rpy", element) or (0.0, 0.0, 0.0),
            src=self._loc(el),
        )

    def _one(self, el: etree._Element, tag: str, element: str) -> etree._Element | None:
        # Children are namespace-free in practice; iterchildren(tag) avoids building QNames.
        found = [c for c in el.iterchildren(tag, "{*}" + tag)]
        if len(found) > 1:
            self.findings.warn(
                "repeated-element",
                f"<{tag}> given {len(found)} times; the first is used",
                element=element,
                loc=self._loc(found[1]),
                stage=STAGE,
            )
        return found[0] if found else None

    def _name(self, el: etree._Element, kind: str) -> str:
        name = el.get("name")
        if name is None:
            raise self._fail(el, f"<{kind}> has no name")
        return name

    # ---- materials -----------------------------------------------------------------------
    def _material(self, el: etree._Element, element: str) -> Material:
        name = el.get("name", "")
        color_el = self._one(el, "color", element)
        texture_el = self._one(el, "texture", element)
        color: RGBA | None = None
        if color_el is not None:
            v = self._vec(color_el, "rgba", 4, element)
            if v is None:
                raise self._fail(color_el, "<color> needs rgba", element)
            color = (v[0], v[1], v[2], v[3])
        mat = Material(name=name, color=color, src=self._loc(el))
        if texture_el is not None:
            mat.texture = texture_el.get("filename")
            if mat.texture:
                try:
                    mat.texture_path = self.resolver.resolve(mat.texture, self.base_dir).path
                except BrokenReferenceError as exc:
                    self.findings.warn(
                        "texture-unresolved", exc.message, element=element, loc=self._loc(texture_el), stage=STAGE
                    )
        for child in el:
            if isinstance(child.tag, str) and _tag(child) not in ("color", "texture"):
                self._unknown(child, f"material {name!r}")
                mat.extensions.append(self._extension(child))
        return mat

    def _add_material(self, el: etree._Element, robot: Robot) -> tuple[str, str]:
        mat = self._material(el, f"material {el.get('name', '')!r}")
        robot.materials.append(mat)
        return ("material", mat.name)

    # ---- links ---------------------------------------------------------------------------
    def _add_link(self, el: etree._Element, robot: Robot) -> tuple[str, str]:
        name = self._name(el, "link")
        label = f"link {name!r}"
        link = Link(name=name, src=self._loc(el))
        link.extra_attrs = {str(k): str(v) for k, v in el.attrib.items() if k != "name"}
        for child in el:
            if not isinstance(child.tag, str):
                continue
            tag = _tag(child)
            if tag == "inertial":
                if link.inertial is not None:
                    raise self._fail(child, "a link has at most one <inertial>", label)
                link.inertial = self._inertial(child, label)
            elif tag in ("visual", "collision"):
                self._add_shape(child, tag, label, link)
            else:
                self._unknown(child, label)
                link.extensions.append(self._extension(child))
        robot.links.append(link)
        return ("link", name)

    def _inertial(self, el: etree._Element, label: str) -> Inertial:
        inertial = Inertial(origin=self._pose(self._one(el, "origin", label), label), src=self._loc(el))
        mass_el = self._one(el, "mass", label)
        if mass_el is not None:
            inertial.mass = self._float(mass_el, "value", label, required=True)
        else:
            # Carried as written (the mass is unknown); validation blames the source, not robodesc,
            # when a consumer refuses the file for it.
            self.findings.warn(
                "inertial-without-mass",
                "<inertial> has no <mass>: urdfdom and MuJoCo refuse the file; USD leaves the mass to the simulator",
                element=label,
                loc=inertial.src,
                stage=STAGE,
            )
        inertia_el = self._one(el, "inertia", label)
        if inertia_el is not None:
            diag = [self._float(inertia_el, a, label, required=True) for a in ("ixx", "iyy", "izz")]
            off = [self._float(inertia_el, a, label) for a in ("ixy", "ixz", "iyz")]
            inertial.inertia = Inertia(
                ixx=diag[0] or 0.0,
                iyy=diag[1] or 0.0,
                izz=diag[2] or 0.0,
                ixy=off[0] or 0.0,
                ixz=off[1] or 0.0,
                iyz=off[2] or 0.0,
                src=self._loc(inertia_el),
            )
        for child in el:
            if isinstance(child.tag, str) and _tag(child) not in ("origin", "mass", "inertia"):
                self._unknown(child, f"{label} <inertial>")
        return inertial

    def _add_shape(self, el: etree._Element, tag: str, label: str, link: Link) -> None:
        try:
            if tag == "visual":
                visual = self._visual(el, label, link)
                if visual is not None:
                    link.visuals.append(visual)
            else:
                collision = self._collision(el, label, link)
                if collision is not None:
                    link.collisions.append(collision)
        except _UnmodelledShape as shape:
            self.findings.warn(
                "unmodelled-geometry",
                f"<{tag}> with geometry <{shape.tag}>, which robodesc does not model: {_OTHER_TARGETS} "
                "(urdfdom refuses the file; pybullet reads planes and heightfields)",
                element=label,
                loc=self._loc(el),
                stage=STAGE,
            )
            link.extensions.append(self._extension(el))
        except _ZeroShape:
            pass  # reported where the size was read

    def _visual(self, el: etree._Element, label: str, link: Link) -> Visual | None:
        geometry = self._geometry(el, label)
        if geometry is None:
            return None
        visual = Visual(
            geometry=geometry,
            origin=self._pose(self._one(el, "origin", label), label),
            name=el.get("name"),
            src=self._loc(el),
        )
        mat_el = self._one(el, "material", label)
        if mat_el is not None:
            visual.material = self._material(mat_el, label)
        for child in el:
            if isinstance(child.tag, str) and _tag(child) not in ("origin", "geometry", "material"):
                self._unknown(child, f"{label} <visual>")
                visual.extensions.append(self._extension(child))
        return visual

    def _collision(self, el: etree._Element, label: str, link: Link) -> Collision | None:
        geometry = self._geometry(el, label)
        if geometry is None:
            return None
        collision = Collision(
            geometry=geometry,
            origin=self._pose(self._one(el, "origin", label), label),
            name=el.get("name"),
            src=self._loc(el),
        )
        for child in el:
            if isinstance(child.tag, str) and _tag(child) not in ("origin", "geometry"):
                self._unknown(child, f"{label} <collision>")
                collision.extensions.append(self._extension(child))
        return collision

    def _geometry(self, el: etree._Element, label: str) -> Geometry | None:
        """The shape inside ``el``'s ``<geometry>``; ``None`` when a missing mesh is dropped."""
        geom_el = self._one(el, "geometry", label)
        if geom_el is None:
            raise self._fail(el, f"<{_tag(el)}> has no <geometry>", label)
        shapes = [c for c in geom_el if isinstance(c.tag, str)]
        if not shapes:
            raise self._fail(geom_el, "<geometry> holds no shape", label)
        if len(shapes) > 1:
            # urdfdom, pybullet and the Isaac importer all read the first shape and ignore the rest.
            self.findings.warn(
                "extra-shapes",
                f"<geometry> holds {len(shapes)} shapes ({', '.join('<' + _tag(c) + '>' for c in shapes)}); "
                "the first is used, as urdfdom and pybullet do",
                element=label,
                loc=self._loc(shapes[1]),
                stage=STAGE,
            )
        shape = shapes[0]
        tag = _tag(shape)
        loc = self._loc(shape)
        if tag == "box":
            size = self._vec3(shape, "size", label)
            if size is None:
                raise self._fail(shape, "<box> needs size", label)
            self._zero_size(el, shape, label, size)
            return Box(size=size, src=loc)
        if tag in ("cylinder", "capsule"):
            radius = _req(self._float(shape, "radius", label, required=True))
            length = _req(self._float(shape, "length", label, required=True))
            self._zero_size(el, shape, label, (radius,) if tag == "capsule" else (radius, length))
            return (Cylinder if tag == "cylinder" else Capsule)(radius=radius, length=length, src=loc)
        if tag == "sphere":
            radius = _req(self._float(shape, "radius", label, required=True))
            self._zero_size(el, shape, label, (radius,))
            return Sphere(radius=radius, src=loc)
        if tag == "mesh":
            uri = shape.get("filename")
            if not uri:
                raise self._fail(shape, "<mesh> needs filename", label)
            mesh = Mesh(uri=uri, scale=self._vec3(shape, "scale", label), src=loc)
            return self._resolve_mesh(mesh, label)
        if self.options.strict:
            raise self._fail(shape, f"unknown geometry <{tag}>", label)
        raise _UnmodelledShape(tag)

    def _zero_size(self, el: etree._Element, shape: etree._Element, label: str, sizes: tuple[float, ...]) -> None:
        """A primitive with a zero dimension has no volume to draw or collide with: drop it.
        (Negative sizes are left to the verifier, which refuses them.)"""
        if any(s == 0 for s in sizes) and all(s >= 0 for s in sizes):
            self.findings.warn(
                "zero-size-shape",
                f"<{_tag(el)}> has a <{_tag(shape)}> of zero size; it was dropped "
                "(urdfdom keeps it, MuJoCo and PhysX refuse zero-size colliders)",
                element=label,
                loc=self._loc(shape),
                stage=STAGE,
            )
            raise _ZeroShape()

    def _resolve_mesh(self, mesh: Mesh, label: str) -> Geometry | None:
        try:
            resolved = self.resolver.resolve(mesh.uri, self.base_dir)
        except PathEscapeError as exc:
            raise PathEscapeError(f"mesh {mesh.uri!r}: {exc.message}", element=label, loc=mesh.src) from None
        except BrokenReferenceError as exc:
            return self._missing_mesh(mesh, label, f"mesh {mesh.uri!r}: {exc.message}")
        mesh.path, mesh.package = resolved.path, resolved.package
        if resolved.how == BY_FOLDER_NAME and resolved.package is not None:
            self._by_folder(resolved.package[0], resolved.path, resolved.package[1], mesh.src)
        if os.path.isfile(resolved.path):
            return mesh
        return self._missing_mesh(mesh, label, f"mesh file {resolved.path!r} does not exist (from {mesh.uri!r})")

    def _by_folder(self, name: str, path: str, inner: str, loc: SourceLoc | None) -> None:
        if name in self._folder_packages:
            return
        self._folder_packages.add(name)
        root = path[: len(path) - len(inner)].rstrip("/" + os.sep) if inner and path.endswith(inner) else path
        self.findings.warn(
            "package-by-folder",
            f"package {name!r} is not a ROS package here; the folder {root!r} of that name beside or above "
            f"the input was used (--package {name}=DIR chooses another)",
            loc=loc,
            stage=STAGE,
        )

    def _missing_mesh(self, mesh: Mesh, label: str, message: str) -> Geometry | None:
        policy = self.options.missing_mesh
        if policy is MissingMesh.ERROR:
            raise BrokenReferenceError(
                message + "; --missing-mesh warn|primitive|drop chooses another policy", element=label, loc=mesh.src
            )
        mesh.path = None
        if policy is MissingMesh.WARN:
            self.findings.warn("missing-mesh", message + "; reference kept", element=label, loc=mesh.src, stage=STAGE)
            return mesh
        if policy is MissingMesh.DROP:
            self.findings.warn(
                "missing-mesh",
                message + "; this visual/collision was dropped",
                element=label,
                loc=mesh.src,
                stage=STAGE,
            )
            return None
        size = mesh.scale or (1.0, 1.0, 1.0)
        self.findings.warn(
            "missing-mesh",
            message + f"; replaced by a box of its scale {size}",
            element=label,
            loc=mesh.src,
            stage=STAGE,
        )
        return Box(size=(abs(size[0]), abs(size[1]), abs(size[2])), src=mesh.src)

    # ---- joints --------------------------------------------------------------------------
    def _add_joint(self, el: etree._Element, robot: Robot) -> tuple[str, str]:
        name = self._name(el, "joint")
        label = f"joint {name!r}"
        raw_type = el.get("type")
        try:
            jtype = JointType(raw_type)
        except ValueError:
            allowed = ", ".join(t.value for t in JointType)
            raise self._fail(el, f"unknown joint type {raw_type!r} (one of {allowed})", label) from None
        parent_el = self._one(el, "parent", label)
        child_el = self._one(el, "child", label)
        if parent_el is None or not parent_el.get("link"):
            raise self._fail(el, "needs <parent link=...>", label)
        if child_el is None or not child_el.get("link"):
            raise self._fail(el, "needs <child link=...>", label)
        joint = Joint(
            name=name,
            type=jtype,
            parent=parent_el.get("link", ""),
            child=child_el.get("link", ""),
            origin=self._pose(self._one(el, "origin", label), label),
            src=self._loc(el),
        )
        axis_el = self._one(el, "axis", label)
        if axis_el is not None:
            joint.axis = self._vec3(axis_el, "xyz", label)
        limit_el = self._one(el, "limit", label)
        if limit_el is not None:
            joint.limit = Limit(
                lower=self._float(limit_el, "lower", label),
                upper=self._float(limit_el, "upper", label),
                effort=self._float(limit_el, "effort", label),
                velocity=self._float(limit_el, "velocity", label),
                src=self._loc(limit_el),
            )
        if (
            joint.limit is not None
            and jtype in (JointType.REVOLUTE, JointType.PRISMATIC)
            and (joint.limit.lower is None or joint.limit.upper is None)
        ):
            missing = " and ".join(b for b in ("lower", "upper") if getattr(joint.limit, b) is None)
            self.findings.warn(
                "limit-unbounded",
                f"<limit> of a {jtype.value} joint without {missing}: urdfdom (ROS) reads a missing bound as 0, "
                "MuJoCo, pybullet and Drake as no limit; robodesc keeps it unset (SDF and USD get no limit)",
                element=label,
                loc=self._loc(limit_el) if limit_el is not None else joint.src,
                stage=STAGE,
            )
        limit = joint.limit
        if limit is not None and limit.lower is not None and limit.upper is not None and limit.lower > limit.upper:
            # pybullet (pybullet_data's biped2d_pybullet.urdf) reads lower > upper as "no limit"; urdfdom
            # keeps the numbers and every engine then clamps to nothing. Read as pybullet reads it.
            self.findings.warn(
                "limit-inverted",
                f"lower limit {limit.lower:g} is above upper limit {limit.upper:g}: read as pybullet reads it, "
                "an unlimited joint (the effort and velocity limits are kept); --strict refuses it",
                element=label,
                loc=limit.src or joint.src,
                stage=STAGE,
            )
            limit.lower = limit.upper = None
        dyn_el = self._one(el, "dynamics", label)
        if dyn_el is not None:
            joint.dynamics = Dynamics(
                damping=self._float(dyn_el, "damping", label),
                friction=self._float(dyn_el, "friction", label),
                spring_stiffness=self._float(dyn_el, "spring_stiffness", label),
                spring_reference=self._float(dyn_el, "spring_reference", label),
                src=self._loc(dyn_el),
            )
            joint.armature = self._float(dyn_el, "armature", label)
        mimic_el = self._one(el, "mimic", label)
        if mimic_el is not None:
            leader = mimic_el.get("joint")
            if not leader:
                raise self._fail(mimic_el, "<mimic> needs joint", label)
            joint.mimic = Mimic(
                joint=leader,
                multiplier=self._float(mimic_el, "multiplier", label),
                offset=self._float(mimic_el, "offset", label),
                src=self._loc(mimic_el),
            )
        sc_el = self._one(el, "safety_controller", label)
        if sc_el is not None:
            try:
                joint.safety_controller = SafetyController(
                    k_velocity=_req(self._float(sc_el, "k_velocity", label, required=True)),
                    k_position=self._float(sc_el, "k_position", label),
                    soft_lower_limit=self._float(sc_el, "soft_lower_limit", label),
                    soft_upper_limit=self._float(sc_el, "soft_upper_limit", label),
                    src=self._loc(sc_el),
                )
            except ParseError as exc:
                joint.extensions.append(self._carried_verbatim(sc_el, exc))
        cal_el = self._one(el, "calibration", label)
        if cal_el is not None:
            try:
                joint.calibration = Calibration(
                    rising=self._float(cal_el, "rising", label),
                    falling=self._float(cal_el, "falling", label),
                    reference_position=self._float(cal_el, "reference_position", label),
                    src=self._loc(cal_el),
                )
            except ParseError as exc:
                joint.extensions.append(self._carried_verbatim(cal_el, exc))
        known = {"parent", "child", "origin", "axis", "limit", "dynamics", "mimic", "safety_controller", "calibration"}
        for child in el:
            if isinstance(child.tag, str) and _tag(child) not in known:
                self._unknown(child, label)
                joint.extensions.append(self._extension(child))
        dont_collapse = el.get("dont_collapse")
        if dont_collapse is not None:
            joint.dont_collapse = dont_collapse.strip().lower() in ("true", "1")
        joint.extra_attrs = {str(k): str(v) for k, v in el.attrib.items() if k not in ("name", "type", "dont_collapse")}
        robot.joints.append(joint)
        return ("joint", name)

    # ---- Isaac extension tags --------------------------------------------------------------
    def _add_loop_joint(self, el: etree._Element, robot: Robot) -> tuple[str, str]:
        name = self._name(el, "loop_joint")
        label = f"loop_joint {name!r}"
        frames: list[LoopFrame] = []
        for tag in ("link1", "link2"):
            side = self._one(el, tag, label)
            if side is None or not side.get("link"):
                raise self._fail(el, f"needs <{tag} link=...>", label)
            frames.append(
                LoopFrame(
                    link=side.get("link", ""),
                    origin=Pose(
                        xyz=self._vec3(side, "xyz", label) or (0.0, 0.0, 0.0),
                        rpy=self._vec3(side, "rpy", label) or (0.0, 0.0, 0.0),
                        src=self._loc(side),
                    ),
                    src=self._loc(side),
                )
            )
        loop = LoopJoint(
            name=name, type=el.get("type", "spherical"), link1=frames[0], link2=frames[1], src=self._loc(el)
        )
        axis_el = self._one(el, "axis", label)
        if axis_el is not None:
            loop.axis = self._vec3(axis_el, "xyz", label)
        robot.loop_joints.append(loop)
        return ("loop_joint", name)

    def _add_fixed_frame(self, el: etree._Element, robot: Robot) -> tuple[str, str]:
        name = self._name(el, "fixed_frame")
        label = f"fixed_frame {name!r}"
        parent = self._one(el, "parent", label)
        if parent is None or not parent.get("link"):
            raise self._fail(el, "needs <parent link=...>", label)
        robot.fixed_frames.append(
            FixedFrame(
                name=name,
                parent=parent.get("link", ""),
                origin=self._pose(self._one(el, "origin", label), label),
                src=self._loc(el),
            )
        )
        return ("fixed_frame", name)

    def _add_sensor(self, el: etree._Element, robot: Robot) -> tuple[str, str]:
        name = self._name(el, "sensor")
        label = f"sensor {name!r}"
        raw_type = (el.get("type") or "").strip()
        stype = _SENSOR_TYPES.get(raw_type.lower())
        if stype is None:
            message = f"sensor type {raw_type!r} is not one robodesc models ({', '.join(sorted(_SENSOR_TYPES))}): kept verbatim"
            if self.options.strict:
                raise self._fail(el, message.removesuffix(": kept verbatim"), label)
            self.findings.warn("unknown-sensor", message, element=label, loc=self._loc(el), stage=STAGE)
            robot.extensions.append(self._extension(el, self._last_anchor))
            return self._last_anchor or ("sensor", name)
        parent = self._one(el, "parent", label)
        if parent is None or not (parent.get("link") or parent.get("joint")):
            raise self._fail(el, "needs <parent link=...> (or <parent joint=...>)", label)
        sensor = Sensor(
            name=name,
            type=stype,
            parent=parent.get("link", ""),
            parent_joint=parent.get("joint"),
            origin=self._pose(self._one(el, "origin", label), label),
            update_rate=self._float(el, "update_rate", label),
            isaac_sim_config=el.get("isaac_sim_config"),
            src=self._loc(el),
        )
        handled = {"parent", "origin"}
        camera_el = self._one(el, "camera", label)
        if camera_el is not None:
            handled.add("camera")
            image = self._one(camera_el, "image", label)
            if image is not None:
                width, height = self._float(image, "width", label), self._float(image, "height", label)
                sensor.camera = CameraSpec(
                    width=int(width) if width is not None else None,
                    height=int(height) if height is not None else None,
                    hfov=self._float(image, "hfov", label),
                    format=image.get("format"),
                    near=self._float(image, "near", label),
                    far=self._float(image, "far", label),
                )
        ray_el = self._one(el, "ray", label)
        if ray_el is not None:
            handled.add("ray")
            spec = RaySpec()
            for axis_tag in ("horizontal", "vertical"):
                ax = self._one(ray_el, axis_tag, label)
                if ax is not None:
                    samples = self._float(ax, "samples", label)
                    setattr(
                        spec,
                        axis_tag,
                        RayAxis(
                            samples=int(samples) if samples is not None else None,
                            resolution=self._float(ax, "resolution", label),
                            min_angle=self._float(ax, "min_angle", label),
                            max_angle=self._float(ax, "max_angle", label),
                        ),
                    )
            range_el = self._one(ray_el, "range", label)
            if range_el is not None:
                spec.min_range = self._float(range_el, "min", label)
                spec.max_range = self._float(range_el, "max", label)
            sensor.ray = spec
        for child in el:
            if isinstance(child.tag, str) and _tag(child) not in handled:
                sensor.extensions.append(self._extension(child))
        robot.sensors.append(sensor)
        return ("sensor", name)

    # ---- ros_control ---------------------------------------------------------------------
    def _add_transmission(self, el: etree._Element, robot: Robot) -> tuple[str, str]:
        name = self._name(el, "transmission")
        label = f"transmission {name!r}"
        tr = Transmission(name=name, src=self._loc(el))
        type_el = self._one(el, "type", label)
        tr.type = (type_el.text or "").strip() if type_el is not None else el.get("type")
        for child in el:
            if not isinstance(child.tag, str):
                continue
            tag = _tag(child)
            if tag == "type":
                continue
            if tag == "joint":
                tr.joints.append(
                    TransmissionJoint(
                        name=self._name(child, "joint"),
                        hardware_interfaces=_texts(child, "hardwareInterface"),
                        src=self._loc(child),
                    )
                )
            elif tag == "actuator":
                red = [c for c in child if isinstance(c.tag, str) and _tag(c) == "mechanicalReduction"]
                reduction: float | None = None
                if red:
                    try:
                        reduction = float((red[0].text or "").strip())
                    except ValueError:
                        bad = self._fail(
                            red[0],
                            f"<mechanicalReduction>{red[0].text}</mechanicalReduction>: expected a number",
                            label,
                        )
                        tr.extensions.append(self._carried_verbatim(child, bad))
                        continue
                tr.actuators.append(
                    TransmissionActuator(
                        name=self._name(child, "actuator"),
                        hardware_interfaces=_texts(child, "hardwareInterface"),
                        mechanical_reduction=reduction,
                        src=self._loc(child),
                    )
                )
            else:
                tr.extensions.append(self._extension(child))
        robot.transmissions.append(tr)
        return ("transmission", name)

    def _add_ros2_control(self, el: etree._Element, robot: Robot) -> tuple[str, str]:
        name = self._name(el, "ros2_control")
        label = f"ros2_control {name!r}"
        rc = Ros2Control(name=name, type=el.get("type", "system"), src=self._loc(el))
        for child in el:
            if not isinstance(child.tag, str):
                continue
            tag = _tag(child)
            if tag == "hardware":
                plugin = [c for c in child if isinstance(c.tag, str) and _tag(c) == "plugin"]
                rc.plugin = (plugin[0].text or "").strip() if plugin else None
                rc.hardware_params = _params(child)
            elif tag == "joint":
                cj = ControlJoint(name=self._name(child, "joint"), params=_params(child), src=self._loc(child))
                for iface in child:
                    if not isinstance(iface.tag, str):
                        continue
                    itag = _tag(iface)
                    if itag in ("command_interface", "state_interface"):
                        target = cj.command_interfaces if itag == "command_interface" else cj.state_interfaces
                        target.append(ControlInterface(name=iface.get("name", ""), params=_params(iface)))
                    elif itag != "param":
                        self._unknown(iface, label)
                rc.joints.append(cj)
            else:
                rc.extensions.append(self._extension(child))
        robot.ros2_controls.append(rc)
        return ("ros2_control", name)


def _tag(el: etree._Element) -> str:
    return etree.QName(el).localname if isinstance(el.tag, str) else ""


def _texts(el: etree._Element, tag: str) -> list[str]:
    return [(c.text or "").strip() for c in el if isinstance(c.tag, str) and _tag(c) == tag]


def _params(el: etree._Element) -> dict[str, str]:
    return {c.get("name", ""): (c.text or "").strip() for c in el if isinstance(c.tag, str) and _tag(c) == "param"}


def _req(value: T | None) -> T:
    assert value is not None  # _float(required=True) raised already
    return value


def read_urdf_string(
    text: str | bytes,
    *,
    file: str | None = None,
    base_dir: str | None = None,
    options: LoadOptions | None = None,
    resolver: PackageResolver | None = None,
    findings: Findings | None = None,
) -> Robot:
    """Parse URDF text into the IR. ``file`` is used for messages and package discovery."""
    opts = options or LoadOptions()
    found = findings if findings is not None else Findings()
    root = parse_xml(text, file, found)
    reader = UrdfReader(
        file=file,
        base_dir=base_dir
        if base_dir is not None
        else (os.path.dirname(os.path.abspath(file)) if file else os.getcwd()),
        options=opts,
        resolver=resolver or PackageResolver(explicit=dict(opts.package_paths), input_file=file),
        findings=found,
    )
    robot = reader.read(root)
    robot.package_roots = reader.resolver.roots()
    read_gazebo_contact(robot, found)
    return robot
