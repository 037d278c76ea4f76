"""What PhysX parsed from a USD, read back in PhysX's own interpreter (never imported by robodesc).

ovphysx lives in its own environment (:mod:`robodesc.validation.physx_python` says why), so
robodesc starts this file there and speaks JSON: one request on standard input ``{"usd": path}``,
one answer on standard output::

    {"ovphysx": version,
     "articulations": [{"path", "dofs", "links", "joints", "fixed_base"}],
     "bodies": {prim path: {"kind": "link" | "rigid", "mass", "inertia": 9 floats (COM frame),
                            "com": 3 floats (body frame), "com_orientation": xyzw}},
     "joints": {prim path: [{"stiffness", "damping", "limit": [lo, hi], "max_velocity", "max_force",
                             "armature", "static_friction", "dynamic_friction", "viscous_friction",
                             "drive_type"}, ... one per unlocked axis]}}

or ``{"error": message}``. The stage goes through ovstage (with the PhysX and Newton schemas
registered, as Isaac Sim registers them) into ovphysx on CPU exactly as written; the values are
what PhysX holds after parsing (no step is needed: properties are readable once attached). Angular
quantities are PhysX's: limits in degrees, gains and rate coefficients per degree, max velocity in
deg/s (readable.md, "Articulation joints"); robodesc converts on its side.
"""
# mypy: ignore-errors

from __future__ import annotations

import contextlib
import json
import math
import sys
import traceback

_BODY = ("mass", "inertia", "centerOfMassPosition", "centerOfMassOrientation")
_DOF = {
    "jointStiffness": "stiffness",
    "jointDamping": "damping",
    "jointLimit": "limit",
    "jointMaxVelocity": "max_velocity",
    "jointMaxForce": "max_force",
    "jointArmature": "armature",
    "jointStaticFriction": "static_friction",
    "jointDynamicFriction": "dynamic_friction",
    "jointViscousFriction": "viscous_friction",
    "jointDriveType": "drive_type",
}
_ARTICULATION = {"dofCount": "dofs", "linkCount": "links", "jointCount": "joints", "isFixedBase": "fixed_base"}


def _number(x):
    """JSON has no infinity: PhysX's FLT_MAX ("unbounded") and inf travel as None."""
    x = float(x)
    return None if not math.isfinite(x) or abs(x) >= 3.0e38 else x


def _attach(physx, usd):
    import ovphysx
    import ovstage
    from ovphysx.samples.python_samples.schema_support import physx_schema_paths

    roots = [str(p) for p in physx_schema_paths()]
    with contextlib.suppress(FileNotFoundError):  # newton-usd-schemas is optional
        roots.append(str(ovphysx.newton_schema_root()))
    ovstage.population.register_usd_schemas(roots)
    stage = ovstage.Stage("robodesc-physx-read")
    ovstage.population.open_usd(stage, usd, ordinal=1, domains=ovstage.PopulationDomain.ALL)
    stage.advance_write_floor(ordinal=1).wait()
    physx.wait_task(physx.attach_ovstage(stage, read_ordinal=1))
    return stage


def _read(physx, kind, names):
    """{attribute: {prim path: value rows}} for every group the read returns."""
    from ovphysx.types import ObjectScope

    out = {}
    with physx.read_sync(kind, list(names), scope=ObjectScope.ALL) as result:
        words = result.dictionary
        for group in result.groups:
            if group.is_delete or not group.tensors:
                continue
            name = words.token_to_string(group.attribute)
            paths = words.get_path_strings(group.prim_list)
            column = out.setdefault(name, {})
            if group.is_array:  # one tensor per prim (joints: one row per unlocked axis)
                for path, tensor in zip(paths, group.tensors, strict=False):
                    column[str(path)] = tensor.numpy().copy().tolist()
            else:  # one tensor, one row per prim
                rows = group.tensors[0].numpy().copy().tolist()
                for path, row in zip(paths, rows, strict=False):
                    column[str(path)] = row
    return out


def _flat(v):
    return [_number(x) for x in (v if isinstance(v, list) else [v])]


def read(usd):
    import ovphysx
    from ovphysx.types import SimObjectType

    ovphysx.set_global_config(ovphysx.GlobalConfigKey.CPU_ONLY, True)
    physx = ovphysx.PhysX()
    stage = _attach(physx, usd)
    try:
        answer = {"ovphysx": str(ovphysx.__version__), "articulations": [], "bodies": {}, "joints": {}}
        arts = _read(physx, SimObjectType.ARTICULATION, _ARTICULATION)
        for path in sorted(next(iter(arts.values()), {})):
            row = {"path": path}
            for attr, key in _ARTICULATION.items():
                row[key] = int(_flat(arts.get(attr, {}).get(path, [0]))[0] or 0)
            answer["articulations"].append(row)
        for kind, label in ((SimObjectType.ARTICULATION_LINK, "link"), (SimObjectType.RIGID_BODY, "rigid")):
            got = _read(physx, kind, _BODY)
            for path in got.get("mass", {}):
                answer["bodies"][path] = {
                    "kind": label,
                    "mass": _flat(got["mass"][path])[0],
                    "inertia": _flat(got.get("inertia", {}).get(path, [])),
                    "com": _flat(got.get("centerOfMassPosition", {}).get(path, [])),
                    "com_orientation": _flat(got.get("centerOfMassOrientation", {}).get(path, [])),
                }
        dofs = _read(physx, SimObjectType.ARTICULATION_JOINT, _DOF)
        paths = sorted({p for column in dofs.values() for p in column})
        for path in paths:
            axes = []
            count = len(dofs.get("jointLimit", {}).get(path, []))
            for k in range(count):
                axis = {}
                for attr, key in _DOF.items():
                    rows = dofs.get(attr, {}).get(path)
                    if rows is None or k >= len(rows):
                        axis[key] = None
                        continue
                    value = _flat(rows[k])
                    axis[key] = value if key == "limit" else value[0]
                axes.append(axis)
            answer["joints"][path] = axes
        return answer
    finally:
        physx.wait_task(physx.detach_ovstage())
        stage.destroy()
        physx.destroy()


def main():
    try:
        request = json.loads(sys.stdin.read())
        answer = read(request["usd"])
    except Exception as exc:  # the message travels to robodesc, which names the file
        traceback.print_exc(file=sys.stderr)
        answer = {"error": f"{type(exc).__name__}: {str(exc).strip()[:500]}"}
    sys.stdout.write(json.dumps(answer) + "\n")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
