"""Lower a HoloScript ``.holo`` composition (the syntax tree of holo_parser) to the IR.

The rules (docs/compositions.md has the full list; every inference is reported as a finding):
- Only what describes a robot is read: objects (``object``, ``orb``, ``entity``, shape blocks ...)
  anywhere in ``composition``/``scene``/group blocks and nested in each other, templates, joint
  blocks, the environment's gravity. Every other block is skipped with an info finding. A
  composition in which nothing declares a joint holds no robot, and is refused saying so.
- Positions are world positions of the composition (metres), rotations roll-pitch-yaw in degrees;
  every link frame sits at its object's world pose, visuals at the link origin, and joint origins
  are the relative transforms between the world poses.
- Joints in every spelling HoloScript uses: ``@joint { }`` / ``@joint(...)``, ``@joint_revolute``
  & co. with ``joint_*`` properties, ``behavior "RevoluteJoint"``, ``joint_type``/``parent``,
  ``joint "Name" { parent, child }`` blocks and ``robot { joints { } }``. Angles are degrees.
- The base is the first static object (else the root of the joint tree; it then floats). An object
  without a joint is fixed to its enclosing object, else to the most recent robot object before it.
- Templates are defaults the object overrides; a name used twice gets a unique link name.
- ``@grabbable`` objects without a joint, and static objects nothing connects to, are props.

>>> result = load_holo_text('''composition "Pendulum" {
...   object "Base" { @physics { type: "static" mass: 1 } geometry: "box" scale: 0.1 position: [0, 0, 1] }
...   object "Bob" { @joint { jointType: "hinge" connectedBody: "Base" axis: [0, 1, 0] limits: { min: -90, max: 90 } }
...                  geometry: "sphere" scale: 0.05 position: [0, 0, 0.5] mass: 0.2 }
... }''', "pendulum.holo")
>>> result.robot.joint("Bob_joint").origin.xyz
(0.0, 0.0, -0.5)
"""

from __future__ import annotations

import difflib
import math
import os
from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from robodesc.frontends.compose.builder import JOINT_TYPES, Part, RobotBuilder, joint_type
from robodesc.frontends.compose.colors import ColorError, parse_color
from robodesc.frontends.compose.meshes import resolve_mesh
from robodesc.frontends.compose.solids import POLYHEDRA, cone, polyhedron, torus
from robodesc.frontends.holo.parser import Block, Document, Expr, Trait, Value, parse
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.frontends.packages import PackageResolver
from robodesc.ir.diagnostics import BrokenReferenceError, Findings, ParseError, SourceLoc
from robodesc.ir.geometry import RGBA, Box, Capsule, Cylinder, Geometry, Inertia, Mesh, Pose, Sphere, Vec3
from robodesc.ir.model import CameraSpec, JointType, RayAxis, RaySpec, Robot, SafetyController
from robodesc.ir.transforms import Mat, matrix_pose, pose_matrix

STAGE = "compose:holo"
# HoloScript's URDF compiler gives every body without a mass this many kilograms.
HOLOSCRIPT_DEFAULT_MASS = 1.0

MESH_SUFFIXES = (".stl", ".obj", ".dae", ".glb", ".gltf", ".fbx", ".ply", ".usd", ".usda", ".usdc", ".usdz", ".3ds")
PRIMITIVES = ("box", "cube", "sphere", "cylinder", "cone", "capsule", "plane")
# HoloScript shapes URDF lacks, and the primitive each is written as (with a finding).
ROUND_SOLIDS = ("dodecahedron", "icosahedron", "octahedron", "tetrahedron", "icosphere", "geodesic")
RING_SOLIDS = ("torus", "ring", "disc", "disk", "tube")
# Primitive shapes HoloScript declares as blocks (`sphere "Ball" { }`), from its PRIMITIVE_SHAPES.
SHAPE_KINDS = ("cube", "box", "sphere", "cylinder", "cone", "torus", "plane", "capsule", "ring")
OBJECT_KINDS = ("object", "orb", "entity", "instanced_object", "spatial_agent", "link", "end_effector", *SHAPE_KINDS)
# Blocks that only hold objects: their pose (if any) composes into their children's.
GROUP_KINDS = ("spatial_group", "group", "scene", "composition", "robot", "spawn_group", "zone")
JOINT_KINDS = ("joint",)
# Trait spellings of a joint: @joint_revolute ... (HoloScript's own URDF compiler reads only @joint).
JOINT_TRAITS = {
    "joint_revolute": "revolute",
    "joint_hinge": "revolute",
    "joint_continuous": "continuous",
    "joint_prismatic": "prismatic",
    "joint_slider": "prismatic",
    "joint_fixed": "fixed",
    "joint_ball": "spherical",
    "joint_spherical": "spherical",
}
KNOWN_PROPS = frozenset(
    {
        "geometry",
        "position",
        "rotation",
        "scale",
        "color",
        "material",
        "mass",
        "physics",
        "parent",
        "joint_type",
        "axis",
        "limits",
        "joint_name",
        "radius",
        "height",
        "length",
        "size",
        "joint_parent",
        "joint_axis",
        "joint_limits",
        "joint_effort",
        "joint_origin",
        "joint_friction",
        "joint_damping",
        "max_velocity",
        "armature",
        "static",
        "fixed",
        "mesh",
        "rigidbody",
        "behavior",
    }
)
KNOWN_TRAITS = frozenset(
    {"physics", "rigid", "collidable", "trigger", "grabbable", "joint", "sensor", "actuator", "static", *JOINT_TRAITS}
)
BEHAVIOR_JOINTS: dict[str, str] = {
    "RevoluteJoint": "revolute",
    "HingeJoint": "revolute",
    "ContinuousJoint": "continuous",
    "PrismaticJoint": "prismatic",
    "SliderJoint": "prismatic",
    "FixedJoint": "fixed",
    "BallJoint": "spherical",
    "SphericalJoint": "spherical",
}
SENSOR_PARAMS = frozenset(
    {
        "type",
        "name",
        "fov",
        "width",
        "height",
        "near",
        "far",
        "format",
        "topic",
        "frameName",
        "updateRate",
        "samples",
        "verticalSamples",
        "minAngle",
        "maxAngle",
        "minRange",
        "maxRange",
        "noise",
        "isaac_sim_config",
        "position",
        "rotation",
    }
)


@dataclass(slots=True)
class HoloProp:
    """A body of the composition that is not part of the robot (a ``@grabbable`` prop, a static fixture).

    ``pose`` is in the composition's (Z-up) world frame; an SDF world writer can place it as a model.
    """

    name: str
    kind: str  # "grabbable" or "static"
    geometry: Geometry | None
    pose: Pose
    mass: float | None
    color: RGBA | None
    src: SourceLoc | None = None


@dataclass(slots=True)
class HoloResult:
    robot: Robot
    props: list[HoloProp]
    findings: Findings
    gravity: Vec3 | None = None


def load_holo(path: str, options: LoadOptions | None = None, findings: Findings | None = None) -> HoloResult:
    from robodesc.frontends.xml_safety import read_text  # regular files only: a named pipe must not hang

    text = read_text(path)
    return load_holo_text(text, path, options, findings)


def load_holo_text(
    text: str, file: str, options: LoadOptions | None = None, findings: Findings | None = None
) -> HoloResult:
    out = findings if findings is not None else Findings()
    doc = parse(text, file)
    return _Lowerer(doc, file, options or LoadOptions(), out).run()


def holo_frontend(path: str, options: LoadOptions, findings: Findings) -> Robot:
    """The frontend registered for ``.holo`` (props are reported as findings; ``load_holo`` returns them)."""
    return load_holo(path, options, findings).robot


# ---- the composition's objects, flattened ------------------------------------------------------
@dataclass(slots=True)
class _Obj:
    name: str
    block: Block
    props: dict[str, Value]
    traits: list[Trait]
    behaviors: list[Block]
    world: Mat
    enclosing: str | None
    index: int

    @property
    def label(self) -> str:
        return f"object {self.name!r}"

    def trait(self, name: str) -> Trait | None:
        for t in self.traits:
            if t.name == name:
                return t
        return None

    def traits_named(self, name: str) -> list[Trait]:
        return [t for t in self.traits if t.name == name]


@dataclass(slots=True)
class _JointSpec:
    type: str
    type_loc: SourceLoc
    parent: str | None
    parent_loc: SourceLoc | None
    params: dict[str, Value]
    loc: SourceLoc
    notation: str
    name: str | None = None
    in_degrees: set[str] = field(default_factory=set)


class _Lowerer:
    def __init__(self, doc: Document, file: str, options: LoadOptions, findings: Findings) -> None:
        self.doc = doc
        self.file = file
        self.options = options
        self.findings = findings
        self.templates: dict[str, Block] = {}
        self.objects: dict[str, _Obj] = {}
        # Original name -> the unique name of its first object, for names used more than once.
        self.renamed: dict[str, str] = {}
        self.joint_decls: list[tuple[Block, str | None]] = []
        # Objects drawn as a stand-in primitive whose inertia is another shape's: (kind, a, b).
        self._solids: dict[str, tuple[str, float, float]] = {}
        # Empty links standing for bodies the file names but does not declare.
        self._synthetic: set[str] = set()
        self.up = np.eye(4)
        self.y_up = False
        self.gravity: Vec3 | None = None
        self._cylinder_noted = False

    # ---- messages ----------------------------------------------------------------------------
    def fail(self, message: str, element: str, loc: SourceLoc | None) -> ParseError:
        return ParseError(message, element=element, loc=loc)

    def note(
        self, code: str, message: str, element: str = "", loc: SourceLoc | None = None, *, warn: bool = False
    ) -> None:
        if warn:
            self.findings.warn(code, message, element=element, loc=loc, stage=STAGE)
        else:
            self.findings.info(code, message, element=element, loc=loc, stage=STAGE)

    # ---- top level ---------------------------------------------------------------------------
    def run(self) -> HoloResult:
        comps = [b for b in self.doc.body.children if b.kind == "composition"]
        comp = comps[0] if len(comps) == 1 else self.doc.body
        name = (comp.name if len(comps) == 1 else None) or os.path.splitext(os.path.basename(self.file))[0]
        for key, loc in self.doc.duplicate_keys:
            self.note("duplicate-key", f"key {key!r} is given twice; the last one counts", loc=loc, warn=True)
        for skipped in self.doc.skipped:
            self.note(
                "ignored-block",
                f"'{skipped.kind}' {'block' if skipped.why == 'code' else 'statement'} ignored: "
                "it is not part of a robot description",
                loc=skipped.loc,
            )
        if self.doc.stray:
            text, loc = self.doc.stray[0]
            self.note(
                "ignored-syntax",
                f"{len(self.doc.stray)} stray token(s) between declarations stepped over, as HoloScript's parser "
                f"does (the first: {text[:20]!r})",
                loc=loc,
                warn=True,
            )
        for key, loc in self.doc.equals_props:
            self.note("equals-property", f"'{key} = ...' read as '{key}: ...' (HoloScript's reading)", loc=loc)
        self._environment(comp)
        self._collect_templates(comp)
        self._walk(comp.children if comp is not self.doc.body else self.doc.body.children, self.up, None, ())
        if not self.objects and not self.joint_decls:
            raise self.fail(
                "the composition holds no robot: it declares no objects and no joints",
                f"composition {name!r}",
                comp.loc,
            )
        return self._build(name, comp)

    def _environment(self, comp: Block) -> None:
        envs = [b for b in comp.children if b.kind == "environment"]
        ignored: list[str] = []
        for env in envs:
            for key, value in env.props.items():
                if key == "gravity" and isinstance(value.data, (list, dict)):
                    g = self.vec3(value, "environment.gravity", "environment")
                    self.gravity = g
                elif key == "gravity":
                    self.note(
                        "ignored-gravity",
                        f"gravity {_describe(value)} is no vector: it does not tell which way is up",
                        "environment",
                        value.loc,
                        warn=True,
                    )
                else:
                    ignored.append(key)
            for child in env.children:
                ignored.append(child.kind)
        if ignored:
            self.note(
                "ignored-environment",
                f"environment settings {', '.join(sorted(set(ignored)))} are simulator settings, not part of the robot",
                loc=envs[0].loc,
            )
        gravity = self.gravity
        if gravity is None:
            self.note(
                "assumed-up-axis",
                "no environment gravity: positions are read with +z up (the robot convention)",
                loc=comp.loc,
            )
            return
        norm = math.sqrt(sum(c * c for c in gravity))
        if norm == 0:
            return
        unit = tuple(c / norm for c in gravity)
        if np.allclose(unit, (0, 0, -1), atol=1e-6):
            return
        if np.allclose(unit, (0, -1, 0), atol=1e-6):
            # A Y-up scene: rotate it +90° about X so that +y becomes +z, as the IR wants.
            self.y_up = True
            self.up = np.array([[1, 0, 0, 0], [0, 0, -1, 0], [0, 1, 0, 0], [0, 0, 0, 1]], dtype=float)
            self.note(
                "converted-up-axis",
                "gravity points along -y: the composition is Y-up; it is rotated +90° about x into robodesc's Z-up frame",
                loc=envs[0].loc,
            )
            return
        raise self.fail(
            f"gravity {list(gravity)} is not along -z or -y; robodesc cannot tell which way is up",
            "environment",
            envs[0].props["gravity"].loc,
        )

    def _collect_templates(self, block: Block) -> None:
        for child in block.children:
            if child.kind == "template":
                if not child.name:
                    raise self.fail("a template needs a name", "template", child.loc)
                if child.name in self.templates:
                    first = self.templates[child.name]
                    raise self.fail(
                        f"duplicate template name {child.name!r} (first at {first.name_loc})",
                        f"template {child.name!r}",
                        child.name_loc,
                    )
                self.templates[child.name] = child
            elif child.kind in GROUP_KINDS:
                self._collect_templates(child)

    def _walk(self, blocks: Iterable[Block], frame: Mat, enclosing: str | None, scope: tuple[str, ...]) -> None:
        for block in blocks:
            if block.kind in OBJECT_KINDS and block.kind not in ("composition",):
                if block.kind in SHAPE_KINDS and "geometry" not in block.props:
                    block.props["geometry"] = Value(block.kind, block.loc)
                obj = self._object(block, frame, enclosing, scope)
                self._walk([c for c in block.children if c.kind != "behavior"], obj.world, obj.name, (*scope, obj.name))
            elif block.kind in GROUP_KINDS:
                label = f"{block.kind} {block.name!r}" if block.name else block.kind
                for key in block.props:
                    if key not in ("origin", "position", "rotation"):
                        self.note("ignored-property", f"property {key!r} ignored", label, block.prop_locs[key])
                local = self._pose_matrix(block.props, label, position_keys=("origin", "position"))
                inner = (*scope, block.name) if block.name else scope
                if block.kind == "robot":
                    self._robot_block(block)
                self._walk(block.children, frame @ local, enclosing, inner)
            elif block.kind in JOINT_KINDS:
                self.joint_decls.append((block, enclosing))
            elif block.kind == "behavior":
                self.note("ignored-block", "behavior outside an object ignored", f"behavior {block.name!r}", block.loc)
            elif block.kind not in ("template", "environment"):
                what = f"'{block.kind}' block" + (f" {block.name!r}" if block.name else "")
                self.note("ignored-block", f"{what} ignored: it is not part of a robot description", loc=block.loc)

    def _robot_block(self, block: Block) -> None:
        """``robot NAME { base_link { mass } joints { hip { type, axis, limits } } }`` (the robotics
        plugin's Isaac Lab bridge): an unnamed block is a link named by its keyword, and each block
        inside ``joints`` a joint named by its keyword."""
        for child in block.children:
            if child.name is not None or child.kind in (*OBJECT_KINDS, *GROUP_KINDS, *JOINT_KINDS, "template"):
                continue
            if child.kind == "joints":
                for j in child.children:
                    j.name, j.kind = j.kind, "joint"
                    j.name_loc = j.loc
                child.kind = "group"
                self.note("robot-joints", "each block in 'joints' read as a joint named by its keyword", loc=child.loc)
            else:
                child.name, child.kind = child.kind, "link"
                child.name_loc = child.loc
                self.note("robot-link", f"block '{child.name}' read as a link of that name", loc=child.loc)

    def _object(self, block: Block, frame: Mat, enclosing: str | None, scope: tuple[str, ...]) -> _Obj:
        name = block.name or block.kind
        if not block.name:
            self.note("unnamed-object", f"unnamed {block.kind} block named {name!r}", block.kind, block.loc)
        if name in self.objects or name in self.renamed:
            # HoloScript allows the same name twice; links need unique names.
            unique = _unique(f"{scope[-1]}_{name}" if scope else name, set(self.objects) | set(self.renamed))
            first = self.objects[self.renamed.get(name, name)].block
            self.note(
                "renamed-duplicate",
                f"object name {name!r} is used again (first at {first.name_loc}): this one's link is named {unique!r}"
                f"; references to {name!r} mean the first",
                f"object {name!r}",
                block.name_loc,
                warn=True,
            )
            self.renamed.setdefault(name, name)
            name = unique
        label = f"object {name!r}"
        props = dict(block.props)
        traits = list(block.traits)
        behaviors = [c for c in block.children if c.kind == "behavior"]
        template: Block | None = None
        if block.using is not None:
            template = self.templates.get(block.using)
            if template is None and not _suggest(block.using, self.templates):
                self.note(
                    "unknown-template",
                    f"template {block.using!r} is not defined in this file (HoloScript may import it): "
                    "its defaults are not applied",
                    label,
                    block.using_loc,
                    warn=True,
                )
            elif template is None:
                raise BrokenReferenceError(
                    f"template {block.using!r} is not defined{_suggest(block.using, self.templates)}",
                    element=label,
                    loc=block.using_loc,
                )
        if template is not None:
            self._note_overrides(template, block, label)
            props = _merge_props(template.props, block.props)
            traits = _merge_traits(template.traits, block.traits)
            if _trait_or_prop_mass(template) is not None and _trait_or_prop_mass(block) is not None:
                props, traits = _drop_template_mass(props, traits, block)
            mine = {b.name for b in behaviors}
            behaviors = [b for b in template.children if b.kind == "behavior" and b.name not in mine] + behaviors
        self._normalize_shape_and_mass(block, props, label)
        if "position" not in props and "joint_origin" in props:
            props["position"] = props["joint_origin"]
            self.note(
                "joint-origin-as-position",
                "joint_origin read as the object's position",
                label,
                props["joint_origin"].loc,
            )
        local = self._pose_matrix(props, label, position_keys=("position",))
        obj = _Obj(name, block, props, traits, behaviors, frame @ local, enclosing, len(self.objects))
        self.objects[name] = obj
        return obj

    def _normalize_shape_and_mass(self, block: Block, props: dict[str, Value], label: str) -> None:
        """Other spellings of shape and mass: ``mesh: { type: "cube", width, height, depth }`` or
        ``mesh: "file.glb"`` for ``geometry``; ``rigidbody: { mass }`` (or a ``rigidbody { }`` block)
        for ``mass``. Each reading is an info finding."""
        mesh = props.get("mesh")
        if "geometry" not in props and mesh is not None:
            if isinstance(mesh.data, str):
                props["geometry"] = mesh
                self.note("mesh-as-geometry", "mesh read as the geometry", label, mesh.loc)
            elif isinstance(mesh.data, dict) and isinstance(mesh.data.get("type", Value(None, mesh.loc)).data, str):
                d = mesh.data
                props["geometry"] = d["type"]
                if "scale" not in props:
                    dims = {k: d[k] for k in ("width", "height", "depth", "radius", "size") if k in d}
                    if "radius" in dims:
                        r = self.num(dims["radius"], "mesh.radius", label)
                        h = self.num(dims["height"], "mesh.height", label) if "height" in dims else 2 * r
                        props["scale"] = Value(
                            [Value(2 * r, mesh.loc), Value(h, mesh.loc), Value(2 * r, mesh.loc)], mesh.loc
                        )
                    elif "size" in dims:
                        props["scale"] = dims["size"]
                    elif dims:
                        w, h, dp = (
                            self.num(dims[k], f"mesh.{k}", label) if k in dims else 1.0
                            for k in ("width", "height", "depth")
                        )
                        props["scale"] = Value([Value(w, mesh.loc), Value(h, mesh.loc), Value(dp, mesh.loc)], mesh.loc)
                self.note(
                    "mesh-as-geometry",
                    "mesh { type, width, height, depth } read as the geometry and its scale",
                    label,
                    mesh.loc,
                )
        if _trait_or_prop_mass(block) is None and "mass" not in props:
            rb = props.get("rigidbody")
            rb_props = rb.data if rb is not None and isinstance(rb.data, dict) else None
            if rb_props is None:
                child = next((c for c in block.children if c.kind == "rigidbody"), None)
                rb_props = child.props if child is not None else None
            if rb_props is not None and "mass" in rb_props:
                props["mass"] = rb_props["mass"]
                self.note("rigidbody-mass", "rigidbody mass read as the object's mass", label, rb_props["mass"].loc)

    def _note_overrides(self, template: Block, block: Block, label: str) -> None:
        """Template values are defaults: say which the object overrides (an info finding)."""
        over: list[str] = [k for k in block.props if k in template.props]
        tmass = _trait_or_prop_mass(template)
        omass = _trait_or_prop_mass(block)
        if tmass is not None and omass is not None and "mass" not in over:
            over.append("mass")
        names = {t.name for t in template.traits}
        over += [f"@{t.name}" for t in block.traits if t.name in names and t.params and t.name != "sensor"]
        if over:
            self.note(
                "template-override",
                f"overrides template {template.name!r} defaults: {', '.join(sorted(set(over)))}",
                label,
                block.name_loc,
            )

    # ---- values ------------------------------------------------------------------------------
    def num(self, value: Value, path: str, element: str) -> float:
        if isinstance(value.data, bool) or not isinstance(value.data, float):
            raise self.fail(f"{path}: expected a number, got {_describe(value)}", element, value.loc)
        return value.data

    def string(self, value: Value, path: str, element: str) -> str:
        if not isinstance(value.data, str):
            raise self.fail(f"{path}: expected a string, got {_describe(value)}", element, value.loc)
        return value.data

    def vec3(self, value: Value, path: str, element: str) -> Vec3:
        if isinstance(value.data, dict):
            d = value.data
            unknown = [k for k in d if k not in ("x", "y", "z")]
            if unknown:
                raise self.fail(
                    f"{path}: unknown component {unknown[0]!r} (x, y, z)", element, value.key_locs[unknown[0]]
                )
            x, y, z = (self.num(d[k], f"{path}.{k}", element) if k in d else 0.0 for k in ("x", "y", "z"))
            return (x, y, z)
        if not isinstance(value.data, list) or len(value.data) != 3:
            raise self.fail(f"{path}: expected [x, y, z], got {_describe(value)}", element, value.loc)
        a, b, c = (self.num(v, f"{path}[{i}]", element) for i, v in enumerate(value.data))
        return (a, b, c)

    def _pose_matrix(self, props: dict[str, Value], label: str, position_keys: tuple[str, ...]) -> Mat:
        xyz: Vec3 = (0.0, 0.0, 0.0)
        for key in position_keys:
            if (key in props and isinstance(props[key].data, (str, Expr, bool))) or (
                key in props and props[key].data is None
            ):
                self.note(
                    "ignored-property",
                    f"{key} {_describe(props[key])} is no [x, y, z]: the origin is used",
                    label,
                    props[key].loc,
                    warn=True,
                )
            elif key in props:
                xyz = self.vec3(props[key], key, label)
        rpy: Vec3 = (0.0, 0.0, 0.0)
        if "rotation" in props and not isinstance(props["rotation"].data, (list, dict)):
            self.note(
                "ignored-property",
                f"rotation {_describe(props['rotation'])} is no [roll, pitch, yaw]: no rotation is applied",
                label,
                props["rotation"].loc,
                warn=True,
            )
        elif "rotation" in props:
            deg = self.vec3(props["rotation"], "rotation", label)
            if sum(1 for d in deg if d != 0) > 1:
                self.note(
                    "rotation-convention",
                    f"rotation {list(deg)} read as roll-pitch-yaw in degrees about fixed x, y, z axes (URDF's "
                    "convention); a three.js Euler 'XYZ' reading would differ",
                    label,
                    props["rotation"].loc,
                )
            rpy = (math.radians(deg[0]), math.radians(deg[1]), math.radians(deg[2]))
        return pose_matrix(Pose(xyz=xyz, rpy=rpy))

    # ---- building ----------------------------------------------------------------------------
    def _joint_blocks(self) -> dict[str, _JointSpec]:
        """``joint "Name" [@joint_revolute] { type, axis, limits, parent, child }`` declarations.

        A declaration naming an object as ``child`` is that object's joint. Without a child, the
        joint moves a new, empty link ``<Name>_link``; a parent that is no object becomes an empty
        link of that name. Each of these is reported."""
        specs: dict[str, _JointSpec] = {}
        previous_child: str | None = None
        for block, enclosing in self.joint_decls:
            jname = block.name or f"joint_{len(specs) + 1}"
            label = f"joint {jname!r}"
            p = {k[6:] if k.startswith("joint_") else k: v for k, v in block.props.items()}
            for t in block.traits:
                p.update(t.params)
            jtype_text = next((JOINT_TRAITS[t.name] for t in block.traits if t.name in JOINT_TRAITS), None)
            type_value = p.get("type") or p.get("jointType")
            if type_value is not None:
                jtype_text = self.string(type_value, "type", label)
            if jtype_text is None:
                raise self.fail("a joint needs a type (type: revolute, or @joint_revolute)", label, block.loc)
            parent_value = p.get("parent") or p.get("connectedBody")
            parent = self._text(parent_value, "parent", label)
            if parent is None:
                parent = previous_child or enclosing
                if parent is not None:
                    self.note(
                        "inferred-parent",
                        f"the joint names no parent: it hangs from {parent!r}, "
                        + ("the link the previous joint moves" if parent == previous_child else "its enclosing object"),
                        label,
                        block.loc,
                    )
            if parent is not None and parent not in self.objects:
                self._empty_link(parent, None, block, f"{label} names parent {parent!r}, which is no object")
            child = self._text(p.get("child"), "child", label)
            if child is None:
                child = _unique(f"{jname}_link", set(self.objects))
                self._empty_link(child, parent, block, f"{label} names no child object")
            elif child not in self.objects:
                raise BrokenReferenceError(
                    f"joint child {child!r} is not an object of this composition{_suggest(child, self.objects)}",
                    element=label,
                    loc=p["child"].loc,
                )
            if child in specs:
                raise self.fail(f"object {child!r} has two joints", label, block.loc)
            specs[child] = _JointSpec(
                type=jtype_text,
                type_loc=block.loc if type_value is None else type_value.loc,
                parent=parent,
                parent_loc=None if parent_value is None else parent_value.loc,
                params=p,
                loc=block.loc,
                notation="joint block",
                name=jname,
            )
            previous_child = child
        return specs

    def _empty_link(self, name: str, parent: str | None, block: Block, why: str, *, place: bool = True) -> None:
        world = self.objects[parent].world if parent in self.objects else self.up
        if place and ("position" in block.props or "origin" in block.props):
            world = world @ self._pose_matrix(block.props, f"joint {block.name!r}", ("origin", "position"))
        self.objects[name] = _Obj(name, block, {}, [], [], world, parent, len(self.objects))
        self._synthetic.add(name)
        self.note(
            "empty-link",
            f"{why}: a link {name!r} without shape or mass stands for it",
            f"joint {block.name!r}" if block.kind in JOINT_KINDS else f"object {block.name!r}",
            block.loc,
            warn=True,
        )

    def _build(self, name: str, comp: Block) -> HoloResult:
        props: list[HoloProp] = []
        joints: dict[str, _JointSpec] = {}
        declared = self._joint_blocks()
        for obj in self.objects.values():
            spec = self._joint_spec(obj) if obj.block.kind not in JOINT_KINDS else None
            if obj.name in declared:
                if spec is not None:
                    raise self.fail(
                        f"joint given twice ({spec.notation} and a joint block at {declared[obj.name].loc})",
                        obj.label,
                        spec.loc,
                    )
                spec = declared[obj.name]
            if spec is not None:
                joints[obj.name] = spec
            for key in obj.props:
                if key not in KNOWN_PROPS:
                    self.note("ignored-property", f"property {key!r} ignored", obj.label, obj.block.prop_locs.get(key))
            for trait in obj.traits:
                if trait.name not in KNOWN_TRAITS:
                    self.note("ignored-trait", f"trait @{trait.name} ignored", obj.label, trait.loc)
                elif trait.name == "trigger":
                    self.note(
                        "ignored-trait", "@trigger volumes are not part of a robot description", obj.label, trait.loc
                    )
        if not joints:
            raise self.fail(
                f"the composition holds no robot: none of its {len(self.objects)} objects declares a joint "
                '(@joint, @joint_revolute, behavior "RevoluteJoint", joint_type, parent, or a joint block)',
                f"composition {name!r}",
                comp.loc,
            )
        referenced = {s.parent for s in joints.values() if s.parent is not None}
        for spec_owner, spec in list(joints.items()):
            real = [n for n in self.objects if n not in self._synthetic]
            if spec.parent is not None and spec.parent not in self.objects and not _suggest(spec.parent, real):
                # No object of that name, nor one close to it: the body is declared elsewhere (an
                # import, a part of the scene HoloScript resolves at run time). An empty link stands for it.
                owner = self.objects[spec_owner]
                self._empty_link(
                    spec.parent,
                    None,
                    owner.block,
                    f"{spec.notation} of object {spec_owner!r} names parent {spec.parent!r}, which is no object of this file",
                    place=False,
                )
            elif spec.parent is not None and spec.parent not in self.objects:
                raise BrokenReferenceError(
                    f"{spec.notation} parent {spec.parent!r} is not an object of this composition"
                    f"{_suggest(spec.parent, self.objects)}",
                    element=f"object {spec_owner!r}",
                    loc=spec.parent_loc,
                )
        # Which objects are robot bodies.
        bodies: list[_Obj] = []
        root: _Obj | None = None
        for obj in self.objects.values():
            if obj.trait("grabbable") is not None and obj.name in joints:
                self.note(
                    "grabbable-link",
                    "@grabbable object declares a joint: it is a robot link (the joint wins over the prop reading)",
                    obj.label,
                    obj.block.loc,
                )
            elif obj.trait("grabbable") is not None:
                if obj.name in referenced:
                    raise self.fail("a @grabbable prop cannot carry robot joints", obj.label, obj.block.loc)
                props.append(self._prop(obj, "grabbable"))
                self.note(
                    "prop",
                    "@grabbable object is a free prop, not a robot link (load_holo returns it for world files)",
                    obj.label,
                    obj.block.loc,
                )
                continue
            if self._is_static(obj) and root is not None and obj.name not in referenced and obj.name not in joints:
                props.append(self._prop(obj, "static"))
                self.note(
                    "prop",
                    f"static object is not connected to the robot (its base is {root.name!r}); treated as a fixture",
                    obj.label,
                    obj.block.loc,
                )
                continue
            if root is None and self._is_static(obj) and obj.name not in joints:
                root = obj
            bodies.append(obj)
        if not bodies:
            raise self.fail("the composition has no robot objects (only props)", f"composition {name!r}", comp.loc)
        if root is None:
            # The root of the joint tree the author wrote: the first object a joint hangs from that
            # hangs from nothing itself (a scene's first object may be its sky); else the first
            # object without a joint.
            hubs = [b for b in bodies if b.name not in joints and b.name in referenced]
            candidates = hubs or [b for b in bodies if b.name not in joints]
            root = candidates[0] if candidates else bodies[0]
            how = (
                "the first object a joint names as its parent and that has no joint itself"
                if hubs
                else ("the first object without a joint")
            )
            self.note(
                "inferred-base",
                f'no static object (@physics {{ type: "static" }}, @static): {how} is the base, and it floats',
                root.label,
                root.block.loc,
                warn=True,
            )
        if root.name in joints:
            raise self.fail("the base cannot have a joint", root.label, joints[root.name].loc)
        statics = {b.name for b in bodies if self._is_static(b)} - {root.name}
        for static_name in sorted(statics):
            obj = self.objects[static_name]
            self.note(
                "static-link",
                "static object inside the robot: read as a link (only the base is fixed)",
                obj.label,
                obj.block.loc,
                warn=True,
            )

        builder = RobotBuilder(
            name,
            source_file=self.file,
            options=self.options,
            findings=self.findings,
            src=comp.loc,
            fixed_base=self._fixed_base(root),
        )
        body_names = [b.name for b in bodies]
        used_joint_names: set[str] = set()
        parent_of: dict[str, str] = {}
        movable: set[str] = set()
        for i, obj in enumerate(bodies):
            if obj is root:
                continue
            spec = joints.get(obj.name)
            parent = spec.parent if spec is not None else None
            if parent is None:
                parent = self._inferred_parent(obj, body_names[:i], root)
                what = f"its {spec.notation} names no parent" if spec is not None else "it has no joint"
                how = (
                    "the object it is declared in"
                    if obj.enclosing == parent
                    else "the base (it stands for a body declared elsewhere)"
                    if obj.name in self._synthetic
                    else "the most recent robot object declared before it"
                )
                self.note(
                    "inferred-parent",
                    f"{what}: attached to {parent!r}, {how}" + ("" if spec is not None else ", by a fixed joint"),
                    obj.label,
                    obj.block.loc,
                )
            elif parent not in body_names:
                raise BrokenReferenceError(
                    f"{spec.notation if spec else 'joint'} parent {parent!r} is a prop, not part of the robot",
                    element=obj.label,
                    loc=spec.parent_loc if spec else obj.block.loc,
                )
            if spec is None:
                actuator = obj.trait("actuator")
                if actuator is not None:
                    raise self.fail("@actuator on an object without a joint", obj.label, actuator.loc)
                jname = _unique(f"{parent}_to_{obj.name}", used_joint_names)
                builder.joint(jname, JointType.FIXED, parent, obj.name, src=obj.block.loc)
                parent_of[obj.name] = parent
            else:
                jname = _unique(spec.name or f"{obj.name}_joint", used_joint_names)
                if self._joint(builder, obj, spec, parent, jname) is not JointType.FIXED:
                    movable.add(obj.name)
                parent_of[obj.name] = parent
            used_joint_names.add(jname)
        for obj in bodies:
            self._link(builder, obj, moves=_moves(obj.name, parent_of, movable))
        for obj in bodies:
            self._sensors(builder, obj)
        robot = builder.build()
        return HoloResult(robot, props, self.findings, self.gravity)

    def _is_static(self, obj: _Obj) -> bool:
        """``@physics { type: "static" }``, or the ``@static`` trait / ``static: true`` / ``fixed: true``."""
        if obj.trait("static") is not None:
            return True
        if any(obj.props.get(k) is not None and obj.props[k].data is True for k in ("static", "fixed")):
            return True
        t = obj.trait("physics")
        if t is None or "type" not in t.params:
            return False
        return t.params["type"].data == "static"

    def _fixed_base(self, root: _Obj) -> bool | None:
        if self._is_static(root):
            return True
        t = root.trait("physics")
        if t is None or "type" not in t.params:
            return None
        return t.params["type"].data in ("static", "kinematic")

    def _inferred_parent(self, obj: _Obj, before: list[str], root: _Obj) -> str:
        if obj.enclosing is not None and obj.enclosing in before:
            return obj.enclosing
        if obj.name in self._synthetic:
            # A stand-in for a body declared elsewhere: the base holds it (a chain through the
            # objects declared before it could close a loop through its own children).
            return root.name
        return before[-1] if before else root.name

    # ---- joints ------------------------------------------------------------------------------
    def _text(self, value: Value | None, path: str, label: str) -> str | None:
        if value is None:
            return None
        return self.string(value, path, label)

    def _joint_spec(self, obj: _Obj) -> _JointSpec | None:
        specs: list[_JointSpec] = []
        label = obj.label
        for t in obj.traits_named("joint"):
            p = t.params
            key = next((k for k in ("jointType", "type", "_arg0") if k in p), None)
            if key is None:
                raise self.fail(
                    "@joint needs jointType (revolute, continuous, prismatic, fixed, ball ...)", label, t.loc
                )
            parent = p.get("connectedBody") or p.get("parent")
            specs.append(
                _JointSpec(
                    type=self.string(p[key], f"@joint.{key}", label),
                    type_loc=p[key].loc,
                    parent=self._text(parent, "@joint.connectedBody", label),
                    parent_loc=None if parent is None else parent.loc,
                    params=p,
                    loc=t.loc,
                    notation="@joint",
                    name=self._text(p.get("name"), "@joint.name", label),
                )
            )
        for t in obj.traits:
            if t.name not in JOINT_TRAITS:
                continue
            # @joint_revolute with joint_* properties (HoloScript's Isaac Lab examples).
            p = {**{k[6:] if k.startswith("joint_") else k: v for k, v in obj.props.items()}, **t.params}
            parent = p.get("parent") or p.get("connectedBody")
            specs.append(
                _JointSpec(
                    type=JOINT_TRAITS[t.name],
                    type_loc=t.loc,
                    parent=self._text(parent, "joint_parent", label),
                    parent_loc=None if parent is None else parent.loc,
                    params=p,
                    loc=t.loc,
                    notation=f"@{t.name}",
                    name=self._text(obj.props.get("joint_name"), "joint_name", label),
                )
            )
        joint_behaviors = [b for b in obj.behaviors if b.name in BEHAVIOR_JOINTS]
        override = obj.props.get("behavior")
        for b in obj.behaviors:
            if b.name not in BEHAVIOR_JOINTS:
                self.note("ignored-behavior", f"behavior {b.name!r} ignored", label, b.loc)
                continue
            params = b.props
            if override is not None and isinstance(override.data, dict) and len(joint_behaviors) == 1:
                # `behavior: { axis: [0, 1, 0] }` on an object using a template whose behavior block
                # is the joint: the object's values win, key by key, as template values do.
                params = {**b.props, **override.data}
                self.note(
                    "template-override",
                    f"behavior: {{ {', '.join(override.data)} }} overrides behavior {b.name!r} of its template",
                    label,
                    override.loc,
                )
            parent = params.get("connectedBody") or params.get("parent") or obj.props.get("parent")
            specs.append(
                _JointSpec(
                    type=BEHAVIOR_JOINTS[b.name],
                    type_loc=b.name_loc,
                    parent=self._text(parent, "parent", label),
                    parent_loc=None if parent is None else parent.loc,
                    params=params,
                    loc=b.loc,
                    notation=f'behavior "{b.name}"',
                )
            )
        if "joint_type" in obj.props:
            parent = obj.props.get("parent") or obj.props.get("joint_parent")
            specs.append(
                _JointSpec(
                    type=self.string(obj.props["joint_type"], "joint_type", label),
                    type_loc=obj.props["joint_type"].loc,
                    parent=self._text(parent, "parent", label),
                    parent_loc=None if parent is None else parent.loc,
                    params={k: v for k, v in obj.props.items() if k in ("axis", "limits")},
                    loc=obj.block.prop_locs.get("joint_type", obj.block.loc),
                    notation="joint_type",
                    name=self._text(obj.props.get("joint_name"), "joint_name", label),
                )
            )
        elif ("parent" in obj.props or "joint_parent" in obj.props) and not specs:
            pkey = "parent" if "parent" in obj.props else "joint_parent"
            parent = obj.props[pkey]
            specs.append(
                _JointSpec(
                    type="fixed",
                    type_loc=parent.loc,
                    parent=self.string(parent, pkey, label),
                    parent_loc=parent.loc,
                    params={},
                    loc=obj.block.prop_locs.get(pkey, obj.block.loc),
                    notation=pkey,
                )
            )
        if len(specs) > 1:
            raise self.fail(
                f"joint given twice ({specs[0].notation} at {specs[0].loc} and {specs[1].notation}); keep one",
                label,
                specs[1].loc,
            )
        return specs[0] if specs else None

    def _joint(self, builder: RobotBuilder, obj: _Obj, spec: _JointSpec, parent: str, name: str) -> JointType:
        label = obj.label
        key = spec.type.strip().lower()
        if key not in JOINT_TYPES and not _suggest(key, JOINT_TYPES):
            # spring, d6, distance ...: physics constraints with no URDF joint. HoloScript's own
            # compiler writes them as fixed without a word; robodesc does the same, and says so.
            self.note(
                "unsupported-joint-type",
                f"joint type {spec.type!r} has no URDF/SDF/USD equivalent: written as a fixed joint; its "
                "other parameters are dropped",
                label,
                spec.type_loc,
                warn=True,
            )
            key = "fixed"
        jtype = joint_type(key, label, spec.type_loc)
        p = spec.params
        angular = jtype in (JointType.REVOLUTE, JointType.CONTINUOUS)
        # Revolute limits, offsets and soft limits are degrees in HoloScript; prismatic ones metres.
        k = math.pi / 180.0 if angular else 1.0
        axis: Vec3 | None = None
        if "axis" in p:
            axis = self.vec3(p["axis"], f"{spec.notation}.axis", label) if not isinstance(p["axis"].data, str) else None
            if isinstance(p["axis"].data, str):
                from robodesc.frontends.compose.builder import axis_vector

                try:
                    axis = axis_vector(p["axis"].data)
                except ValueError as exc:
                    raise self.fail(str(exc), label, p["axis"].loc) from None
            if not any(axis or ()):
                raise self.fail("axis is the zero vector", label, p["axis"].loc)
        elif jtype.dof > 0 and jtype is not JointType.SPHERICAL and jtype is not JointType.FLOATING:
            self.note("default-axis", "no axis given: URDF's default +x applies", label, spec.loc, warn=True)
        lower = upper = effort = velocity = None
        limit_loc = spec.loc
        if not spec.notation.startswith("behavior"):
            if "limits" in p and isinstance(p["limits"].data, list):
                lim = p["limits"]
                limit_loc = lim.loc
                pair = lim.data if isinstance(lim.data, list) else []
                if len(pair) != 2:
                    raise self.fail(f"limits: expected [min, max], got {_describe(lim)}", label, lim.loc)
                lower = self.num(pair[0], "limits[0]", label) * k
                upper = self.num(pair[1], "limits[1]", label) * k
            elif "limits" in p:
                lim = p["limits"]
                limit_loc = lim.loc
                if not isinstance(lim.data, dict):
                    raise self.fail(
                        f"limits: expected {{ min, max, effort, velocity }}, got {_describe(lim)}", label, lim.loc
                    )
                d = lim.data
                for key in d:
                    if key not in ("min", "max", "lower", "upper", "effort", "velocity"):
                        raise self.fail(
                            f"limits: unknown key {key!r}{_suggest(key, ('min', 'max', 'effort', 'velocity'))}",
                            label,
                            lim.key_locs[key],
                        )
                lo = d.get("min") or d.get("lower")
                hi = d.get("max") or d.get("upper")
                lower = None if lo is None else self.num(lo, "limits.min", label) * k
                upper = None if hi is None else self.num(hi, "limits.max", label) * k
                effort = self.num(d["effort"], "limits.effort", label) if "effort" in d else None
                velocity = self.num(d["velocity"], "limits.velocity", label) if "velocity" in d else None
            for key in ("effort", "max_effort", "maxTorque", "maxForce", "torque"):
                if key in p and effort is None:
                    effort = self.num(p[key], key, label)
            for key in ("velocity", "max_velocity", "maxVelocity"):
                if key in p and velocity is None:
                    velocity = self.num(p[key], key, label)
        else:
            if "lowerLimit" in p:
                lower = self.num(p["lowerLimit"], "lowerLimit", label) * k
            if "upperLimit" in p:
                upper = self.num(p["upperLimit"], "upperLimit", label) * k
            if "maxVelocity" in p:
                velocity = self.num(p["maxVelocity"], "maxVelocity", label)
            for key in ("maxTorque", "maxForce", "maxEffort"):
                if key in p:
                    effort = self.num(p[key], key, label)
        if lower is not None and upper is not None and lower > upper:
            raise self.fail("the lower limit is above the upper limit", label, limit_loc)
        if angular and lower is not None and upper is not None and _looks_like_radians(lower / k, upper / k):
            self.note(
                "radian-looking-limits",
                f"limits [{lower / k:g}, {upper / k:g}] are read in degrees (HoloScript's unit for angles) but look like "
                f"radians; if radians were meant, write [{math.degrees(lower / k):.4g}, {math.degrees(upper / k):.4g}]",
                label,
                limit_loc,
                warn=True,
            )
        if jtype is JointType.REVOLUTE and (lower is None or upper is None):
            self.note(
                "unlimited-revolute",
                "revolute joint without min/max limits: written as a continuous joint (it may turn freely)",
                label,
                spec.loc,
                warn=True,
            )
            jtype, lower, upper = JointType.CONTINUOUS, None, None
        if jtype is JointType.PRISMATIC and (lower is None or upper is None):
            raise self.fail("a prismatic joint needs limits { min, max } (metres)", label, limit_loc)
        damping = self.num(p["damping"], "damping", label) if "damping" in p else None
        friction = self.num(p["friction"], "friction", label) if "friction" in p else None
        armature = self.num(p["armature"], "armature", label) if "armature" in p else None
        mimic = multiplier = offset = None
        if "mimic" in p:
            m = p["mimic"]
            if isinstance(m.data, str):
                mimic = m.data
            elif isinstance(m.data, dict) and "joint" in m.data:
                mimic = self.string(m.data["joint"], "mimic.joint", label)
                if "multiplier" in m.data:
                    multiplier = self.num(m.data["multiplier"], "mimic.multiplier", label)
                if "offset" in m.data:
                    offset = self.num(m.data["offset"], "mimic.offset", label) * k
            else:
                raise self.fail("mimic: expected { joint, multiplier, offset }", label, m.loc)
            # The author names the leader by its object; joints are named after their objects.
            if mimic in self.objects:
                mimic = f"{mimic}_joint"
        safety = None
        if "safetyController" in p:
            sc = p["safetyController"]
            if not isinstance(sc.data, dict):
                raise self.fail("safetyController: expected an object", label, sc.loc)
            d = sc.data

            def get(*names: str) -> Value | None:
                for nm in names:
                    if nm in d:
                        return d[nm]
                return None

            kv = get("kVelocity", "k_velocity")
            if kv is None:
                raise self.fail("safetyController needs kVelocity", label, sc.loc)
            kp, sl, su = (
                get("kPosition", "k_position"),
                get("softLowerLimit", "soft_lower_limit"),
                get("softUpperLimit", "soft_upper_limit"),
            )
            safety = SafetyController(
                k_velocity=self.num(kv, "safetyController.kVelocity", label),
                k_position=None if kp is None else self.num(kp, "safetyController.kPosition", label),
                soft_lower_limit=None if sl is None else self.num(sl, "safetyController.softLowerLimit", label) * k,
                soft_upper_limit=None if su is None else self.num(su, "safetyController.softUpperLimit", label) * k,
                src=sc.loc,
            )
        builder.joint(
            name,
            jtype,
            parent,
            obj.name,
            axis=axis,
            lower=lower,
            upper=upper,
            effort=effort,
            velocity=velocity,
            damping=damping,
            friction=friction,
            mimic=mimic,
            multiplier=multiplier,
            offset=offset,
            safety=safety,
            armature=armature,
            src=spec.loc,
            limit_src=limit_loc,
            display_name=None,
        )
        for act in obj.traits_named("actuator"):
            if jtype is JointType.FIXED:
                raise self.fail("@actuator on an object whose joint is fixed", label, act.loc)
            a = act.params
            builder.actuator(
                name,
                type=self.string(a["transmissionType"], "@actuator.transmissionType", label)
                if "transmissionType" in a
                else "transmission_interface/SimpleTransmission",
                interface=self.string(a["hardwareInterface"], "@actuator.hardwareInterface", label)
                if "hardwareInterface" in a
                else None,
                reduction=self.num(a["mechanicalReduction"], "@actuator.mechanicalReduction", label)
                if "mechanicalReduction" in a
                else None,
                name=self.string(a["name"], "@actuator.name", label) if "name" in a else None,
                src=act.loc,
            )
        return jtype

    # ---- links -------------------------------------------------------------------------------
    def _link(self, builder: RobotBuilder, obj: _Obj, *, moves: bool = False) -> None:
        label = obj.label
        geom, origin, geom_loc = self._geometry(obj)
        parts: list[Part] = []
        color = self._color(obj)
        material = self._material(obj)
        if geom is not None:
            parts.append(
                Part(
                    geometry=geom,
                    origin=origin,
                    color=color,
                    material=material,
                    collision=obj.trait("collidable") is not None,
                    src=geom_loc,
                )
            )
        else:
            self.note("no-geometry", "object has no geometry: a link without visuals", label, obj.block.loc)
        mass, inertia = self._mass(obj)
        if geom is None and inertia is None and mass is not None:
            self.note(
                "mass-without-shape",
                f"mass {mass:g} kg without a shape or an inertia tensor: no inertia can be computed, the link gets "
                "no inertial",
                label,
                obj.block.loc,
                warn=True,
            )
            mass = None
        com: Pose | None = None
        solid = self._solids.get(obj.name)
        if solid is not None and mass is not None and inertia is None:
            kind, a, b = solid
            props = (
                cone(mass, a, b)
                if kind == "cone"
                else torus(mass, a, b)
                if kind == "torus"
                else polyhedron(kind, mass, a)
            )
            inertia = Inertia(*props.inertia, src=geom_loc)
            com = matrix_pose(pose_matrix(origin or Pose()) @ pose_matrix(Pose(xyz=(0.0, 0.0, props.com_z))))
        if mass is None and moves:
            # A body that moves needs a mass in every simulator. HoloScript's own URDF compiler gives
            # 1 kg (and, without a shape, the inertia of a 1 m cube); robodesc does the same, and says so.
            mass = HOLOSCRIPT_DEFAULT_MASS
            if geom is None:
                inertia = Inertia(mass / 6.0, mass / 6.0, mass / 6.0, src=obj.block.loc)
            self.note(
                "default-mass",
                f"moving object has no mass: {mass:g} kg, HoloScript's default"
                + (", with the inertia of a 1 m cube (it has no shape)" if geom is None else ""),
                label,
                obj.block.loc,
                warn=True,
            )
        if mass is None:
            self.note(
                "no-mass",
                "object has no mass (mass, @physics { mass } or physics: { mass })",
                label,
                obj.block.loc,
                warn=True,
            )
        builder.link(
            obj.name,
            *parts,
            mass=mass,
            inertia=inertia,
            com=com,
            pose=matrix_pose(obj.world),
            frame="world",
            element=label,
            src=obj.block.name_loc,
        )

    def _geometry(self, obj: _Obj) -> tuple[Geometry | None, Pose | None, SourceLoc | None]:
        label = obj.label
        if "geometry" not in obj.props:
            return None, None, None
        gval = obj.props["geometry"]
        kind = self.string(gval, "geometry", label)
        scale = self._scale(obj)
        sx, sy, sz = scale
        lowered = kind.lower()
        if lowered.endswith(MESH_SUFFIXES) or "/" in kind or "://" in kind:
            return Mesh(uri=kind, scale=scale, src=gval.loc), None, gval.loc
        true_kind = lowered
        if lowered in ROUND_SOLIDS:
            self.note(
                "substituted-geometry",
                f"URDF has no {lowered}: written as the sphere of its scale (the closest primitive)"
                + ("; its inertia is the polyhedron's" if lowered in POLYHEDRA else ""),
                label,
                gval.loc,
                warn=True,
            )
            lowered = "sphere"
        elif lowered in RING_SOLIDS:
            self.note(
                "substituted-geometry",
                f"URDF has no {lowered}: written as the cylinder of its extents (the closest primitive); "
                "its inertia is the solid torus's ([outer diameter, tube diameter, outer diameter])",
                label,
                gval.loc,
                warn=True,
            )
            lowered = "cylinder"
        elif lowered not in PRIMITIVES:
            self.note(
                "substituted-geometry",
                f"geometry {kind!r} is no primitive robodesc knows ({', '.join(PRIMITIVES)}) and no mesh file: "
                "written as the box of its scale",
                label,
                gval.loc,
                warn=True,
            )
            lowered = "box"
        up_rot = Pose(rpy=(-math.pi / 2, 0.0, 0.0)) if self.y_up else None
        if lowered in ("box", "cube"):
            return Box(size=(sx, sy, sz), src=gval.loc), None, gval.loc
        if lowered == "sphere":
            if not (sx == sy == sz):
                self.note(
                    "non-uniform-sphere",
                    f"sphere scale {list(scale)} is not uniform: radius from the largest",
                    label,
                    gval.loc,
                    warn=True,
                )
            if true_kind in POLYHEDRA:
                self._solids[obj.name] = (true_kind, max(scale) / 2.0, 0.0)
            return Sphere(radius=max(scale) / 2.0, src=gval.loc), None, gval.loc
        if lowered == "plane":
            self.note(
                "plane-as-box", "plane read as a 1 mm thick box of its x and z extents", label, gval.loc, warn=True
            )
            return Box(size=(sx, sz, 0.001), src=gval.loc), None, gval.loc
        # Cylinder-like primitives: HoloScript's scale is [diameter, height, diameter].
        if not self._cylinder_noted:
            self._cylinder_noted = True
            self.note(
                "cylinder-convention",
                "cylinder-like scale read as [diameter, height, diameter] with the height along the up axis",
                label,
                gval.loc,
            )
        if sx != sz:
            self.note(
                "elliptic-cylinder",
                f"{lowered} scale {list(scale)} has different x and z diameters; the larger is used",
                label,
                gval.loc,
                warn=True,
            )
        radius = max(sx, sz) / 2.0
        if lowered == "cone":
            self.note(
                "cone-as-cylinder",
                "URDF has no cone: written as a cylinder of the same extents; its inertia and centre of mass "
                "are the cone's (apex up, as three.js draws it)",
                label,
                gval.loc,
                warn=True,
            )
        if lowered == "cone":
            self._solids[obj.name] = ("cone", radius, sy)
        elif true_kind in RING_SOLIDS:
            tube = min(sy, radius) / 2.0
            self._solids[obj.name] = ("torus", radius - tube, tube)
        if lowered == "capsule":
            if sy < 2 * radius:
                raise self.fail(f"capsule height {sy:g} is less than its diameter {2 * radius:g}", label, gval.loc)
            return Capsule(radius=radius, length=sy - 2 * radius, src=gval.loc), up_rot, gval.loc
        return Cylinder(radius=radius, length=sy, src=gval.loc), up_rot, gval.loc

    def _scale_from_dimensions(self, obj: _Obj) -> Vec3:
        """``radius``/``height``/``length``/``size`` instead of ``scale`` (HoloScript's Isaac Lab examples)."""
        label = obj.label
        p = obj.props
        if "size" in p:
            size = p["size"]
            if isinstance(size.data, float):
                return (size.data, size.data, size.data)
            return self.vec3(size, "size", label)
        radius = self.num(p["radius"], "radius", label) if "radius" in p else None
        height = None
        for key in ("height", "length"):
            if key in p:
                height = self.num(p[key], key, label)
                break
        d = 2.0 * radius if radius is not None else (height or 1.0)
        h = height if height is not None else d
        self.note(
            "dimensions-as-scale",
            f"radius/height read as the scale [{d:g}, {h:g}, {d:g}] (diameter, height, diameter)",
            label,
            obj.block.loc,
        )
        return (d, h, d)

    def _scale(self, obj: _Obj) -> Vec3:
        label = obj.label
        if "scale" not in obj.props and any(k in obj.props for k in ("radius", "height", "length", "size")):
            return self._scale_from_dimensions(obj)
        if "scale" not in obj.props:
            if "geometry" in obj.props:
                self.note(
                    "default-scale", "no scale: the unit primitive (1 m) is used", label, obj.props["geometry"].loc
                )
            return (1.0, 1.0, 1.0)
        value = obj.props["scale"]
        if isinstance(value.data, float):
            s = value.data
            scale = (s, s, s)
        else:
            scale = self.vec3(value, "scale", label)
        if any(not c > 0 for c in scale):
            raise self.fail(f"scale must be positive, got {list(scale)}", label, value.loc)
        return scale

    def _material(self, obj: _Obj) -> str | None:
        value = obj.props.get("material")
        if value is None:
            return None
        if isinstance(value.data, str):
            return value.data
        if isinstance(value.data, dict):
            # material: { preset: "chrome", color: ..., metalness: ... }: the name, and the colour
            # when the object gives none; the rendering parameters are not part of URDF.
            for key in ("name", "preset", "type"):
                if key in value.data and isinstance(value.data[key].data, str):
                    return str(value.data[key].data)
            return None
        self.note("ignored-property", f"material {_describe(value)} ignored", obj.label, value.loc, warn=True)
        return None

    def _color(self, obj: _Obj) -> RGBA | None:
        value = obj.props.get("color")
        material = obj.props.get("material")
        if value is None and material is not None and isinstance(material.data, dict):
            value = material.data.get("color") or material.data.get("baseColor")
        if value is None:
            return None
        if isinstance(value.data, Expr):
            self.note("ignored-property", f"color {_describe(value)} ignored", obj.label, value.loc, warn=True)
            return None
        try:
            if isinstance(value.data, list):
                return parse_color([self.num(v, "color", obj.label) for v in value.data])
            return parse_color(self.string(value, "color", obj.label))
        except ColorError as exc:
            raise self.fail(str(exc), obj.label, value.loc) from None

    def _mass(self, obj: _Obj) -> tuple[float | None, Inertia | None]:
        label = obj.label
        found: list[tuple[str, float, SourceLoc]] = []
        inertia_value: Value | None = None
        if "mass" in obj.props:
            found.append(("mass", self.num(obj.props["mass"], "mass", label), obj.props["mass"].loc))
        t = obj.trait("physics")
        if t is not None:
            if "mass" in t.params:
                found.append(
                    ("@physics.mass", self.num(t.params["mass"], "@physics.mass", label), t.params["mass"].loc)
                )
            if "inertia" in t.params:
                inertia_value = t.params["inertia"]
        if "physics" in obj.props:
            ph = obj.props["physics"]
            if not isinstance(ph.data, dict):
                raise self.fail(f"physics: expected {{ mass, inertia }}, got {_describe(ph)}", label, ph.loc)
            if "mass" in ph.data:
                found.append(("physics.mass", self.num(ph.data["mass"], "physics.mass", label), ph.data["mass"].loc))
            if "inertia" in ph.data:
                if inertia_value is not None:
                    raise self.fail("inertia given twice (@physics and physics:)", label, ph.data["inertia"].loc)
                inertia_value = ph.data["inertia"]
        mass = None
        if found:
            first = found[0]
            for other in found[1:]:
                if not math.isclose(other[1], first[1], rel_tol=1e-9, abs_tol=1e-12):
                    raise self.fail(
                        f"{other[0]} {other[1]:g} contradicts {first[0]} {first[1]:g} (at {first[2]})", label, other[2]
                    )
            mass = first[1]
            if mass < 0:
                raise self.fail(f"mass must be positive, got {mass:g}", label, first[2])
        inertia = None
        if inertia_value is not None:
            if not isinstance(inertia_value.data, dict):
                raise self.fail("inertia: expected { ixx, iyy, izz, ixy, ixz, iyz }", label, inertia_value.loc)
            d = inertia_value.data
            for key in d:
                if key not in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz"):
                    raise self.fail(
                        f"inertia: unknown key {key!r}{_suggest(key, ('ixx', 'iyy', 'izz', 'ixy', 'ixz', 'iyz'))}",
                        label,
                        inertia_value.key_locs[key],
                    )
            for key in ("ixx", "iyy", "izz"):
                if key not in d:
                    raise self.fail(f"inertia needs {key}", label, inertia_value.loc)
            v = {
                k: self.num(d[k], f"inertia.{k}", label) if k in d else 0.0
                for k in ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")
            }
            inertia = Inertia(v["ixx"], v["iyy"], v["izz"], v["ixy"], v["ixz"], v["iyz"], src=inertia_value.loc)
            if mass is None:
                raise self.fail("an inertia tensor needs a mass", label, inertia_value.loc)
        return mass, inertia

    def _prop(self, obj: _Obj, kind: str) -> HoloProp:
        geom, _, geom_loc = self._geometry(obj)
        if isinstance(geom, Mesh):
            resolver = PackageResolver(explicit=dict(self.options.package_paths), input_file=self.file)
            policy = self.options.missing_mesh
            geom = resolve_mesh(
                geom,
                element=obj.label,
                loc=geom_loc,
                base_dir=os.path.dirname(os.path.abspath(self.file)),
                resolver=resolver,
                policy=MissingMesh.WARN if policy is MissingMesh.ERROR else policy,
                findings=self.findings,
            )
        mass, _ = self._mass(obj)
        return HoloProp(obj.name, kind, geom, matrix_pose(obj.world), mass, self._color(obj), obj.block.loc)

    # ---- sensors -----------------------------------------------------------------------------
    def _sensors(self, builder: RobotBuilder, obj: _Obj) -> None:
        label = obj.label
        for t in obj.traits_named("sensor"):
            p = t.params
            if "type" not in p:
                self.note(
                    "ignored-sensor",
                    "@sensor without a type (camera, depth, lidar, imu, force_torque, contact, gps) ignored",
                    label,
                    t.loc,
                    warn=True,
                )
                continue
            stype = self.string(p["type"], "@sensor.type", label)
            for key in p:
                if key not in SENSOR_PARAMS:
                    self.note("ignored-parameter", f"@sensor parameter {key!r} ignored", label, t.key_locs.get(key))
            base = self.string(p["name"], "@sensor.name", label) if "name" in p else f"{obj.name}_{stype}"
            name = base
            i = 2
            while builder_has_sensor(builder, name):
                name = f"{base}_{i}"
                i += 1
            pose = self._local_pose(p, label)
            camera = ray = None
            if stype in ("camera", "depth"):
                fov = self._angle_rad(p, "fov", label)
                camera = CameraSpec(
                    width=self._int(p, "width", label),
                    height=self._int(p, "height", label),
                    hfov=fov,
                    near=self.num(p["near"], "@sensor.near", label) if "near" in p else None,
                    far=self.num(p["far"], "@sensor.far", label) if "far" in p else None,
                    format=self.string(p["format"], "@sensor.format", label) if "format" in p else None,
                )
            elif stype in ("lidar", "ray"):
                horizontal = RayAxis(
                    samples=self._int(p, "samples", label),
                    min_angle=self._angle_rad(p, "minAngle", label),
                    max_angle=self._angle_rad(p, "maxAngle", label),
                )
                vertical = RayAxis(samples=self._int(p, "verticalSamples", label)) if "verticalSamples" in p else None
                ray = RaySpec(
                    horizontal=horizontal,
                    vertical=vertical,
                    min_range=self.num(p["minRange"], "@sensor.minRange", label) if "minRange" in p else None,
                    max_range=self.num(p["maxRange"], "@sensor.maxRange", label) if "maxRange" in p else None,
                )
            builder.sensor(
                name,
                stype,
                obj.name,
                pose=pose,
                update_rate=self.num(p["updateRate"], "@sensor.updateRate", label) if "updateRate" in p else None,
                topic=self.string(p["topic"], "@sensor.topic", label) if "topic" in p else None,
                noise=self.num(p["noise"], "@sensor.noise", label) if "noise" in p else None,
                camera=camera,
                ray=ray,
                isaac_sim_config=self.string(p["isaac_sim_config"], "@sensor.isaac_sim_config", label)
                if "isaac_sim_config" in p
                else None,
                src=t.loc,
            )
            if "frameName" in p:
                frame_name = self.string(p["frameName"], "@sensor.frameName", label)
                builder.frame(frame_name, obj.name, pose, src=p["frameName"].loc)

    def _local_pose(self, p: dict[str, Value], label: str) -> Pose | None:
        if "position" not in p and "rotation" not in p:
            return None
        xyz = self.vec3(p["position"], "@sensor.position", label) if "position" in p else (0.0, 0.0, 0.0)
        deg = self.vec3(p["rotation"], "@sensor.rotation", label) if "rotation" in p else (0.0, 0.0, 0.0)
        return Pose(xyz=xyz, rpy=(math.radians(deg[0]), math.radians(deg[1]), math.radians(deg[2])))

    def _angle_rad(self, p: dict[str, Value], key: str, label: str) -> float | None:
        if key not in p:
            return None
        value = self.num(p[key], f"@sensor.{key}", label)
        if abs(value) > 2 * math.pi:
            self.note(
                "sensor-angle-unit",
                f"@sensor.{key} = {value:g} is read in radians (as URDF and SDF sensors are) but looks like degrees",
                label,
                p[key].loc,
                warn=True,
            )
        return value

    def _int(self, p: dict[str, Value], key: str, label: str) -> int | None:
        if key not in p:
            return None
        value = self.num(p[key], f"@sensor.{key}", label)
        if value != int(value) or value < 0:
            raise self.fail(f"@sensor.{key}: expected a whole number, got {value:g}", label, p[key].loc)
        return int(value)


def builder_has_sensor(builder: RobotBuilder, name: str) -> bool:
    return name in builder._sensors


def _trait_or_prop_mass(block: Block) -> Value | None:
    for t in block.traits:
        if t.name == "physics" and "mass" in t.params:
            return t.params["mass"]
    if "mass" in block.props:
        return block.props["mass"]
    ph = block.props.get("physics")
    if ph is not None and isinstance(ph.data, dict) and "mass" in ph.data:
        return ph.data["mass"]
    return None


def _drop_template_mass(
    props: dict[str, Value], traits: list[Trait], block: Block
) -> tuple[dict[str, Value], list[Trait]]:
    """The object gives its own mass: every mass that only the template gave goes (defaults, not rivals)."""
    props = dict(props)
    if "mass" not in block.props:
        props.pop("mass", None)
    ph = props.get("physics")
    own_ph = block.props.get("physics")
    own_has = own_ph is not None and isinstance(own_ph.data, dict) and "mass" in own_ph.data
    if ph is not None and isinstance(ph.data, dict) and "mass" in ph.data and not own_has:
        data = {k: v for k, v in ph.data.items() if k != "mass"}
        props["physics"] = Value(data, ph.loc, {k: v for k, v in ph.key_locs.items() if k != "mass"})
    own_trait_mass = any(t.name == "physics" and "mass" in t.params for t in block.traits)
    out: list[Trait] = []
    for t in traits:
        if t.name == "physics" and "mass" in t.params and not own_trait_mass:
            t = Trait(t.name, {k: v for k, v in t.params.items() if k != "mass"}, t.loc, t.key_locs, t.in_header)
        out.append(t)
    return props, out


def _merge_props(base: dict[str, Value], over: dict[str, Value]) -> dict[str, Value]:
    out = dict(base)
    for key, value in over.items():
        out[key] = _merge_value(out[key], value) if key in out else value
    return out


def _merge_value(base: Value, over: Value) -> Value:
    if isinstance(base.data, dict) and isinstance(over.data, dict):
        merged = dict(base.data)
        locs = dict(base.key_locs)
        for key, value in over.data.items():
            merged[key] = _merge_value(merged[key], value) if key in merged else value
            locs[key] = over.key_locs.get(key, over.loc)
        return Value(merged, over.loc, locs)
    return over


def _merge_traits(base: list[Trait], over: list[Trait]) -> list[Trait]:
    """Template traits overridden key by key by the object's; sensors accumulate."""
    out: list[Trait] = []
    over_names = {t.name for t in over if t.name != "sensor"}
    for t in base:
        if t.name in over_names:
            mine = next(o for o in over if o.name == t.name)
            params = _merge_props(t.params, mine.params)
            out.append(Trait(t.name, params, mine.loc, {**t.key_locs, **mine.key_locs}, mine.in_header))
        else:
            out.append(t)
    done = {t.name for t in base}
    out += [t for t in over if t.name == "sensor" or t.name not in done]
    return out


def _moves(name: str, parent_of: dict[str, str], movable: set[str]) -> bool:
    """Whether a movable joint lies between the base and ``name``."""
    seen: set[str] = set()
    while name in parent_of and name not in seen:
        if name in movable:
            return True
        seen.add(name)
        name = parent_of[name]
    return False


def _looks_like_radians(lower: float, upper: float) -> bool:
    """Both limits within 2π and at least one a multiple of π/2 (±1.57, ±3.14, 6.28)."""
    if max(abs(lower), abs(upper)) > 2 * math.pi + 1e-3 or (lower == 0 and upper == 0):
        return False
    return any(v != 0 and abs(v / (math.pi / 2) - round(v / (math.pi / 2))) < 2e-3 for v in (lower, upper))


def _unique(name: str, used: set[str]) -> str:
    out, i = name, 2
    while out in used:
        out = f"{name}_{i}"
        i += 1
    return out


def _describe(value: Value) -> str:
    d = value.data
    if isinstance(d, bool):
        return f"a boolean ({str(d).lower()})"
    if isinstance(d, float):
        return f"a number ({d:g})"
    if isinstance(d, str):
        return f"a string ({d!r})"
    if isinstance(d, list):
        return f"a list of {len(d)}"
    if isinstance(d, dict):
        return "an object"
    if isinstance(d, Expr):
        return f"an expression ({d.text!r})"
    return "null"


def _suggest(name: str, known: Iterable[str]) -> str:
    close = difflib.get_close_matches(name, list(known), n=1)
    return f"; did you mean {close[0]!r}?" if close else ""
