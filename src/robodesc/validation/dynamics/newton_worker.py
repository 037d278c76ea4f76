"""The scenarios in Newton, run by Newton's own interpreter (never imported by robodesc).

Newton needs Python >= 3.10 with ``newton[importers,sim]`` (the consumer tier's venv); robodesc
starts this file there and speaks JSON: one request on standard input
``{"usd", "root", "scenarios", "setup"}`` (setup as :meth:`Setup.as_dict`), one answer on standard
output ``{"newton": version, "runs": [Run fields]}`` or ``{"error": message}``.

Newton reads the USD with ``add_usd``: bodies, joints and the drives robodesc wrote (gains in the
USD's own units, converted by Newton), and the colliders' physics materials. The solver is
``SolverMuJoCo`` on CPU (``use_mujoco_cpu``): Newton's production solver, deterministic on CPU.
"""
# mypy: ignore-errors

from __future__ import annotations

import math
import warnings

_SAMPLE = 0.01
_BOX, _BOX_H = 0.05, 0.01  # the slide block's half length and height (mujoco_run: why flat)


def _short(label):
    return label.rstrip("/").split("/")[-1]


def _builder(gravity=None):
    import newton

    return newton.ModelBuilder(gravity=gravity) if gravity is not None else newton.ModelBuilder()


def _load(req, floating, floor=False):
    """(model, mu): the USD as Newton builds it, with a ground plane of the robot's own friction
    when ``floor`` (equal friction on both sides: every combine rule then gives it). One build per
    scenario: add_usd is most of Newton's cost on mesh-heavy robots."""
    import newton

    builder = _builder()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        builder.add_usd(req["usd"], floating=floating, enable_self_collisions=False, load_visual_shapes=False)
    mu = _robot_mu(builder, req["setup"].get("feet") or ())
    if floor:
        builder.add_ground_plane(cfg=newton.ModelBuilder.ShapeConfig(mu=1.0 if mu is None else mu))
    return builder.finalize(device="cpu"), mu


def _robot_mu(builder, feet):
    """The most common friction of the robot's shapes: its feet's when it stands on some (as the
    other engines' runners), else all shapes'. A body's label ends with its prim name."""
    values = [round(float(v), 6) for v in builder.shape_material_mu]
    labels = list(getattr(builder, "body_label", None) or getattr(builder, "body_key", None) or [])
    on_feet = [
        v
        for v, body in zip(values, builder.shape_body, strict=False)
        if 0 <= body < len(labels) and _short(str(labels[body])) in set(feet)
    ]
    values = on_feet or values
    return max(set(values), key=values.count) if values else None


def _names(model, usd):
    """Joint name -> (q index, dof count); USD prim names fall back to their displayName."""
    from pxr import Usd

    stage = Usd.Stage.Open(usd)
    starts = model.joint_q_start.numpy()
    out = {}
    for j, label in enumerate(model.joint_label):
        name = _short(label)
        prim = stage.GetPrimAtPath(label) if label.startswith("/") else None
        if prim is not None and prim.IsValid() and prim.GetMetadata("displayName"):
            out[prim.GetMetadata("displayName")] = (int(starts[j]), int(starts[j + 1]) - int(starts[j]))
        out[name] = (int(starts[j]), int(starts[j + 1]) - int(starts[j]))
    return out


def _run_robot(req, scenario):
    import newton
    import numpy as np

    setup = req["setup"]
    floor = scenario == "drop"
    model, mu = _load(req, floating=floor, floor=floor)
    names = _names(model, req["usd"])
    pose = {n: v for n, v in setup["pose"].items() if n in names and names[n][1] == 1}
    state0, state1, control = model.state(), model.state(), model.control()
    q = model.joint_q.numpy().copy()
    # The followers of mimic joints start where their leader puts them (Setup.start).
    for n, v in setup.get("start", pose).items():
        if n in names and names[n][1] == 1:
            q[names[n][0]] = v
    root_body = 0
    if floor:
        # The free root's coordinates come first: px py pz qx qy qz qw.
        q[2] = setup["stand_height"] + setup["drop_clearance"]
        q[3:7] = [0.0, 0.0, 0.0, 1.0]
    _start(model, state0, control, q, pose, names)
    solver = newton.solvers.SolverMuJoCo(model, use_mujoco_cpu=True, disable_contacts=not floor)
    dt = setup["timestep"]
    steps = max(1, round(setup["duration"] / dt))
    every = max(1, round(_SAMPLE / dt))
    run = {"scenario": scenario, "ok": True, "error": "", "mu": mu, "trajectory": []}
    run["mass"] = float(model.body_mass.numpy().sum())
    contacts = None
    drives = _drives(model, control, names, pose)
    peak = {n: 0.0 for n in drives}
    for step in range(steps):
        state0.clear_forces()
        solver.step(state0, state1, control, contacts, dt)
        state0, state1 = state1, state0
        if drives:
            jq, jqd = state0.joint_q.numpy(), state0.joint_qd.numpy()
            for n, (qi, di, ke, kd, target, limit) in drives.items():
                tau = abs(ke * (target - float(jq[qi])) - kd * float(jqd[di]))
                peak[n] = max(peak[n], min(tau, limit) if limit > 0 else tau)
        if (step + 1) % every == 0:
            jq = state0.joint_q.numpy()
            if not np.all(np.isfinite(jq)):
                return {**run, "ok": False, "error": f"state not finite after {(step + 1) * dt:.3g} s"}
            run["trajectory"].append([(step + 1) * dt, {n: float(jq[names[n][0]]) for n in pose}])
            if floor:
                bq = [float(c) for c in state0.body_q.numpy()[root_body]]
                run.setdefault("heights", []).append([(step + 1) * dt, bq[2]])
                if setup.get("record"):  # body_q is px py pz qx qy qz qw; the answer's is xyz, wxyz
                    run.setdefault("root", []).append([(step + 1) * dt, [*bq[:3], bq[6], *bq[3:6]]])
    jq = state0.joint_q.numpy()
    final = {n: float(jq[names[n][0]]) for n in pose}
    worst = max(((abs(v - pose[n]), n) for n, v in final.items()), default=(0.0, ""))
    run.update(final_q=final, drift=worst[0], worst_joint=worst[1], peak_effort=peak)
    if floor:
        bq = state0.body_q.numpy()[root_body]
        qx, qy = float(bq[3]), float(bq[4])
        run.update(height=float(bq[2]), tilt=math.acos(max(-1.0, min(1.0, 1.0 - 2.0 * (qx * qx + qy * qy)))))
    return run


def _start(model, state, control, q, pose, names):
    """The state at coordinates ``q`` (bodies by forward kinematics), drive targets at ``pose``."""
    import newton

    state.joint_q.assign(q)
    newton.eval_fk(model, state.joint_q, state.joint_qd, state)
    if control.joint_target_q is not None:
        target = control.joint_target_q.numpy().copy()
        for n, v in pose.items():
            target[names[n][0]] = v
        control.joint_target_q.assign(target)


def _drives(model, control, names, pose):
    """Joint -> (q index, qd index, ke, kd, target, effort limit) for the driven joints: the drive's
    effort, ke (target - q) - kd qd, is evaluated after every step (implicit drives apply it at the
    step's end), clamped to the effort limit Newton read."""
    ke, kd = getattr(model, "joint_target_ke", None), getattr(model, "joint_target_kd", None)
    if ke is None or kd is None or control.joint_target_q is None:
        return {}
    ke, kd = ke.numpy(), kd.numpy()
    limits = getattr(model, "joint_effort_limit", None)
    limits = limits.numpy() if limits is not None else None
    targets = control.joint_target_q.numpy()  # coordinate layout, as joint_q
    q_starts, qd_starts = model.joint_q_start.numpy(), model.joint_qd_start.numpy()
    dof_of_q = {int(q_starts[j]): int(qd_starts[j]) for j in range(len(qd_starts) - 1)}
    out = {}
    for n in pose:
        qi = names[n][0]
        di = dof_of_q.get(qi)
        if di is None:
            continue
        limit = float(limits[di]) if limits is not None else 0.0
        out[n] = (qi, di, float(ke[di]), float(kd[di]), float(targets[qi]), limit if limit < 1e30 else 0.0)
    return out


def _block_travel(mu, angle, setup):
    """A horizontal plane with gravity tilted by ``angle``: the same as a tilted plane."""
    import newton
    import numpy as np
    import warp as wp

    g = 9.81
    builder = _builder(gravity=(g * math.sin(angle), 0.0, -g * math.cos(angle)))
    cfg = newton.ModelBuilder.ShapeConfig(mu=mu)
    builder.add_ground_plane(cfg=cfg)
    body = builder.add_body(xform=wp.transform((0.0, 0.0, _BOX_H + 1e-4), wp.quat_identity()))
    box_cfg = newton.ModelBuilder.ShapeConfig(mu=mu, density=1.0 / (8 * _BOX * _BOX * _BOX_H))
    builder.add_shape_box(body, hx=_BOX, hy=_BOX, hz=_BOX_H, cfg=box_cfg)
    model = builder.finalize(device="cpu")
    s0, s1, control = model.state(), model.state(), model.control()
    newton.eval_fk(model, s0.joint_q, s0.joint_qd, s0)
    start = s0.body_q.numpy()[0][:3].copy()
    solver = newton.solvers.SolverMuJoCo(model, use_mujoco_cpu=True, cone="elliptic")
    dt = setup["timestep"]
    for _ in range(max(1, round(setup["duration"] / dt))):
        s0.clear_forces()
        solver.step(s0, s1, control, None, dt)
        s0, s1 = s1, s0
    return float(np.linalg.norm(s0.body_q.numpy()[0][:3] - start))


def _slide(req, mu):
    from worker_loop import slide_run

    if mu is None:
        _, mu = _load(req, floating=False)
    return slide_run("Newton", mu, lambda angle: _block_travel(mu, angle, req["setup"]))


def _version():
    import newton

    return newton.__version__


def _terrain_heightfields(builder, fields):
    """Every static triangle mesh of the world stage (its terrains: the robot's shapes all belong to
    bodies) out of collision, and each terrain's heightfield (``fields``: .npz files robodesc
    rasterized, MJCF's grid) in its place. Newton's MuJoCo solver collides a mesh as its convex hull,
    and a heightfield as one: a box dropped into gap_40cm's gap rests on the hull, falls in here.
    Returns the labels of the meshes taken out."""
    import newton
    import numpy as np
    import warp as wp

    if not fields:
        return []
    out = []
    for i in range(len(builder.shape_type)):
        if builder.shape_body[i] == -1 and builder.shape_type[i] == newton.GeoType.MESH:
            builder.shape_flags[i] &= ~int(newton.ShapeFlags.COLLIDE_SHAPES)
            out.append(str(builder.shape_label[i]))
    for field in fields:
        data = np.load(field["npz"])
        z, x0, y0, step = data["z"], float(data["x0"]), float(data["y0"]), float(data["step"])
        tx, ty, tz, yaw = (float(v) for v in data["frame"])
        rows, cols = z.shape
        hx, hy = (cols - 1) * step / 2, (rows - 1) * step / 2
        cx, cy = x0 + hx, y0 + hy  # the grid's centre in the terrain's frame
        c, s = math.cos(yaw), math.sin(yaw)
        xform = wp.transform((tx + c * cx - s * cy, ty + s * cx + c * cy, tz), wp.quat_rpy(0.0, 0.0, yaw))
        field_ = newton.Heightfield(
            data=z.astype(np.float32), nrow=rows, ncol=cols, hx=hx, hy=hy, min_z=float(z.min()), max_z=float(z.max())
        )
        builder.add_shape_heightfield(xform=xform, heightfield=field_, label=field.get("label"))
    return out


def _stand(req):
    """The stand on a world: the world stage as Newton reads it (``add_usd``), its terrains as
    heightfields (:func:`_terrain_heightfields`), the robot's joints at the home pose and its free
    root at the spawn; the feet's body poses at the start and the end."""
    import newton
    import numpy as np

    setup = req["setup"]
    world = setup["world"]
    builder = _builder()
    fields = world.get("heightfields") or []
    if fields:
        # Newton's default contact gap (0.1 m) reaches MuJoCo as every geom's ``gap``, and against a
        # heightfield MuJoCo 3.17 then keeps no contact active: the robot and a box fell through it.
        builder.rigid_gap = 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        builder.add_usd(req["usd"], floating=True, enable_self_collisions=False, load_visual_shapes=False)
    swapped = _terrain_heightfields(builder, fields)
    model = builder.finalize(device="cpu")
    names = _names(model, req["usd"])
    pose = {n: v for n, v in setup["pose"].items() if n in names and names[n][1] == 1}
    labels = [_short(str(b)) for b in model.body_label]
    root = labels.index(req["root"]) if req["root"] in labels else 0
    free = [j for j in range(model.joint_count) if int(model.joint_child.numpy()[j]) == root]
    if not free:
        return {"scenario": "stand", "ok": False, "error": "the robot's root has no joint Newton can move"}
    start = int(model.joint_q_start.numpy()[free[0]])
    q = model.joint_q.numpy().copy()
    for n, v in pose.items():
        q[names[n][0]] = v
    x, y, z, yaw = world["spawn"]
    q[start : start + 7] = [x, y, z, 0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)]
    state0, state1, control = model.state(), model.state(), model.control()
    _start(model, state0, control, q, pose, names)
    feet = {n: labels.index(n) for n in world["feet"] if n in labels}

    def poses():
        bq = state0.body_q.numpy()
        # Newton's transforms: px py pz qx qy qz qw; the answer's: x y z qw qx qy qz.
        return {
            n: [*(float(v) for v in bq[i][:3]), float(bq[i][6]), *(float(v) for v in bq[i][3:6])]
            for n, i in feet.items()
        }

    run = {"scenario": "stand", "ok": True, "error": "", "feet_start": poses(), "terrain_swapped": swapped}
    solver = newton.solvers.SolverMuJoCo(model, use_mujoco_cpu=True)
    dt = setup["timestep"]
    for _ in range(max(1, round(world["duration"] / dt))):
        state0.clear_forces()
        solver.step(state0, state1, control, None, dt)
        state0, state1 = state1, state0
    bq = state0.body_q.numpy()
    if not np.all(np.isfinite(bq)):
        return {**run, "ok": False, "error": f"state not finite after {world['duration']:.3g} s"}
    qx, qy = float(bq[root][3]), float(bq[root][4])
    prefix = str(model.body_label[root]).rsplit("/", 1)[0]
    masses = model.body_mass.numpy()
    run.update(
        feet_end=poses(),
        height=float(bq[root][2]),
        tilt=math.acos(max(-1.0, min(1.0, 1.0 - 2.0 * (qx * qx + qy * qy)))),
        mass=float(sum(m for m, label in zip(masses, model.body_label, strict=True) if str(label).startswith(prefix))),
    )
    return run


def _scenario(req, name, mu):
    if name == "stand":
        return _stand(req)
    return _slide(req, mu) if name == "slide" else _run_robot(req, name)


if __name__ == "__main__":
    from worker_loop import serve

    serve("newton", _version, _scenario)
