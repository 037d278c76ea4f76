"""The .usda writer spells numbers and strings exactly as usd-core's own text export does."""

from __future__ import annotations

import random
from pathlib import Path

import numpy as np
import pytest
from pxr import Sdf, Vt

from robodesc.usdfile.usda import format_double, format_float, format_float_array, quote

EDGES = [1e-5, 1e-6, 1.5e-6, 1e-7, 1.234e-7, 123456789012345.0, 1e15, 1e16, 1.5e16, 1e20, 1e21, 1e22, -0.0, 0.0]
EDGES += [0.1, 1 / 3, 100.0, 1234567.0, 12345678.0, 123456789.0, 3e38, 1e-45, 1.17549435e-38, float("nan")]
EDGES += [float("inf"), -float("inf")]


def _values() -> list[float]:
    rng = random.Random(1)
    values = list(EDGES)
    values += [rng.uniform(-1, 1) * 10 ** rng.randint(-12, 20) for _ in range(5000)]
    values += [float(np.float32(rng.uniform(-1, 1))) for _ in range(5000)]
    values += [round(rng.uniform(-1, 1), rng.randint(1, 7)) for _ in range(5000)]
    return values


def _pxr_texts(type_name: Sdf.ValueTypeName, array: object) -> list[str]:
    layer = Sdf.Layer.CreateAnonymous("x.usda")
    prim = Sdf.CreatePrimInLayer(layer, "/p")
    Sdf.AttributeSpec(prim, "a", type_name).default = array
    return layer.ExportToString().split(" a = [")[1].split("]")[0].split(", ")


def test_doubles_match_usd_core() -> None:
    values = _values()
    assert [format_double(v) for v in values] == _pxr_texts(Sdf.ValueTypeNames.DoubleArray, Vt.DoubleArray(values))


def test_floats_match_usd_core_one_by_one_and_vectorised() -> None:
    values = _values()
    expected = _pxr_texts(Sdf.ValueTypeNames.FloatArray, Vt.FloatArray(values))
    assert [format_float(v) for v in values] == expected
    with np.errstate(over="ignore"):
        as_f32 = np.array(values, dtype=np.float64).astype(np.float32)
    assert format_float_array(as_f32) == expected


@pytest.mark.parametrize(
    "text", ['a"b', "a'b", "a\"b'c", "tab\there", "uni\u00e9", 'nl\nx"y', "ctl\x01", "back\\slash"]
)
def test_strings_quote_like_usd_core(text: str) -> None:
    layer = Sdf.Layer.CreateAnonymous("x.usda")
    prim = Sdf.CreatePrimInLayer(layer, "/p")
    Sdf.AttributeSpec(prim, "s", Sdf.ValueTypeNames.String).default = text
    exported = layer.ExportToString()
    assert f"string s = {quote(text)}\n" in exported


def test_deleted_api_schemas_read_back_in_usd_core(tmp_path: Path) -> None:
    from pxr import Usd

    from robodesc.usdfile.spec import Layer
    from robodesc.usdfile.usda import usda_text

    layer = Layer()
    prim = layer.prim("/robot/base", specifier="over")
    prim.deleted_api_schemas.append("PhysicsArticulationRootAPI")
    prim.apply("PhysicsRigidBodyAPI")
    over = tmp_path / "over.usda"
    over.write_text(usda_text(layer))
    base = tmp_path / "base.usda"
    base.write_text(
        '#usda 1.0\ndef Xform "robot" {\n def Xform "base" (prepend apiSchemas = ["PhysicsArticulationRootAPI"]) {}\n}\n'
    )
    root = Sdf.Layer.CreateAnonymous(".usda")
    root.subLayerPaths = [str(over), str(base)]
    # The stronger layer's delete removes what the weaker one applied.
    assert list(Usd.Stage.Open(root).GetPrimAtPath("/robot/base").GetAppliedSchemas()) == ["PhysicsRigidBodyAPI"]
