"""``.xacro`` → URDF text, through the ``xacro`` package.

``$(find pkg)`` is answered by robodesc's :class:`PackageResolver` (so ``--package NAME=DIR`` works
without a ROS install), and every file xacro opens, includes too, must be a regular file and passes
the same hostile-XML check as plain URDF first.

By default the expansion is sandboxed (docs/security.md): expressions go to robodesc's whitelisting
evaluator (:mod:`robodesc.frontends.xacro_eval`) instead of Python's ``eval``; includes and
``xacro.load_yaml`` read only inside the package roots (the input's own package or folder,
``--package`` folders and packages ``$(find)`` resolved); ``$(env)``/``$(optenv)`` see only the
variables named in :attr:`LoadOptions.allowed_env`; a path built from ``$(find pkg)`` that climbs out
of the package is refused after expansion; macro expansion, strings and the output are bounded.
``trust_xacro`` restores upstream xacro's evaluation (code, files, environment) for files the user
trusts; the regular-file, XML and size checks stay.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import time
import xml.parsers.expat
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from lxml import etree

from robodesc.frontends.packages import PackageResolver, package_xml_name
from robodesc.frontends.xacro_eval import EvalError, Function, base_symbols, bounded, evaluate
from robodesc.frontends.xml_safety import parse_xml, read_file, refuse_hostile
from robodesc.ir.diagnostics import Findings, ParseError, SourceLoc

STAGE = "frontend:xacro"

# Work bounds of one expansion. A macro call copies its body: the copies are counted, so that a
# macro calling itself twice per level (2^depth copies) stops here instead of filling memory.
MAX_MACRO_NODES = 1_000_000  # DOM nodes copied by macro calls
# Macro calls. Upstream xacro splices each expansion into its parent with minidom, whose
# insertBefore is linear in the number of siblings, so expansion time is quadratic in the calls
# that land side by side: 10,000 calls cost about 8 s. Robots in the corpora make at most a few
# hundred.
MAX_MACRO_CALLS = 10_000
MAX_OUTPUT_BYTES = 64 * 1024 * 1024  # the expanded URDF
MAX_YAML_BYTES = 16 * 1024 * 1024
TIME_LIMIT = 60.0  # seconds of expansion; a backstop behind the bounds above


class _Refused(Exception):
    """A sandbox rule refused something; becomes a ParseError with this message."""


@dataclass(slots=True)
class _Sandbox:
    resolver: PackageResolver
    roots: list[str]
    allowed_env: frozenset[str]
    environ: Mapping[str, str]
    found: dict[str, str] = field(default_factory=dict)  # package -> root, for the escape check
    macro_nodes: int = 0
    macro_calls: int = 0
    body_sizes: dict[int, int] = field(default_factory=dict)
    deadline: float = 0.0
    warnings: list[str] = field(default_factory=list)

    def inside_roots(self, path: str) -> bool:
        real = os.path.realpath(path)
        for root in self.roots:
            root_real = os.path.realpath(root)
            if real == root_real or real.startswith(root_real.rstrip(os.sep) + os.sep):
                return True
        return False

    def check_read(self, path: str, what: str) -> None:
        if not self.inside_roots(path):
            raise _Refused(
                f"{what} {path!r} is outside the package roots ({', '.join(self.roots)}); robodesc reads only "
                "files of the input's package, --package folders and packages found with $(find) "
                "(give the folder with --package NAME=DIR, or --trust-xacro for files you trust)"
            )

    def tick(self) -> None:
        if time.monotonic() > self.deadline:
            raise _Refused(f"xacro expansion took longer than {TIME_LIMIT:g} s; refused")


def own_root(input_file: str) -> str:
    """The input's package root (the nearest folder above it with a package.xml), else its folder."""
    here = os.path.dirname(os.path.abspath(input_file))
    probe = here
    while True:
        if package_xml_name(probe) is not None:
            return probe
        parent = os.path.dirname(probe)
        if parent == probe:
            return here
        probe = parent


def _count_nodes(node: Any) -> int:
    count = 0
    stack = [node]
    while stack:
        current = stack.pop()
        count += 1
        stack.extend(current.childNodes)
    return count


@contextlib.contextmanager
def _patched_xacro(
    resolver: PackageResolver, sandbox: _Sandbox | None, environ: Mapping[str, str] | None = None
) -> Iterator[Any]:
    import xacro
    from xacro import substitution_args

    saved: list[tuple[Any, str, Any]] = []

    def patch(owner: Any, name: str, value: Any) -> None:
        saved.append((owner, name, getattr(owner, name)))
        setattr(owner, name, value)

    original_parse = xacro.parse

    def find(pkg: str) -> str:
        found = resolver.find_package(pkg)
        if found is None:
            raise xacro.XacroException(
                f"package {pkg!r} not found (give it with --package {pkg}=DIR, or set ROS_PACKAGE_PATH / AMENT_PREFIX_PATH)"
            )
        if sandbox is not None:
            sandbox.found[pkg] = found[0]
            if found[0] not in sandbox.roots:
                sandbox.roots.append(found[0])
        return found[0]

    def parse(inp: Any, filename: str | None = None) -> Any:
        if inp is None and filename is not None:
            path = os.path.join(xacro.root_dir, filename) if hasattr(xacro, "root_dir") else filename
            if sandbox is not None:
                sandbox.check_read(path, "include")
            if not os.path.lexists(path):
                return original_parse(inp, filename)  # let xacro report it (and honour optional="true")
            try:
                data = read_file(path)
            except ParseError as exc:
                raise _Refused(f"include {path!r}: {exc.message}") from None
            refuse_hostile(data, path)
            return original_parse(data.decode("utf-8", "replace"), filename)
        return original_parse(inp, filename)

    patch(substitution_args, "_eval_find", find)
    patch(xacro, "parse", parse)
    if sandbox is not None:
        _patch_sandbox(xacro, substitution_args, sandbox, patch, environ or os.environ)
    try:
        yield xacro
    finally:
        for owner, name, value in reversed(saved):
            setattr(owner, name, value)


def _patch_sandbox(
    xacro: Any,
    substitution_args: Any,
    sandbox: _Sandbox,
    patch: Callable[[Any, str, Any], None],
    environ: Mapping[str, str],
) -> None:
    """Replace every xacro entry point the sandbox guards; this is the whole list of patches. Each
    replacement is built (capturing the original it wraps) before any is installed."""
    load_yaml = _sandboxed_load_yaml(xacro, sandbox)
    symbols = base_symbols(_xacro_members(xacro, sandbox, load_yaml))
    safe_eval, namespace_getattr = _sandboxed_lookups(xacro, sandbox, symbols)
    env, optenv = _sandboxed_environment(substitution_args, sandbox, environ)
    eval_substitution = _sandboxed_substitution_eval(substitution_args, sandbox, symbols, env, optenv)
    resolve_macro = _bounded_resolve_macro(xacro, sandbox)
    resolve, grab_property, setitem = _property_hooks(xacro)

    patch(xacro, "safe_eval", safe_eval)
    patch(xacro, "load_yaml", load_yaml)
    patch(xacro, "resolve_macro", resolve_macro)
    patch(xacro, "grab_property", grab_property)
    patch(xacro.Table, "_resolve_", resolve)
    patch(xacro.Table, "_setitem", setitem)
    patch(xacro.NameSpace, "__getattr__", namespace_getattr)
    patch(substitution_args, "_eval_env", env)
    patch(substitution_args, "_eval_optenv", optenv)
    patch(substitution_args, "_eval", eval_substitution)


def _sandboxed_load_yaml(xacro: Any, sandbox: _Sandbox) -> Callable[[Any], Any]:
    """``xacro.load_yaml`` that reads only regular files inside the package roots, up to
    :data:`MAX_YAML_BYTES`."""
    original_load_yaml = xacro.load_yaml

    def load_yaml(filename: Any) -> Any:
        path = os.path.abspath(xacro.abs_filename_spec(str(filename)))
        sandbox.check_read(path, "xacro.load_yaml of")
        try:
            data = read_file(path, MAX_YAML_BYTES)
        except ParseError as exc:
            raise _Refused(f"xacro.load_yaml({filename!r}): {exc.message}") from None
        if len(data) > MAX_YAML_BYTES:
            raise _Refused(f"xacro.load_yaml({filename!r}): file above {MAX_YAML_BYTES // 2**20} MiB; refused")
        return original_load_yaml(path)

    return load_yaml


def _xacro_members(xacro: Any, sandbox: _Sandbox, load_yaml: Callable[[Any], Any]) -> dict[str, Callable[..., Any]]:
    """The ``xacro.*`` helpers expressions may call; messages become warnings, ``fatal`` an error."""

    def message(kind: str) -> Callable[..., str]:
        def say(*args: Any, **_kwargs: Any) -> str:
            text = " ".join(str(a) for a in args)
            if kind == "fatal":
                raise xacro.XacroException(text)
            sandbox.warnings.append(f"xacro.{kind}: {text}")
            return ""

        return say

    return {
        "load_yaml": load_yaml,
        "abs_filename": lambda name: xacro.abs_filename_spec(str(name)),
        "dotify": xacro.YamlDictWrapper,
        "tokenize": xacro.tokenize,
        "arg": lambda name: xacro.substitution_args_context["arg"][name],
        "message": message("message"),
        "warning": message("warning"),
        "error": message("error"),
        "print_location": lambda *a, **k: "",
        "fatal": message("fatal"),
    }


def _sandboxed_lookups(
    xacro: Any, sandbox: _Sandbox, symbols: Mapping[str, Any]
) -> tuple[Callable[..., Any], Callable[[Any, str], Any]]:
    """``xacro.safe_eval`` through robodesc's evaluator, and attribute access into an include
    namespace (``<xacro:include ns="arm">``, then ``${arm.length}``). Both see only properties, macro
    parameters and ``symbols``."""
    table_type = xacro.Table

    def table_lookup(table: Any, name: str) -> Any:
        """A property or macro parameter visible from ``table``; upstream's global symbols (the root
        dictionary) are never consulted: robodesc's own table answers instead."""
        current = table
        while isinstance(current, table_type):
            if dict.__contains__(current, name):
                return current._resolve_(name)
            current = current.parent
        raise KeyError(name)

    def lookup_for(table: Any) -> Callable[[str], Any]:
        def lookup(name: str) -> Any:
            try:
                return table_lookup(table, name)
            except KeyError:
                pass
            if name in symbols:
                return symbols[name]
            raise NameError(f"name '{name}' is not defined")

        return lookup

    def safe_eval(expr: str, globals: Any, locals: Any = None) -> Any:
        sandbox.tick()
        return evaluate(expr, lookup_for(globals))

    def namespace_getattr(self: Any, item: str) -> Any:
        try:
            return table_lookup(self, item)
        except KeyError:
            raise NameError(f"name '{item}' is not defined") from None

    return safe_eval, namespace_getattr


def _sandboxed_environment(
    substitution_args: Any, sandbox: _Sandbox, environ: Mapping[str, str]
) -> tuple[Callable[[str], str], Callable[..., str]]:
    """``$(env NAME)`` and ``$(optenv NAME default)`` that read only the variables the user named."""

    def env(name: str) -> str:
        if name not in sandbox.allowed_env:
            raise _Refused(
                f"$(env {name}): robodesc reads only environment variables you name (--env {name} allows this one)"
            )
        if name not in environ:
            raise substitution_args.SubstitutionException(f"environment variable {name} is not set")
        return environ[name]

    def optenv(name: str, default: str = "") -> str:
        if name in sandbox.allowed_env and name in environ:
            return environ[name]
        if name not in sandbox.allowed_env and name in environ:
            sandbox.warnings.append(
                f"$(optenv {name}): the environment is not read unless named (--env {name}); used the default"
            )
        return default

    return env, optenv


def _sandboxed_substitution_eval(
    substitution_args: Any,
    sandbox: _Sandbox,
    symbols: Mapping[str, Any],
    env: Callable[[str], str],
    optenv: Callable[..., str],
) -> Callable[[str, dict[str, Any]], str]:
    """``$(eval ...)`` through robodesc's evaluator: ``symbols``, the substitution functions (with
    the sandboxed ``env``/``optenv``) and the arguments."""

    def eval_substitution(expression: str, context: dict[str, Any]) -> str:
        sandbox.tick()
        args = context.setdefault("arg", {})

        def arg(name: str) -> Any:
            return substitution_args.convert_value(substitution_args._eval_arg(name, args=args), "auto")

        functions: dict[str, Any] = {
            **symbols,
            "true": True,
            "false": False,
            "arg": Function("arg", arg),
            "dirname": Function("dirname", lambda: substitution_args._eval_dirname(context.get("filename"))),
            "env": Function("env", env),
            "optenv": Function("optenv", optenv),
            "find": Function("find", substitution_args._eval_find),
        }

        def lookup(name: str) -> Any:
            if name in functions:
                return functions[name]
            if name in args:
                return substitution_args.convert_value(args[name], "auto")
            raise NameError(f"name '{name}' is not defined")

        return str(evaluate(expression, lookup))

    return eval_substitution


def _bounded_resolve_macro(xacro: Any, sandbox: _Sandbox) -> Callable[[str, Any, Any], Any]:
    """``xacro.resolve_macro`` that counts macro calls and the XML nodes their bodies copy, and
    refuses beyond :data:`MAX_MACRO_CALLS` / :data:`MAX_MACRO_NODES`."""
    original_resolve_macro = xacro.resolve_macro

    def resolve_macro(fullname: str, macros: Any, symbols_: Any) -> Any:
        sandbox.tick()
        scoped = original_resolve_macro(fullname, macros, symbols_)
        body = scoped[2].body
        size = sandbox.body_sizes.get(id(body))
        if size is None:
            size = sandbox.body_sizes[id(body)] = _count_nodes(body)
        sandbox.macro_nodes += size
        sandbox.macro_calls += 1
        if sandbox.macro_calls > MAX_MACRO_CALLS:
            raise _Refused(
                f"macro {fullname!r}: more than {MAX_MACRO_CALLS} macro calls (a macro that calls itself more "
                "than once per level grows exponentially); refused"
            )
        if sandbox.macro_nodes > MAX_MACRO_NODES:
            raise _Refused(
                f"macro {fullname!r}: the expansion copies more than {MAX_MACRO_NODES} XML nodes "
                "(a macro that calls itself more than once per level grows exponentially); refused"
            )
        return scoped

    return resolve_macro


def _property_hooks(
    xacro: Any,
) -> tuple[Callable[[Any, str], Any], Callable[[Any, Any], Any], Callable[[Any, str, Any, bool], None]]:
    """``Table._resolve_`` and ``grab_property`` that name the property a failure belongs to (for
    :func:`_sandbox_refusal`), and ``Table._setitem`` that refuses a property value beyond the
    evaluator's bounds."""
    original_resolve = xacro.Table._resolve_

    def resolve(self: Any, key: str) -> Any:
        try:
            return original_resolve(self, key)
        except xacro.XacroException as exc:
            _name_property(exc, key)
            raise

    original_grab_property = xacro.grab_property

    def grab_property(elt: Any, table: Any) -> Any:
        name = elt.getAttribute("name")
        try:
            return original_grab_property(elt, table)
        except xacro.XacroException as exc:
            _name_property(exc, name)
            raise

    original_setitem = xacro.Table._setitem

    def setitem(self: Any, key: str, value: Any, unevaluated: bool) -> None:
        try:
            bounded(value, f"property {key!r}")
        except EvalError as exc:
            raise xacro.XacroException(str(exc)) from None
        original_setitem(self, key, value, unevaluated)

    return resolve, grab_property, setitem


def _name_property(exc: Any, key: str) -> None:
    if key and not getattr(exc, "robodesc_property", None):
        exc.robodesc_property = key


def expand_xacro(
    path: str,
    args: Mapping[str, str],
    resolver: PackageResolver,
    findings: Findings,
    *,
    trust: bool = False,
    allowed_env: Sequence[str] = (),
    roots: Sequence[str] = (),
) -> str:
    """Expand ``path`` with xacro ``args`` and return URDF text.

    Sandboxed unless ``trust``: ``roots`` are folders reads may come from besides the input's own
    package root, ``--package`` folders and packages ``$(find)`` resolves; ``allowed_env`` names the
    environment variables ``$(env)``/``$(optenv)`` may read."""
    loc = SourceLoc(path)
    refuse_hostile(read_file(path), path)
    sandbox = None if trust else _new_sandbox(path, resolver, allowed_env, roots)
    stderr = io.StringIO()
    with (
        _patched_xacro(resolver, sandbox, resolver.environ) as xacro,
        contextlib.redirect_stderr(stderr),
        contextlib.redirect_stdout(stderr),
    ):
        raw = _process_file(xacro, path, args, loc)
    if len(raw) > MAX_OUTPUT_BYTES:
        raise ParseError(f"xacro: the expanded URDF exceeds {MAX_OUTPUT_BYTES // 2**20} MiB; refused", loc=loc)
    for line in stderr.getvalue().splitlines():
        if line.strip():
            findings.warn("xacro", _clean(line), loc=loc, stage=STAGE)
    if sandbox is not None:
        for line in sandbox.warnings:
            findings.warn("xacro", _clean(line), loc=loc, stage=STAGE)
        _check_found_paths(raw, sandbox, loc)
    # xacro writes few, very long lines; re-indent so that file:line in messages is useful.
    # `robodesc expand` prints this same text.
    root = parse_xml(raw, path)
    etree.indent(root, space="  ")
    text: str = etree.tostring(root, encoding="unicode")
    return text


def _new_sandbox(path: str, resolver: PackageResolver, allowed_env: Sequence[str], roots: Sequence[str]) -> _Sandbox:
    """The sandbox of one expansion: reads from the input's own package root, ``roots`` and the
    ``--package`` folders; the environment variables in ``allowed_env``; the clock starts now."""
    allowed_roots = [own_root(path), *(os.path.abspath(r) for r in roots)]
    allowed_roots += [os.path.abspath(d) for d in resolver.explicit.values()]
    return _Sandbox(
        resolver,
        list(dict.fromkeys(allowed_roots)),
        frozenset(allowed_env),
        resolver.environ,
        deadline=time.monotonic() + TIME_LIMIT,
    )


def _process_file(xacro: Any, path: str, args: Mapping[str, str], loc: SourceLoc) -> str:
    """Run (the patched) xacro on ``path``; the XML text, or a :class:`ParseError` for any failure,
    placed in the file xacro was reading."""
    try:
        doc = xacro.process_file(path, mappings=dict(args))
        raw: str = doc.toxml()
        return raw
    except ParseError:
        raise
    except _Refused as exc:
        raise ParseError(f"xacro: {exc}", loc=_where(xacro, loc)) from None
    except xacro.XacroException as exc:
        refusal = _sandbox_refusal(exc, xacro.XacroException)
        if refusal is not None:
            raise ParseError(f"xacro: {refusal}", loc=_where(xacro, loc)) from None
        message = str(exc)
        if "<class '" in message:  # eval_extension's wrapping repeats the inner message with its class
            inner: BaseException = exc
            while isinstance(getattr(inner, "exc", None), BaseException):
                inner = inner.exc  # type: ignore[attr-defined]
            message = str(inner)
        raise ParseError(f"xacro: {_clean(message)}", loc=_where(xacro, loc)) from None
    except xml.parsers.expat.ExpatError as exc:
        raise ParseError(f"xacro: malformed XML: {exc}", loc=loc) from None
    except RecursionError:
        raise ParseError(
            "xacro: recursion too deep (a macro or property that refers to itself, or nesting beyond Python's limit)",
            loc=_where(xacro, loc),
        ) from None
    except MemoryError:
        raise ParseError("xacro: out of memory while expanding; refused", loc=loc) from None
    except Exception as exc:  # xacro surfaces user errors as NameError, KeyError, ...
        raise ParseError(f"xacro: {type(exc).__name__}: {_clean(str(exc))}", loc=_where(xacro, loc)) from None
    finally:
        xacro.init_stacks(None)


def _sandbox_refusal(exc: BaseException, xacro_exception: type) -> str | None:
    """One line for a sandbox refusal or bound that xacro wrapped (once per lazily evaluated
    property on the way): the refusal, the innermost property and expression; ``None`` for other
    errors, which keep xacro's wording."""
    prop: str | None = None
    expression: str | None = None
    current: BaseException | None = exc
    while isinstance(current, xacro_exception):
        prop = getattr(current, "robodesc_property", None) or prop
        found = re.search(r"when evaluating expression '(.*)'", str(getattr(current, "suffix", "") or ""))
        if found:
            expression = found.group(1)
        current = getattr(current, "exc", None)
    if not isinstance(current, _Refused | EvalError):
        return None
    where = ", ".join(
        part
        for part in (f"property {prop!r}" if prop else "", f"expression {expression!r}" if expression else "")
        if part
    )
    return f"{current}" + (f" ({where})" if where else "")


def _where(xacro: Any, fallback: SourceLoc) -> SourceLoc:
    """The file xacro was processing when it failed (an include, not always the input)."""
    stack = getattr(xacro, "filestack", None) or []
    current = next((f for f in reversed(stack) if f), None)
    return SourceLoc(current) if current else fallback


def _check_found_paths(text: str, sandbox: _Sandbox, loc: SourceLoc) -> None:
    """A path built from ``$(find pkg)`` must stay inside pkg: ``$(find pkg)/../../etc`` is refused
    here, after expansion, because xacro splices the folder into text before robodesc sees a URI."""
    for name, root in sandbox.found.items():
        root = root.rstrip(os.sep)
        for match in re.finditer(re.escape(root) + r"((?:/[^\s\"'<>]*)?)", text):
            rest = match.group(1)
            if ".." not in rest:
                continue
            path = os.path.normpath(root + rest)
            if path != root and not path.startswith(root + os.sep):
                raise ParseError(
                    f"xacro: {root + rest!r} leaves the folder of package {name!r} through '..'; refused", loc=loc
                )


def _clean(text: str) -> str:
    return re.sub(r"\x1b\[[0-9;]*m", "", text).strip()
