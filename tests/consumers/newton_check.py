"""Compare what Newton builds from robodesc's USD with what it builds from the source URDF.

Runs inside the Newton consumer environment (Python >= 3.10 with ``newton[importers,sim]``),
never inside robodesc's own. One robot per call; prints one JSON object on standard output:

    python newton_check.py --urdf SRC.urdf --usd OUT.usda [--floating] [--stiffness K] [--damping D]
    python newton_check.py --urdf SRC.urdf --mjcf OUT/robot.xml [--floating] [--stiffness K] [--damping D]

Each check is ``{"name", "ok", "worst", "where", "detail"}``; ``status`` is ``pass`` or
``fail: <first failing checks>``. The reference is Newton's own ``add_urdf`` of the source, with the
same drive gains robodesc was asked for, so every difference is a difference in what robodesc wrote.
With ``--mjcf`` the compared model is Newton's ``add_mjcf`` of robodesc's robot.xml (``check_mjcf``):
an MJCF reader independent of MuJoCo's own, which robodesc's validator already uses.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import traceback
import warnings

import numpy as np

SIM_DT = 0.002


def compare_limits(rep, lo_pairs, hi_pairs):
    """Lower and upper limits, leaving out continuous joints: Newton's add_urdf leaves one at
    lower = upper = 0, or keeps the <limit> a continuous joint may carry (URDF says to ignore it;
    kinova's +-2 pi), where the other importer has +-1e10."""
    unlimited = {
        n
        for (n, a, b), (_, c, d) in zip(lo_pairs, hi_pairs, strict=True)
        if b <= -1e9 and d >= 1e9 and ((a == c == 0.0) or (a <= -6.283 and c >= 6.283))
    }
    rep.compare("limits lower", [p for p in lo_pairs if p[0] not in unlimited], 2e-6, 1e-6)
    rep.compare("limits upper", [p for p in hi_pairs if p[0] not in unlimited], 2e-6, 1e-6)


def _short(label: str) -> str:
    """``panda/panda_link1`` and ``/panda/panda_link1`` and ``/panda/joints/j`` -> the last name."""
    return label.rstrip("/").split("/")[-1]


def _build(kind: str, path: str, args: argparse.Namespace, names: set[str] | None = None):
    import newton

    builder = newton.ModelBuilder()
    # URDF carries no drive gains: give Newton the ones robodesc wrote to the USD.
    builder.default_joint_cfg.target_ke = args.stiffness
    builder.default_joint_cfg.target_kd = args.damping
    info: dict = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if kind == "urdf":
            builder.add_urdf(
                _without_geometry(path),
                floating=args.floating,
                enable_self_collisions=False,
                package_dirs=args.package_dir or None,
            )
        else:
            stage = path
            if args.variant:
                from pxr import Usd

                stage = Usd.Stage.Open(path)
                vset = stage.GetDefaultPrim().GetVariantSets().GetVariantSet("Physics")
                vset.SetVariantSelection(args.variant)
            info = builder.add_usd(stage, enable_self_collisions=False, load_visual_shapes=False)
    model = builder.finalize(device="cpu")
    if kind == "usd":
        _rename_to_display_names(model, path if isinstance(stage, str) else stage, names or set())
    return builder, model, info


def _without_geometry(path: str) -> str:
    """The URDF's text without visuals and colliders: the comparison runs without contacts and
    masses come from <inertial>, and Newton's own mesh reader refuses some corpus meshes
    (anymal's foot DAE) that robodesc reads."""
    import xml.etree.ElementTree as ET

    tree = ET.parse(path)
    for link in tree.getroot().iter("link"):
        for tag in ("visual", "collision"):
            for el in link.findall(tag):
                link.remove(el)
    return ET.tostring(tree.getroot(), encoding="unicode")


def _rename_to_display_names(model, stage, names: set[str]) -> None:
    """robodesc sanitises names for USD and keeps the original as ``displayName``: a prim whose
    name the reference does not know is compared by its display name (the Isaac folder's URDF is
    sanitised too, so there the prim name matches)."""
    from pxr import Usd

    if isinstance(stage, str):
        stage = Usd.Stage.Open(stage)
    for labels in (model.body_label, model.joint_label):
        for i, label in enumerate(labels):
            prim = stage.GetPrimAtPath(label) if label.startswith("/") else None
            if prim is not None and prim.IsValid():
                shown = prim.GetMetadata("displayName")
                if shown and _short(label) not in names:
                    labels[i] = label.rsplit("/", 1)[0] + "/" + shown


class Report:
    def __init__(self, side: str = "usd") -> None:
        self.checks: list[dict] = []
        self.side = side  # what the reference is compared with, in messages

    def add(self, name: str, ok: bool, worst: float | None = None, where: str = "", detail: str = "") -> None:
        self.checks.append(
            {
                "name": name,
                "ok": bool(ok),
                "worst": None if worst is None else float(worst),
                "where": where,
                "detail": detail,
            }
        )

    def compare(self, name: str, pairs: list[tuple[str, float, float]], rtol: float, atol: float) -> None:
        """Worst |a - b| - (atol + rtol |a|) over named pairs; infinities must match exactly."""
        worst, where, ok = 0.0, "", True
        for label, a, b in pairs:
            a, b = float(a), float(b)
            if math.isinf(a) or math.isinf(b) or a >= 1e5 or b >= 1e5:
                # Newton's "unlimited" is 1e6 (velocity, effort) or inf: both must be unlimited.
                big_a, big_b = math.isinf(a) or a >= 1e5, math.isinf(b) or b >= 1e5
                if big_a != big_b:
                    ok, where, worst = False, f"{label}: urdf {a:g} {self.side} {b:g}", math.inf
                continue
            err = abs(a - b)
            if err > atol + rtol * abs(a):
                ok = False
                if err > worst or where == "" or worst == 0.0:
                    worst, where = err, f"{label}: urdf {a:.6g} {self.side} {b:.6g}"
            elif ok and err > worst:
                worst, where = err, label
        self.add(name, ok, worst, where)


def _dof_table(builder, model, skip_base: bool) -> dict[str, list[int]]:
    """Joint name -> its DOF indices (the base joint left out)."""
    starts = model.joint_qd_start.numpy()
    out: dict[str, list[int]] = {}
    for j, label in enumerate(model.joint_label):
        lo, hi = int(starts[j]), int(starts[j + 1])
        if skip_base and j == 0 and int(model.joint_parent.numpy()[j]) == -1:
            continue
        out[_short(label)] = list(range(lo, hi))
    return out


def _coord_table(model) -> dict[str, list[int]]:
    starts = model.joint_q_start.numpy()
    return {_short(label): list(range(int(starts[j]), int(starts[j + 1]))) for j, label in enumerate(model.joint_label)}


def check(args: argparse.Namespace) -> dict:
    import newton

    rep = Report()
    bu, mu, _ = _build("urdf", args.urdf, args)
    known = {_short(x) for x in (*mu.body_label, *mu.joint_label)}
    bs, ms, _ = _build("usd", args.usd, args, known)

    # --- structure ------------------------------------------------------------------------
    bodies_u = [_short(b) for b in mu.body_label]
    bodies_s = [_short(b) for b in ms.body_label]
    rep.add(
        "bodies",
        sorted(bodies_u) == sorted(bodies_s),
        detail=f"urdf {len(bodies_u)} usd {len(bodies_s)}"
        + (
            ""
            if sorted(bodies_u) == sorted(bodies_s)
            else f"; only urdf {sorted(set(bodies_u) - set(bodies_s))[:5]}, only usd {sorted(set(bodies_s) - set(bodies_u))[:5]}"
        ),
    )
    base_u = [j for j in range(mu.joint_count) if int(mu.joint_parent.numpy()[j]) == -1]
    base_s = [j for j in range(ms.joint_count) if int(ms.joint_parent.numpy()[j]) == -1]
    jt_u = mu.joint_type.numpy()
    jt_s = ms.joint_type.numpy()
    base_types_u = sorted(int(jt_u[j]) for j in base_u)
    base_types_s = sorted(int(jt_s[j]) for j in base_s)
    rep.add("base joint", base_types_u == base_types_s, detail=f"urdf {base_types_u} usd {base_types_s}")
    joints_u = {_short(mu.joint_label[j]): int(jt_u[j]) for j in range(mu.joint_count) if j not in base_u}
    joints_s = {_short(ms.joint_label[j]): int(jt_s[j]) for j in range(ms.joint_count) if j not in base_s}
    rep.add(
        "joints",
        set(joints_u) == set(joints_s),
        detail=f"urdf {len(joints_u)} usd {len(joints_s)}"
        + (
            ""
            if set(joints_u) == set(joints_s)
            else f"; only urdf {sorted(set(joints_u) - set(joints_s))[:5]}, only usd {sorted(set(joints_s) - set(joints_u))[:5]}"
        ),
    )
    rep.add(
        "dof", mu.joint_dof_count == ms.joint_dof_count, detail=f"urdf {mu.joint_dof_count} usd {ms.joint_dof_count}"
    )
    bad_types = [n for n in joints_u if n in joints_s and joints_u[n] != joints_s[n]]
    rep.add("joint types", not bad_types, where=", ".join(bad_types[:5]))
    if not rep.checks[0]["ok"] or not rep.checks[2]["ok"] or bad_types:
        return _finish(rep)

    # --- mass properties ------------------------------------------------------------------
    bi_u = {n: i for i, n in enumerate(bodies_u)}
    bi_s = {n: i for i, n in enumerate(bodies_s)}
    mass_u, mass_s = mu.body_mass.numpy(), ms.body_mass.numpy()
    com_u, com_s = mu.body_com.numpy(), ms.body_com.numpy()
    in_u, in_s = mu.body_inertia.numpy(), ms.body_inertia.numpy()
    # UsdPhysics cannot say "zero mass" (0 means "compute it from the colliders"), and a zero
    # tensor means the same: such source bodies are counted, not compared.
    massless = [n for n in bodies_u if float(mass_u[bi_u[n]]) == 0.0]
    no_tensor = [n for n in bodies_u if n not in massless and not np.any(in_u[bi_u[n]])]
    weighed = [n for n in bodies_u if n not in massless]
    rep.compare("mass", [(n, mass_u[bi_u[n]], mass_s[bi_s[n]]) for n in weighed], 1e-6, 1e-9)
    if massless or no_tensor:
        rep.checks[-1]["detail"] = (
            f"{len(massless)} massless and {len(no_tensor)} zero-tensor source bodies not compared "
            "(UsdPhysics reads 0 as 'compute from colliders')"
        )
    rep.compare(
        "com", [(f"{n}[{k}]", com_u[bi_u[n]][k], com_s[bi_s[n]][k]) for n in weighed for k in range(3)], 0, 1e-6
    )
    inertia_pairs = []
    for n in weighed:
        if n in no_tensor:
            continue
        a, b = in_u[bi_u[n]], in_s[bi_s[n]]
        scale = max(float(np.abs(a).max()), 1e-12)
        for r in range(3):
            for c in range(3):
                # Relative to the body's largest moment: principal axes are float32 quaternions.
                inertia_pairs.append((f"{n}[{r}{c}]", a[r][c] / scale, b[r][c] / scale))
    rep.compare("inertia", inertia_pairs, 0, 2e-5)

    # --- per-DOF parameters ---------------------------------------------------------------
    dofs_u = _dof_table(bu, mu, skip_base=True)
    dofs_s = _dof_table(bs, ms, skip_base=True)
    if getattr(args, "gains", None):
        # The source's own servos (an MJCF's actuators, joint -> [kp, kv] in SI per radian or
        # metre): a URDF carries no gains, so the reference is given the ones robodesc's USD writes
        # for them (docs/mjcf-input.md), instead of one constant for every joint.
        ke, kd = mu.joint_target_ke.numpy(), mu.joint_target_kd.numpy()
        for n, (kp, kv) in args.gains.items():
            for i in dofs_u.get(n, []):
                ke[i], kd[i] = kp, kv
        mu.joint_target_ke.assign(ke)
        mu.joint_target_kd.assign(kd)
    mimic_u = (
        {_short(mu.joint_label[j]) for j in range(mu.joint_count) if int(mu.joint_mimic_joint.numpy()[j]) >= 0}
        if mu.joint_mimic_joint is not None
        else set()
    )
    names = [n for n in dofs_u if n in dofs_s and len(dofs_u[n]) == len(dofs_s[n])]
    # Newton's add_urdf gives a mimic follower the same position drive as every joint, which pulls
    # it against its mimic constraint; robodesc's USD (like Isaac Sim's importer) gives it a drive
    # without gains. For the runs below the URDF side's follower drives get the USD's gains.
    if mimic_u:
        ke, kd = mu.joint_target_ke.numpy(), mu.joint_target_kd.numpy()
        mode = mu.joint_target_mode.numpy()
        ke_s, kd_s, mode_s = ms.joint_target_ke.numpy(), ms.joint_target_kd.numpy(), ms.joint_target_mode.numpy()
        for n in mimic_u:
            if n in names:
                for i, j in zip(dofs_u[n], dofs_s[n], strict=True):
                    ke[i], kd[i], mode[i] = ke_s[j], kd_s[j], mode_s[j]
        mu.joint_target_ke.assign(ke)
        mu.joint_target_kd.assign(kd)
        mu.joint_target_mode.assign(mode)

    def pairs(attr: str, scale: float = 1.0, only=None):
        a_u, a_s = getattr(mu, attr).numpy(), getattr(ms, attr).numpy()
        out = []
        for n in names:
            if only is not None and not only(n):
                continue
            for k, (i, j) in enumerate(zip(dofs_u[n], dofs_s[n], strict=True)):
                out.append((f"{n}[{k}]" if len(dofs_u[n]) > 1 else n, a_u[i] * scale, a_s[j] * scale))
        return out

    # Limits: degrees in float32 on the USD side.
    lo_pairs, hi_pairs = pairs("joint_limit_lower"), pairs("joint_limit_upper")
    compare_limits(rep, lo_pairs, hi_pairs)
    driven = lambda n: n not in mimic_u  # noqa: E731
    rep.compare("drive stiffness", pairs("joint_target_ke", only=driven), 1e-5, 1e-9)
    rep.compare("drive damping", pairs("joint_target_kd", only=driven), 1e-5, 1e-9)
    mode_u, mode_s = mu.joint_target_mode.numpy(), ms.joint_target_mode.numpy()
    bad_modes = [
        n
        for n in names
        if driven(n) and any(int(mode_u[i]) != int(mode_s[j]) for i, j in zip(dofs_u[n], dofs_s[n], strict=True))
    ]
    rep.add("drive modes", not bad_modes, where=", ".join(bad_modes[:5]))
    rep.compare("armature", pairs("joint_armature"), 1e-5, 1e-12)
    rep.compare("passive damping", pairs("joint_damping"), 1e-5, 1e-12)
    rep.compare("friction", pairs("joint_friction"), 1e-5, 1e-12)
    # URDF velocity 0 is a placeholder too (robodesc writes no velocity limit for it).
    # A mimic follower has no velocity limit in robodesc's USD (PhysX runs away with one; docs/usd.md).
    vel_pairs = pairs("joint_velocity_limit", only=driven)
    zero_velocity = [p for p in vel_pairs if p[1] == 0.0 and p[2] >= 1e5]
    rep.compare("velocity limit", [p for p in vel_pairs if p not in zero_velocity], 1e-5, 1e-9)
    if zero_velocity:
        rep.checks[-1]["detail"] = f"{len(zero_velocity)} DOFs with URDF velocity 0 read as 'not given'"
    # URDF effort 0 is a placeholder: UsdPhysics (and Isaac Sim's importer) write no maxForce for
    # it, Newton's add_urdf reads it as "no force". Compared as "not given", and the URDF side
    # takes the USD's (unlimited) value for the run.
    eff_u, eff_s = mu.joint_effort_limit.numpy(), ms.joint_effort_limit.numpy()
    zero_effort = [n for n in names if all(float(eff_u[i]) == 0.0 for i in dofs_u[n])]
    for n in zero_effort:
        for i, j in zip(dofs_u[n], dofs_s[n], strict=True):
            eff_u[i] = eff_s[j]
    if zero_effort:
        mu.joint_effort_limit.assign(eff_u)
    rep.compare("effort limit", pairs("joint_effort_limit"), 1e-6, 1e-9)
    if zero_effort:
        rep.checks[-1]["detail"] = f"{len(zero_effort)} joints with URDF effort 0 read as 'not given'"

    # --- forward kinematics at random configurations --------------------------------------
    coords_u = _coord_table(mu)
    coords_s = _coord_table(ms)
    rng = np.random.default_rng(7)
    lo_u, hi_u = mu.joint_limit_lower.numpy(), mu.joint_limit_upper.numpy()
    worst, where = 0.0, ""
    for trial in range(5):
        q_u = mu.joint_q.numpy().copy()
        q_s = ms.joint_q.numpy().copy()
        for n in names:
            if n not in coords_u or n not in coords_s or len(coords_u[n]) != len(dofs_u[n]):
                continue  # ball/free joints: coordinates are quaternions, left at rest
            for ci, cj, d in zip(coords_u[n], coords_s[n], dofs_u[n], strict=True):
                lo, hi = float(lo_u[d]), float(hi_u[d])
                lo, hi = max(lo, -math.pi), min(hi, math.pi)
                v = rng.uniform(lo, hi) if hi > lo else lo
                q_u[ci] = v
                q_s[cj] = v
        su, ss = mu.state(), ms.state()
        su.joint_q.assign(q_u)
        ss.joint_q.assign(q_s)
        newton.eval_fk(mu, su.joint_q, su.joint_qd, su)
        newton.eval_fk(ms, ss.joint_q, ss.joint_qd, ss)
        bq_u, bq_s = su.body_q.numpy(), ss.body_q.numpy()
        for n in bodies_u:
            a, b = bq_u[bi_u[n]], bq_s[bi_s[n]]
            e = float(np.linalg.norm(a[:3] - b[:3]))
            qa, qb = a[3:].astype(np.float64), b[3:].astype(np.float64)
            # Twice the chord between the unit quaternions: the angle, without acos's noise near 1.
            ang = 2 * min(float(np.linalg.norm(qa - qb)), float(np.linalg.norm(qa + qb)))
            e = max(e, ang * 0.1)  # a radian of orientation error counts as 0.1 m
            if e > worst:
                worst, where = e, f"{n} (trial {trial})"
    rep.add("fk", worst <= 1e-5, worst, where)

    # --- 200 steps of SolverMuJoCo, same gains and targets on both ----------------------------
    if args.steps > 0:
        rep.checks.extend(_trajectory(mu, ms, names, dofs_u, dofs_s, coords_u, coords_s, bodies_u, bi_u, bi_s, args))
    return _finish(rep)


# robodesc's token mass on a moving body that has none (emit/mjcf/bodies.py STUB_MASS): MuJoCo
# refuses a massless moving body, the URDF reference has mass 0 there.
STUB_MASS = 1e-3


def joints_by_child(
    labels: list[str], children: list[int], parents: list[int], types: list[int], body_labels: list[str]
):
    """Each joint keyed by its child body's name: ``{child: (joint name, type, parent name or "")}``.

    MJCF has no name for a weld (a body without a joint; Newton calls it ``<body>_joint``) and
    writes a URDF planar joint as three joints on one body (one D6 in Newton), so joints are paired
    by the body they move, which both formats name after the link."""
    out = {}
    for label, child, parent, kind in zip(labels, children, parents, types, strict=True):
        parent_name = _short(body_labels[parent]) if parent >= 0 else ""
        out[_short(body_labels[child])] = (_short(label), int(kind), parent_name)
    return out


def mass_pairs(ref: dict[str, float], mjcf: dict[str, float]) -> tuple[list[tuple[str, float, float]], list[str]]:
    """(body, reference mass, MJCF mass) to compare, and the bodies that carry robodesc's token
    mass where the reference has none (said, not compared)."""
    pairs, stubs = [], []
    for name, a in ref.items():
        if name not in mjcf:
            continue
        b = mjcf[name]
        if a == 0.0 and abs(b - STUB_MASS) <= 1e-9:
            stubs.append(name)
        else:
            pairs.append((name, a, b))
    return pairs, stubs


def mimic_table(
    joint_names: list[str], rows: list[tuple[int, int, float, float]]
) -> dict[str, tuple[str, float, float]]:
    """follower -> (leader, offset, multiplier), from (follower index, leader index, offset, multiplier)."""
    return {joint_names[f]: (joint_names[lead], float(c0), float(c1)) for f, lead, c0, c1 in rows}


def compare_mimic(ref: dict[str, tuple[str, float, float]], mjcf: dict[str, tuple[str, float, float]]) -> list[str]:
    """The followers whose leader, offset or multiplier differ (or that one side lacks)."""
    bad = sorted(set(ref) ^ set(mjcf))
    for name in sorted(set(ref) & set(mjcf)):
        (la, oa, ma), (lb, ob, mb) = ref[name], mjcf[name]
        if la != lb or abs(oa - ob) > 1e-6 * max(1.0, abs(oa)) or abs(ma - mb) > 1e-6 * max(1.0, abs(ma)):
            bad.append(name)
    return bad


def _build_mjcf(path: str):
    """Newton's own MJCF import, as a user runs it: welds, freejoint, actuators and equalities read
    from the file (no gains given to the builder)."""
    import newton

    builder = newton.ModelBuilder()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        builder.add_mjcf(path, enable_self_collisions=False, parse_visuals=False)
    return builder, builder.finalize(device="cpu")


def check_mjcf(args: argparse.Namespace) -> dict:
    """robodesc's robot.xml through Newton's ``add_mjcf`` against Newton's ``add_urdf`` of the
    reference URDF: bodies, joints, masses, inertias, limits, gains, effort (the actuators'
    forcerange), armature, damping, friction, mimic, FK at random configurations and a
    200-step SolverMuJoCo run."""
    import newton

    rep = Report(side="mjcf")
    _bu, mu, _ = _build("urdf", args.urdf, args)
    try:
        _bm, mm = _build_mjcf(args.mjcf)
    except Exception as exc:
        rep.add("loads", False, detail=f"{type(exc).__name__}: {str(exc).splitlines()[0][:250]}")
        return _finish(rep)
    rep.add("loads", True, detail=f"{mm.body_count} bodies, {mm.joint_dof_count} DOFs")

    # --- structure, keyed by body -----------------------------------------------------------
    bodies_u = [_short(b) for b in mu.body_label]
    bodies_m = [_short(b) for b in mm.body_label]
    # A URDF "world" link is MuJoCo's own world body in the MJCF.
    bodies_u = [b for b in bodies_u if b != "world" or "world" in bodies_m]
    same_bodies = sorted(bodies_u) == sorted(bodies_m)
    rep.add(
        "bodies",
        same_bodies,
        detail=f"urdf {len(bodies_u)} mjcf {len(bodies_m)}"
        + (
            ""
            if same_bodies
            else f"; only urdf {sorted(set(bodies_u) - set(bodies_m))[:5]}, only mjcf {sorted(set(bodies_m) - set(bodies_u))[:5]}"
        ),
    )
    ju = joints_by_child(
        list(mu.joint_label),
        mu.joint_child.numpy().tolist(),
        mu.joint_parent.numpy().tolist(),
        mu.joint_type.numpy().tolist(),
        list(mu.body_label),
    )
    jm = joints_by_child(
        list(mm.joint_label),
        mm.joint_child.numpy().tolist(),
        mm.joint_parent.numpy().tolist(),
        mm.joint_type.numpy().tolist(),
        list(mm.body_label),
    )
    if "world" not in bodies_m:  # the URDF's world link is the MJCF's world
        ju.pop("world", None)
        ju = {b: (j, t, "" if p == "world" else p) for b, (j, t, p) in ju.items()}
    common = [b for b in bodies_m if b in ju and b in jm]
    bad_types = [b for b in common if ju[b][1] != jm[b][1] or ju[b][2] != jm[b][2]]
    rep.add(
        "joint types and parents",
        not bad_types,
        where=", ".join(
            f"{b}: urdf {ju[b][1]}<-{ju[b][2] or 'world'} mjcf {jm[b][1]}<-{jm[b][2] or 'world'}" for b in bad_types[:3]
        ),
    )
    fixed = int(newton.JointType.FIXED)
    d6 = int(newton.JointType.D6)
    # The base joint has no source name (Newton calls the URDF's "floating_base", the MJCF's
    # freejoint is named after the root): its type is compared above.
    bad_names = [b for b in common if ju[b][1] not in (fixed, d6) and ju[b][2] and ju[b][0] != jm[b][0]]
    rep.add("joint names", not bad_names, where=", ".join(f"{ju[b][0]} -> {jm[b][0]}" for b in bad_names[:3]))
    rep.add(
        "dof", mu.joint_dof_count == mm.joint_dof_count, detail=f"urdf {mu.joint_dof_count} mjcf {mm.joint_dof_count}"
    )
    if not same_bodies or bad_types or mu.joint_dof_count != mm.joint_dof_count:
        return _finish(rep)

    # --- mass properties --------------------------------------------------------------------
    bi_u = {_short(n): i for i, n in enumerate(mu.body_label)}
    bi_m = {_short(n): i for i, n in enumerate(mm.body_label)}
    mass_u, mass_m = mu.body_mass.numpy(), mm.body_mass.numpy()
    com_u, com_m = mu.body_com.numpy(), mm.body_com.numpy()
    in_u, in_m = mu.body_inertia.numpy(), mm.body_inertia.numpy()
    pairs_mass, stubs = mass_pairs(
        {n: float(mass_u[bi_u[n]]) for n in bodies_m}, {n: float(mass_m[bi_m[n]]) for n in bodies_m}
    )
    rep.compare("mass", pairs_mass, 1e-6, 1e-9)
    if stubs:
        rep.checks[-1]["detail"] = (
            f"{len(stubs)} massless moving bodies carry the {STUB_MASS:g} kg MuJoCo needs ({', '.join(stubs[:3])})"
        )
    weighed = [n for n, a, _ in pairs_mass if a > 0.0]
    rep.compare(
        "com", [(f"{n}[{k}]", com_u[bi_u[n]][k], com_m[bi_m[n]][k]) for n in weighed for k in range(3)], 0, 1e-6
    )
    inertia_pairs = []
    for n in weighed:
        a, b = in_u[bi_u[n]], in_m[bi_m[n]]
        if not np.any(a):
            continue
        scale = max(float(np.abs(a).max()), 1e-12)
        for r in range(3):
            for c in range(3):
                # Relative to the largest moment: Newton reads fullinertia as float32, and robodesc
                # raises a moment below 1e-6 of the largest (mjcf-inertia-floor).
                inertia_pairs.append((f"{n}[{r}{c}]", a[r][c] / scale, b[r][c] / scale))
    rep.compare("inertia", inertia_pairs, 0, 2e-5)

    # --- per-DOF parameters, keyed by the body the joint moves -------------------------------
    def dof_table(model, table):
        starts = model.joint_qd_start.numpy()
        qstarts = model.joint_q_start.numpy()
        child = model.joint_child.numpy()
        dofs, coords = {}, {}
        for j in range(model.joint_count):
            name = _short(model.body_label[int(child[j])])
            dofs[name] = list(range(int(starts[j]), int(starts[j + 1])))
            coords[name] = list(range(int(qstarts[j]), int(qstarts[j + 1])))
        return dofs, coords

    dofs_u, coords_u = dof_table(mu, ju)
    dofs_m, coords_m = dof_table(mm, jm)
    base = [b for b in common if ju[b][2] == ""]
    names = [b for b in common if b not in base and dofs_u[b] and len(dofs_u[b]) == len(dofs_m[b])]

    mimic_u = {}
    if mu.joint_mimic_joint is not None:
        mj_idx, mj_coef = mu.joint_mimic_joint.numpy(), mu.joint_mimic_coeffs.numpy()
        rows = [(j, int(mj_idx[j]), mj_coef[j][0], mj_coef[j][1]) for j in range(mu.joint_count) if int(mj_idx[j]) >= 0]
        mimic_u = mimic_table([_short(mu.body_label[int(c)]) for c in mu.joint_child.numpy()], rows)
    mimic_m = {}
    if mm.constraint_mimic_count:
        rows = list(
            zip(
                mm.constraint_mimic_joint0.numpy().tolist(),
                mm.constraint_mimic_joint1.numpy().tolist(),
                mm.constraint_mimic_coef0.numpy().tolist(),
                mm.constraint_mimic_coef1.numpy().tolist(),
                strict=True,
            )
        )
        mimic_m = mimic_table([_short(mm.body_label[int(c)]) for c in mm.joint_child.numpy()], rows)
    bad_mimic = compare_mimic(mimic_u, mimic_m)
    rep.add("mimic", not bad_mimic, where=", ".join(bad_mimic[:5]), detail=f"{len(mimic_u)} mimic joints")

    def pairs(a_u, a_m, only=None):
        out = []
        for n in names:
            if only is not None and not only(n):
                continue
            for k, (i, j) in enumerate(zip(dofs_u[n], dofs_m[n], strict=True)):
                out.append((f"{n}[{k}]" if len(dofs_u[n]) > 1 else n, a_u[i], a_m[j]))
        return out

    def attr_pairs(attr, only=None):
        return pairs(getattr(mu, attr).numpy(), getattr(mm, attr).numpy(), only)

    lo_pairs, hi_pairs = attr_pairs("joint_limit_lower"), attr_pairs("joint_limit_upper")
    compare_limits(rep, lo_pairs, hi_pairs)
    driven = lambda n: n not in mimic_u  # noqa: E731
    rep.compare("actuator kp", attr_pairs("joint_target_ke", only=driven), 1e-6, 1e-9)
    rep.compare("actuator kv", attr_pairs("joint_target_kd", only=driven), 1e-6, 1e-9)
    rep.compare("armature", attr_pairs("joint_armature"), 1e-5, 1e-12)
    rep.compare("passive damping", attr_pairs("joint_damping"), 1e-5, 1e-12)
    rep.compare("friction", attr_pairs("joint_friction"), 1e-5, 1e-12)
    # MJCF puts the effort limit on the actuator (forcerange), which Newton keeps in its MuJoCo
    # attributes and not in joint_effort_limit; URDF effort 0 is "not given" (no forcerange).
    effort_m = np.full(mm.joint_dof_count, math.inf)
    mj = mm.mujoco
    if getattr(mj, "actuator_trnid", None) is not None and len(mj.actuator_trnid.numpy()):
        for (dof, _), has, rng in zip(
            mj.actuator_trnid.numpy(), mj.actuator_has_forcerange.numpy(), mj.actuator_forcerange.numpy(), strict=True
        ):
            if int(has) and 0 <= int(dof) < len(effort_m):
                effort_m[int(dof)] = max(abs(float(rng[0])), abs(float(rng[1])))
    eff_u = mu.joint_effort_limit.numpy().astype(float)
    eff_u = np.where(eff_u == 0.0, math.inf, eff_u)
    rep.compare("effort limit (forcerange)", pairs(eff_u, effort_m, only=driven), 1e-6, 1e-9)
    n_act = len(mj.actuator_trnid.numpy()) if getattr(mj, "actuator_trnid", None) is not None else 0
    n_driven = sum(1 for n in names if driven(n) and jm[n][1] != fixed)
    rep.add("actuators", n_act >= n_driven, detail=f"{n_act} actuators, {n_driven} driven joints")

    # --- FK at random configurations (same coordinates on both sides) -------------------------
    q_u0, q_m0 = mu.joint_q.numpy().copy(), mm.joint_q.numpy().copy()
    for b in base:  # the root starts where the MJCF puts it (raised onto the floor when floating)
        if len(coords_u[b]) == len(coords_m[b]):
            q_u0[coords_u[b]] = q_m0[coords_m[b]]
    mu.joint_q.assign(q_u0)
    rng_ = np.random.default_rng(7)
    lo_u, hi_u = mu.joint_limit_lower.numpy(), mu.joint_limit_upper.numpy()
    worst, where = 0.0, ""
    for trial in range(5):
        q_u, q_m = q_u0.copy(), q_m0.copy()
        for n in names:
            if len(coords_u[n]) != len(dofs_u[n]) or len(coords_m[n]) != len(coords_u[n]):
                continue
            for ci, cj, d in zip(coords_u[n], coords_m[n], dofs_u[n], strict=True):
                lo, hi = max(float(lo_u[d]), -math.pi), min(float(hi_u[d]), math.pi)
                v = rng_.uniform(lo, hi) if hi > lo else lo
                q_u[ci] = q_m[cj] = v
        su, sm = mu.state(), mm.state()
        su.joint_q.assign(q_u)
        sm.joint_q.assign(q_m)
        newton.eval_fk(mu, su.joint_q, su.joint_qd, su)
        newton.eval_fk(mm, sm.joint_q, sm.joint_qd, sm)
        bq_u, bq_m = su.body_q.numpy(), sm.body_q.numpy()
        for n in bodies_m:
            a, b = bq_u[bi_u[n]], bq_m[bi_m[n]]
            e = float(np.linalg.norm(a[:3] - b[:3]))
            qa, qb = a[3:].astype(np.float64), b[3:].astype(np.float64)
            ang = 2 * min(float(np.linalg.norm(qa - qb)), float(np.linalg.norm(qa + qb)))
            e = max(e, ang * 0.1)
            if e > worst:
                worst, where = e, f"{n} (trial {trial})"
    # 5e-5 m, not the USD check's 1e-5: add_mjcf composes every body's world pose in float32 and
    # takes each joint frame as inverse(parent) * child, so joint frames differ from the numbers
    # robodesc wrote (the source's, digit for digit) by up to 1.3e-6 m on anymal_c, and the feet
    # at random angles by 1.2e-5 m. A written number that is wrong is off by far more.
    rep.add("fk", worst <= 5e-5, worst, where, detail="tolerance 5e-5 m (add_mjcf's float32 world round trip)")

    # --- 200 steps of SolverMuJoCo -------------------------------------------------------------
    if args.steps > 0:
        # Start and hold at zero clamped into the limits (the MJCF's home keyframe, which add_mjcf
        # does not read): a start outside a limit would compare two engines' limit responses.
        q_m, lo_m, hi_m = mm.joint_q.numpy().copy(), mm.joint_limit_lower.numpy(), mm.joint_limit_upper.numpy()
        for n in names:
            if len(coords_m[n]) == len(dofs_m[n]):
                for c, d in zip(coords_m[n], dofs_m[n], strict=True):
                    q_m[c] = min(max(q_m[c], lo_m[d]), hi_m[d])
        mm.joint_q.assign(q_m)
        if mm.joint_target_q is not None:
            t_m = mm.joint_target_q.numpy().copy()
            for n in names:
                if len(coords_m[n]) == len(dofs_m[n]):
                    for c in coords_m[n]:
                        t_m[c] = q_m[c]
            mm.joint_target_q.assign(t_m)
        if mimic_u:  # the follower has no actuator in MJCF: the URDF side's drive is taken off too
            ke, kd, mode = mu.joint_target_ke.numpy(), mu.joint_target_kd.numpy(), mu.joint_target_mode.numpy()
            ke_m, kd_m, mode_m = mm.joint_target_ke.numpy(), mm.joint_target_kd.numpy(), mm.joint_target_mode.numpy()
            for n in mimic_u:
                if n in names:
                    for i, j in zip(dofs_u[n], dofs_m[n], strict=True):
                        ke[i], kd[i], mode[i] = ke_m[j], kd_m[j], mode_m[j]
            mu.joint_target_ke.assign(ke)
            mu.joint_target_kd.assign(kd)
            mu.joint_target_mode.assign(mode)
        rep.checks.extend(
            _trajectory(mu, mm, names, dofs_u, dofs_m, coords_u, coords_m, bodies_m, bi_u, bi_m, args, side="MJCF")
        )
    return _finish(rep)


def _trajectory(
    mu, ms, names, dofs_u, dofs_s, coords_u, coords_s, bodies_u, bi_u, bi_s, args, side: str = "USD"
) -> list[dict]:
    import newton

    out: list[dict] = []
    try:
        solver_s = newton.solvers.SolverMuJoCo(ms, use_mujoco_cpu=True, disable_contacts=True)
    except Exception as exc:
        detail = f"{type(exc).__name__}: {exc}"[:300]
        return [{"name": f"mujoco build ({side})", "ok": False, "worst": None, "where": "", "detail": detail}]
    refused = ""
    try:
        solver_u = newton.solvers.SolverMuJoCo(mu, use_mujoco_cpu=True, disable_contacts=True)
    except Exception as exc:
        # The reference itself cannot run (a boundary inertia that float32 breaks, say): the USD
        # still has to run finite, but there is nothing to track.
        refused = f"{type(exc).__name__}: {exc}".splitlines()[0][:200]
        solver_u = None
    su0, su1, ss0, ss1 = mu.state(), mu.state(), ms.state(), ms.state()
    cu, cs = mu.control(), ms.control()
    # The USD's initial state and targets (0 clamped into the limits) on both sides.
    q_u = mu.joint_q.numpy().copy()
    q_s = ms.joint_q.numpy().copy()
    t_s = ms.joint_target_q.numpy()
    tq_u = cu.joint_target_q.numpy().copy() if cu.joint_target_q is not None else None
    # Positions and position targets are indexed by coordinate (joint_q_start), not by DOF.
    for n in names:
        if n in coords_u and n in coords_s and len(coords_u[n]) == len(dofs_u[n]):
            for ci, cj in zip(coords_u[n], coords_s[n], strict=True):
                q_u[ci] = q_s[cj]
                if tq_u is not None:
                    tq_u[ci] = t_s[cj]
    su0.joint_q.assign(q_u)
    if tq_u is not None:
        cu.joint_target_q.assign(tq_u)
    newton.eval_fk(mu, su0.joint_q, su0.joint_qd, su0)
    newton.eval_fk(ms, ss0.joint_q, ss0.joint_qd, ss0)
    fixed = not args.floating
    tol = 1e-3 if fixed else 1e-2
    worst, where, finite = 0.0, "", True
    for step in range(args.steps):
        ss0.clear_forces()
        solver_s.step(ss0, ss1, cs, None, SIM_DT)
        ss0, ss1 = ss1, ss0
        bq_s = ss0.body_q.numpy()
        if not np.all(np.isfinite(bq_s)):
            finite = False
            where = f"step {step}"
            break
        if solver_u is None:
            continue
        su0.clear_forces()
        solver_u.step(su0, su1, cu, None, SIM_DT)
        su0, su1 = su1, su0
        bq_u = su0.body_q.numpy()
        for n in bodies_u:
            e = float(np.linalg.norm(bq_u[bi_u[n]][:3] - bq_s[bi_s[n]][:3]))
            if e > worst:
                worst, where = e, f"{n} at step {step + 1}"
    out.append(
        {"name": "trajectory finite", "ok": finite, "worst": None, "where": where if not finite else "", "detail": ""}
    )
    if solver_u is None:
        detail = f"not compared: MuJoCo refuses the reference URDF ({refused})"
        out.append({"name": "trajectory", "ok": finite, "worst": None, "where": "", "detail": detail})
        return out
    out.append(
        {
            "name": f"trajectory ({'fixed' if fixed else 'floating'}, {args.steps} steps)",
            "ok": finite and worst <= tol,
            "worst": worst,
            "where": where,
            "detail": f"tolerance {tol:g} m",
        }
    )
    return out


def _finish(rep: Report) -> dict:
    failed = [c for c in rep.checks if not c["ok"]]
    status = (
        "pass"
        if not failed
        else "fail: "
        + "; ".join(
            f"{c['name']}"
            + (f" ({c['where']})" if c["where"] else "")
            + (f" {c['detail']}" if c["detail"] and not c["where"] else "")
            for c in failed[:4]
        )
    )
    notes = [c["detail"] for c in rep.checks if c["ok"] and c["detail"].startswith("not compared")]
    if status == "pass" and notes:
        status = "pass; trajectory " + notes[0]
    return {"status": status, "checks": rep.checks}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--urdf", help="the reference URDF (Newton's add_urdf of it is the reference)")
    ap.add_argument("--usd", help="robodesc's USD, or an importer's")
    ap.add_argument("--mjcf", help="robodesc's robot.xml: Newton's add_mjcf of it is compared instead of a USD")
    ap.add_argument("--fallback-urdf", help="reference when Newton refuses --urdf (robodesc's own URDF)")
    ap.add_argument("--floating", action="store_true", help="the robot floats (no fixed base)")
    ap.add_argument("--stiffness", type=float, default=100.0, help="SI stiffness robodesc was given")
    ap.add_argument("--damping", type=float, default=1.0, help="SI drive damping robodesc was given")
    ap.add_argument("--package-dir", action="append", default=[], help="package roots for package:// URIs")
    ap.add_argument("--variant", default=None, help="select this Physics variant first (Isaac importer output)")
    ap.add_argument("--steps", type=int, default=200)
    ap.add_argument("--gains", type=json.loads, default=None, help='per-joint reference gains, {"joint": [kp, kv]}')
    ap.add_argument("--cases", help="a JSON list of cases (keys: name, urdf, usd or mjcf, and the options above)")
    ap.add_argument("--out", default=None, help="write the JSON here (Warp prints to standard output)")
    args = ap.parse_args(argv)
    result: dict = {}
    if args.cases:
        with open(args.cases, encoding="utf-8") as f:
            cases = json.load(f)
        for case in cases:
            one = argparse.Namespace(**{**vars(args), "cases": None, **case})
            result[case["name"]] = _run_case(one)
    elif args.urdf and (args.usd or args.mjcf):
        result = _run_case(args)
    else:
        ap.error("give --urdf and --usd (or --mjcf), or --cases")
    text = json.dumps(result)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            f.write(text + "\n")
    else:
        sys.stdout.write(text + "\n")
    return 0


def _run_case(args: argparse.Namespace) -> dict:
    args.floating = bool(args.floating)
    args.mjcf = getattr(args, "mjcf", None)
    run = check_mjcf if args.mjcf else check
    reference = "source URDF"
    try:
        try:
            result = run(args)
        except Exception:
            if not args.fallback_urdf:
                raise
            refused = traceback.format_exc().strip().splitlines()[-1]
            args.urdf = args.fallback_urdf
            reference = f"robodesc's URDF (Newton refuses the source: {refused[:200]})"
            result = run(args)
    except Exception as exc:  # one robot's failure is its result
        result = {
            "status": f"fail: {type(exc).__name__}: {str(exc)[:300]}",
            "checks": [],
            "traceback": traceback.format_exc()[-2000:],
        }
    result["reference"] = reference
    return result


if __name__ == "__main__":
    os.environ.setdefault("PXR_WORK_THREAD_LIMIT", "1")
    import warp as wp

    wp.config.quiet = True
    raise SystemExit(main())
