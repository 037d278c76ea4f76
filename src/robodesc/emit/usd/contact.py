"""Contact in USD: physics materials bound to colliders, in UsdPhysics', PhysX's and Newton's terms.

One material per distinct set of contact parameters, under ``<robot>/PhysicsMaterials``, bound to
each collider with the physics purpose (``material:binding:physics``), so colliders with equal
properties share one. The mapping from the IR (Gazebo's ODE vocabulary, SI), docs/contact.md:

- ``mu`` -> ``physics:staticFriction`` and ``physics:dynamicFriction`` (ODE has one Coulomb
  coefficient; PhysX, Newton and MuJoCo have one isotropic coefficient: a different ``mu2`` or an
  ``fdir1`` cannot be carried, and a warning says so);
- ``restitution`` -> ``physics:restitution``;
- ``kp``/``kd`` -> PhysX compliant contact (``physxMaterial:compliantContactStiffness`` N/m,
  ``...Damping`` N·s/m) and ``newton:contactStiffness``/``newton:contactDamping``;
- ``torsional``/``rolling`` -> ``newton:torsionalFriction``/``newton:rollingFriction`` (m);
- ``min_depth`` -> the collider's ``physxCollision:restOffset`` = -min_depth (it rests that deep);
- ``max_vel`` -> the body's ``physxRigidBody:maxDepenetrationVelocity``;
- the friction combine rule (``--friction-combine``, ``min`` under ``--preset gazebo_parity``, as ODE
  combines) -> ``physxMaterial:frictionCombineMode``. PhysX combines per pair of materials; ODE
  takes the minimum of the two; Isaac Lab's default multiplies.
"""

from __future__ import annotations

from robodesc.emit.usd.context import CONTACT_SCOPE, PHYSICS, UsdContext, unique_name
from robodesc.ir.contact import Contact
from robodesc.usdfile.spec import Prim

# (mu, restitution, kp, kd, torsional, rolling, combine): what makes two materials the same.
MaterialKey = tuple[float | None, float | None, float | None, float | None, float | None, float | None, str | None]


class PhysicsMaterials:
    def __init__(self, ctx: UsdContext) -> None:
        self.ctx = ctx
        self.by_key: dict[MaterialKey, str] = {}
        self.used: set[str] = set()
        self.scope = f"{ctx.robot_path}/{CONTACT_SCOPE}"
        self.warned: set[str] = set()

    def bind(self, prim: Prim, contact: Contact | None, label: str) -> None:
        """Bind the material for ``contact`` to the collider ``prim`` (nothing when neither the
        source nor the options say anything about contact: PhysX's default material applies)."""
        combine = self.ctx.options.friction_combine
        if contact is None and combine is None:
            return
        c = contact or Contact()
        self._warn_unrepresentable(c, label)
        # A bound material's unset friction reads as UsdPhysics' default, 0: say the engine default
        # the collider would have had instead (--default-friction; PhysX's default material: 0.5).
        mu = c.mu if c.mu is not None else self.ctx.options.default_friction
        key: MaterialKey = (mu, c.restitution, c.kp, c.kd, c.torsional, c.rolling, combine)
        if all(v is None for v in key):
            return
        path = self.by_key.get(key)
        if path is None:
            path = self._define(key)
            self.by_key[key] = path
        prim.apply("MaterialBindingAPI")
        prim.rel("material:binding:physics", [path])
        if c.min_depth is not None and self.ctx.options.rest_offset is None:
            prim.apply("PhysxCollisionAPI")
            prim.attr("physxCollision:restOffset", "float", -c.min_depth)

    def _define(self, key: MaterialKey) -> str:
        ctx = self.ctx
        if not self.by_key:
            ctx.define(PHYSICS, self.scope, "Scope")
        path = f"{self.scope}/{unique_name('contact', self.used, 'contact')}"
        material = ctx.define(PHYSICS, path, "Material")
        mu, restitution, kp, kd, torsional, rolling, combine = key
        material.apply("PhysicsMaterialAPI")
        if mu is not None:
            material.attr("physics:staticFriction", "float", mu)
            material.attr("physics:dynamicFriction", "float", mu)
        if restitution is not None:
            material.attr("physics:restitution", "float", restitution)
        if kp is not None or kd is not None or combine is not None:
            material.apply("PhysxMaterialAPI")
            if combine is not None:
                material.attr("physxMaterial:frictionCombineMode", "token", combine, uniform=True)
            if kp is not None:
                material.attr("physxMaterial:compliantContactStiffness", "float", kp)
            if kd is not None:
                material.attr("physxMaterial:compliantContactDamping", "float", kd)
        newton = {
            "newton:contactStiffness": kp,
            "newton:contactDamping": kd,
            "newton:torsionalFriction": torsional,
            "newton:rollingFriction": rolling,
        }
        if any(v is not None for v in newton.values()):
            material.apply("NewtonMaterialAPI")
            for name, value in newton.items():
                if value is not None:
                    material.attr(name, "float", value)
        return path

    def _warn_unrepresentable(self, c: Contact, label: str) -> None:
        lost = []
        if c.mu2 is not None and c.mu is not None and c.mu2 != c.mu:
            lost.append(f"mu2 {c.mu2:g} (PhysX and Newton have one friction coefficient: mu {c.mu:g} is used)")
        if c.fdir1 is not None:
            lost.append("fdir1 (no anisotropic friction direction in UsdPhysics, PhysX or Newton)")
        if c.bounce_threshold is not None and c.restitution:
            lost.append("the bounce threshold (PhysX has one per scene: physxScene:bounceThreshold)")
        for what in lost:
            key = f"{label}:{what.split(' ')[0]}"
            if key in self.warned:
                continue
            self.warned.add(key)
            self.ctx.findings.warn(
                "contact-not-representable",
                f"contact parameter {what}; left out of the USD",
                element=label,
                loc=c.src,
                stage="emit:usd",
            )
