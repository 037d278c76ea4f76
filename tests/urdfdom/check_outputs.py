"""Compile every robot of the examples, the compositions, the fuzz seeds and the corpus to each URDF
robodesc writes for ROS (``-t urdf`` from a composition, ``--ros2``, ``-t isaac``) and run urdfdom's
``check_urdf`` on the result (the test tier, ``tests/urdfdom/run.sh``); with ``ROBODESC_HOLOSCRIPT_DIR``
set, also every ``.holo`` file of that folder (HoloScript's own robot files, not part of robodesc).

Prints one line per output and a summary; exits 1 when urdfdom refused any output that robodesc wrote
for ROS. ``-t urdf`` of a URDF input is a faithful round trip: it is checked and reported, but its
refusals (a pybullet file's capsules) are the source's, and robodesc said so in a warning.
"""

from __future__ import annotations

import argparse
import glob
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
COMPOSITION = (".yaml", ".holo", ".py")


def inputs(corpus: bool) -> list[tuple[str, list[str]]]:
    """(input file, extra CLI arguments)."""
    out: list[tuple[str, list[str]]] = []
    ex = os.path.join(ROOT, "examples")
    for path in sorted(glob.glob(os.path.join(ex, "*.*"))):
        out.append((path, []))
    out.append((os.path.join(ex, "urdf", "gripper_arm.urdf"), []))
    out.append((os.path.join(ex, "urdf", "pendulum.urdf.xacro"), ["--package", f"robodesc_examples={ex}/urdf"]))
    for path in sorted(glob.glob(os.path.join(ROOT, "tests", "compose", "holo", "*.holo"))):
        out.append((path, []))
    for path in sorted(glob.glob(os.path.join(ROOT, "tests", "fuzz", "seeds", "*.*"))):
        if os.path.isfile(path):
            out.append((path, []))
    for path in sorted(glob.glob(os.path.join(HERE, "fixtures", "*.urdf"))):
        out.append((path, []))
    if corpus:
        sys.path.insert(0, os.path.join(ROOT, "src"))
        from robodesc.validation.corpora import all_robots

        for robot in all_robots(os.path.join(ROOT, "..", "shared", "corpus")):
            extra: list[str] = []
            for name, folder in robot.packages.items():
                extra += ["--package", f"{name}={folder}"]
            out.append((robot.path, extra))
        holo = os.path.join(ROOT, "..", "shared", "corpus", "holoscript", "isaac-sim-robot-arm.holo")
        if os.path.isfile(holo):
            out.append((holo, []))
    # HoloScript's own robot files, when the tier is given a folder of them (tests/urdfdom/run.sh).
    holoscript = os.environ.get("ROBODESC_HOLOSCRIPT_DIR")
    if holoscript:
        for path in sorted(glob.glob(os.path.join(holoscript, "**", "*.holo"), recursive=True)):
            out.append((path, []))
    return out


def compile_one(path: str, extra: list[str], target: str, out: str) -> tuple[int, str]:
    cmd = [sys.executable, "-m", "robodesc", "compile", path, "-t", target, "-o", out, "-q", "--no-validate", *extra]
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"))
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=600)
    return proc.returncode, proc.stderr.strip()


def check_urdf(path: str, binary: str = "check_urdf") -> tuple[bool, str]:
    proc = subprocess.run([binary, path], capture_output=True, text=True, timeout=120)
    text = (proc.stdout + proc.stderr).strip().splitlines()
    # urdfdom logs some refusals (a <capsule> visual of URDF 1.0) and still loads the rest, without
    # the element: an "Error:" line counts as a refusal too.
    errors = [line.strip() for line in text if line.lstrip().startswith("Error")]
    return proc.returncode == 0 and not errors, (errors[0] if errors else (text[-1] if text else ""))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--corpus", action="store_true", help="also the real-robot corpus (slow)")
    parser.add_argument("--targets", default="urdf,ros2,isaac")
    args = parser.parse_args()
    if shutil.which("check_urdf") is None:
        print("check_urdf not found: apt-get install liburdfdom-tools", file=sys.stderr)
        return 2
    checked = refused_ros = refused_roundtrip = skipped = 0
    with tempfile.TemporaryDirectory() as tmp:
        for n, (path, extra) in enumerate(inputs(args.corpus)):
            for target in args.targets.split(","):
                out = os.path.join(tmp, f"{n}_{target}" + (".urdf" if target == "urdf" else ""))
                code, err = compile_one(path, extra, target, out)
                rel = os.path.relpath(path, ROOT)
                if code != 0:
                    skipped += 1
                    print(f"skip   {target:5} {rel}: compile exit {code}: {err.splitlines()[-1] if err else ''}")
                    continue
                files = [out] if target == "urdf" else sorted(glob.glob(os.path.join(out, "*.urdf")))
                for urdf in files:
                    ok, msg = check_urdf(urdf)
                    checked += 1
                    for_ros = target != "urdf" or path.endswith(COMPOSITION)
                    if not ok:
                        if for_ros:
                            refused_ros += 1
                        else:
                            refused_roundtrip += 1
                    verdict = "ok" if ok else ("REFUSED" if for_ros else "refused (round trip of the source)")
                    print(f"{verdict:7} {target:5} {rel}: {'' if ok else msg}")
    print(
        f"check_urdf: {checked} outputs checked, {refused_ros} written for ROS refused, "
        f"{refused_roundtrip} faithful URDF round trips refused, {skipped} not compiled"
    )
    return 1 if refused_ros else 0


if __name__ == "__main__":
    sys.exit(main())
