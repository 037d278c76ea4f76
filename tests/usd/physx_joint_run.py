"""Run in PhysX's interpreter (``robodesc.validation.physx_python``): step each USD stage given and
write, as one JSON document (a file: Warp prints its banner on standard output), what PhysX parsed for its articulation joints and their motion.

    python physx_joint_run.py CASES.json OUT.json
    OUT.json: {"cases": [{"parsed": {...}, "t": [...], "q": [...], "qd": [...]}]}

CASES.json: ``[{"usd": PATH, "dt": seconds, "steps": N}, ...]``. ``q``/``qd`` are the first DOF's
position and velocity after each step, in PhysX's stage units (degrees and deg/s for a revolute
joint). The PhysX and Newton schemas register before the first stage populates, as ovphysx asks.
"""

from __future__ import annotations

import json
import sys
from typing import Any

PARSED = (
    "jointArmature",
    "jointMaxVelocity",
    "jointStaticFriction",
    "jointDynamicFriction",
    "jointViscousFriction",
    "jointMaxForce",
    "jointMaxActuatorVelocity",
    "jointVelocityDependentResistance",
)


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
        cases = json.load(fh)
    ovstage.population.register_usd_schemas(
        [*[str(p) for p in physx_schema_paths()], str(ovphysx.newton_schema_root())]
    )
    physx = PhysX()
    joint = SimObjectType.ARTICULATION_JOINT

    def read(attr: str) -> list[float]:
        out = []
        with physx.read_sync(joint, [attr], scope=ObjectScope.ALL) as result:
            for group in result.groups:
                # One tensor per joint of the group.
                if not group.is_delete:
                    out += [np.asarray(t.numpy(), dtype=float).ravel().copy() for t in group.tensors]
        return [float(v) for v in np.concatenate(out)] if out else []

    results: list[dict[str, Any]] = []
    for ordinal, case in enumerate(cases, start=1):
        stage = ovstage.Stage(f"case{ordinal}")
        ovstage.population.open_usd(stage, case["usd"], ordinal=ordinal, domains=ovstage.PopulationDomain.ALL)
        stage.advance_write_floor(ordinal=ordinal).wait()
        physx.wait_task(physx.attach_ovstage(stage, read_ordinal=ordinal))
        try:
            parsed = {name: read(name) for name in PARSED}
            t, q, qd = [], [], []
            for step in range(1, int(case["steps"]) + 1):
                physx.step_sync(float(case["dt"]))
                t.append(step * float(case["dt"]))
                q.append(read("jointPosition")[0])
                qd.append(read("jointVelocity")[0])
            results.append({"parsed": parsed, "t": t, "q": q, "qd": qd})
        finally:
            physx.wait_task(physx.detach_ovstage())
            stage.destroy()
    physx.destroy()
    with open(sys.argv[2], "w", encoding="utf-8") as fh:
        json.dump({"cases": results}, fh)


if __name__ == "__main__":
    main()
