"""The Isaac Sim 6 route's composed stage: a root layer sublayering ``<robot>_physics.usda`` over the
importer's USD with its ``physx`` variant selected (``emit/isaac/composed.py``), and the source's
names carried onto the importer's prims so the scenarios find the joints.

usd-core reads every layer here; the run through the real importer and PhysX is
``tests/isaac/test_physics_layer.py``'s last tests and the tier (``tests/consumers/isaac6_layer.py``).
"""

from __future__ import annotations

from pathlib import Path

import pytest
from pxr import Sdf, Usd, UsdPhysics

import robodesc
from robodesc.emit.isaac.composed import composed_stage, write_composed_stage
from robodesc.usdfile.spec import Layer
from robodesc.usdfile.usda import usda_text
from robodesc.usdfile.usdc import usdc_bytes

# An "import" as Isaac Sim 6.2's importer lays it out: the physics inside the unselected variant.
IMPORTED = """#usda 1.0
(
    defaultPrim = "arm"
)

def Xform "arm" (
    prepend variantSets = "Physics"
)
{
    def Xform "Geometry"
    {
        def Xform "base_link"
        {
        }
    }
    variantSet "Physics" = {
        "none" {
        }
        "physx" {
            over "Geometry"
            {
                over "base_link" (
                    prepend apiSchemas = ["PhysicsRigidBodyAPI", "PhysicsMassAPI"]
                )
                {
                    float physics:mass = 2
                }
            }
        }
    }
}
"""

PHYSICS = """#usda 1.0
(
    defaultPrim = "arm"
)

over "arm"
{
    over "Geometry"
    {
        over "base_link"
        {
            float physics:mass = 3.5
        }
    }
}
"""


def test_text_is_what_usd_core_writes() -> None:
    layer = composed_stage("/arm", ["./arm_physics.usda", "./imported/arm.usda"], scene=True)
    sdf = Sdf.Layer.CreateAnonymous(".usda")
    sdf.defaultPrim = "arm"
    sdf.subLayerPaths = ["./arm_physics.usda", "./imported/arm.usda"]
    for key, value in (("metersPerUnit", 1.0), ("kilogramsPerUnit", 1.0), ("upAxis", "Z")):
        sdf.pseudoRoot.SetInfo(key, value)
    over = Sdf.CreatePrimInLayer(sdf, "/arm")
    over.specifier = Sdf.SpecifierOver
    over.variantSelections["Physics"] = "physx"
    scene = Sdf.PrimSpec(sdf.pseudoRoot, "PhysicsScene", Sdf.SpecifierDef, "PhysicsScene")
    assert scene
    assert usda_text(layer) == sdf.ExportToString()


def test_several_selections_are_sorted_as_sdf_sorts_them() -> None:
    layer = Layer()
    layer.prim("/r", specifier="over").variant_selections.update({"Physics": "physx", "Alpha": "x"})
    sdf = Sdf.Layer.CreateAnonymous(".usda")
    prim = Sdf.CreatePrimInLayer(sdf, "/r")
    prim.specifier = Sdf.SpecifierOver
    prim.variantSelections["Physics"] = "physx"
    prim.variantSelections["Alpha"] = "x"
    assert usda_text(layer) == sdf.ExportToString()


def test_crate_form_refuses_a_selection() -> None:
    with pytest.raises(ValueError, match=r"variant selections are written to \.usda only"):
        usdc_bytes(composed_stage("arm", ["a.usda"]))


def test_not_a_root_prim_is_refused() -> None:
    with pytest.raises(ValueError, match="not a root prim"):
        composed_stage("/arm/Geometry", [])


def test_the_layer_wins_and_the_variant_brings_the_importers_physics(tmp_path: Path) -> None:
    (tmp_path / "imported").mkdir()
    (tmp_path / "imported" / "arm.usda").write_text(IMPORTED)
    (tmp_path / "arm_physics.usda").write_text(PHYSICS)
    only_import = write_composed_stage(str(tmp_path / "settings.usda"), "arm", [str(tmp_path / "imported/arm.usda")])
    with_layer = write_composed_stage(
        str(tmp_path / "layer.usda"), "arm", [str(tmp_path / "arm_physics.usda"), str(tmp_path / "imported/arm.usda")]
    )
    # Paths relative to the root layer: the three files move together.
    assert Sdf.Layer.FindOrOpen(with_layer).subLayerPaths == ["./arm_physics.usda", "./imported/arm.usda"]
    for path, mass in ((only_import, 2.0), (with_layer, 3.5)):
        stage = Usd.Stage.Open(path)
        base = stage.GetPrimAtPath("/arm/Geometry/base_link")
        # Without the selection the importer's asset has no rigid body at all.
        assert base.HasAPI(UsdPhysics.RigidBodyAPI)
        assert base.GetAttribute("physics:mass").Get() == pytest.approx(mass)
    imported = Usd.Stage.Open(str(tmp_path / "imported" / "arm.usda"))
    assert not imported.GetPrimAtPath("/arm/Geometry/base_link").HasAPI(UsdPhysics.RigidBodyAPI)


SPIRIT_LIKE = """<robot name="leg">
  <link name="body"><inertial><mass value="2"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="8"><inertial><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="0" type="revolute"><parent link="body"/><child link="8"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="10" velocity="5"/></joint>
</robot>
"""


def test_the_source_names_ride_on_the_importers_prims(tmp_path: Path) -> None:
    # Spirit's joints are 0..11 (a0..a11 in the Isaac URDF, the names the importer uses): the
    # scenarios look joints up by the source's names, which only displayName then carries.
    source = tmp_path / "leg.urdf"
    source.write_text(SPIRIT_LIKE)
    result = robodesc.compile_for_isaac_sim(str(source), tmp_path / "isaac", validate=False)
    layer = Sdf.Layer.FindOrOpen(result.files["physics_layer"])
    joint = layer.GetPrimAtPath("/leg/Physics/a0")
    link = layer.GetPrimAtPath("/leg/Geometry/body/a8")
    assert joint.GetInfo("displayName") == "0"
    assert link.GetInfo("displayName") == "8"
    # A name the importer kept needs none.
    assert not layer.GetPrimAtPath("/leg/Geometry/body").HasInfo("displayName")


def test_instanceable_is_written_as_usd_core_writes_it() -> None:
    layer = Layer()
    prim = layer.prim("/r/c", specifier="over")
    prim.instanceable = False
    prim.display_name = "c"
    prim.kind = "component"
    sdf = Sdf.Layer.CreateAnonymous(".usda")
    spec = Sdf.CreatePrimInLayer(sdf, "/r/c")
    spec.specifier = Sdf.SpecifierOver
    spec.instanceable = False
    spec.SetInfo("displayName", "c")
    spec.kind = "component"
    assert usda_text(layer) == sdf.ExportToString()
    with pytest.raises(ValueError, match=r"instanceable is written to \.usda only"):
        usdc_bytes(layer)
