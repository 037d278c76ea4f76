"""Bad compositions: one precise message with file:line:column, the right error class, no traceback."""

from __future__ import annotations

from pathlib import Path

import pytest

from robodesc.cli import main
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir.diagnostics import BrokenReferenceError, ParseError, RobodescError

BAD = Path(__file__).parent / "bad"

# file -> (error class, "line:col", fragment of the message after the location)
CASES: dict[str, tuple[type[RobodescError], str, str]] = {
    "unknown_key.yaml": (
        ParseError,
        "4:40",
        "links.base.geometry.cylinder: unknown key 'lenght'; did you mean 'length'?",
    ),
    "wrong_type.yaml": (ParseError, "12:14", "joints.elbow.limits.lower: expected a number, got a string ('ninety')"),
    "dangling_parent.yaml": (
        BrokenReferenceError,
        "7:5",
        "joint 'shoulder': parent link 'basee' is not defined; did you mean 'base'?",
    ),
    "cycle.yaml": (ParseError, "8:7", "joint 'j2': joints form a cycle: b -> a -> b"),
    "duplicate_name.yaml": (ParseError, "4:3", "links: duplicate key 'base' (first at line 3)"),
    "duplicate_template_name.yaml": (ParseError, "8:13", "link 'L_foot': duplicate link name 'L_foot'"),
    "invalid_inertia.yaml": (
        ParseError,
        "6:14",
        "link 'base': invalid inertia tensor: principal moments break the triangle inequality",
    ),
    "missing_mesh.yaml": (
        BrokenReferenceError,
        "4:5",
        "link 'base': mesh file 'meshes/no_such_part.stl' does not exist",
    ),
    "bad_yaml_syntax.yaml": (ParseError, "4:1", "YAML syntax: expected ',' or '}'"),
    "unbalanced.holo": (ParseError, "1:1", "unbalanced braces: composition Bad opened here is never closed"),
    "bad_token.holo": (ParseError, "5:11", "object 'Base': mass: expected a number, got an expression ('1 %')"),
    "bad_value.holo": (ParseError, "4:22", "expected a value, found operator '#'"),
    "unterminated_string.holo": (ParseError, "3:15", "unterminated string"),
    "dangling.holo": (
        BrokenReferenceError,
        "4:51",
        "object 'Arm': @joint parent 'Basee' is not an object of this composition; did you mean 'BaseLink'?",
    ),
    "cycle.holo": (ParseError, "4:5", "joint 'A_joint': joints form a cycle: B -> A -> B"),
    "invalid_inertia.holo": (
        ParseError,
        "8:16",
        "object 'Base': invalid inertia tensor: inertia tensor is not positive",
    ),
    "missing_mesh.holo": (BrokenReferenceError, "4:15", "object 'Base': mesh file 'meshes/base_v9.stl' does not exist"),
    "wrong_type.holo": (ParseError, "3:37", "object 'Base': @physics.mass: expected a number, got a string ('heavy')"),
    # Numbers beyond the float range: one finite check for YAML and HoloScript (a 1e999 rotation
    # once reached math.sin and ended in "math domain error", exit 3).
    "infinite_rotation.holo": (
        ParseError,
        "7:19",
        "object 'Arm': rotation[1]: expected a finite number, got inf (beyond the float range, ±1.798e+308)",
    ),
    "infinite_number.yaml": (ParseError, "5:49", "links.arm.mass: expected a finite number, got '1e999'"),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_one_precise_message(name: str) -> None:
    cls, where, what = CASES[name]
    path = str(BAD / name)
    with pytest.raises(RobodescError) as info:
        load_path(path, LoadOptions(missing_mesh=MissingMesh.ERROR))  # a missing mesh is a warning by default
    assert type(info.value) is cls
    text = str(info.value)
    assert text.startswith(f"{path}:{where}: "), text
    assert what in text, text
    assert "\n" not in text


@pytest.mark.parametrize("name", ["unknown_key.yaml", "unbalanced.holo", "missing_mesh.holo", "cycle.yaml"])
def test_cli_prints_one_line_and_exits_2(name: str, tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "robot.urdf"
    # A missing mesh is a warning by default (docs/diagnostics.md); asked to, it refuses.
    code = main(["compile", str(BAD / name), "-o", str(out), "-q", "--missing-mesh", "error"])
    err = capsys.readouterr().err
    _, where, _ = CASES[name]
    assert code == 2, err
    assert "Traceback" not in err
    errors = [line for line in err.splitlines() if line.startswith("error:")]
    assert errors and f"{name}:{where}:" in errors[0], err
    assert not out.exists()


# Every place a .holo number is read: 1e999 (inf) in any of them is one ParseError naming the
# element and where, never an exception from the maths behind it.
HOLO_NUMBER = """composition "Inf" {
  environment { gravity: [0, 0, G] }
  object "Base" { @physics { type: "static" mass: 1 } geometry: "box" scale: 0.1 }
  object "Arm" {
    @joint { jointType: "revolute" connectedBody: "Base" axis: [0, AX, 1] limits: { min: LO, max: 90 } damping: DA }
    @sensor { type: "camera" fov: FOV width: 64 height: 48 }
    geometry: "cylinder" scale: [0.1, SY, 0.1] position: [0, 0, PZ] rotation: [RX, 0, 0] mass: MA color: [CR, 0, 0]
  }
  object "Ring" { geometry: "torus" size: SZ physics: { mass: 1, inertia: { ixx: IX, iyy: 1, izz: 1 } } }
}
"""
HOLO_SLOTS = ("G", "AX", "LO", "DA", "FOV", "SY", "PZ", "RX", "MA", "CR", "SZ", "IX")


@pytest.mark.parametrize("slot", HOLO_SLOTS)
@pytest.mark.parametrize("written", ["1e999", "-1e999", "0x" + "f" * 300])
def test_holo_numbers_beyond_the_float_range(slot: str, written: str) -> None:
    from robodesc.frontends.holo.lower import load_holo_text

    text = HOLO_NUMBER
    for other in sorted(HOLO_SLOTS, key=len, reverse=True):
        text = text.replace(other, written if other == slot else "-9.81" if other == "G" else "1")
    with pytest.raises(ParseError) as info:
        load_holo_text(text, "inf.holo")
    assert "expected a finite number, got" in str(info.value), str(info.value)
    assert str(info.value).startswith("inf.holo:")


@pytest.mark.parametrize("value", ["1e999", "-.inf", ".nan"])
def test_yaml_numbers_beyond_the_float_range(value: str, tmp_path: Path) -> None:
    path = tmp_path / "inf.yaml"
    path.write_text(
        "robot: inf\nlinks:\n  base: {geometry: {box: [0.1, 0.1, 0.1]}, mass: 1}\n"
        f"  arm: {{geometry: {{sphere: {{radius: {value}}}}}, mass: 1}}\n"
        "joints:\n  j: {type: fixed, parent: base, child: arm}\n"
    )
    with pytest.raises(ParseError) as info:
        load_path(str(path))
    assert str(info.value) == f"{path}:4:37: links.arm.geometry.sphere.radius: expected a finite number, got {value!r}"
