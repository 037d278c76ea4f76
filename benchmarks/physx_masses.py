"""Run in PhysX's interpreter (``robodesc.validation.physx_python``): the mass ovphysx gives each
body of each USD file named on standard input (one per line), as JSON into the file named by
the first argument (PhysX prints to standard output):
``{path: {prim: kg}}`` or ``{path: "error: ..."}``. Used by ``usd_masses.py``."""

# mypy: ignore-errors
# (runs in its consumer's own interpreter, whose packages the project env does not have)

from __future__ import annotations

import json
import sys


def masses(physx, ovstage, path: str) -> dict[str, float]:  # type: ignore[no-untyped-def]
    from ovphysx.types import ObjectScope, SimObjectType

    stage = ovstage.Stage("masses")
    try:
        ovstage.population.open_usd(stage, path, ordinal=1, domains=ovstage.PopulationDomain.ALL)
        stage.advance_write_floor(ordinal=1).wait()
        physx.wait_task(physx.attach_ovstage(stage, read_ordinal=1))
        out: dict[str, float] = {}
        names = ovstage.PathDictionary(stage)
        for kind in (SimObjectType.ARTICULATION_LINK, SimObjectType.RIGID_BODY):
            with physx.read_sync(kind, ["mass"], scope=ObjectScope.ALL) as result:
                for group in result.groups:
                    prims = names.get_path_strings(group.prim_list)
                    values = group.tensors[0].numpy().reshape(-1)
                    for prim, value in zip(prims, values, strict=True):
                        out[str(prim)] = float(value)
        physx.wait_all()
        physx.wait_task(physx.detach_ovstage())
        return out
    finally:
        stage.destroy()


def main() -> None:
    import ovphysx
    import ovstage
    from ovphysx import PhysX
    from ovphysx.samples.python_samples.schema_support import physx_schema_paths

    PhysX.set_cpu_mode(True)
    ovstage.population.register_usd_schemas(
        [*[str(p) for p in physx_schema_paths()], str(ovphysx.newton_schema_root())]
    )
    physx = PhysX()
    report: dict[str, object] = {}
    for line in sys.stdin:
        path = line.strip()
        if not path:
            continue
        try:
            report[path] = masses(physx, ovstage, path)
        except Exception as exc:  # one bad file must not lose the others' numbers
            report[path] = f"error: {exc}"
    physx.wait_all()
    with open(sys.argv[1], "w", encoding="utf-8") as f:
        json.dump(report, f)


if __name__ == "__main__":
    main()
