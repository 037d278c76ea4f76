"""Principal moments and axes of inertia tensors, and their physical-validity check, in plain floats.

A 3x3 symmetric eigenproblem is solved here with cyclic Jacobi rotations instead of LAPACK: the
verifier and the USD emitter need it for every link, and importing numpy for it would cost more than
converting a small robot. Jacobi is also the most accurate method for this size (it finds small
moments to full relative precision) and, unlike LAPACK, gives the same bits on every machine.
"""

from __future__ import annotations

import math

from robodesc.ir.geometry import Inertia, Vec3
from robodesc.ir.rigid import Mat3, determinant, matmul, transpose

# Sweeps of all three rotations; 3x3 problems converge in 4 to 6.
_MAX_SWEEPS = 50
_PAIRS = ((0, 1), (0, 2), (1, 2))


def tensor_rows(inertia: Inertia) -> Mat3:
    i = inertia
    return ((i.ixx, i.ixy, i.ixz), (i.ixy, i.iyy, i.iyz), (i.ixz, i.iyz, i.izz))


def symmetric_eigen(m: Mat3) -> tuple[Vec3, Mat3]:
    """Eigenvalues (ascending) and a right-handed rotation whose columns are the matching unit
    eigenvectors, of a finite symmetric 3x3 matrix (only its upper triangle is read).

    Each eigenvector's sign is a convention: of the rotations with these axes, the one closest to
    the identity (largest trace), so a nearly diagonal tensor gets nearly the identity."""
    a = [
        [float(m[0][0]), float(m[0][1]), float(m[0][2])],
        [0.0, float(m[1][1]), float(m[1][2])],
        [0.0, 0.0, float(m[2][2])],
    ]
    v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    for sweep in range(_MAX_SWEEPS):
        if a[0][1] == 0.0 and a[0][2] == 0.0 and a[1][2] == 0.0:
            break
        for p, q in _PAIRS:
            _rotate(a, v, p, q, late=sweep >= 3)
    values = (a[0][0], a[1][1], a[2][2])
    order = sorted(range(3), key=lambda k: values[k])
    columns = [(v[0][k], v[1][k], v[2][k]) for k in order]
    if determinant(transpose((columns[0], columns[1], columns[2]))) < 0:
        columns[2] = (-columns[2][0], -columns[2][1], -columns[2][2])
    # Flipping two axes keeps the rotation proper: pick the flip with the largest trace.
    best = max(
        ((1, 1, 1), (-1, -1, 1), (-1, 1, -1), (1, -1, -1)), key=lambda s: sum(s[k] * columns[k][k] for k in range(3))
    )
    signed = [(best[k] * c[0], best[k] * c[1], best[k] * c[2]) for k, c in enumerate(columns)]
    rotation = transpose((signed[0], signed[1], signed[2]))
    return (values[order[0]], values[order[1]], values[order[2]]), rotation


def _rotate(a: list[list[float]], v: list[list[float]], p: int, q: int, *, late: bool) -> None:
    """One Jacobi rotation zeroing ``a[p][q]`` (Numerical Recipes' ``jacobi``, upper triangle only)."""
    apq = a[p][q]
    if apq == 0.0:
        return
    g = 100.0 * abs(apq)
    app, aqq = a[p][p], a[q][q]
    if late and abs(app) + g == abs(app) and abs(aqq) + g == abs(aqq):
        a[p][q] = 0.0  # below the diagonal's rounding: converged
        return
    h = aqq - app
    if abs(h) + g == abs(h):
        t = apq / h  # t = 1 / (2 theta) when theta overflows
    else:
        theta = 0.5 * h / apq
        t = 1.0 / (abs(theta) + math.sqrt(1.0 + theta * theta))
        if theta < 0.0:
            t = -t
    c = 1.0 / math.sqrt(1.0 + t * t)
    s = t * c
    tau = s / (1.0 + c)
    a[p][p] = app - t * apq
    a[q][q] = aqq + t * apq
    a[p][q] = 0.0
    r = 3 - p - q  # the third index
    arp = a[min(r, p)][max(r, p)]
    arq = a[min(r, q)][max(r, q)]
    a[min(r, p)][max(r, p)] = arp - s * (arq + arp * tau)
    a[min(r, q)][max(r, q)] = arq + s * (arp - arq * tau)
    for row in v:
        vp, vq = row[p], row[q]
        row[p] = vp - s * (vq + vp * tau)
        row[q] = vq + s * (vp - vq * tau)


def principal_moments(m: Mat3) -> Vec3:
    return symmetric_eigen(m)[0]


def rotate_tensor(m: Mat3, rotation: Mat3) -> Mat3:
    """A tensor given in frame B expressed in frame A, where ``rotation`` maps B to A."""
    return matmul(matmul(rotation, m), transpose(rotation))


def inertia_problem(inertia: Inertia, *, rel_tol: float = 1e-6) -> str | None:
    """Why a tensor is not physical, or ``None``.

    Physical means: symmetric positive definite, and the principal moments satisfy the triangle
    inequality (each at most the sum of the other two). ``rel_tol`` absorbs the rounding of the
    printed values that real files carry (a thin rod's I1 + I2 = I3 exactly).
    """
    m = tensor_rows(inertia)
    flat = [x for row in m for x in row]
    if not all(math.isfinite(x) for x in flat):
        return "inertia has a non-finite value"
    if not any(flat):
        return "inertia tensor is zero"
    a, b, c = principal_moments(m)
    scale = max(abs(a), abs(b), abs(c))
    # The moments are exact to ~1e-16 relative; anything below 1e-14 of the largest one is zero.
    if a <= 1e-14 * scale:
        return f"inertia tensor is not positive definite (principal moments {a:.6g}, {b:.6g}, {c:.6g})"
    if c > (a + b) * (1 + rel_tol) + rel_tol * scale:
        return f"principal moments break the triangle inequality ({c:.6g} > {a:.6g} + {b:.6g})"
    return None


# Newton 1.8 (newton/_src/geometry/inertia.py, verify_and_correct_inertia) "corrects" a tensor whose
# smallest principal moment is below max(1e-6 x the largest, 1e-10 kg·m²), by adding that threshold
# plus 1e-6 kg·m² to the diagonal: for a light body (go1's 1e-6 kg "base") a change of orders of
# magnitude, made silently in the USD it loads ("Inertia validation corrected 1 bodies").
ENGINE_REL_FLOOR = 1e-6
ENGINE_ABS_FLOOR = 1e-10  # kg·m²


def engine_floor(inertia: Inertia) -> float:
    """The smallest principal moment Newton leaves alone for this tensor (kg·m²)."""
    c = max(principal_moments(tensor_rows(inertia)))
    return max(ENGINE_REL_FLOOR * c, ENGINE_ABS_FLOOR)


def below_engine_floor(inertia: Inertia) -> str | None:
    """Why Newton would change a physical tensor, or ``None``."""
    a, _, c = principal_moments(tensor_rows(inertia))
    floor = max(ENGINE_REL_FLOOR * c, ENGINE_ABS_FLOOR)
    if a < floor:
        return (
            f"smallest principal moment {a:.3g} kg·m² is below {floor:.3g} (Newton raises it, adding "
            "about 1e-6 kg·m² to every moment)"
        )
    return None
