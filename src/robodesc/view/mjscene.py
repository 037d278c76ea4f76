"""A MuJoCo model built straight from the IR with ``mujoco.MjSpec``, for pictures only.

Every visual and collider is a geom of the world body at its home-pose frame, colliding with
nothing (no bodies or joints: a picture needs positions, not dynamics). Meshes go
in as vertex and face arrays from robodesc's own readers, so no mesh file is converted and no
MJCF is written. Visuals are geom group 1, colliders group 3: the renderer picks one or the other.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from robodesc.ir.geometry import Box, Capsule, Cylinder, Geometry, Material, Mesh, Pose, Sphere
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame, link_frames, pose_frame
from robodesc.meshes.buffers import MeshReadError
from robodesc.meshes.data import MeshCache
from robodesc.view.scene import COLLIDER_RGBA, DEFAULT_RGBA, home

if TYPE_CHECKING:
    from robodesc.emit.common.world import TerrainGrid
    from robodesc.view.world import ViewWorld

VISUAL_GROUP = 1
COLLISION_GROUP = 3
FLOOR_GROUP = 0  # the clips' floor (build_posable)
WORLD_GROUP = 0  # the world's ground, drawn with either
WORLD_RGBA = (0.55, 0.6, 0.5, 1.0)
PLANE_HALF = 20.0  # m: a picture's stand-in for an infinite plane


@dataclass(slots=True)
class BuiltModel:
    model: Any  # mujoco.MjModel
    visuals: int = 0
    collisions: int = 0
    skipped: list[str] = field(default_factory=list)  # shapes left out, and why
    bodies: dict[str, int] = field(default_factory=dict)  # build_posable: link -> its mocap index


def _rgba(material: Material | None, named: dict[str, Material]) -> list[float]:
    if material is not None and material.color is None:
        material = named.get(material.name, material)
    return list(material.color) if material is not None and material.color is not None else list(DEFAULT_RGBA)


class _Builder:
    def __init__(self, mujoco: Any, size: tuple[int, int]) -> None:
        self.mj = mujoco
        self.spec = mujoco.MjSpec()
        self.spec.modelname = "robodesc_picture"
        # No inertia from geometry: a body without joints needs none, and degenerate meshes (open,
        # flat, inside out) would otherwise stop the compile on their volume.
        self.spec.compiler.inertiafromgeom = mujoco.mjtInertiaFromGeom.mjINERTIAFROMGEOM_FALSE
        self.spec.visual.global_.offwidth = max(size[0], 64)
        self.spec.visual.global_.offheight = max(size[1], 64)
        # No shadow map: the headlight casts none, and a 4096² depth buffer costs a software GL
        # context about a quarter of a second to make.
        self.spec.visual.quality.shadowsize = 0
        self.spec.visual.headlight.ambient = [0.35, 0.35, 0.35]
        self.spec.visual.headlight.diffuse = [0.65, 0.65, 0.65]
        self.spec.visual.headlight.specular = [0.1, 0.1, 0.1]
        self.spec.add_texture(
            name="sky",
            type=mujoco.mjtTexture.mjTEXTURE_SKYBOX,
            builtin=mujoco.mjtBuiltin.mjBUILTIN_GRADIENT,
            rgb1=[0.96, 0.97, 0.98],
            rgb2=[0.80, 0.82, 0.86],
            width=64,
            height=64,
        )
        self.meshes = MeshCache()
        self.mesh_names: dict[tuple[str, Any], str | None] = {}
        self.skipped: list[str] = []

    def mesh(self, geometry: Mesh) -> str | None:
        if geometry.path is None:
            self.skipped.append(f"{geometry.uri}: file not found")
            return None
        key = (geometry.path, geometry.scale)
        if key not in self.mesh_names:
            try:
                data = self.meshes.get(geometry.path, geometry.scale)
            except MeshReadError as exc:
                self.skipped.append(f"{geometry.uri}: {exc}")
                self.mesh_names[key] = None
                return None
            name = f"mesh{len(self.mesh_names)}"
            mesh = self.spec.add_mesh(name=name)
            # The readers' buffers as numpy views: MuJoCo copies them without a Python list between.
            mesh.uservert = np.frombuffer(data.points, dtype=np.float32)
            mesh.userface = np.frombuffer(data.face_vertex_indices, dtype=np.int32)
            mesh.inertia = self.mj.mjtMeshInertia.mjMESH_INERTIA_SHELL
            self.mesh_names[key] = name
        return self.mesh_names[key]

    def geom(
        self, body: Any, geometry: Geometry, origin: Pose | None, rgba: list[float], group: int, link: Frame
    ) -> bool:
        g = self.mj.mjtGeom
        frame = link @ pose_frame(origin)
        kw: dict[str, Any] = {
            "pos": list(frame.translation),
            "quat": list(frame.quat()),
            "rgba": rgba,
            "group": group,
            "contype": 0,
            "conaffinity": 0,
        }
        if isinstance(geometry, Box):
            kw.update(type=g.mjGEOM_BOX, size=[s / 2 for s in geometry.size])
        elif isinstance(geometry, Cylinder):
            kw.update(type=g.mjGEOM_CYLINDER, size=[geometry.radius, geometry.length / 2, 0])
        elif isinstance(geometry, Sphere):
            kw.update(type=g.mjGEOM_SPHERE, size=[geometry.radius, 0, 0])
        elif isinstance(geometry, Capsule):
            kw.update(type=g.mjGEOM_CAPSULE, size=[geometry.radius, geometry.length / 2, 0])
        else:
            name = self.mesh(geometry)
            if name is None:
                return False
            kw.update(type=g.mjGEOM_MESH, meshname=name)
        if any(not (s > 0) for s in kw.get("size", [1.0])[:1]):
            return False
        body.add_geom(**kw)
        return True


def build_model(
    robot: Robot, size: tuple[int, int] = (640, 480), collision: bool = False, world: ViewWorld | None = None
) -> BuiltModel:
    """The picture model of ``robot`` at its home pose (every joint at zero, or at the limit nearest
    zero; mimic joints follow), for an offscreen buffer of ``size`` (width, height): its visuals,
    or with ``collision`` (or when it has no visual that can be drawn) its colliders. Only the
    shapes drawn are built: MuJoCo's mesh processing is most of a render's time. With ``world``,
    the robot stands on its ground (one robot per copy), drawn in group :data:`WORLD_GROUP`."""
    import mujoco

    if not collision:
        built = _build(mujoco, robot, size, visual=True, world=world)
        if built.visuals:
            return built
    return _build(mujoco, robot, size, visual=False, world=world)


def build_posable(
    robot: Robot, size: tuple[int, int] = (640, 480), collision: bool = False, floor: float | None = None
) -> BuiltModel:
    """The picture model of ``robot`` with one mocap body per link (``BuiltModel.bodies``), so a
    clip poses it frame by frame (robodesc.view.video) from link frames the IR's kinematics give;
    ``floor``: the half size (m) of a checkered floor at z = 0, in :data:`FLOOR_GROUP`."""
    import mujoco

    if not collision:
        built = _build(mujoco, robot, size, visual=True, posable=True, floor=floor)
        if built.visuals:
            return built
    return _build(mujoco, robot, size, visual=False, posable=True, floor=floor)


def _build(
    mujoco: Any,
    robot: Robot,
    size: tuple[int, int],
    visual: bool,
    world: ViewWorld | None = None,
    posable: bool = False,
    floor: float | None = None,
) -> BuiltModel:
    builder = _Builder(mujoco, size)
    named = {m.name: m for m in robot.materials}
    q = {j.name: home(j) for j in robot.joints if j.mimic is None and j.type.dof == 1}
    frames = link_frames(robot, q)
    visuals = collisions = 0
    bodies: dict[str, str] = {}
    for root in world.roots if world is not None else [Frame()]:
        for link in robot.links:
            frame = frames.get(link.name)
            if frame is None:  # not reachable from a root: the verifier refused such robots already
                continue
            frame = root @ frame
            # Every geom on the world body at its home-pose frame: MuJoCo's mjSpec walks every body
            # each time a geom is added (mjCModel::MakeTreeLists), so a body per link made a
            # 50,000-link picture quadratic; the picture needs no bodies. A clip needs them, one
            # mocap body per link with its geoms in the link's frame (clips draw no world).
            body = builder.spec.worldbody
            if posable:
                body = builder.spec.worldbody.add_body(name=f"link{len(bodies)}", mocap=True)
                bodies[link.name] = body.name
                frame = Frame()
            for v in link.visuals if visual else ():
                visuals += builder.geom(body, v.geometry, v.origin, _rgba(v.material, named), VISUAL_GROUP, frame)
            for c in () if visual else link.collisions:
                collisions += builder.geom(
                    body, c.geometry, c.origin, [*COLLIDER_RGBA[:3], 1.0], COLLISION_GROUP, frame
                )
    if world is not None:
        _world(builder, world)
    if floor is not None:
        _add_floor(builder, floor)
    if posable:
        # No multisampling for clips: software GL (llvmpipe) spends most of a frame resolving it.
        builder.spec.visual.quality.offsamples = 0
    model = _compile(builder)
    mocap = {name: int(model.body_mocapid[model.body(body).id]) for name, body in bodies.items()}
    return BuiltModel(model=model, visuals=visuals, collisions=collisions, skipped=builder.skipped, bodies=mocap)


def _add_floor(builder: _Builder, half: float) -> None:
    mj = builder.mj
    builder.spec.add_texture(
        name="floor",
        type=mj.mjtTexture.mjTEXTURE_2D,
        builtin=mj.mjtBuiltin.mjBUILTIN_CHECKER,
        rgb1=[0.72, 0.74, 0.77],
        rgb2=[0.62, 0.64, 0.68],
        width=256,
        height=256,
    )
    material = builder.spec.add_material(name="floor", texrepeat=[4, 4], texuniform=True)
    material.textures[mj.mjtTextureRole.mjTEXROLE_RGB] = "floor"
    builder.spec.worldbody.add_geom(
        type=mj.mjtGeom.mjGEOM_PLANE,
        size=[half, half, 0.01],
        material="floor",
        group=FLOOR_GROUP,
        contype=0,
        conaffinity=0,
    )


def _world(builder: _Builder, world: ViewWorld) -> None:
    """The world's ground as MuJoCo draws it in scene.xml: each terrain's heightfield (a flat one a
    slab), meshes without one as meshes, primitives and planes as themselves."""
    from robodesc.ir.world import HeightImage, Plane

    mj = builder.mj
    g = mj.mjtGeom
    placed = world.placed
    body = builder.spec.worldbody
    # A checker of 0.5 m squares (scene.xml's ground): slopes and steps read in a picture by its lines.
    builder.spec.add_texture(
        name="ground", type=mj.mjtTexture.mjTEXTURE_2D, builtin=mj.mjtBuiltin.mjBUILTIN_CHECKER,
        rgb1=[0.45, 0.52, 0.42], rgb2=[0.38, 0.44, 0.36], mark=mj.mjtMark.mjMARK_EDGE, markrgb=[0.8, 0.8, 0.8],
        width=64, height=64,
    )  # fmt: skip
    material = builder.spec.add_material(name="ground", texuniform=True, texrepeat=[2.0, 2.0])
    material.textures[mj.mjtTextureRole.mjTEXROLE_RGB] = "ground"
    for static in placed.world.bodies:
        for collider in static.colliders:
            base = {"material": "ground", "group": WORLD_GROUP, "contype": 0, "conaffinity": 0}
            grid = placed.grid_of(collider)
            frame = pose_frame(static.pose) @ pose_frame(collider.origin)
            if grid is not None:
                _heightfield(builder, body, grid, base)
            elif isinstance(collider.shape, Plane):
                body.add_geom(
                    type=g.mjGEOM_PLANE, size=[PLANE_HALF, PLANE_HALF, 0.05], pos=list(frame.translation),
                    quat=list(frame.quat()), **base,
                )  # fmt: skip
            elif not isinstance(collider.shape, HeightImage) and not builder.geom(
                body, collider.shape, None, list(WORLD_RGBA), WORLD_GROUP, frame
            ):
                builder.skipped.append(f"the world's {static.name}/{collider.name}")


def _heightfield(builder: _Builder, body: Any, grid: TerrainGrid, base: dict[str, Any]) -> None:
    """The heightfield as scene.xml writes it (emit/common/world.py, ``TerrainGrid.mujoco``)."""
    from robodesc.emit.common.world import HFIELD_BASE

    g = builder.mj.mjtGeom
    field = grid.mujoco()
    width, depth = field.half
    at = {"pos": list(field.frame.translation), "quat": list(field.frame.quat()), **base}
    if field.heights is None:
        body.add_geom(type=g.mjGEOM_BOX, size=[width, depth, HFIELD_BASE / 2], **at)
        return
    rows, cols = field.heights.shape
    name = f"hfield{len(builder.spec.hfields)}"
    builder.spec.add_hfield(
        name=name, nrow=rows, ncol=cols, size=[width, depth, field.span, HFIELD_BASE],
        userdata=field.heights.ravel().astype(np.float32),
    )  # fmt: skip
    body.add_geom(type=g.mjGEOM_HFIELD, hfieldname=name, **at)


def _compile(builder: _Builder) -> Any:
    """Compile the spec; a mesh MuJoCo refuses (too few faces, all points in a plane ...) is taken
    out and the compile tried again, so one bad file does not cost the whole picture."""
    spec = builder.spec
    for _ in range(len(spec.meshes) + 1):
        try:
            return spec.compile()
        except ValueError as exc:
            text = str(exc)
            bad = next((m for m in spec.meshes if f"'{m.name}'" in text or f"{m.name}" in text.split()), None)
            if bad is None:
                raise
            builder.skipped.append(f"{bad.name}: MuJoCo refused it ({text.splitlines()[0]})")
            for geom in list(spec.geoms):
                if geom.meshname == bad.name:
                    spec.delete(geom)
            spec.delete(bad)
    return spec.compile()
