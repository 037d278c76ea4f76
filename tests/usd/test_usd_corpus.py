"""Every real robot of the corpora converts to USD and reads back consistently.

Slow tier (``-m slow``). Per robot: load → isaac_sim passes (sanitize names, unique materials,
inertia repair) → emit_usd → usd-core physics parser → compare with the IR (bodies, joints, limits,
drives, masses, articulation root) and forward kinematics at one random configuration. A summary
table with the reason of every failure and the time per robot is printed.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import pytest
from usd_readback import check_against_ir, parse, random_configurations, usd_forward_kinematics

from robodesc.emit.usd import UsdOptions, emit_usd
from robodesc.frontends.load import load_path
from robodesc.frontends.options import LoadOptions, MissingMesh
from robodesc.ir.diagnostics import RobodescError
from robodesc.ir.transforms import forward_kinematics
from robodesc.validation.corpora import all_robots

SHARED_CORPUS = Path(__file__).resolve().parents[2] / ".." / "shared" / "corpus"


def _passes():  # type: ignore[no-untyped-def]
    try:
        from robodesc.passes.pipeline import run_passes
    except ImportError:
        return None
    return run_passes


@pytest.mark.slow
def test_corpus_converts(tmp_path: Path) -> None:
    robots = all_robots(str(SHARED_CORPUS))
    if not robots:
        pytest.skip("no corpus installed")
    run_passes = _passes()
    rows: list[tuple[str, str, str, float, str]] = []
    failures: list[str] = []
    for entry in robots:
        label = f"{entry.corpus}/{entry.name}"
        start = time.perf_counter()
        stage = "load"
        try:
            loaded = load_path(
                entry.path,
                LoadOptions(package_paths=entry.packages, xacro_args=entry.xacro_args, missing_mesh=MissingMesh.WARN),
            )
            robot = loaded.robot
            stage = "passes"
            if run_passes is None:
                rows.append((label, "skipped", stage, 0.0, "passes package not available (names not sanitized)"))
                continue
            run_passes(robot, preset="isaac_sim")
            stage = "emit"
            out = tmp_path / f"{entry.corpus}_{entry.name.replace('/', '_')}.usdc"
            floating = any(j.type.dof == 6 for j in robot.joints)
            options = UsdOptions(fix_base=not floating)
            emit_start = time.perf_counter()
            findings = emit_usd(robot, str(out), options)
            emit_time = time.perf_counter() - emit_start
            stage = "readback"
            parsed = parse(str(out))
            check_against_ir(parsed, robot, options)
            q = random_configurations(robot, 1, seed=7)[0]
            expected = forward_kinematics(robot, q)
            got = usd_forward_kinematics(parsed, q)
            worst = max(float(np.abs(got[name] - m).max()) for name, m in expected.items())
            assert worst < 1e-5, f"forward kinematics differs by {worst:.3g}"
            notes = sorted({f.code for f in findings})
            rows.append((label, "ok", f"emit {emit_time * 1000:.0f} ms", time.perf_counter() - start, ", ".join(notes)))
        except RobodescError as exc:
            # An input defect robodesc reports cleanly (before or in the emitter) is not a crash.
            rows.append((label, "refused", stage, time.perf_counter() - start, str(exc)[:160]))
        except Exception as exc:
            rows.append((label, "FAILED", stage, time.perf_counter() - start, f"{type(exc).__name__}: {exc}"[:160]))
            failures.append(f"{label}: {stage}: {type(exc).__name__}: {exc}")
    width = max(len(r[0]) for r in rows)
    print(f"\n{'robot'.ljust(width)}  status   stage/emit      total s  notes")
    for label, status, stage, seconds, notes in rows:
        print(f"{label.ljust(width)}  {status.ljust(7)}  {stage.ljust(14)}  {seconds:7.2f}  {notes}")
    ok = sum(1 for r in rows if r[1] == "ok")
    print(f"{ok}/{len(rows)} converted; total {sum(r[3] for r in rows):.1f} s")
    assert not failures, "\n".join(failures)
