"""Shared test fixtures.

Golden files live beside the tests that use them (``tests/<area>/golden/``). Regenerate them with
``pytest --update-golden`` and review the diff like code.
"""

from __future__ import annotations

import difflib
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SHARED = (ROOT / ".." / "shared").resolve()
CORPUS = SHARED / "corpus"
QUADSDK = CORPUS / "quadsdk"
SPIRIT_XACRO = QUADSDK / "spirit_description/models/spirit/urdf/spirit.urdf.xacro"
GO2_XACRO = QUADSDK / "go2_description/models/go2/urdf/go2.urdf.xacro"
WORLDS = QUADSDK / "worlds"
HOLO_ARM = CORPUS / "holoscript/isaac-sim-robot-arm.holo"
EXAMPLES = ROOT / "examples"


def pytest_addoption(parser: pytest.Parser) -> None:
    parser.addoption("--update-golden", action="store_true", help="rewrite golden files from the current output")


class Golden:
    def __init__(self, directory: Path, update: bool) -> None:
        self.directory = directory
        self.update = update

    def check(self, name: str, actual: str) -> None:
        path = self.directory / name
        if self.update:
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(actual, encoding="utf-8")
            return
        if not path.exists():
            pytest.fail(f"golden file {path} is missing; run pytest --update-golden and review it")
        expected = path.read_text(encoding="utf-8")
        if expected != actual and not same_within_rounding(expected, actual):
            diff = "".join(
                list(difflib.unified_diff(expected.splitlines(True), actual.splitlines(True), str(path), "actual"))[:80]
            )
            pytest.fail(f"output differs from golden file {path} (pytest --update-golden rewrites it):\n{diff}")


# Numbers computed through BLAS (mesh inertia via trimesh and numpy's dot products) differ in the
# last bits between OpenBLAS kernels (OPENBLAS_CORETYPE=SkylakeX vs Haswell): golden files compare
# every number at this relative tolerance, and everything else exactly.
GOLDEN_REL_TOL = 1e-12
_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def same_within_rounding(expected: str, actual: str) -> bool:
    """True when the texts differ only in numbers, each within GOLDEN_REL_TOL (relative to the
    larger magnitude, with an absolute floor of GOLDEN_REL_TOL * 1e-12 for values near zero)."""
    if _NUMBER.sub("#", expected) != _NUMBER.sub("#", actual):
        return False
    for a, b in zip(_NUMBER.findall(expected), _NUMBER.findall(actual), strict=True):
        if a == b:
            continue
        x, y = float(a), float(b)
        if abs(x - y) > GOLDEN_REL_TOL * max(abs(x), abs(y), 1e-12):
            return False
    return True


@pytest.fixture
def golden(request: pytest.FixtureRequest) -> Golden:
    directory = Path(request.node.fspath).parent / "golden"
    return Golden(directory, bool(request.config.getoption("--update-golden")))


# The tests of PhysX as a structural consumer; every other test compiles USD without it (about 5 s a
# compile where a PhysX interpreter exists: docs/validation.md, "USD in PhysX").
PHYSX_CONSUMER_TESTS = {"test_physx_consumer.py", "test_physx_tier.py"}


@pytest.fixture(autouse=True)
def _physx_check_only_where_tested(request: pytest.FixtureRequest, monkeypatch: pytest.MonkeyPatch) -> None:
    if Path(request.node.fspath).name not in PHYSX_CONSUMER_TESTS:
        monkeypatch.setenv("ROBODESC_VALIDATE_PHYSX", "0")


@pytest.fixture(autouse=True)
def _single_thread_usd(monkeypatch: pytest.MonkeyPatch) -> None:
    # usd-core's physics parser has crashed with many colliders on one body when threaded.
    monkeypatch.setenv("PXR_WORK_THREAD_LIMIT", "1")
    os.environ.setdefault("PXR_WORK_THREAD_LIMIT", "1")
