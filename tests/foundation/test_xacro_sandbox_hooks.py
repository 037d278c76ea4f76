"""The xacro sandbox's hooks: which xacro entry points it replaces, and what each replacement does.

A guard for refactoring ``frontends/xacro_expand.py``: every hook must stay installed while a
sandboxed expansion runs and be removed afterwards, and each keeps its refusal and message."""

from __future__ import annotations

from pathlib import Path

import pytest

from robodesc.frontends.packages import PackageResolver
from robodesc.frontends.xacro_expand import _patched_xacro, _Sandbox, expand_xacro
from robodesc.ir.diagnostics import Findings, ParseError

# (module, attribute) pairs: the sandbox replaces all of them; find and parse are replaced always.
SANDBOXED = [
    ("xacro", "safe_eval"),
    ("xacro", "load_yaml"),
    ("xacro", "resolve_macro"),
    ("xacro", "grab_property"),
    ("xacro.Table", "_resolve_"),
    ("xacro.Table", "_setitem"),
    ("xacro.NameSpace", "__getattr__"),
    ("substitution_args", "_eval_env"),
    ("substitution_args", "_eval_optenv"),
    ("substitution_args", "_eval"),
]
ALWAYS = [("substitution_args", "_eval_find"), ("xacro", "parse")]


def _entry_points() -> dict[tuple[str, str], object]:
    import xacro
    from xacro import substitution_args

    owners = {
        "xacro": xacro,
        "xacro.Table": xacro.Table,
        "xacro.NameSpace": xacro.NameSpace,
        "substitution_args": substitution_args,
    }
    return {(o, a): owners[o].__dict__[a] for o, a in SANDBOXED + ALWAYS}


def _xacro(folder: Path, body: str) -> Path:
    path = folder / "r.urdf.xacro"
    path.write_text(f'<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">{body}</robot>')
    return path


def _expand(
    path: Path, environ: dict[str, str] | None = None, allowed_env: tuple[str, ...] = ()
) -> tuple[str, Findings]:
    findings = Findings()
    resolver = PackageResolver(input_file=str(path), environ=environ or {})
    return expand_xacro(str(path), {}, resolver, findings, allowed_env=allowed_env), findings


def test_sandbox_replaces_every_entry_point_and_restores_them(tmp_path: Path) -> None:
    before = _entry_points()
    resolver = PackageResolver(input_file=str(tmp_path / "r.xacro"), environ={})
    sandbox = _Sandbox(resolver, [str(tmp_path)], frozenset(), {})
    with _patched_xacro(resolver, sandbox, {}):
        during = _entry_points()
    assert [key for key in before if during[key] is before[key]] == []
    assert _entry_points() == before
    with _patched_xacro(resolver, None):  # --trust-xacro: upstream's evaluation
        trusted = _entry_points()
    assert [key for key in before if trusted[key] is not before[key]] == ALWAYS
    assert _entry_points() == before


def test_environment_is_read_only_when_named(tmp_path: Path) -> None:
    environ = {"SECRET": "s3cret", "NAMED": "ok"}
    path = _xacro(tmp_path, '<link name="$(env SECRET)"/>')
    with pytest.raises(ParseError, match=r"\$\(env SECRET\): robodesc reads only environment variables you name"):
        _expand(path, environ)
    path = _xacro(tmp_path, '<link name="$(env NAMED)_$(optenv SECRET dflt)_$(optenv NAMED x)"/>')
    text, findings = _expand(path, environ, ("NAMED",))
    assert '<link name="ok_dflt_ok"/>' in text
    assert [f.message for f in findings] == [
        "$(optenv SECRET): the environment is not read unless named (--env SECRET); used the default"
    ]


def test_eval_substitution_and_include_namespace(tmp_path: Path) -> None:
    (tmp_path / "arm.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><xacro:property name="length" value="0.5"/></robot>'
    )
    path = _xacro(
        tmp_path,
        '<xacro:arg name="n" default="3"/><xacro:include filename="arm.xacro" ns="arm"/>'
        '<link name="l$(eval n * 2)_${arm.length * 2}"/>',
    )
    text, _ = _expand(path)
    assert '<link name="l6_1.0"/>' in text
    path = _xacro(tmp_path, '<xacro:include filename="arm.xacro" ns="arm"/><link name="${arm.width}"/>')
    with pytest.raises(ParseError, match="the dictionary has no key 'width'"):
        _expand(path)


def test_xacro_messages_become_warnings_and_fatal_an_error(tmp_path: Path) -> None:
    path = _xacro(tmp_path, "<link name=\"a${xacro.warning('careful', 1)}\"/>")
    text, findings = _expand(path)
    assert '<link name="a"/>' in text
    assert [f.message for f in findings] == ["xacro.warning: careful 1"]
    path = _xacro(tmp_path, "<link name=\"${xacro.fatal('stop here')}\"/>")
    with pytest.raises(ParseError, match="stop here"):
        _expand(path)


def test_property_bounds_name_the_property(tmp_path: Path) -> None:
    path = _xacro(tmp_path, '<xacro:property name="big" value="${9**9**9}"/><link name="${big}"/>')
    with pytest.raises(ParseError, match=r"the limit is 4096 \(property 'big', expression '9\*\*9\*\*9'\)"):
        _expand(path)
    path = _xacro(
        tmp_path, '<xacro:property name="long" value="${\'x\' * 600000 + \'y\' * 600000}"/><link name="${long}"/>'
    )
    with pytest.raises(ParseError, match="long"):
        _expand(path)


def test_macro_calls_are_bounded(tmp_path: Path) -> None:
    body = (
        '<xacro:macro name="m" params="d"><xacro:if value="${d > 0}">'
        '<xacro:m d="${d - 1}"/><xacro:m d="${d - 1}"/></xacro:if></xacro:macro>'
        '<xacro:m d="20"/><link name="l"/>'
    )
    with pytest.raises(ParseError, match="macro 'm': more than 10000 macro calls"):
        _expand(_xacro(tmp_path, body))
