"""Small programs the world tests run in PhysX's interpreter (ovphysx cannot live in robodesc's
environment: validation/physx_python.py). Each opens the USD named by argv[1] as written."""

from __future__ import annotations

ATTACH = """
import json, sys, numpy as np, ovphysx, ovstage
from ovphysx import PhysX
from ovphysx.samples.python_samples.schema_support import physx_schema_paths
from ovphysx.types import ObjectScope, SimObjectType
ovstage.population.register_usd_schemas([*[str(p) for p in physx_schema_paths()], str(ovphysx.newton_schema_root())])
PhysX.set_cpu_mode(True)
physx = PhysX()
stage = ovstage.Stage("test")
ovstage.population.open_usd(stage, sys.argv[1], ordinal=1, domains=ovstage.PopulationDomain.ALL)
stage.advance_write_floor(ordinal=1).wait()
physx.wait_task(physx.attach_ovstage(stage, read_ordinal=1))
physx.wait_all()
"""

DETACH = """
physx.wait_all()
physx.wait_task(physx.detach_ovstage())
stage.destroy()
physx.destroy()
"""


def positions(object_type: str, attribute: str) -> str:
    """Step argv[2] seconds at 1 ms, then print every row of ``attribute`` of ``object_type``."""
    return (
        ATTACH
        + f"""
for _ in range(int(float(sys.argv[2]) * 1000)):
    physx.step_sync(0.001)
def read():
    with physx.read_sync(SimObjectType.{object_type}, [{attribute!r}], scope=ObjectScope.ALL) as result:
        return [row for g in result.groups for t in g.tensors for row in np.atleast_2d(t.numpy()).tolist()]
rows = read()
"""
        + DETACH
        + "print(json.dumps(rows))\n"
    )


# Contact sensors: the mean net normal force of each body argv[2] names (JSON) over the last 0.25 s
# of 1.5 s (a robot standing on drives sways a little).
CONTACT = (
    ATTACH
    + """
binding = physx.create_contact_binding(sensor_patterns=json.loads(sys.argv[2]))
out = np.zeros((binding.sensor_count, 3), dtype=np.float32)
total = np.zeros((binding.sensor_count, 3))
steps, window = 1500, 250
for i in range(steps):
    physx.step(0.001)
    if i >= steps - window:
        physx.wait_all()
        binding.read_net_normal_forces(out)
        total += out
physx.wait_all()
print(json.dumps({"forces": (total / window).tolist()}))
binding.destroy()
"""
    + DETACH
)
