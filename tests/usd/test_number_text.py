"""The C number parser (``robodesc.meshes._numtext``) against numpy.fromstring, the parser it replaced.

Both must give the same doubles bit for bit (the golden files and the pycollada comparison rest on
it) and refuse the same tokens. The numpy fallback, used when the extension was not built, is run
through the same mesh reader to show both give one result.
"""

from __future__ import annotations

import random
from array import array
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest
from lxml import etree
from test_mesh_readers import corpus_files, dae, geometry, instance, node, triangles

from robodesc.meshes import text_numbers as number_text
from robodesc.meshes.collada import read_collada


@contextmanager
def numpy_only() -> Iterator[None]:
    """number_text as installed without a C compiler: numpy.fromstring parses."""
    native = number_text._numtext
    number_text._numtext = None
    try:
        yield
    finally:
        number_text._numtext = native


def numpy_floats(text: str) -> array[float] | None:
    with numpy_only():
        return number_text.parse_floats(text)


def assert_same_floats(text: str) -> None:
    got = number_text.parse_floats(text)
    expected = numpy_floats(text)
    assert got is not None and expected is not None, text
    assert got.tobytes() == expected.tobytes(), text


def test_native_parser_is_built() -> None:
    # pip install (the README's commands, CI) compiles it; a plain source checkout on PYTHONPATH
    # does not, and then runs the numpy fallback, slower.
    assert number_text.native(), "robodesc.meshes._numtext is not built: pip install -e . compiles it"


def random_token(rng: random.Random) -> str:
    value = rng.choice(
        [
            rng.uniform(-1, 1),
            rng.uniform(-1e3, 1e3),
            rng.lognormvariate(0, 30) * rng.choice([-1, 1]),
            rng.randint(-(10**6), 10**6),
            rng.choice([0.0, -0.0, 1e-300, 5e-324, 1.7976931348623157e308, 2.0**53, 2.0**53 + 2]),
        ]
    )
    style = rng.randrange(9)
    if style == 0:
        return repr(float(value))
    if style == 1:
        return f"{value:.7g}"
    if style == 2:
        return f"{value:.10f}"
    if style == 3:
        return f"{value:.17e}"
    if style == 4:
        return f"{value:+.6E}"
    if style == 5:  # leading zeros, a bare point, no fraction digits
        return rng.choice(["007.5", "-0.", ".5", "+.25e-3", "1.", "0000", "-0", "1e+22", "1e-22", "9e23"])
    if style == 6:  # more digits than the fast path takes
        return f"{rng.randint(10**18, 10**25)}.{rng.randint(0, 10**9)}"
    if style == 7:
        return rng.choice(["nan", "-nan", "inf", "-Infinity", "+inf", "NaN", "1e400", "-1e-400"])
    return str(int(value))


@pytest.mark.parametrize("seed", range(5))
def test_random_floats_like_numpy(seed: int) -> None:
    rng = random.Random(seed)
    tokens = [random_token(rng) for _ in range(4000)]
    for token in tokens:
        assert_same_floats(token)
    assert_same_floats(rng.choice([" ", "\n", "\t", "\r\n "]).join(tokens))


@pytest.mark.parametrize(
    "text", ["1 x 2", "1,2", "1e", "1e+", "--1", "0x10", "1_000", "1.2.3", ".", "+", "1 2 3f", "inf1"]
)
def test_bad_floats_refused_like_numpy(text: str) -> None:
    assert number_text.parse_floats(text) is None
    assert numpy_floats(text) is None


@pytest.mark.parametrize(
    ("text", "expected"),
    [("", []), ("  \n\t ", []), ("1 2\n3", [1, 2, 3]), ("-7 +8", [-7, 8]), ("9223372036854775807", [2**63 - 1])],
)
def test_ints(text: str, expected: list[int]) -> None:
    got = number_text.parse_ints(text)
    assert got is not None and got.typecode == "q"
    assert got.tolist() == expected


@pytest.mark.parametrize("text", ["1.5", "1e3", "x", "9223372036854775808", "1 2 -", "0x1"])
def test_bad_ints_refused(text: str) -> None:
    assert number_text.parse_ints(text) is None


def test_numpy_fallback_reads_the_same(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    scene = node("<rotate>0 0 1 30</rotate><translate>0.1 -2e-3 7</translate>" + instance("g"))
    path = tmp_path / "mesh.dae"
    path.write_text(dae(geometry("g", triangles("g", "0 1 2 0 2 3 3 4 5")), scene))
    native = read_collada(str(path))
    monkeypatch.setattr(number_text, "_numtext", None)
    assert not number_text.native()
    assert read_collada(str(path)).tobytes() == native.tobytes()
    assert number_text.parse_floats(" \n ") is not None
    assert number_text.parse_floats("1 x") is None


@pytest.mark.slow
def test_corpus_numbers_like_numpy() -> None:
    # Every number array of every COLLADA file in the corpora, parsed both ways.
    files = corpus_files(".dae")
    if not files:
        pytest.skip("no COLLADA corpus installed")
    arrays = 0
    for path in files:
        parser = etree.XMLParser(huge_tree=True, resolve_entities=False, no_network=True)
        for element in etree.parse(path, parser).iter("{*}float_array", "{*}p", "{*}vcount"):
            text = element.text or ""
            if not text.strip():
                continue
            arrays += 1
            if etree.QName(element).localname == "float_array":
                assert_same_floats(text)
            else:
                got = number_text.parse_ints(text)
                with numpy_only():
                    expected = number_text.parse_ints(text)
                assert got is not None and expected is not None and got.tobytes() == expected.tobytes()
    assert arrays > 1000
