"""How a collider touches the world: friction, restitution and contact compliance.

Gazebo's vocabulary (ODE's, as URDF ``<gazebo>`` blocks and SDF ``<surface>`` write it) is the IR's,
in SI units; each target converts to its engine's own terms (docs/contact.md). Every field is
``None`` when the input did not give it: "not given" is never a default written into the IR.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

from robodesc.ir.diagnostics import SourceLoc

Vec3 = tuple[float, float, float]


@dataclass(slots=True)
class Contact:
    # Coulomb friction coefficients along the first and second friction directions (ODE mu, mu2;
    # Gazebo Classic's mu1, mu2). Most engines have one isotropic coefficient.
    mu: float | None = None
    mu2: float | None = None
    # The first friction direction in the collision's frame (ODE fdir1), for anisotropic friction.
    fdir1: Vec3 | None = None
    torsional: float | None = None  # torsional friction coefficient (spin about the normal)
    rolling: float | None = None  # rolling friction coefficient
    restitution: float | None = None  # coefficient of restitution, 0 to 1
    bounce_threshold: float | None = None  # m/s: slower impacts do not bounce
    kp: float | None = None  # N/m: contact stiffness
    kd: float | None = None  # N·s/m: contact damping
    min_depth: float | None = None  # m: penetration allowed before the contact pushes back
    max_vel: float | None = None  # m/s: largest velocity the contact may use to correct penetration
    src: SourceLoc | None = None

    def given(self) -> dict[str, object]:
        """The parameters the input gave, by name."""
        return {
            f.name: getattr(self, f.name) for f in fields(self) if f.name != "src" and getattr(self, f.name) is not None
        }

    def merged_over(self, base: Contact | None) -> Contact:
        """These parameters, with ``base``'s where these are not given (a collision's own over its link's)."""
        if base is None:
            return self
        values = {name: value for name, value in base.given().items()}
        values.update(self.given())
        return Contact(**values, src=self.src or base.src)  # type: ignore[arg-type]
