"""SDF's frame semantics (libsdformat's pose graph, as Drake applies it), resolved to one frame.

Every link, joint, ``<frame>`` and nested model is a frame; each ``<pose>`` is relative to the frame
its ``relative_to`` names, or by default: a link's to its model's frame, a joint's to its child link,
a frame's to what it is ``attached_to`` (itself defaulting to the model's frame), a nested model's
to its parent's frame. Names resolve in the scope they are written in (``arm::hand`` reaches into a
nested model; ``__model__`` is the scope's own model frame). :class:`Frames` gives each frame's pose
in the frame of the model read, and the link each frame is attached to.

SDF 1.4 to 1.6 have no ``relative_to``: their defaults are the same, and a 1.5/1.6 ``frame=``
attribute (never applied by Gazebo) is a warning.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from lxml import etree

from robodesc.frontends.sdf.source import STAGE, Scope, Source
from robodesc.frontends.sdf.values import loc, pose_value, tag
from robodesc.ir.diagnostics import Findings, ParseError
from robodesc.ir.transforms import Mat, pose_matrix

WORLD = "world"


@dataclass(slots=True)
class Node:
    name: str  # scoped
    kind: str  # "model", "link", "joint", "frame"
    element: etree._Element
    scope: Scope  # the scope the element is written in (a nested model's is its parent's)
    file: str
    pose: etree._Element | None


@dataclass
class Frames:
    source: Source
    findings: Findings
    nodes: dict[str, Node] = field(default_factory=dict)
    _poses: dict[str, Mat] = field(default_factory=dict)
    _visiting: set[str] = field(default_factory=set)

    @classmethod
    def build(cls, source: Source, findings: Findings) -> Frames:
        frames = cls(source, findings)
        for scope in source.scopes():
            if scope.parent is not None:
                frames._add(Node(scope.name, "model", scope.element, scope.parent, scope.pose_file, scope.pose))
            for child in scope.element:
                kind = tag(child)
                if kind not in ("link", "joint", "frame"):
                    continue
                name = child.get("name") or ""
                if not name:
                    raise ParseError(f"a <{kind}> needs a name", loc=loc(scope.file, child))
                frames._add(Node(scope.scoped(name), kind, child, scope, scope.file, child.find("pose")))
        return frames

    def _add(self, node: Node) -> None:
        if node.name in self.nodes:
            raise ParseError(
                f"the name {node.name!r} is used twice in one model (links, joints, frames and models share one "
                "namespace in SDF)",
                loc=loc(node.file, node.element),
            )
        self.nodes[node.name] = node

    def resolve(self, name: str, scope: Scope, element: etree._Element, what: str) -> str:
        """The scoped frame ``name`` refers to, written in ``scope``."""
        text = name.strip()
        if text == "__model__":
            return scope.frame
        if text == WORLD:
            return WORLD
        if text.startswith("__model__::"):
            text = text[len("__model__::") :]
        scoped = scope.scoped(text)
        if scoped in self.nodes:
            return scoped
        raise ParseError(f"{what} {name!r} names no frame of model {scope.frame!r}", loc=loc(scope.file, element))

    def in_model(self, name: str) -> Mat:
        """The pose of frame ``name`` in the model's frame."""
        if name == "__model__":
            return np.eye(4)
        if name in self._poses:
            return self._poses[name]
        node = self.nodes[name]
        if name in self._visiting:
            raise ParseError(f"the poses of {name!r} form a cycle", loc=loc(node.file, node.element))
        self._visiting.add(name)
        try:
            pose = self.relative_to(node.pose, node.scope, node.file, self.default_base(node))
            self._poses[name] = pose
        finally:
            self._visiting.discard(name)
        return pose

    def relative_to(self, pose: etree._Element | None, scope: Scope, file: str, default: str) -> Mat:
        """A ``<pose>`` in ``scope`` resolved to the model's frame; ``default`` is its frame when it names none."""
        base = default
        if pose is not None:
            named = pose.get("relative_to")
            if named:
                base = self.resolve(named, scope, pose, "pose relative_to")
            if pose.get("frame"):
                self.findings.warn(
                    "sdf-pose-frame",
                    f"frame={pose.get('frame')!r} (SDF 1.5/1.6) is not applied, as Gazebo never applied it; the pose "
                    "is read in its default frame",
                    element="pose",
                    loc=loc(file, pose),
                    stage=STAGE,
                )
        if base == WORLD and pose is not None:
            raise ParseError("a pose inside a model cannot be relative to the world", loc=loc(file, pose))
        return self.in_model(base) @ pose_matrix(pose_value(file, pose))

    def default_base(self, node: Node) -> str:
        scope = node.scope
        if node.kind == "joint":
            child = node.element.findtext("child")
            if child is None:
                raise ParseError("a <joint> needs a <child>", loc=loc(node.file, node.element))
            return self.resolve(child, scope, node.element, "joint child")
        if node.kind == "frame":
            attached = node.element.get("attached_to")
            return self.resolve(attached, scope, node.element, "frame attached_to") if attached else scope.frame
        return scope.frame

    def link_of(self, name: str) -> str:
        """The link frame ``name`` is attached to (a model's canonical link)."""
        seen: set[str] = set()
        while True:
            if name in seen:
                node = self.nodes[name]
                raise ParseError(f"frame {name!r} is attached to itself", loc=loc(node.file, node.element))
            seen.add(name)
            if name == "__model__":
                return self.canonical(self.source.top)
            node = self.nodes[name]
            if node.kind == "link":
                return name
            if node.kind == "model":
                return self.canonical(next(s for s in self.source.scopes() if s.name == name))
            name = self.default_base(node)
            if name == WORLD:
                raise ParseError(
                    "a frame attached to the world is not part of the robot", loc=loc(node.file, node.element)
                )

    def canonical(self, scope: Scope) -> str:
        named = scope.element.get("canonical_link")
        if named:
            return self.resolve(named, scope, scope.element, "canonical_link")
        for child in scope.element:
            if tag(child) == "link":
                return scope.scoped(child.get("name") or "")
        for nested in scope.children:
            return self.canonical(nested)
        raise ParseError(f"model {scope.frame!r} has no link", loc=loc(scope.file, scope.element))
