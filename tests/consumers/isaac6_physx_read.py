"""Run in PhysX's interpreter (``robodesc.validation.physx_python``): open each USD stage given and
write, as one JSON document, what PhysX (ovphysx) parsed for its articulation: per link (by prim
name) mass, inertia and its shapes' friction, per joint (by prim name) drive gains, limits, effort and velocity bounds,
armature and friction, and the articulation's counts.

    python isaac6_physx_read.py STAGES.json OUT.json
    STAGES.json: ["a.usda", ...]   OUT.json: {"stages": [{"links": {...}, "joints": {...}, ...}]}

Angular quantities are as PhysX reads USD: degrees (limits, velocities), per degree (gains).
"""

from __future__ import annotations

import json
import sys
from typing import Any

JOINT = (
    "jointStiffness",
    "jointDamping",
    "jointLimit",
    "jointMaxVelocity",
    "jointMaxForce",
    "jointArmature",
    "jointStaticFriction",
    "jointDynamicFriction",
    "jointViscousFriction",
)
LINK = ("mass", "inertia", "staticFriction", "dynamicFriction")
ARTICULATION = ("dofCount", "linkCount", "isFixedBase")


def main() -> None:
    import numpy as np
    import ovphysx  # type: ignore[import-not-found]
    import ovstage  # type: ignore[import-not-found]
    from ovphysx import PhysX
    from ovphysx.samples.python_samples.schema_support import (  # type: ignore[import-not-found]
        physx_schema_paths,
    )
    from ovphysx.types import ObjectScope, SimObjectType  # type: ignore[import-not-found]

    with open(sys.argv[1], encoding="utf-8") as fh:
        stages = json.load(fh)
    ovstage.population.register_usd_schemas(
        [*[str(p) for p in physx_schema_paths()], str(ovphysx.newton_schema_root())]
    )
    physx = PhysX()

    def read(kind: Any, attrs: tuple[str, ...]) -> dict[str, dict[str, list[float]]]:
        """prim leaf name -> attribute -> values (one row per axis, flattened)."""
        out: dict[str, dict[str, list[float]]] = {}
        for attr in attrs:
            with physx.read_sync(kind, [attr], scope=ObjectScope.ALL) as result:
                for group in result.groups:
                    if group.is_delete:
                        continue
                    paths = result.dictionary.get_path_strings(group.prim_list)
                    tensors = list(group.tensors)
                    if len(tensors) == len(paths):  # array group: one tensor per prim
                        rows = [np.asarray(t.numpy(), dtype=float).ravel() for t in tensors]
                    else:  # fixed group: row i of the one tensor is prim i
                        data = np.asarray(tensors[0].numpy(), dtype=float)
                        rows = [data[i].ravel() for i in range(len(paths))]
                    for path, row in zip(paths, rows, strict=True):
                        out.setdefault(str(path).rsplit("/", 1)[-1], {})[attr] = [float(v) for v in row]
        return out

    results: list[dict[str, Any]] = []
    for ordinal, path in enumerate(stages, start=1):
        stage = ovstage.Stage(f"stage{ordinal}")
        ovstage.population.open_usd(stage, path, ordinal=ordinal, domains=ovstage.PopulationDomain.ALL)
        stage.advance_write_floor(ordinal=ordinal).wait()
        physx.wait_task(physx.attach_ovstage(stage, read_ordinal=ordinal))
        try:
            results.append(
                {
                    "usd": path,
                    "links": read(SimObjectType.ARTICULATION_LINK, LINK),
                    "joints": read(SimObjectType.ARTICULATION_JOINT, JOINT),
                    "articulations": read(SimObjectType.ARTICULATION, ARTICULATION),
                }
            )
        finally:
            physx.wait_task(physx.detach_ovstage())
            stage.destroy()
    physx.destroy()
    with open(sys.argv[2], "w", encoding="utf-8") as fh:
        json.dump({"stages": results}, fh)


if __name__ == "__main__":
    main()
