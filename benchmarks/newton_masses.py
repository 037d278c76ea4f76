"""Run in Newton's interpreter (``~/.cache/robodesc-consumers/newton``): the mass Newton's
``add_usd`` gives each body of each USD file named on standard input (one per line), as JSON into
the file named by the first argument: ``{path: {body: kg}}`` or ``{path: "error: ..."}``. Used by
``usd_masses.py``."""

# mypy: ignore-errors
# (runs in its consumer's own interpreter, whose packages the project env does not have)

from __future__ import annotations

import json
import sys


def masses(path: str) -> dict[str, float]:
    """Each body's mass; the key ``"#corrected"`` holds how many bodies Newton's inertia
    validation changed (it warns "Inertia validation corrected N bodies")."""
    import re
    import warnings

    import newton

    builder = newton.ModelBuilder()
    builder.add_usd(path, load_visual_shapes=False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        model = builder.finalize(device="cpu")
    corrected = 0
    for w in caught:
        m = re.search(r"corrected (\d+) bod", str(w.message))
        if m:
            corrected += int(m.group(1))
    labels = getattr(model, "body_label", None) or model.body_key
    out = {str(k): float(m) for k, m in zip(labels, model.body_mass.numpy(), strict=True)}
    out["#corrected"] = float(corrected)
    return out


def main() -> None:
    import warp as wp

    wp.config.quiet = True
    report: dict[str, object] = {}
    for line in sys.stdin:
        path = line.strip()
        if path:
            try:
                report[path] = masses(path)
            except Exception as exc:  # one bad file must not lose the others' numbers
                report[path] = f"error: {exc}"
    with open(sys.argv[1], "w", encoding="utf-8") as f:
        json.dump(report, f)


if __name__ == "__main__":
    main()
