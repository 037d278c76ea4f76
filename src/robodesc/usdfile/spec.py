"""An in-memory USD layer (prims, properties, the metadata robodesc writes), serialised by
:mod:`robodesc.usdfile.usda` as text and :mod:`robodesc.usdfile.usdc` as a binary crate file.

Why not usd-core: importing ``pxr`` costs 0.2-0.3 s, more than converting a whole small robot, and
the CLI pays it on every run. The layer model below is the small part of Sdf that an asset writer
needs; usd-core stays the reference the tests compare both serialisations against.

Values are plain Python, chosen by the attribute's ``type_name`` (see :data:`VALUE_TYPES`):

- ``bool``, ``int``, ``float``, ``double``: Python ``bool`` / ``int`` / ``float``;
- ``string``, ``token``: ``str``; ``asset``: :class:`AssetPath`;
- vectors and colours (``float3``, ``double3``, ``point3f``, ``color3f``, ``texCoord2f`` ...): a
  tuple of floats; quaternions (``quatf``, ``quatd``): ``(w, x, y, z)``;
- arrays (``...[]``): a sequence of the scalar form, a numpy array of shape ``(n,)`` or
  ``(n, k)`` (numpy stays optional: nothing here imports it), or an ``array.array`` holding the
  scalars flat, element after element, of the attribute's C type (``"f"`` for float-based types,
  ``"d"`` for double-based, ``"i"`` for int), which the .usdc writer copies as it is.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any


class AssetPath(str):
    """The value of an ``asset`` attribute (written ``@path@``)."""

    __slots__ = ()


@dataclass(slots=True, frozen=True)
class ValueType:
    scalar: str  # bool | int | float | double | half | string | token | asset
    width: int  # 1 for scalars, 2-4 for vectors and quaternions
    role: str  # "" | "Point" | "Normal" | "Vector" | "Color" | "TextureCoordinate" | "Quat"


def _vec(scalar: str, width: int, role: str = "") -> ValueType:
    return ValueType(scalar, width, role)


# The scalar (non-array) type names robodesc writes; every one also exists as ``name[]``.
VALUE_TYPES: dict[str, ValueType] = {
    "bool": _vec("bool", 1),
    "int": _vec("int", 1),
    "uint": _vec("uint", 1),
    "float": _vec("float", 1),
    "double": _vec("double", 1),
    "string": _vec("string", 1),
    "token": _vec("token", 1),
    "asset": _vec("asset", 1),
    "float2": _vec("float", 2),
    "float3": _vec("float", 3),
    "double3": _vec("double", 3),
    "point3f": _vec("float", 3, "Point"),
    "normal3f": _vec("float", 3, "Normal"),
    "vector3f": _vec("float", 3, "Vector"),
    "color3f": _vec("float", 3, "Color"),
    "texCoord2f": _vec("float", 2, "TextureCoordinate"),
    "quatf": _vec("float", 4, "Quat"),
    "quatd": _vec("double", 4, "Quat"),
}


def value_type(type_name: str) -> tuple[ValueType, bool]:
    """(element type, is array) of an attribute type name; KeyError for names robodesc does not write."""
    if type_name.endswith("[]"):
        return VALUE_TYPES[type_name[:-2]], True
    return VALUE_TYPES[type_name], False


@dataclass(slots=True)
class Attribute:
    name: str
    type_name: str
    value: Any = None  # None: declared without a default (an output that only connects)
    custom: bool = False
    uniform: bool = False
    interpolation: str | None = None  # primvar interpolation metadata
    connections: list[str] = field(default_factory=list)  # explicit connectionPaths (property paths)


@dataclass(slots=True)
class Relationship:
    name: str
    targets: list[str] = field(default_factory=list)  # explicit targetPaths
    custom: bool = False


Property = Attribute | Relationship


@dataclass(slots=True, frozen=True)
class Payload:
    asset_path: str
    prim_path: str  # "" = the target layer's defaultPrim


@dataclass(slots=True)
class Prim:
    name: str
    specifier: str = "def"  # def | over | class
    type_name: str = ""
    api_schemas: list[str] = field(default_factory=list)  # written as a prepended list op
    kind: str | None = None
    asset_name: str | None = None  # assetInfo = {string name = ...}
    display_name: str | None = None
    payloads: list[Payload] = field(default_factory=list)  # written as a prepended list op
    properties: dict[str, Property] = field(default_factory=dict)
    children: dict[str, Prim] = field(default_factory=dict)
    # Written as a deleted list op (.usda only): a layer over another asset removes an API schema
    # that asset applied (the Isaac physics layer moves the articulation root).
    deleted_api_schemas: list[str] = field(default_factory=list)
    # Variant set name -> the selected variant (.usda only): a root layer over an imported asset
    # selects the importer's ``Physics = "physx"``, which the importer leaves unselected.
    variant_selections: dict[str, str] = field(default_factory=dict)
    # ``instanceable`` metadata (.usda only); None writes none. A layer over an imported asset sets
    # it false to edit what the asset put inside an instance (Isaac Sim 6's mesh colliders).
    instanceable: bool | None = None

    def child(self, name: str, type_name: str = "", specifier: str = "def") -> Prim:
        """The named child, created (with this type and specifier) if it is not there yet."""
        found = self.children.get(name)
        if found is None:
            found = Prim(name, specifier, type_name)
            self.children[name] = found
        return found

    def apply(self, schema: str) -> None:
        if schema not in self.api_schemas:
            self.api_schemas.append(schema)

    def attr(
        self,
        name: str,
        type_name: str,
        value: Any,
        *,
        custom: bool = False,
        uniform: bool = False,
        interpolation: str | None = None,
    ) -> Attribute:
        value_type(type_name)  # refuse type names the writers do not know, here rather than at write time
        attribute = Attribute(name, type_name, value, custom, uniform, interpolation)
        self.properties[name] = attribute
        return attribute

    def connect(self, name: str, type_name: str, source: str) -> Attribute:
        """An attribute without a value whose only opinion is a connection to ``source``."""
        attribute = self.attr(name, type_name, None)
        attribute.connections = [source]
        return attribute

    def rel(self, name: str, targets: Sequence[str], *, custom: bool = False) -> Relationship:
        relationship = Relationship(name, list(targets), custom)
        self.properties[name] = relationship
        return relationship


@dataclass(slots=True)
class Layer:
    default_prim: str | None = None
    meters_per_unit: float | None = None
    kilograms_per_unit: float | None = None
    up_axis: str | None = None
    sublayers: list[str] = field(default_factory=list)
    root: Prim = field(default_factory=lambda: Prim(""))

    def prim(self, path: str, type_name: str = "", specifier: str = "def") -> Prim:
        """The prim at an absolute path; missing ancestors are created as ``over``s (as Sdf does)."""
        if not path.startswith("/") or path == "/":
            raise ValueError(f"not an absolute prim path: {path!r}")
        node = self.root
        names = path[1:].split("/")
        for name in names[:-1]:
            node = node.child(name, specifier="over")
        return node.child(names[-1], type_name, specifier)

    def find(self, path: str) -> Prim | None:
        node: Prim | None = self.root
        for name in path[1:].split("/"):
            if node is None:
                return None
            node = node.children.get(name)
        return node
