"""Independent URDF consumers for tests: Pinocchio and yourdfpy read the source and robodesc's output,
and the numbers they report are compared."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin


@dataclass
class PinView:
    model: pin.Model

    @classmethod
    def from_text(cls, text: str) -> PinView:
        return cls(pin.buildModelFromXML(text))

    def frames(self) -> list[str]:
        return [f.name for f in self.model.frames]

    def compare(self, other: PinView, *, samples: int = 5, tol: float = 1e-9, seed: int = 0) -> list[str]:
        """Differences between two models of the same robot, as readable lines (empty when identical)."""
        a, b = self.model, other.model
        out: list[str] = []
        if [a.names[i] for i in range(a.njoints)] != [b.names[i] for i in range(b.njoints)]:
            return ["joint names differ"]
        if a.nq != b.nq:
            return [f"nq {a.nq} != {b.nq}"]
        if self.frames() != other.frames():
            return ["frame names differ"]
        for name, x, y in (
            ("lower limits", a.lowerPositionLimit, b.lowerPositionLimit),
            ("upper limits", a.upperPositionLimit, b.upperPositionLimit),
            ("effort limits", a.effortLimit, b.effortLimit),
            ("velocity limits", a.velocityLimit, b.velocityLimit),
            ("damping", a.damping, b.damping),
            ("friction", a.friction, b.friction),
        ):
            if not np.allclose(x, y, rtol=0, atol=tol, equal_nan=True):
                out.append(f"{name} differ")
        for i in range(a.njoints):
            ia, ib = a.inertias[i], b.inertias[i]
            if abs(ia.mass - ib.mass) > tol * max(1.0, abs(ia.mass)):
                out.append(f"mass of joint body {a.names[i]}: {ia.mass} != {ib.mass}")
            if not np.allclose(ia.lever, ib.lever, atol=tol) or not np.allclose(ia.inertia, ib.inertia, atol=tol):
                out.append(f"inertia of joint body {a.names[i]} differs")
        rng = np.random.default_rng(seed)
        da, db = a.createData(), b.createData()
        for _ in range(samples):
            lo = np.where(np.isfinite(a.lowerPositionLimit), a.lowerPositionLimit, -np.pi)
            hi = np.where(np.isfinite(a.upperPositionLimit), a.upperPositionLimit, np.pi)
            q = lo + (hi - lo) * rng.random(a.nq) if a.nq else np.zeros(0)
            pin.framesForwardKinematics(a, da, q)
            pin.framesForwardKinematics(b, db, q)
            for k, frame in enumerate(a.frames):
                if not np.allclose(da.oMf[k].homogeneous, db.oMf[k].homogeneous, atol=tol):
                    out.append(f"forward kinematics of frame {frame.name} differs")
                    break
        return out
