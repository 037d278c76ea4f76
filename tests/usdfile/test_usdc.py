"""The crate writer (:mod:`robodesc.usdfile.usdc`) read back by usd-core.

Every file written here is opened with ``Sdf.Layer.FindOrOpen`` (or ``Usd.Stage.Open``) and checked
through pxr's API: values bit-exact after the float32/float64 cast the type implies, metadata, list
ops, children and property order. The same layer written as usda and imported by pxr must read
back identically, and the list and numpy spellings of an array must give identical bytes.
"""

from __future__ import annotations

import math
import struct
import subprocess
import sys
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from pxr import Gf, Sdf, Usd, UsdGeom, UsdPhysics

from robodesc.usdfile.spec import VALUE_TYPES, AssetPath, Attribute, Layer, Payload, ValueType, value_type
from robodesc.usdfile.usda import usda_text
from robodesc.usdfile.usdc import usdc_bytes
from robodesc.usdfile.usdc_encoding import encode_ints, fast_compress

SRC = Path(__file__).resolve().parents[2] / "src"
DTYPES = {"bool": np.bool_, "int": np.int32, "uint": np.uint32, "float": np.float32, "double": np.float64}

SCALARS: dict[str, Any] = {
    "bool": True,
    "int": -123456,
    "uint": 4_000_000_000,  # past int32: PhysX's timeStepsPerSecond is a uint
    "float": 0.1,
    "double": 0.1,  # not exact as a float: written out of line
    "string": 'a "quoted"\nstring, é',
    "token": "vertex",
    "asset": AssetPath("./meshes/base.usdc"),
    "float2": (0.25, -1e-3),
    "float3": (0.1, -2.0, 3e20),
    "double3": (0.1, -2.0, 1e300),
    "point3f": (1.0, 2.0, 3.0),  # small integers: inlined in the ValueRep
    "normal3f": (0.0, -0.0, 1.0),  # -0.0 must keep its sign, so this one is not inlined
    "vector3f": (-128, 127, 5),  # the int8 limits, still inlined
    "color3f": (0.5, 0.25, 1.0),
    "texCoord2f": (0.5, 128.0),  # 128 is past int8: out of line
    "quatf": (0.5, 0.1, 0.2, 0.3),  # (w, x, y, z)
    "quatd": (math.sqrt(0.5), 0.0, math.sqrt(0.5), -0.0),
}

ARRAYS: dict[str, list[Any]] = {
    "bool": [True, False, True],
    "int": [0, -1, 2**31 - 1, -(2**31), 17] * 4,
    "uint": [0, 1, 2**32 - 1, 17] * 5,
    "float": [0.1, -0.0, math.inf, math.nan, 1e-40, 3.4e38, 1.0],
    "double": [0.1, -0.0, -math.inf, math.nan, 5e-324, 1.7e308, 1.0],
    "string": ["", "a", 'b "c"', "a"],
    "token": ["x", "y", "x"],
    "asset": [AssetPath("./a.png"), AssetPath("b/c.usd"), AssetPath("")],
}
for _name, _vtype in VALUE_TYPES.items():
    if _vtype.width > 1:
        ARRAYS[_name] = [SCALARS[_name], tuple(float(i) - 0.5 for i in range(_vtype.width)), SCALARS[_name]]


def write(tmp_path: Path, layer: Layer, name: str = "layer.usdc") -> Path:
    path = tmp_path / name
    path.write_bytes(usdc_bytes(layer))
    return path


def open_layer(tmp_path: Path, layer: Layer, name: str = "layer.usdc") -> Sdf.Layer:
    opened = Sdf.Layer.FindOrOpen(str(write(tmp_path, layer, name)))
    assert opened is not None
    return opened


def expected(vtype: ValueType, value: Any) -> Any:
    """What pxr must read back: text as str, numbers as numpy of the element type (quats w first)."""
    if vtype.scalar in ("string", "token", "asset"):
        return [str(v) for v in value] if isinstance(value, list) else str(value)
    return np.asarray(value, dtype=DTYPES[vtype.scalar])


def read_back(vtype: ValueType, is_array: bool, value: Any) -> Any:
    """pxr's value in the form of :func:`expected`."""
    if vtype.scalar == "asset":
        return [a.path for a in value] if is_array else value.path
    if vtype.scalar in ("string", "token"):
        return [str(v) for v in value] if is_array else str(value)
    dtype = DTYPES[vtype.scalar]
    if vtype.role == "Quat":
        if is_array:
            return np.asarray(value, dtype=dtype)[:, [3, 0, 1, 2]]  # memory order is x, y, z, w
        return np.asarray([value.GetReal(), *value.GetImaginary()], dtype=dtype)
    return np.asarray(list(value) if vtype.width > 1 and not is_array else value, dtype=dtype)


def assert_same(got: Any, want: Any) -> None:
    if isinstance(want, np.ndarray):
        assert got.dtype == want.dtype and got.shape == want.shape
        assert got.tobytes() == want.tobytes(), (got, want)  # bit-exact: NaN, -0.0, subnormals
    else:
        assert got == want


def typed_layer(form: str) -> Layer:
    """One attribute per type, scalar and array, arrays as lists or as numpy arrays."""
    layer = Layer()
    prim = layer.prim("/Values", "Scope")
    for name, vtype in VALUE_TYPES.items():
        prim.attr(f"s_{name}", name, SCALARS[name])
        items = ARRAYS[name]
        if form == "numpy" and vtype.scalar not in ("string", "token", "asset"):
            prim.attr(f"a_{name}", name + "[]", np.asarray(items, dtype=DTYPES[vtype.scalar]))
        elif form == "numpy":
            prim.attr(f"a_{name}", name + "[]", np.asarray([str(v) for v in items]))
        else:
            prim.attr(f"a_{name}", name + "[]", list(items))
        prim.attr(f"e_{name}", name + "[]", [])
    return layer


@pytest.mark.parametrize("form", ["list", "numpy"])
def test_every_value_type_reads_back_exactly(tmp_path: Path, form: str) -> None:
    sdf = open_layer(tmp_path, typed_layer(form))
    for name, vtype in VALUE_TYPES.items():
        for prefix, type_name, value in (
            ("s", name, SCALARS[name]),
            ("a", name + "[]", ARRAYS[name]),
            ("e", name + "[]", []),
        ):
            spec = sdf.GetAttributeAtPath(f"/Values.{prefix}_{name}")
            assert spec.typeName == Sdf.ValueTypeNames.Find(type_name), type_name
            got = read_back(vtype, prefix != "s", spec.default)
            want = expected(vtype, value)
            if prefix == "e" and isinstance(want, np.ndarray):
                want = want.reshape((0, vtype.width) if vtype.width > 1 else (0,))
            assert_same(got, want)


def test_list_and_numpy_arrays_write_identical_bytes() -> None:
    assert usdc_bytes(typed_layer("list")) == usdc_bytes(typed_layer("numpy"))


def test_numpy_arrays_of_other_dtypes_are_cast() -> None:
    def layer_with(points: Any, indices: Any, quats: Any) -> Layer:
        layer = Layer()
        prim = layer.prim("/Mesh", "Mesh")
        prim.attr("points", "point3f[]", points)
        prim.attr("faceVertexIndices", "int[]", indices)
        prim.attr("orientations", "quatf[]", quats)
        return layer

    points = [(0.1, 0.2, 0.3), (1e-3, 2.5, -7.0)]
    indices = [0, 1, 2, 2, 1, 0]
    quats = [(1.0, 0.0, 0.0, 0.0), (0.5, 0.5, 0.5, 0.5)]
    as_lists = usdc_bytes(layer_with(points, indices, quats))
    as_numpy = usdc_bytes(
        layer_with(np.asarray(points), np.asarray(indices, dtype=np.int64), np.asarray(quats, dtype=np.float64))
    )
    assert as_lists == as_numpy


def full_layer() -> Layer:
    """Every kind of metadata and spec the model holds."""
    layer = Layer(
        default_prim="Robot",
        meters_per_unit=0.01,
        kilograms_per_unit=1.0,
        up_axis="Z",
        sublayers=["./Robot_physics.usda", "./Robot_sensor.usdc"],
    )
    robot = layer.prim("/Robot", "Xform")
    robot.kind = "component"
    robot.asset_name = "Robot"
    robot.display_name = "My Robot (v2)"
    robot.apply("PhysicsArticulationRootAPI")
    robot.apply("NewtonArticulationRootAPI")
    robot.payloads = [Payload("./Robot_geometry.usdc", "/Geometry"), Payload("./other.usdc", "")]
    # Property order is authoring order, deliberately not alphabetical.
    robot.attr("zeta", "float", 1.5, custom=True)
    robot.rel("physics:filteredPairs", ["/Robot/base", "/Robot/arm/hand"], custom=True)
    robot.attr("alpha", "token[]", ["a", "b"], uniform=True)
    robot.rel("empty", [])
    base = layer.prim("/Robot/base", "Xform")
    base.apply("PhysicsRigidBodyAPI")
    base.attr("xformOp:translate", "double3", (0.0, 0.0, 0.5))
    base.attr("xformOpOrder", "token[]", ["xformOp:translate"], uniform=True)
    mesh = layer.prim("/Robot/base/visual", "Mesh")
    mesh.attr("primvars:st", "texCoord2f[]", [(0.0, 0.0), (1.0, 0.5)], interpolation="faceVarying")
    mesh.attr("primvars:displayColor", "color3f[]", [(0.8, 0.1, 0.1)], interpolation="constant")
    layer.prim("/Robot/arm/hand", "Xform")  # arm: an over created on the way
    layer.prim("/Robot/Looks", "Scope")
    material = layer.prim("/Robot/Looks/red", "Material")
    material.connect("outputs:surface", "token", "/Robot/Looks/red/shader.outputs:surface")
    shader = layer.prim("/Robot/Looks/red/shader", "Shader")
    shader.attr("info:id", "token", "UsdPreviewSurface", uniform=True)
    shader.attr("inputs:diffuseColor", "color3f", (0.8, 0.1, 0.1))
    shader.attr("outputs:surface", "token", None)
    layer.prim("/Robot/ClassDef", specifier="class")
    layer.prim("/Elsewhere", "Scope", specifier="over")
    return layer


def test_metadata_and_structure_read_back(tmp_path: Path) -> None:
    sdf = open_layer(tmp_path, full_layer())
    assert sdf.defaultPrim == "Robot"
    assert sdf.pseudoRoot.GetInfo("metersPerUnit") == 0.01
    assert sdf.pseudoRoot.GetInfo("kilogramsPerUnit") == 1.0
    assert sdf.pseudoRoot.GetInfo("upAxis") == "Z"
    assert list(sdf.subLayerPaths) == ["./Robot_physics.usda", "./Robot_sensor.usdc"]
    assert [(o.offset, o.scale) for o in sdf.subLayerOffsets] == [(0.0, 1.0), (0.0, 1.0)]
    assert list(sdf.rootPrims.keys()) == ["Robot", "Elsewhere"]

    robot = sdf.GetPrimAtPath("/Robot")
    assert robot.specifier == Sdf.SpecifierDef and robot.typeName == "Xform"
    assert robot.kind == "component"
    assert dict(robot.assetInfo) == {"name": "Robot"}
    assert robot.GetInfo("displayName") == "My Robot (v2)"
    schemas = robot.GetInfo("apiSchemas")
    assert not schemas.isExplicit
    assert list(schemas.prependedItems) == ["PhysicsArticulationRootAPI", "NewtonArticulationRootAPI"]
    assert not schemas.explicitItems and not schemas.appendedItems
    payloads = robot.payloadList
    assert not payloads.isExplicit
    assert [(p.assetPath, p.primPath) for p in payloads.prependedItems] == [
        ("./Robot_geometry.usdc", Sdf.Path("/Geometry")),
        ("./other.usdc", Sdf.Path()),
    ]
    assert all(p.layerOffset == Sdf.LayerOffset() for p in payloads.prependedItems)
    assert list(robot.nameChildren.keys()) == ["base", "arm", "Looks", "ClassDef"]
    assert list(robot.properties.keys()) == ["zeta", "physics:filteredPairs", "alpha", "empty"]

    zeta = sdf.GetAttributeAtPath("/Robot.zeta")
    assert zeta.custom and zeta.variability == Sdf.VariabilityVarying and zeta.default == 1.5
    alpha = sdf.GetAttributeAtPath("/Robot.alpha")
    assert not alpha.custom and alpha.variability == Sdf.VariabilityUniform
    pairs = sdf.GetRelationshipAtPath("/Robot.physics:filteredPairs")
    assert pairs.custom and pairs.targetPathList.isExplicit
    assert list(pairs.targetPathList.explicitItems) == ["/Robot/base", "/Robot/arm/hand"]
    empty = sdf.GetRelationshipAtPath("/Robot.empty")
    assert not empty.custom and empty.targetPathList.isExplicit and not empty.targetPathList.explicitItems

    assert sdf.GetPrimAtPath("/Robot/arm").specifier == Sdf.SpecifierOver
    assert sdf.GetPrimAtPath("/Robot/arm").typeName == ""
    assert sdf.GetPrimAtPath("/Robot/ClassDef").specifier == Sdf.SpecifierClass
    assert sdf.GetPrimAtPath("/Elsewhere").specifier == Sdf.SpecifierOver
    st = sdf.GetAttributeAtPath("/Robot/base/visual.primvars:st")
    assert st.GetInfo("interpolation") == "faceVarying"
    surface = sdf.GetAttributeAtPath("/Robot/Looks/red.outputs:surface")
    assert not surface.HasDefaultValue()
    assert surface.connectionPathList.isExplicit
    assert list(surface.connectionPathList.explicitItems) == ["/Robot/Looks/red/shader.outputs:surface"]
    assert not sdf.GetAttributeAtPath("/Robot/Looks/red/shader.outputs:surface").HasDefaultValue()
    head = (tmp_path / "layer.usdc").read_bytes()[:16]
    assert head == b"PXR-USDC" + bytes((0, 8, 0, 0, 0, 0, 0, 0))  # crate 0.8.0


def _specs(layer: Sdf.Layer) -> dict[str, Any]:
    """Each spec's type, info values and children, property children as a set (usda sorts them)."""
    out: dict[str, Any] = {}

    def visit(path: Sdf.Path) -> None:
        spec = layer.GetObjectAtPath(path)
        if spec is None:  # relationship / connection target paths, not specs of their own
            return
        info = {}
        for key in spec.ListInfoKeys():
            if key == "subLayerOffsets":  # no Python converter for the vector
                info[key] = [(o.offset, o.scale) for o in layer.subLayerOffsets]
            else:
                value = spec.GetInfo(key)
                info[key] = str(value) if "ListOp" in type(value).__name__ else value
        entry: dict[str, Any] = {"type": type(spec).__name__, "info": info}
        if isinstance(spec, Sdf.PrimSpec):
            entry["children"] = list(spec.nameChildren.keys())
            entry["properties"] = set(spec.properties.keys())
        out[str(path)] = entry

    layer.Traverse(Sdf.Path.absoluteRootPath, visit)
    return out


def test_reads_back_like_the_usda_form(tmp_path: Path) -> None:
    layer = full_layer()
    values = typed_layer("list").root.children["Values"]
    for attr in values.properties.values():  # NaN never compares equal: leave it to the bit-exact test
        if isinstance(attr, Attribute) and attr.type_name in ("float[]", "double[]"):
            attr.value = [v for v in attr.value if v == v]
    layer.root.children["Values"] = values
    crate = open_layer(tmp_path, layer)
    text = Sdf.Layer.CreateAnonymous(".usda")
    assert text.ImportFromString(usda_text(layer))
    mine, reference = _specs(crate), _specs(text)
    assert mine.keys() == reference.keys()
    for path, entry in reference.items():
        # The text parser marks every property's custom field; crate, like Sdf, only writes true.
        want = {k: v for k, v in entry["info"].items() if not (k == "custom" and v is False)}
        got = {k: v for k, v in mine[path]["info"].items() if not (k == "custom" and v is False)}
        assert got == want, path
        assert mine[path].keys() == entry.keys()
        for key in ("type", "children", "properties"):
            assert mine[path].get(key) == entry.get(key), (path, key)


def test_empty_layer(tmp_path: Path) -> None:
    sdf = open_layer(tmp_path, Layer())
    assert not sdf.rootPrims
    assert not sdf.pseudoRoot.ListInfoKeys()
    assert Usd.Stage.Open(sdf) is not None


def test_million_point_array(tmp_path: Path) -> None:
    rng = np.random.default_rng(7)
    points = rng.standard_normal((1_000_000, 3)).astype(np.float32)
    layer = Layer()
    layer.prim("/Mesh", "Mesh").attr("points", "point3f[]", points)
    sdf = open_layer(tmp_path, layer)
    got = np.asarray(sdf.GetAttributeAtPath("/Mesh.points").default)
    assert got.dtype == np.float32 and got.tobytes() == points.tobytes()


def test_deterministic() -> None:
    assert usdc_bytes(full_layer()) == usdc_bytes(full_layer())
    layer = full_layer()
    assert usdc_bytes(layer) == usdc_bytes(layer)


def test_identical_values_are_stored_once() -> None:
    points = np.arange(3000, dtype=np.float32).reshape(1000, 3)
    one, two = Layer(), Layer()
    one.prim("/A", "Mesh").attr("points", "point3f[]", points)
    for name in ("A", "B"):
        two.prim(f"/{name}", "Mesh").attr("points", "point3f[]", points)
    assert len(usdc_bytes(two)) - len(usdc_bytes(one)) < 200


def robot_files(tmp_path: Path) -> Path:
    """A layered asset: a main layer with a physics sublayer and a geometry payload, all crate."""
    geometry = Layer(default_prim="Geometry", meters_per_unit=1.0, up_axis="Z")
    mesh = geometry.prim("/Geometry/box", "Mesh")
    mesh.attr("points", "point3f[]", np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float32))
    mesh.attr("faceVertexCounts", "int[]", np.array([4], dtype=np.int32))
    mesh.attr("faceVertexIndices", "int[]", np.arange(4, dtype=np.int32))
    mesh.attr("normals", "normal3f[]", [(0.0, 0.0, 1.0)] * 4, interpolation="vertex")
    write(tmp_path, geometry, "robot_geometry.usdc")

    physics = Layer(meters_per_unit=1.0, kilograms_per_unit=1.0, up_axis="Z")
    robot = physics.prim("/robot", specifier="over")
    robot.apply("PhysicsArticulationRootAPI")
    for link, z in (("base", 0.0), ("arm", 0.5)):
        body = physics.prim(f"/robot/{link}", specifier="over")
        body.apply("PhysicsRigidBodyAPI")
        body.apply("PhysicsMassAPI")
        body.attr("physics:mass", "float", 2.0 if link == "base" else 0.5)
        body.attr("physics:centerOfMass", "point3f", (0.0, 0.0, z / 2))
        collider = physics.prim(f"/robot/{link}/collision", specifier="over")
        collider.apply("PhysicsCollisionAPI")
    joint = physics.prim("/robot/joints/shoulder", "PhysicsRevoluteJoint")
    joint.rel("physics:body0", ["/robot/base"])
    joint.rel("physics:body1", ["/robot/arm"])
    joint.attr("physics:axis", "token", "Y", uniform=True)
    joint.attr("physics:localPos0", "point3f", (0.0, 0.0, 0.5))
    joint.attr("physics:localRot0", "quatf", (1.0, 0.0, 0.0, 0.0))
    joint.attr("physics:localPos1", "point3f", (0.0, 0.0, 0.0))
    joint.attr("physics:localRot1", "quatf", (1.0, 0.0, 0.0, 0.0))
    joint.attr("physics:lowerLimit", "float", -90.0)
    joint.attr("physics:upperLimit", "float", 90.0)
    physics.prim("/physicsScene", "PhysicsScene").attr("physics:gravityMagnitude", "float", 9.81)
    write(tmp_path, physics, "robot_physics.usdc")

    main = Layer(default_prim="robot", meters_per_unit=1.0, kilograms_per_unit=1.0, up_axis="Z")
    main.sublayers.append("./robot_physics.usdc")
    robot = main.prim("/robot", "Xform")
    robot.kind = "component"
    for link, z in (("base", 0.0), ("arm", 0.5)):
        xform = main.prim(f"/robot/{link}", "Xform")
        xform.attr("xformOp:translate", "double3", (0.0, 0.0, z))
        xform.attr("xformOp:orient", "quatf", (math.sqrt(0.5), 0.0, 0.0, math.sqrt(0.5)))
        xform.attr("xformOpOrder", "token[]", ["xformOp:translate", "xformOp:orient"], uniform=True)
        cube = main.prim(f"/robot/{link}/collision", "Cube")
        cube.attr("size", "double", 0.1)
        visual = main.prim(f"/robot/{link}/visual", "Xform")
        visual.payloads.append(Payload("./robot_geometry.usdc", ""))
    main.prim("/robot/joints", "Scope")
    return write(tmp_path, main, "robot.usdc")


def test_composed_stage_with_physics(tmp_path: Path) -> None:
    stage = Usd.Stage.Open(str(robot_files(tmp_path)))
    assert stage is not None
    assert stage.GetDefaultPrim().GetPath() == "/robot"
    assert UsdGeom.GetStageUpAxis(stage) == "Z"
    assert UsdGeom.GetStageMetersPerUnit(stage) == 1.0
    box = stage.GetPrimAtPath("/robot/arm/visual/box")  # through the payload's defaultPrim
    assert box.IsValid() and box.GetTypeName() == "Mesh"
    assert len(UsdGeom.Mesh(box).GetPointsAttr().Get()) == 4
    arm = stage.GetPrimAtPath("/robot/arm")
    assert arm.HasAPI(UsdPhysics.RigidBodyAPI)  # from the sublayer's over
    world = UsdGeom.Xformable(arm).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
    assert world.ExtractTranslation() == Gf.Vec3d(0, 0, 0.5)
    assert Gf.IsClose(world.ExtractRotation().GetAxis(), Gf.Vec3d(0, 0, 1), 1e-6)
    assert [str(p.GetPath()) for p in stage.Traverse()][:3] == ["/robot", "/robot/base", "/robot/base/collision"]

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        parsed = UsdPhysics.LoadUsdPhysicsFromRange(stage, ["/"])
    found = {
        str(kind): {str(p): d for p, d in zip(paths, descs, strict=True)} for kind, (paths, descs) in parsed.items()
    }
    assert set(found["RigidBody"]) == {"/robot/base", "/robot/arm"}
    assert set(found["Articulation"]) == {"/robot"}
    joint = found["RevoluteJoint"]["/robot/joints/shoulder"]
    assert (str(joint.body0), str(joint.body1)) == ("/robot/base", "/robot/arm")
    assert (joint.limit.lower, joint.limit.upper) == (-90.0, 90.0)
    assert set(found["Scene"]) == {"/physicsScene"}


BAD_VALUES = [
    ("float3", (1.0, 2.0), "2 components"),
    ("float3", 1.0, "3-tuple"),
    ("int", 2**31, "<= 2147483647"),
    ("int", 1.5, "integer"),
    ("float", "1.0", "not a float"),
    ("float", 1e39, "float"),
    ("double", None, None),  # no default: fine
    ("bool", "yes", "not a bool"),
    ("string", 3, "not a string"),
    ("token", "a\0b", "NUL"),
    ("quatf", (1.0, 0.0, 0.0), "3 components"),
    ("float[]", [1.0, 1e39], "float32"),
    ("float[]", "abc", "not an array"),
    ("int[]", [1, 2.5], "integer"),
    ("int[]", np.array([2**40]), "int32"),
    ("int[]", np.array([1.5]), "dtype"),
    ("float3[]", [(1.0, 2.0, 3.0), (1.0, 2.0)], "element 1"),
    ("float3[]", np.zeros((3, 2)), "shape"),
    ("float[]", np.array([1e39]), "float32"),
    ("bool[]", [True, 1], "bool"),
    ("token[]", ["a", 1], "not a string"),
    ("half", 1.0, "unknown type name"),
]


@pytest.mark.parametrize(("type_name", "value", "message"), BAD_VALUES)
def test_values_that_do_not_fit_name_the_property(type_name: str, value: Any, message: str | None) -> None:
    layer = Layer()
    prim = layer.prim("/Robot/link", "Xform")
    prim.properties["attr"] = Attribute("attr", type_name, value)
    if message is None:
        usdc_bytes(layer)
        return
    with pytest.raises(ValueError, match=r"^/Robot/link\.attr \(") as info:
        usdc_bytes(layer)
    assert message in str(info.value)


@pytest.mark.parametrize(
    ("build", "match"),
    [
        (lambda layer: layer.prim("/Robot", "Xform").connect("c", "token", "Robot.x"), r"/Robot\.c .*absolute"),
        (lambda layer: layer.prim("/Robot", "Xform").rel("r", ["/Robot/a b"]), r"/Robot\.r .*absolute"),
        (lambda layer: layer.prim("/Robot", "Xform").children.update(x=Layer().prim("/a.b")), r"/Robot/a\.b:"),
        (lambda layer: setattr(layer.prim("/Robot"), "specifier", "define"), "specifier"),
        (lambda layer: setattr(layer, "meters_per_unit", "1"), "layer metadata"),
    ],
)
def test_bad_names_and_metadata(build: Any, match: str) -> None:
    layer = Layer()
    build(layer)
    with pytest.raises(ValueError, match=match):
        usdc_bytes(layer)


def test_many_prims_and_tokens(tmp_path: Path) -> None:
    """Enough names that the structural sections need 16- and 32-bit integer codes."""
    layer = Layer()
    root = layer.prim("/Wide", "Scope")
    for i in range(20_000):
        root.child(f"p{i}", "Xform").attr(f"a{i}", "int", i)
    sdf = open_layer(tmp_path, layer)
    names = list(sdf.GetPrimAtPath("/Wide").nameChildren.keys())
    assert names == [f"p{i}" for i in range(20_000)]
    assert sdf.GetAttributeAtPath("/Wide/p19999.a19999").default == 19999


def _decode_ints(data: bytes, count: int) -> list[int]:
    """A reference decoder written from integerCoding.cpp's description."""
    common = struct.unpack_from("<i", data)[0]
    pos = 4 + (count * 2 + 7) // 8
    out, value = [], 0
    for i in range(count):
        code = (data[4 + i // 4] >> (2 * (i % 4))) & 3
        if code == 0:
            delta = common
        else:
            fmt = {1: "<b", 2: "<h", 3: "<i"}[code]
            delta = struct.unpack_from(fmt, data, pos)[0]
            pos += struct.calcsize(fmt)
        value = (value + delta + 2**31) % 2**32 - 2**31
        out.append(value)
    assert pos == len(data)
    return out


@pytest.mark.parametrize(
    "values",
    [[], [0], [-1], [5, 5, 5, 5, 5], [1, 2, 3, 100, 40000, -40000, 2**31 - 1, -(2**31), 0], list(range(0, 3000, 7))],
)
def test_integer_coding(values: list[int]) -> None:
    encoded = encode_ints(values)
    if values:
        assert _decode_ints(encoded, len(values)) == values
    else:
        assert encoded == b""  # compresses to the 2-byte empty block usd-core writes too


def test_literal_lz4_framing() -> None:
    # What usd-core writes for the field sets of an empty layer: [~0].
    assert fast_compress(encode_ints([0xFFFFFFFF])) == bytes.fromhex("0050ffffffff00")
    for size in (14, 15, 16, 269, 270, 271, 1000):
        framed = fast_compress(bytes(size))
        # chunk count, token 0xF0 at 15+, extension bytes summing to size - 15, the literals
        assert framed[0] == 0 and len(framed) == size + 2 + (0 if size < 15 else (size - 15) // 255 + 1)


def test_module_imports_neither_pxr_nor_numpy() -> None:
    # Load the writer without robodesc's package __init__, which pulls in the whole compiler.
    code = f"""
import sys, types
package = types.ModuleType("robodesc")
package.__path__ = [{str(SRC / "robodesc")!r}]
sys.modules["robodesc"] = package
from robodesc.usdfile.spec import Layer, AssetPath, Payload
from robodesc.usdfile.usdc import usdc_bytes
layer = Layer(default_prim="r", sublayers=["./a.usda"])
prim = layer.prim("/r", "Mesh")
prim.payloads.append(Payload("./g.usdc", ""))
prim.attr("points", "point3f[]", [(0.0, 1.0, 2.0)])
prim.attr("orient", "quatf[]", [(1.0, 0.0, 0.0, 0.0)])
prim.attr("tex", "asset", AssetPath("./t.png"))
usdc_bytes(layer)
print(sorted(m for m in sys.modules if m.split(".")[0] in ("pxr", "numpy")))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_value_type_table_is_covered() -> None:
    for name in VALUE_TYPES:
        assert value_type(name + "[]")[1]
        assert name in SCALARS and name in ARRAYS
