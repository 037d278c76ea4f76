"""Actuators: what a joint's motor can give (the IR's effort limit) and how it is driven.

MuJoCo's ``position``, ``velocity``, ``motor`` and ``<general>`` are one thing compiled: a gain and
a bias, ``force = gain·ctrl + bias0 + bias1·length + bias2·velocity``, times ``gear`` at the joint.
Read from the compiled model, a ``<general>`` with ``biasprm="0 -kp -kv"`` is the position servo it
is (menagerie's Panda).

- Effort: ``forcerange`` times ``|gear|`` where the actuator limits its force; else, for a motor,
  its control range times gain and gear; else the joint's ``actuatorfrcrange``. The largest
  magnitude, as the IR's limit is symmetric.
- A gear other than 1 is a simple transmission's mechanical reduction (the MJCF emitter writes it
  back as ``gear``); the actuator's kind is its hardware interface.
- The servo itself is the joint's ``drive``: its kind (position, velocity, effort for a motor) and
  its gains in joint space (``kp·gear²``). Targets write those gains where the user gives none
  (emit/common/source_drives.py).
- Actuators on tendons, sites or bodies (a Cartesian actuator, adhesion) have no IR form: warnings.
"""

from __future__ import annotations

from robodesc.frontends.mjcf.context import Reading
from robodesc.ir.model import Drive, Limit, Transmission, TransmissionActuator, TransmissionJoint

_JOINT, _JOINTINPARENT = 0, 1
_GAIN_FIXED = 0
_BIAS_NONE, _BIAS_AFFINE = 0, 1
_INTERFACES = {
    "position": "hardware_interface/PositionJointInterface",
    "velocity": "hardware_interface/VelocityJointInterface",
    "motor": "hardware_interface/EffortJointInterface",
}
_TRANSMISSION_KINDS = {2: "slider-crank", 3: "tendon", 4: "site", 5: "body"}


def classify(gaintype: int, gain: float, biastype: int, bias: tuple[float, float, float]) -> tuple[str, float, float]:
    """(kind, kp, kv) of an actuator from its compiled gain and bias: position, velocity, motor or general."""
    if gaintype != _GAIN_FIXED:
        return "general", 0.0, 0.0
    if biastype == _BIAS_NONE:
        return "motor", 0.0, 0.0
    if biastype == _BIAS_AFFINE and bias[0] == 0.0:
        if bias[1] != 0.0 and abs(bias[1] + gain) <= 1e-12 * max(abs(gain), 1.0):
            return "position", gain, -bias[2]
        if bias[1] == 0.0 and abs(bias[2] + gain) <= 1e-12 * max(abs(gain), 1.0):
            return "velocity", 0.0, gain
    return "general", 0.0, 0.0


def read_actuators(r: Reading) -> None:
    m = r.model
    joints = r.robot.joint_map()
    for a in range(m.nu):
        name = r.name("actuator", a) or f"actuator{a}"
        label = f"actuator {name!r}"
        loc = r.loc("actuator", a)
        trn = int(m.actuator_trntype[a])
        if trn not in (_JOINT, _JOINTINPARENT):
            r.warn(
                "mjcf-actuator-not-held",
                f"an actuator on a {_TRANSMISSION_KINDS.get(trn, 'non-joint')} has no IR form: URDF, SDF, USD and "
                "MJCF outputs leave it out (each target drives the joints instead)",
                label,
                loc,
            )
            continue
        joint = joints.get(r.joint_of.get(int(m.actuator_trnid[a][0]), ""))
        if joint is None or joint.type.dof != 1:
            r.warn("mjcf-actuator-not-held", "an actuator of a multi-DOF joint has no IR form: left out", label, loc)
            continue
        gear = float(m.actuator_gear[a][0])
        gain = float(m.actuator_gainprm[a][0])
        bias = (float(m.actuator_biasprm[a][0]), float(m.actuator_biasprm[a][1]), float(m.actuator_biasprm[a][2]))
        kind, kp, kv = classify(int(m.actuator_gaintype[a]), gain, int(m.actuator_biastype[a]), bias)
        effort = _effort(r, a, kind, gain, gear)
        if effort is not None:
            if joint.limit is None:
                joint.limit = Limit(src=loc)
            if joint.limit.effort is None or effort < joint.limit.effort:
                joint.limit.effort = effort
        if kind == "general":
            r.warn(
                "mjcf-actuator-general",
                "a <general> actuator that is neither a position, velocity nor force servo (gain/bias types "
                f"{int(m.actuator_gaintype[a])}/{int(m.actuator_biastype[a])}): its effort limit is kept, "
                "each target drives the joint with its own gains",
                label,
                loc,
            )
        if int(m.actuator_dyntype[a]) != 0:
            r.warn(
                "mjcf-actuator-dynamics",
                "actuator activation dynamics (filter, integrator, muscle) have no IR form: every output drives "
                "the joint directly",
                label,
                loc,
            )
        interface = _INTERFACES.get(kind)
        r.robot.transmissions.append(
            Transmission(
                name=r.unique(f"{name}_transmission", set(t.name for t in r.robot.transmissions)),
                type="transmission_interface/SimpleTransmission",
                joints=[TransmissionJoint(joint.name, [interface] if interface else [], src=loc)],
                actuators=[
                    TransmissionActuator(name, [interface] if interface else [], mechanical_reduction=gear, src=loc)
                ],
                src=loc,
            )
        )
        # A servo's gains in joint space: force gear·kp·(ctrl - gear·q) is kp·gear² per unit of q.
        if kind == "position":
            joint.drive = Drive("position", kp * gear * gear, kv * gear * gear, src=loc)
        elif kind == "velocity":
            joint.drive = Drive("velocity", 0.0, kv * gear * gear, src=loc)
        elif kind == "motor":
            joint.drive = Drive("effort", src=loc)


def _effort(r: Reading, a: int, kind: str, gain: float, gear: float) -> float | None:
    m = r.model
    if bool(m.actuator_forcelimited[a]):
        lo, hi = float(m.actuator_forcerange[a][0]), float(m.actuator_forcerange[a][1])
        return max(abs(lo), abs(hi)) * abs(gear)
    if kind == "motor" and bool(m.actuator_ctrllimited[a]):
        lo, hi = float(m.actuator_ctrlrange[a][0]), float(m.actuator_ctrlrange[a][1])
        return max(abs(lo), abs(hi)) * abs(gain * gear)
    return None
