"""robodesc's YAML composition format (schema in docs/compositions.md).

>>> robot = load_yaml_text('''
... robot: pendulum
... units: {angle: deg}
... links:
...   base: {geometry: {box: [0.1, 0.1, 0.1]}, mass: 1}
...   bob: {geometry: {sphere: 0.05}, mass: 0.2, pose: [0, 0, -0.5]}
... joints:
...   swing: {type: revolute, parent: base, child: bob, axis: y, limits: {lower: -90, upper: 90}}
... ''', "pendulum.yaml")
>>> robot.joint("swing").limit.upper
1.5707963267948966
"""

from __future__ import annotations

import os

from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from robodesc.frontends.compose.builder import JOINT_TYPES, SENSOR_TYPES, Frame, Part, RobotBuilder, axis_vector
from robodesc.frontends.compose.colors import ColorError, parse_color
from robodesc.frontends.compose.decls import (
    ActuatorDecl,
    Decls,
    FrameDecl,
    JointDecl,
    LinkDecl,
    LoopDecl,
    SensorDecl,
    apply,
    mirrored,
    renamed,
)
from robodesc.frontends.compose.shapes import box, capsule, cylinder, mesh, sphere
from robodesc.frontends.compose.units import ANGLE_UNITS, LENGTH_UNITS
from robodesc.frontends.compose.yaml_nodes import NodeReader, compose_text, merge_nodes
from robodesc.frontends.options import LoadOptions
from robodesc.ir.contact import Contact
from robodesc.ir.diagnostics import Findings, ParseError, SourceLoc
from robodesc.ir.geometry import Geometry, Inertia, Pose
from robodesc.ir.model import CameraSpec, JointType, RayAxis, RaySpec, Robot, SafetyController

STAGE = "compose"

TOP_KEYS = (
    "robot",
    "units",
    "base",
    "materials",
    "links",
    "joints",
    "loop_joints",
    "frames",
    "sensors",
    "templates",
    "use",
    "definitions",
)
BODY_KEYS = ("links", "joints", "loop_joints", "frames", "sensors")
UNIT_KEYS = ("angle", "length")
PART_KEYS = ("geometry", "origin", "color", "material", "visual", "collision", "mass", "density", "name")
LINK_KEYS = (*PART_KEYS, "parts", "inertia", "com", "pose", "contact")
# A link's surface parameters (docs/contact.md), in the IR's names and SI units.
CONTACT_KEYS = (
    "mu",
    "mu2",
    "torsional",
    "rolling",
    "restitution",
    "bounce_threshold",
    "kp",
    "kd",
    "min_depth",
    "max_vel",
)
GEOMETRY_KINDS = ("box", "cylinder", "sphere", "capsule", "mesh")
POSE_KEYS = ("xyz", "rpy")
PLACED_POSE_KEYS = ("xyz", "rpy", "frame")
INERTIA_KEYS = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")
JOINT_KEYS = (
    "type",
    "parent",
    "child",
    "origin",
    "axis",
    "limits",
    "dynamics",
    "mimic",
    "armature",
    "actuator",
    "safety",
)
LIMIT_KEYS = ("lower", "upper", "effort", "velocity")
DYNAMICS_KEYS = ("damping", "friction")
MIMIC_KEYS = ("joint", "multiplier", "offset")
ACTUATOR_KEYS = ("transmission", "interface", "reduction", "name")
SAFETY_KEYS = ("k_velocity", "k_position", "soft_lower", "soft_upper")
LOOP_KEYS = ("type", "link1", "link2", "axis")
LOOP_SIDE_KEYS = ("link", "xyz", "rpy", "frame")
FRAME_KEYS = ("parent", "pose")
SENSOR_KEYS = ("type", "parent", "pose", "update_rate", "topic", "noise", "isaac_sim_config", "camera", "ray")
CAMERA_KEYS = ("width", "height", "hfov", "near", "far", "format")
RAY_KEYS = ("horizontal", "vertical", "min_range", "max_range")
RAY_AXIS_KEYS = ("samples", "resolution", "min_angle", "max_angle")
USE_KEYS = ("template", "prefix", "suffix", "mirror", "overrides")


def load_yaml(path: str, options: LoadOptions, findings: Findings) -> Robot:
    """The frontend registered for ``.yaml``/``.yml``."""
    from robodesc.frontends.xml_safety import read_text  # regular files only: a named pipe must not hang

    text = read_text(path)
    return load_yaml_text(text, path, options, findings)


def load_yaml_text(text: str, file: str, options: LoadOptions | None = None, findings: Findings | None = None) -> Robot:
    """Read a YAML composition given as text; ``file`` names it in messages and anchors relative paths."""
    reader = _Reader(NodeReader(file), findings if findings is not None else Findings())
    return reader.robot(text, options or LoadOptions())


class _Reader:
    def __init__(self, nodes: NodeReader, findings: Findings) -> None:
        self.n = nodes
        self.findings = findings
        self.angle = 1.0
        self.length = 1.0
        self.materials: dict[str, tuple[float, float, float, float]] = {}

    # ---- top level --------------------------------------------------------------------------
    def robot(self, text: str, options: LoadOptions) -> Robot:
        n = self.n
        root = compose_text(text, n.file)
        if root is None:
            raise ParseError(
                "the file is empty; a composition needs at least 'robot:' and 'links:'", loc=SourceLoc(n.file)
            )
        extra = [str(k.value) for k, _ in n.pairs(root, "top level") if str(k.value).startswith("x-")]
        entries = n.mapping(root, "top level", [*TOP_KEYS, *extra], required=("robot", "links"))
        name = n.string(entries["robot"], "robot")
        self._units(entries.get("units"), root)
        fixed_base = None
        if "base" in entries:
            fixed_base = n.choice(entries["base"], "base", ("fixed", "floating")) == "fixed"
        if "materials" in entries:
            for mname, mnode, mpath in n.items(entries["materials"], "materials"):
                self.materials[mname] = self._color(mnode, mpath)
        decls = self._body(entries, "")
        templates: dict[str, Node] = {}
        if "templates" in entries:
            for tname, tnode, tpath in n.items(entries["templates"], "templates"):
                n.mapping(tnode, tpath, BODY_KEYS)
                templates[tname] = tnode
        if "use" in entries:
            for i, unode in enumerate(n.sequence(entries["use"], "use")):
                decls.extend(self._instance(unode, f"use[{i}]", templates))
        builder = RobotBuilder(
            name,
            source_file=n.file,
            options=options,
            findings=self.findings,
            src=n.loc(entries["robot"]),
            fixed_base=fixed_base,
        )
        apply(decls, builder)
        return builder.build()

    def _units(self, node: Node | None, root: Node) -> None:
        if node is None:
            self.findings.info(
                "default-units",
                "no 'units:' given: angles are read in radians and lengths in metres (the defaults)",
                loc=self.n.loc(root),
                stage=STAGE,
            )
            return
        units = self.n.mapping(node, "units", UNIT_KEYS)
        if "angle" in units:
            self.angle = ANGLE_UNITS[self.n.choice(units["angle"], "units.angle", tuple(ANGLE_UNITS))]
        if "length" in units:
            self.length = LENGTH_UNITS[self.n.choice(units["length"], "units.length", tuple(LENGTH_UNITS))]

    def _instance(self, node: Node, path: str, templates: dict[str, Node]) -> Decls:
        n = self.n
        use = n.mapping(node, path, USE_KEYS, required=("template",))
        tname = n.string(use["template"], f"{path}.template")
        if tname not in templates:
            import difflib

            close = difflib.get_close_matches(tname, list(templates), n=1)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise n.fail(use["template"], f"{path}.template", f"no template named {tname!r}{hint}")
        body = templates[tname]
        if "overrides" in use:
            n.mapping(use["overrides"], f"{path}.overrides", BODY_KEYS)
            body = merge_nodes(body, use["overrides"], n, f"{path}.overrides")
        decls = self._body(n.mapping(body, f"{path} ({tname})", BODY_KEYS), f"{path} ({tname})")
        prefix = n.string(use["prefix"], f"{path}.prefix") if "prefix" in use else ""
        suffix = n.string(use["suffix"], f"{path}.suffix") if "suffix" in use else ""
        if not prefix and not suffix:
            self.findings.info(
                "template-unprefixed",
                f"template {tname!r} used without prefix or suffix: its names are used as written",
                loc=n.loc(node),
                stage=STAGE,
            )
        decls = renamed(decls, prefix, suffix)
        if "mirror" in use:
            plane = n.choice(use["mirror"], f"{path}.mirror", ("x", "y", "z"))
            decls = mirrored(decls, plane, self.findings, f"{path} ({tname})", n.loc(use["mirror"]))
        return decls

    def _body(self, entries: dict[str, Node], base: str) -> Decls:
        n = self.n
        out = Decls()
        dot = f"{base}." if base else ""
        if "links" in entries:
            for name, node, path in n.items(entries["links"], f"{dot}links"):
                out.links.append(self._link(name, node, path))
        if "joints" in entries:
            for name, node, path in n.items(entries["joints"], f"{dot}joints"):
                out.joints.append(self._joint(name, node, path))
        if "loop_joints" in entries:
            for name, node, path in n.items(entries["loop_joints"], f"{dot}loop_joints"):
                out.loops.append(self._loop(name, node, path))
        if "frames" in entries:
            for name, node, path in n.items(entries["frames"], f"{dot}frames"):
                f = n.mapping(node, path, FRAME_KEYS, required=("parent",))
                pose, frame = self._placed_pose(f.get("pose"), f"{path}.pose")
                out.frames.append(FrameDecl(name, n.string(f["parent"], f"{path}.parent"), pose, frame, n.loc(node)))
        if "sensors" in entries:
            for name, node, path in n.items(entries["sensors"], f"{dot}sensors"):
                out.sensors.append(self._sensor(name, node, path))
        return out

    # ---- links ------------------------------------------------------------------------------
    def _link(self, name: str, node: Node, path: str) -> LinkDecl:
        n = self.n
        e = n.mapping(node, path, LINK_KEYS)
        decl = LinkDecl(name=name, src=n.loc(node))
        if "parts" in e:
            for key in ("geometry", "origin", "visual", "collision", "name"):
                if key in e:
                    raise n.fail(e[key], f"{path}.{key}", f"give '{key}' inside each of 'parts', or drop 'parts'")
            for i, pnode in enumerate(n.sequence(e["parts"], f"{path}.parts")):
                ppath = f"{path}.parts[{i}]"
                decl.parts.append(
                    self._part(n.mapping(pnode, ppath, PART_KEYS, required=("geometry",)), pnode, ppath, e)
                )
        elif "geometry" in e:
            decl.parts.append(self._part(e, node, path, {}, link_level=True))
        if "mass" in e and "density" in e:
            raise n.fail(e["density"], f"{path}.density", "give mass or density, not both")
        if "parts" in e:
            decl.mass = n.positive(e["mass"], f"{path}.mass", allow_zero=True) if "mass" in e else None
            decl.density = n.positive(e["density"], f"{path}.density") if "density" in e else None
        else:
            # Single-part shorthand: the link's mass is that part's; keep it on the link.
            decl.mass = n.positive(e["mass"], f"{path}.mass", allow_zero=True) if "mass" in e else None
            decl.density = n.positive(e["density"], f"{path}.density") if "density" in e else None
            for part in decl.parts:
                part.mass = part.density = None
        if "inertia" in e:
            decl.inertia = self._inertia(e["inertia"], f"{path}.inertia")
        if "com" in e:
            decl.com = self._pose(e["com"], f"{path}.com")
        if "pose" in e:
            decl.pose, decl.frame = self._placed_pose(e["pose"], f"{path}.pose")
        if "contact" in e:
            c = n.mapping(e["contact"], f"{path}.contact", CONTACT_KEYS)
            values = {key: n.positive(c[key], f"{path}.contact.{key}", allow_zero=True) for key in c}
            decl.contact = Contact(**values, src=n.loc(e["contact"]))  # type: ignore[arg-type]
        return decl

    def _part(
        self, e: dict[str, Node], node: Node, path: str, link: dict[str, Node], *, link_level: bool = False
    ) -> Part:
        n = self.n
        geom = self._geometry(e["geometry"], f"{path}.geometry")
        color_node = e.get("color", link.get("color"))
        material = n.string(e["material"], f"{path}.material") if "material" in e else None
        if material is None and "material" in link:
            material = n.string(link["material"], f"{path}.material")
        color = None
        if color_node is not None:
            color = self._color(color_node, f"{path}.color")
        elif material is not None and material in self.materials:
            color = self.materials[material]
        part = Part(
            geometry=geom,
            origin=self._pose(e["origin"], f"{path}.origin") if "origin" in e else None,
            color=color,
            material=material,
            visual=n.boolean(e["visual"], f"{path}.visual") if "visual" in e else True,
            collision=n.boolean(e["collision"], f"{path}.collision") if "collision" in e else True,
            name=n.string(e["name"], f"{path}.name") if "name" in e else None,
            src=n.loc(node),
        )
        if not link_level:
            if "mass" in e and "density" in e:
                raise n.fail(e["density"], f"{path}.density", "give mass or density, not both")
            part.mass = n.positive(e["mass"], f"{path}.mass", allow_zero=True) if "mass" in e else None
            part.density = n.positive(e["density"], f"{path}.density") if "density" in e else None
        if not part.visual and not part.collision:
            raise n.fail(node, path, "a part with visual: false and collision: false does nothing")
        return part

    def _geometry(self, node: Node, path: str) -> Geometry:
        n = self.n
        e = n.mapping(node, path, GEOMETRY_KINDS)
        if len(e) != 1:
            raise n.fail(node, path, f"give exactly one shape ({', '.join(GEOMETRY_KINDS)}), got {len(e)}")
        kind, value = next(iter(e.items()))
        p = f"{path}.{kind}"
        k = self.length
        geom: Geometry
        if kind == "box":
            if isinstance(value, MappingNode):
                size = n.vec3(n.mapping(value, p, ("size",), required=("size",))["size"], f"{p}.size")
            else:
                size = n.vec3(value, p)
            self._positive_all(value, p, size)
            geom = box(size[0] * k, size[1] * k, size[2] * k)
        elif kind == "sphere":
            if isinstance(value, ScalarNode):
                radius = n.positive(value, p)
            else:
                radius = n.positive(n.mapping(value, p, ("radius",), required=("radius",))["radius"], f"{p}.radius")
            geom = sphere(radius * k)
        elif kind in ("cylinder", "capsule"):
            c = n.mapping(value, p, ("radius", "length"), required=("radius", "length"))
            radius = n.positive(c["radius"], f"{p}.radius")
            length = n.positive(c["length"], f"{p}.length", allow_zero=kind == "capsule")
            geom = cylinder(radius * k, length * k) if kind == "cylinder" else capsule(radius * k, length * k)
        else:
            if isinstance(value, ScalarNode):
                uri, scale = n.string(value, p), None
            else:
                mm = n.mapping(value, p, ("file", "scale"), required=("file",))
                uri = n.string(mm["file"], f"{p}.file")
                scale = None
                if "scale" in mm:
                    if isinstance(mm["scale"], ScalarNode):
                        s = n.number(mm["scale"], f"{p}.scale")
                        scale = (s, s, s)
                    else:
                        scale = n.vec3(mm["scale"], f"{p}.scale")
            geom = mesh(uri, scale)
        geom.src = n.loc(value)
        return geom

    def _positive_all(self, node: Node, path: str, values: tuple[float, ...]) -> None:
        if any(v <= 0 for v in values):
            raise self.n.fail(node, path, f"sizes must be positive, got {', '.join(f'{v:g}' for v in values)}")

    def _inertia(self, node: Node, path: str) -> Inertia:
        n = self.n
        e = n.mapping(node, path, INERTIA_KEYS, required=("ixx", "iyy", "izz"))
        v = {k: n.number(e[k], f"{path}.{k}") if k in e else 0.0 for k in INERTIA_KEYS}
        return Inertia(v["ixx"], v["iyy"], v["izz"], v["ixy"], v["ixz"], v["iyz"], src=n.loc(node))

    def _color(self, node: Node, path: str) -> tuple[float, float, float, float]:
        n = self.n
        try:
            if isinstance(node, SequenceNode):
                return parse_color(n.numbers(node, path, (3, 4)))
            text = n.string(node, path)
            if text in self.materials:
                return self.materials[text]
            return parse_color(text)
        except ColorError as exc:
            raise n.fail(node, path, str(exc)) from None

    # ---- poses --------------------------------------------------------------------------------
    def _pose(self, node: Node, path: str) -> Pose:
        pose, _frame = self._placed_pose(node, path, allow_frame=False)
        assert pose is not None
        return pose

    def _placed_pose(self, node: Node | None, path: str, *, allow_frame: bool = True) -> tuple[Pose | None, Frame]:
        n = self.n
        if node is None:
            return None, "parent"
        if isinstance(node, SequenceNode):
            x, y, z = n.vec3(node, path)
            return Pose(xyz=(x * self.length, y * self.length, z * self.length), src=n.loc(node)), "parent"
        e = n.mapping(node, path, PLACED_POSE_KEYS if allow_frame else POSE_KEYS)
        xyz = n.vec3(e["xyz"], f"{path}.xyz") if "xyz" in e else (0.0, 0.0, 0.0)
        rpy = n.vec3(e["rpy"], f"{path}.rpy") if "rpy" in e else (0.0, 0.0, 0.0)
        frame: Frame = "parent"
        if "frame" in e and n.choice(e["frame"], f"{path}.frame", ("parent", "world")) == "world":
            frame = "world"
        k, a = self.length, self.angle
        return Pose(
            xyz=(xyz[0] * k, xyz[1] * k, xyz[2] * k), rpy=(rpy[0] * a, rpy[1] * a, rpy[2] * a), src=n.loc(node)
        ), frame

    def _axis(self, node: Node, path: str) -> tuple[float, float, float]:
        n = self.n
        try:
            if isinstance(node, ScalarNode):
                return axis_vector(n.string(node, path))
            value = n.vec3(node, path)
        except ValueError as exc:
            raise n.fail(node, path, str(exc)) from None
        if not any(value):
            raise n.fail(node, path, "axis is the zero vector")
        return value

    # ---- joints -------------------------------------------------------------------------------
    def _joint(self, name: str, node: Node, path: str) -> JointDecl:
        n = self.n
        e = n.mapping(node, path, JOINT_KEYS, required=("type", "parent", "child"))
        jtype = JOINT_TYPES[n.choice(e["type"], f"{path}.type", tuple(JOINT_TYPES))]
        decl = JointDecl(
            name=name,
            type=jtype,
            parent=n.string(e["parent"], f"{path}.parent"),
            child=n.string(e["child"], f"{path}.child"),
            src=n.loc(node),
        )
        # Angles for revolute joints, lengths for prismatic ones: the file's units either way.
        k = self.length if jtype is JointType.PRISMATIC else self.angle
        if "origin" in e:
            decl.origin, decl.frame = self._placed_pose(e["origin"], f"{path}.origin")
        if "axis" in e:
            decl.axis = self._axis(e["axis"], f"{path}.axis")
        if "limits" in e:
            lim = n.mapping(e["limits"], f"{path}.limits", LIMIT_KEYS)
            decl.limit_src = n.loc(e["limits"])
            if "lower" in lim:
                decl.lower = n.number(lim["lower"], f"{path}.limits.lower") * k
            if "upper" in lim:
                decl.upper = n.number(lim["upper"], f"{path}.limits.upper") * k
            if "effort" in lim:
                decl.effort = n.positive(lim["effort"], f"{path}.limits.effort", allow_zero=True)
            if "velocity" in lim:
                decl.velocity = n.positive(lim["velocity"], f"{path}.limits.velocity", allow_zero=True) * k
            if decl.lower is not None and decl.upper is not None and decl.lower > decl.upper:
                raise n.fail(e["limits"], f"{path}.limits", "lower is above upper")
        if "dynamics" in e:
            d = n.mapping(e["dynamics"], f"{path}.dynamics", DYNAMICS_KEYS)
            if "damping" in d:
                decl.damping = n.positive(d["damping"], f"{path}.dynamics.damping", allow_zero=True)
            if "friction" in d:
                decl.friction = n.positive(d["friction"], f"{path}.dynamics.friction", allow_zero=True)
        if "mimic" in e:
            mnode = e["mimic"]
            if isinstance(mnode, ScalarNode):
                decl.mimic = n.string(mnode, f"{path}.mimic")
            else:
                mim = n.mapping(mnode, f"{path}.mimic", MIMIC_KEYS, required=("joint",))
                decl.mimic = n.string(mim["joint"], f"{path}.mimic.joint")
                if "multiplier" in mim:
                    decl.multiplier = n.number(mim["multiplier"], f"{path}.mimic.multiplier")
                if "offset" in mim:
                    decl.offset = n.number(mim["offset"], f"{path}.mimic.offset") * k
        if "armature" in e:
            decl.armature = n.positive(e["armature"], f"{path}.armature", allow_zero=True)
        if "actuator" in e:
            decl.actuator = self._actuator(e["actuator"], f"{path}.actuator")
        if "safety" in e:
            s = n.mapping(e["safety"], f"{path}.safety", SAFETY_KEYS, required=("k_velocity",))
            decl.safety = SafetyController(
                k_velocity=n.number(s["k_velocity"], f"{path}.safety.k_velocity"),
                k_position=n.number(s["k_position"], f"{path}.safety.k_position") if "k_position" in s else None,
                soft_lower_limit=n.number(s["soft_lower"], f"{path}.safety.soft_lower") * k
                if "soft_lower" in s
                else None,
                soft_upper_limit=n.number(s["soft_upper"], f"{path}.safety.soft_upper") * k
                if "soft_upper" in s
                else None,
                src=n.loc(e["safety"]),
            )
        return decl

    def _actuator(self, node: Node, path: str) -> ActuatorDecl | None:
        n = self.n
        if isinstance(node, ScalarNode):
            return ActuatorDecl(src=n.loc(node)) if n.boolean(node, path) else None
        a = n.mapping(node, path, ACTUATOR_KEYS)
        decl = ActuatorDecl(src=n.loc(node))
        if "transmission" in a:
            decl.type = n.string(a["transmission"], f"{path}.transmission")
        if "interface" in a:
            decl.interface = n.string(a["interface"], f"{path}.interface")
        if "reduction" in a:
            decl.reduction = n.number(a["reduction"], f"{path}.reduction")
        if "name" in a:
            decl.name = n.string(a["name"], f"{path}.name")
        return decl

    def _loop(self, name: str, node: Node, path: str) -> LoopDecl:
        n = self.n
        e = n.mapping(node, path, LOOP_KEYS, required=("link1", "link2"))
        ltype = (
            n.choice(e["type"], f"{path}.type", ("spherical", "revolute", "continuous", "prismatic", "fixed"))
            if "type" in e
            else "spherical"
        )
        sides: list[tuple[str, Pose | None, Frame]] = []
        for side in ("link1", "link2"):
            s = n.mapping(e[side], f"{path}.{side}", LOOP_SIDE_KEYS, required=("link",))
            pose: Pose | None = None
            frame: Frame = "parent"
            if any(k in s for k in ("xyz", "rpy", "frame")):
                pose, frame = self._placed_pose(
                    _subset(e[side], n, ("xyz", "rpy", "frame"), f"{path}.{side}"), f"{path}.{side}"
                )
            sides.append((n.string(s["link"], f"{path}.{side}.link"), pose, frame))
        if sides[0][2] != sides[1][2] and sides[0][1] is not None and sides[1][1] is not None:
            raise n.fail(node, path, "give both loop sides in the same frame")
        frame_used: Frame = "world" if "world" in (sides[0][2], sides[1][2]) else "parent"
        return LoopDecl(
            name=name,
            type=ltype,
            link1=sides[0][0],
            link2=sides[1][0],
            origin1=sides[0][1],
            origin2=sides[1][1],
            frame=frame_used,
            axis=self._axis(e["axis"], f"{path}.axis") if "axis" in e else None,
            src=n.loc(node),
        )

    def _sensor(self, name: str, node: Node, path: str) -> SensorDecl:
        n = self.n
        e = n.mapping(node, path, SENSOR_KEYS, required=("type", "parent"))
        pose, frame = self._placed_pose(e.get("pose"), f"{path}.pose")
        decl = SensorDecl(
            name=name,
            type=n.choice(e["type"], f"{path}.type", tuple(SENSOR_TYPES)),
            parent=n.string(e["parent"], f"{path}.parent"),
            pose=pose,
            frame=frame,
            src=n.loc(node),
        )
        if "update_rate" in e:
            decl.update_rate = n.positive(e["update_rate"], f"{path}.update_rate")
        if "topic" in e:
            decl.topic = n.string(e["topic"], f"{path}.topic")
        if "noise" in e:
            decl.noise = n.positive(e["noise"], f"{path}.noise", allow_zero=True)
        if "isaac_sim_config" in e:
            decl.isaac_sim_config = n.string(e["isaac_sim_config"], f"{path}.isaac_sim_config")
        if "camera" in e:
            c = n.mapping(e["camera"], f"{path}.camera", CAMERA_KEYS)
            cp = f"{path}.camera"
            decl.camera = CameraSpec(
                width=n.integer(c["width"], f"{cp}.width") if "width" in c else None,
                height=n.integer(c["height"], f"{cp}.height") if "height" in c else None,
                hfov=n.positive(c["hfov"], f"{cp}.hfov") * self.angle if "hfov" in c else None,
                format=n.string(c["format"], f"{cp}.format") if "format" in c else None,
                near=n.positive(c["near"], f"{cp}.near") * self.length if "near" in c else None,
                far=n.positive(c["far"], f"{cp}.far") * self.length if "far" in c else None,
            )
        if "ray" in e:
            r = n.mapping(e["ray"], f"{path}.ray", RAY_KEYS)
            rp = f"{path}.ray"
            decl.ray = RaySpec(
                horizontal=self._ray_axis(r["horizontal"], f"{rp}.horizontal") if "horizontal" in r else None,
                vertical=self._ray_axis(r["vertical"], f"{rp}.vertical") if "vertical" in r else None,
                min_range=n.positive(r["min_range"], f"{rp}.min_range", allow_zero=True) * self.length
                if "min_range" in r
                else None,
                max_range=n.positive(r["max_range"], f"{rp}.max_range") * self.length if "max_range" in r else None,
            )
        return decl

    def _ray_axis(self, node: Node, path: str) -> RayAxis:
        n = self.n
        a = n.mapping(node, path, RAY_AXIS_KEYS)
        return RayAxis(
            samples=n.integer(a["samples"], f"{path}.samples") if "samples" in a else None,
            resolution=n.positive(a["resolution"], f"{path}.resolution") if "resolution" in a else None,
            min_angle=n.number(a["min_angle"], f"{path}.min_angle") * self.angle if "min_angle" in a else None,
            max_angle=n.number(a["max_angle"], f"{path}.max_angle") * self.angle if "max_angle" in a else None,
        )


def _subset(node: Node, n: NodeReader, keys: tuple[str, ...], path: str) -> Node:
    pairs = [(k, v) for k, v in n.pairs(node, path) if k.value in keys]
    return MappingNode("tag:yaml.org,2002:map", pairs, node.start_mark, node.end_mark)


def is_yaml_composition(path: str) -> bool:
    return os.path.splitext(path)[1].lower() in (".yaml", ".yml")
