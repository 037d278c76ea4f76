"""What the modules reading one MJCF share: the compiled model, the tree it came from, the robot
being built, and where each compiled element was written (``file:line`` for every message)."""

from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from lxml import etree

from robodesc.frontends.mjcf.source import STAGE, MjcfSource, tag
from robodesc.frontends.options import LoadOptions
from robodesc.ir.diagnostics import Findings, SourceLoc
from robodesc.ir.model import Robot
from robodesc.ir.rigid import Frame

if TYPE_CHECKING:
    import mujoco

# Compiled element kinds whose ids follow the body tree, and the tags that make them.
_IN_BODY = {"joint": ("joint", "freejoint"), "geom": ("geom",), "site": ("site",), "camera": ("camera",)}


@dataclass
class Reading:
    model: mujoco.MjModel
    source: MjcfSource
    options: LoadOptions
    findings: Findings
    robot: Robot
    # Compiled id -> element, per kind ("body", "joint", "geom", "site", "camera", ...).
    elements: dict[str, dict[int, etree._Element]] = field(default_factory=dict)
    # Per body id: the IR link holding what the body holds, and the map from body to link coordinates.
    link_of: dict[int, str] = field(default_factory=dict)
    content: dict[int, Frame] = field(default_factory=dict)
    # Compiled joint id -> IR joint name (free joints of the root have none).
    joint_of: dict[int, str] = field(default_factory=dict)
    link_names: set[str] = field(default_factory=set)
    # Bodies left out (a scene's objects, with their subtrees): what they hold is left out with them.
    dropped: set[int] = field(default_factory=set)
    joint_names: set[str] = field(default_factory=set)

    def name(self, kind: str, index: int) -> str | None:
        import mujoco

        obj = getattr(mujoco.mjtObj, f"mjOBJ_{kind.upper()}")
        return mujoco.mj_id2name(self.model, obj, index) or None

    def loc(self, kind: str, index: int) -> SourceLoc:
        el = self.elements.get(kind, {}).get(index)
        if el is None and kind in ("joint", "geom", "site", "camera"):
            body = int(
                getattr(self.model, f"{'jnt' if kind == 'joint' else 'cam' if kind == 'camera' else kind}_bodyid")[
                    index
                ]
            )
            el = self.elements.get("body", {}).get(body)
        return self.source.loc(el) if el is not None else SourceLoc(self.source.file)

    def unique(self, wanted: str, taken: set[str]) -> str:
        name, n = wanted, 1
        while name in taken:
            n += 1
            name = f"{wanted}_{n}"
        taken.add(name)
        return name

    def warn(self, code: str, message: str, element: str, loc: SourceLoc | None) -> None:
        self.findings.warn(code, message, element=element, loc=loc, stage=STAGE)

    def info(self, code: str, message: str, element: str, loc: SourceLoc | None) -> None:
        self.findings.info(code, message, element=element, loc=loc, stage=STAGE)


def locate(model: mujoco.MjModel, source: MjcfSource) -> dict[str, dict[int, etree._Element]]:
    """Match compiled ids to elements: bodies in the tree's depth-first order (MuJoCo's numbering),
    and each body's joints, geoms, sites and cameras in the order written. Where the counts differ
    (``<replicate>``, ``<attach>``), elements are matched by name only."""
    import mujoco

    out: dict[str, dict[int, etree._Element]] = defaultdict(dict)
    bodies: list[etree._Element] = []
    owned: dict[int, dict[str, list[etree._Element]]] = {}

    def walk(el: etree._Element, owner: int) -> None:
        for child in el:
            name = tag(child)
            if name == "body":
                bodies.append(child)
                index = len(bodies)
                owned[index] = defaultdict(list)
                walk(child, index)
            elif name == "frame":
                walk(child, owner)
            else:
                for kind, tags in _IN_BODY.items():
                    if name in tags and owner in owned:
                        owned[owner][kind].append(child)

    worlds = list(source.root.iter("worldbody"))
    owned[0] = defaultdict(list)
    for world in worlds:
        walk(world, 0)
    if len(bodies) == model.nbody - 1:
        for i, el in enumerate(bodies, start=1):
            out["body"][i] = el
        counts = {"joint": model.body_jntnum, "geom": model.body_geomnum}
        starts = {"joint": model.body_jntadr, "geom": model.body_geomadr}
        for b, kinds in owned.items():
            for kind in ("joint", "geom"):
                els = kinds.get(kind, [])
                if len(els) == int(counts[kind][b]) and els:
                    for k, el in enumerate(els):
                        out[kind][int(starts[kind][b]) + k] = el
        for kind, body_of in (("site", model.site_bodyid), ("camera", model.cam_bodyid)):
            for b, kinds in owned.items():
                ids = [i for i in range(len(body_of)) if int(body_of[i]) == b]
                els = kinds.get(kind, [])
                if len(ids) == len(els):
                    out[kind].update(zip(ids, els, strict=True))
    # By name, for everything the order did not place (and the model's other sections).
    for kind, tags, obj in (
        ("body", ("body",), mujoco.mjtObj.mjOBJ_BODY),
        ("joint", ("joint", "freejoint"), mujoco.mjtObj.mjOBJ_JOINT),
        ("geom", ("geom",), mujoco.mjtObj.mjOBJ_GEOM),
        ("site", ("site",), mujoco.mjtObj.mjOBJ_SITE),
        ("camera", ("camera",), mujoco.mjtObj.mjOBJ_CAMERA),
        ("tendon", ("fixed", "spatial"), mujoco.mjtObj.mjOBJ_TENDON),
        ("equality", ("connect", "weld", "joint", "tendon", "flex", "distance"), mujoco.mjtObj.mjOBJ_EQUALITY),
        ("key", ("key",), mujoco.mjtObj.mjOBJ_KEY),
    ):
        named = {el.get("name"): el for t in tags for el in source.root.iter(t) if el.get("name")}
        for name, el in named.items():
            index = mujoco.mj_name2id(model, obj, name)
            if index >= 0:
                out[kind].setdefault(index, el)
    actuators = [el for section in source.root.iter("actuator") for el in section if isinstance(el.tag, str)]
    if len(actuators) == model.nu:
        out["actuator"] = dict(enumerate(actuators))
    sensors = [el for section in source.root.iter("sensor") for el in section if isinstance(el.tag, str)]
    if len(sensors) == model.nsensor:
        out["sensor"] = dict(enumerate(sensors))
    equalities = [el for section in source.root.iter("equality") for el in section if isinstance(el.tag, str)]
    if len(equalities) == model.neq:
        out["equality"] = dict(enumerate(equalities))
    return dict(out)
