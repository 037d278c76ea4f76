"""robodesc's xacro expression evaluator against Python's own evaluation, and its refusals.

The evaluator must give what upstream xacro (Python ``eval`` over its symbol table) gives for the
expressions robot descriptions use, and refuse what reaches code, files or unbounded work."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import pytest

from robodesc.frontends.packages import PackageResolver
from robodesc.frontends.xacro_eval import EvalError, Function, base_symbols, evaluate
from robodesc.frontends.xacro_expand import expand_xacro
from robodesc.ir.diagnostics import Findings, ParseError
from tests.conftest import CORPUS

PROPERTIES: dict[str, Any] = {
    "w": 0.05,
    "n": 3,
    "name": "left_arm",
    "prefix": "r_",
    "flag": True,
    "xyz": "0.1 0.2 0.3",
    "items": [1, 2, 3],
    "table": {"a": 1.5, "b": {"c": "deep"}},
}
SAME_AS_PYTHON = [
    "w * 4",
    "-w / 2 + n ** 2 - 7 // 2 % 3",
    "pi / 2",
    "math.pi * 2",
    "radians(90)",
    "degrees(math.atan2(1, 1))",
    "sqrt(w) + cos(0) + sin(pi) + tan(0.1) + exp(1) + log(10) + log10(100) + fabs(-1) + floor(1.5) + ceil(1.2)",
    "abs(-3) + min(1, 2) + max([4, 5]) + round(2.567, 2) + len(name) + sum(items)",
    "1 if flag else 0",
    "'yes' if n > 2 and not flag is False else 'no'",
    "prefix + name + '_joint'",
    "name.upper().replace('_', '-')",
    "' '.join(str(x) for x in [1, 2, 3])",
    "[float(v) * 2 for v in xyz.split()]",
    "{k: v for k, v in zip(['a', 'b'], items)}",
    "items[1:] + items[:1]",
    "table['b']['c']",
    "n == 3 and name != 'x' or w < 0",
    "1 < n <= 3",
    "'arm' in name",
    "int('7') + float('1.5') + bool(0)",
    "sorted(items, reverse=True)",
    "list(range(n))",
    "str(w)",
    "'%s_%d' % (name, n)",
    "'{}_{}'.format(name, n)",
    "f'{name}_{n:03d}'",
    "[x * y for x in items for y in items if x != y]",
    "dict(a=1)['a']",
    "tuple(items)[-1]",
    "name.split('_')[0].startswith('le')",
    "hypot(3, 4)",
    "2 ** 10 ** 2",
    "-n ** 2",
    "(1, 2) + (3,)",
]


def _lookup(name: str) -> Any:
    symbols = base_symbols({})
    if name in PROPERTIES:
        return PROPERTIES[name]
    if name in symbols:
        return symbols[name]
    raise NameError(name)


def _python(expression: str) -> Any:
    namespace: dict[str, Any] = {**{k: getattr(math, k) for k in dir(math) if not k.startswith("_")}}
    namespace["math"] = math
    namespace.update(PROPERTIES)
    return eval(expression, namespace)  # the reference: Python itself, on our own test expressions


@pytest.mark.parametrize("expression", SAME_AS_PYTHON)
def test_evaluator_matches_python(expression: str) -> None:
    assert evaluate(expression, _lookup) == _python(expression)


def test_yaml_style_dotted_keys() -> None:
    from xacro import YamlDictWrapper

    props = {"cfg": YamlDictWrapper({"arm": {"length": 0.5}})}
    assert evaluate("cfg.arm.length * 2", lambda n: props[n]) == 1.0


@pytest.mark.parametrize(
    ("expression", "refusal"),
    [
        ("python.os", "'python' namespace is not available"),
        ("().__class__", "attribute '__class__' is refused"),
        ("name.__class__", "attribute '__class__' is refused"),
        ("_hidden", "name '_hidden' is refused"),
        ("(lambda: 1)()", "a lambda is not allowed"),
        ("9 ** 9 ** 9", "integer power 9 ** 387420489"),
        ("'a' * 10 ** 9", "repetition would build"),
        ("[1] * 10 ** 9", "repetition would build"),
        ("list(range(10 ** 9))", "range of 1000000000 items"),
        ("[x for x in range(10 ** 6)]", "range of 1000000 items"),
        ("'{0.__class__}'.format(1)", "format field {0.__class__} is refused"),
        ("'%999999999d' % 1", "%-format width or precision"),
        ("1 << 100000", "shift by 100000 bits"),
        ("factorial(100000)", "factorial(100000) is refused"),
        ("name.center(10 ** 9)", "padding to 1000000000 characters"),
        ("(x := 1)", "assignment expression"),
        ("items.append", "attribute 'append'"),
        ("math", "must be data"),
        ("b'bytes'", "bytes literals are not allowed"),
        ("-" * 3000 + "1", "nested too deeply"),
        ("+".join(["1"] * 50000), "nested too deeply"),
    ],
)
def test_evaluator_refuses(expression: str, refusal: str) -> None:
    with pytest.raises(EvalError) as caught:
        evaluate(expression, _lookup)
    assert refusal in str(caught.value)


def test_functions_are_whitelist_wrappers() -> None:
    """Every callable an expression can reach is a Function from robodesc's tables."""
    symbols = base_symbols({})
    for value in symbols.values():
        assert isinstance(value, Function | bool | float | type(None)) or type(value).__name__ == "Namespace"


def _xacro(tmp_path: Path, body: str, name: str = "r.urdf.xacro") -> Path:
    path = tmp_path / name
    path.write_text(f'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">{body}</robot>')
    return path


def test_load_yaml_inside_package_root_is_read(tmp_path: Path) -> None:
    (tmp_path / "cfg.yaml").write_text("arm: {length: 0.25}\n")
    path = _xacro(
        tmp_path, '<xacro:property name="c" value="${xacro.load_yaml(\'cfg.yaml\')}"/><link name="l${c.arm.length}"/>'
    )
    text = expand_xacro(str(path), {}, PackageResolver(input_file=str(path)), Findings())
    assert '<link name="l0.25"/>' in text


def test_include_outside_roots_is_refused(tmp_path: Path) -> None:
    outside = tmp_path / "outside.xacro"
    outside.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="o"/></robot>')
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "package.xml").write_text("<package><name>pkg</name></package>")
    path = _xacro(pkg, '<xacro:include filename="../outside.xacro"/>')
    with pytest.raises(ParseError, match="outside the package roots"):
        expand_xacro(str(path), {}, PackageResolver(input_file=str(path)), Findings())
    # --trust-xacro: upstream behaviour, the include is read
    text = expand_xacro(str(path), {}, PackageResolver(input_file=str(path)), Findings(), trust=True)
    assert '<link name="o"/>' in text


def test_symlink_out_of_package_is_refused(tmp_path: Path) -> None:
    (tmp_path / "secret.yaml").write_text("key: secret\n")
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "package.xml").write_text("<package><name>pkg</name></package>")
    (pkg / "link.yaml").symlink_to(tmp_path / "secret.yaml")
    path = _xacro(pkg, "<link name=\"${xacro.load_yaml('link.yaml').key}\"/>")
    with pytest.raises(ParseError, match="outside the package roots"):
        expand_xacro(str(path), {}, PackageResolver(input_file=str(path)), Findings())


def test_corpus_xacro_identical_to_upstream() -> None:
    """Every xacro of the shared corpus expands to the same URDF with and without the sandbox."""
    files = sorted(CORPUS.rglob("*.xacro"))
    assert files
    compared = 0
    for path in files:
        try:
            trusted = expand_xacro(str(path), {}, PackageResolver(input_file=str(path)), Findings(), trust=True)
        except ParseError:
            continue  # an include-only file
        assert expand_xacro(str(path), {}, PackageResolver(input_file=str(path)), Findings()) == trusted, path
        compared += 1
    assert compared >= 2
