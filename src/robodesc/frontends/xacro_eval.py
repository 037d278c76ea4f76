"""A whitelisting evaluator for xacro's ``${...}`` and ``$(eval ...)`` expressions.

Upstream xacro hands every expression to Python's ``eval`` with a "safe" symbol table. That table
still holds the ``python.`` namespace, ``xacro.load_yaml`` (any file) and functions that reach object
internals without ``__`` names, so a downloaded ``.xacro`` can run code, read files and leak them
into the output. This module never calls ``eval``: it parses the expression with :mod:`ast` and
interprets only what robot descriptions use (literals, properties and macro parameters, arithmetic,
comparisons, ``and``/``or``/``if``, indexing, comprehensions, ``math`` functions, a short list of
builtins and string/list/dict methods, ``xacro.*`` helpers). Everything else is refused with a
message naming the construct.

Work is bounded: strings and sequences an expression builds, the bits of integers (``9**9**9``
is refused before it is computed), format widths, repetition and comprehension sizes. Every callable
an expression can reach is a :class:`Function` from the tables below; values stored in properties
are plain data.
"""

from __future__ import annotations

import ast
import math
import operator
import re
import string
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

MAX_STRING = 1_000_000  # characters in any string an expression builds
MAX_ITEMS = 100_000  # items in any list, tuple, dict, range or comprehension
MAX_INT_BITS = 4096  # bits of any integer (about 1,200 decimal digits)
MAX_EXPRESSION = 100_000  # characters of one expression's source
MAX_WIDTH = 10_000  # a format width or precision


class EvalError(Exception):
    """An expression uses something the evaluator refuses, or exceeds a bound."""


@dataclass(frozen=True, slots=True)
class Function:
    """A callable an expression may call: whitelisted here, never a raw Python object."""

    name: str
    impl: Callable[..., Any]

    def __repr__(self) -> str:
        return f"<function {self.name}>"


@dataclass(slots=True)
class Namespace:
    """``math``, ``xacro`` (and the refused ``python``): attribute access to functions."""

    name: str
    members: dict[str, Any] = field(default_factory=dict)
    refusal: str | None = None

    def __repr__(self) -> str:
        return f"<namespace {self.name}>"


# ---- bounds ---------------------------------------------------------------------------------


def bounded(value: Any, what: str = "the result") -> Any:
    """``value`` if it is within the bounds above, else :class:`EvalError`."""
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        if value.bit_length() > MAX_INT_BITS:
            raise EvalError(f"{what} is an integer of {value.bit_length()} bits; the limit is {MAX_INT_BITS}")
    elif isinstance(value, str):
        if len(value) > MAX_STRING:
            raise EvalError(f"{what} is a string of {len(value)} characters; the limit is {MAX_STRING}")
    elif isinstance(value, list | tuple | dict | set | frozenset) and len(value) > MAX_ITEMS:
        raise EvalError(f"{what} has {len(value)} items; the limit is {MAX_ITEMS}")
    return value


def _size_of(value: Any) -> int:
    return len(value) if isinstance(value, str | list | tuple) else 0


def _check_count(count: Any, unit_size: int, what: str) -> None:
    if isinstance(count, int) and not isinstance(count, bool) and count * max(unit_size, 1) > MAX_STRING:
        raise EvalError(f"{what} would build {count} × {unit_size} items; the limit is {MAX_STRING}")


def _power(base: Any, exponent: Any) -> Any:
    if isinstance(base, int) and isinstance(exponent, int) and exponent > 0 and abs(base) > 1:
        bits = exponent * math.log2(abs(base))
        if bits > MAX_INT_BITS:
            raise EvalError(
                f"integer power {base} ** {exponent} would have about {bits:.3g} bits; the limit is {MAX_INT_BITS}"
            )
    if isinstance(base, int) and isinstance(exponent, int) and exponent < 0 and base == 0:
        raise ZeroDivisionError("0 cannot be raised to a negative power")
    return operator.pow(base, exponent)


def _multiply(a: Any, b: Any) -> Any:
    if isinstance(a, str | list | tuple):
        _check_count(b, len(a), "repetition")
    elif isinstance(b, str | list | tuple):
        _check_count(a, len(b), "repetition")
    return a * b


def _lshift(a: Any, b: Any) -> Any:
    if isinstance(b, int) and b > MAX_INT_BITS:
        raise EvalError(f"shift by {b} bits; the limit is {MAX_INT_BITS}")
    return a << b


_PRINTF_FIELD = re.compile(r"%[-#0 +]*(\*|\d+)?(?:\.(\*|\d+))?")


def _modulo(a: Any, b: Any) -> Any:
    if isinstance(a, str):
        for width, precision in _PRINTF_FIELD.findall(a):
            for part in (width, precision):
                if part == "*" or (part and int(part) > MAX_WIDTH):
                    raise EvalError(f"%-format width or precision {part!r} is refused (the limit is {MAX_WIDTH})")
    return a % b


_BINARY: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: operator.add,
    ast.Sub: operator.sub,
    ast.Mult: _multiply,
    ast.Div: operator.truediv,
    ast.FloorDiv: operator.floordiv,
    ast.Mod: _modulo,
    ast.Pow: _power,
    ast.LShift: _lshift,
    ast.RShift: operator.rshift,
    ast.BitAnd: operator.and_,
    ast.BitOr: operator.or_,
    ast.BitXor: operator.xor,
}
_UNARY: dict[type, Callable[[Any], Any]] = {
    ast.USub: operator.neg,
    ast.UAdd: operator.pos,
    ast.Not: operator.not_,
    ast.Invert: operator.invert,
}
_COMPARE: dict[type, Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq,
    ast.NotEq: operator.ne,
    ast.Lt: operator.lt,
    ast.LtE: operator.le,
    ast.Gt: operator.gt,
    ast.GtE: operator.ge,
    ast.In: lambda a, b: a in b,
    ast.NotIn: lambda a, b: a not in b,
    ast.Is: operator.is_,
    ast.IsNot: operator.is_not,
}


# ---- the whitelisted functions ----------------------------------------------------------------


def _format_spec_ok(spec: str) -> None:
    for number in re.findall(r"\d+", spec):
        if int(number) > MAX_WIDTH:
            raise EvalError(f"format width or precision {number} is refused (the limit is {MAX_WIDTH})")


def _str_format(text: str, *args: Any, **kwargs: Any) -> str:
    # str.format can reach attributes ("{0.__class__}") and items: allow plain fields only.
    for _literal, name, spec, _conversion in string.Formatter().parse(text):
        if name is not None and name != "" and not (name.isdigit() or name.isidentifier()):
            raise EvalError(f"format field {{{name}}} is refused: only {{}}, {{0}} and {{name}} fields are allowed")
        if spec:
            if "{" in spec:
                raise EvalError("nested format fields are refused")
            _format_spec_ok(spec)
    return text.format(*args, **kwargs)


def _checked_replace(text: str, old: str, new: str, count: int = -1) -> str:
    occurrences = text.count(old) if old else len(text) + 1
    if count >= 0:
        occurrences = min(occurrences, count)
    if len(text) + occurrences * max(len(new) - len(old), 0) > MAX_STRING:
        raise EvalError(f"str.replace would build more than {MAX_STRING} characters")
    return text.replace(old, new, count)


def _padding(method: Callable[..., str]) -> Callable[..., str]:
    def pad(text: str, width: int, *rest: Any) -> str:
        if isinstance(width, int) and width > MAX_STRING:
            raise EvalError(f"padding to {width} characters; the limit is {MAX_STRING}")
        return method(text, width, *rest)

    return pad


def _join(separator: str, items: Iterable[Any]) -> str:
    parts = list(items)
    if len(separator) * len(parts) + sum(len(p) if isinstance(p, str) else 0 for p in parts) > MAX_STRING:
        raise EvalError(f"str.join would build more than {MAX_STRING} characters")
    return separator.join(parts)


_STR_METHODS: dict[str, Callable[..., Any]] = {
    **{
        name: getattr(str, name)
        for name in [
            "split",
            "rsplit",
            "strip",
            "lstrip",
            "rstrip",
            "lower",
            "upper",
            "title",
            "capitalize",
            "swapcase",
            "casefold",
            "startswith",
            "endswith",
            "find",
            "rfind",
            "index",
            "rindex",
            "count",
            "isdigit",
            "isalpha",
            "isalnum",
            "isspace",
            "islower",
            "isupper",
            "isnumeric",
            "isdecimal",
            "splitlines",
            "partition",
            "rpartition",
            "removeprefix",
            "removesuffix",
        ]
    },
    "replace": _checked_replace,
    "format": _str_format,
    "join": _join,
    "zfill": _padding(str.zfill),
    "center": _padding(str.center),
    "ljust": _padding(str.ljust),
    "rjust": _padding(str.rjust),
}
_LIST_METHODS: dict[str, Callable[..., Any]] = {"index": list.index, "count": list.count}
_TUPLE_METHODS: dict[str, Callable[..., Any]] = {"index": tuple.index, "count": tuple.count}
_DICT_METHODS: dict[str, Callable[..., Any]] = {
    "get": dict.get,
    "keys": lambda d: list(d.keys()),
    "values": lambda d: list(d.values()),
    "items": lambda d: list(d.items()),
}


def _callable_argument(fn: Any) -> Callable[..., Any]:
    if isinstance(fn, Function):
        return fn.impl
    raise EvalError(f"{fn!r} is not a function an expression may pass")


def _range(*args: int) -> list[int]:
    values = range(*args)
    if len(values) > MAX_ITEMS:
        raise EvalError(f"range of {len(values)} items; the limit is {MAX_ITEMS}")
    return list(values)


def _map(fn: Any, *iterables: Iterable[Any]) -> list[Any]:
    impl = _callable_argument(fn)
    return [bounded(impl(*items)) for items in zip(*iterables, strict=False)]


def _sorted(items: Iterable[Any], key: Any = None, reverse: bool = False) -> list[Any]:
    return sorted(items, key=_callable_argument(key) if key is not None else None, reverse=reverse)


def _factorial(n: int) -> int:
    if not isinstance(n, int) or n > 1000:
        raise EvalError(f"factorial({n!r}) is refused (the limit is 1000)")
    return math.factorial(n)


def _bounded_pow(base: Any, exponent: Any) -> Any:
    return _power(base, exponent)


_BUILTINS: dict[str, Callable[..., Any]] = {
    "abs": abs,
    "min": min,
    "max": max,
    "round": round,
    "len": len,
    "str": str,
    "float": float,
    "int": int,
    "bool": bool,
    "list": list,
    "dict": dict,
    "tuple": tuple,
    "set": set,
    "sum": sum,
    "any": any,
    "all": all,
    "zip": lambda *a: list(zip(*a, strict=False)),
    "enumerate": lambda items, start=0: list(enumerate(items, start)),
    "reversed": lambda items: list(reversed(items)),
    "sorted": _sorted,
    "range": _range,
    "map": _map,
    "divmod": divmod,
    "ord": ord,
    "chr": chr,
    "repr": repr,
    "pow": _bounded_pow,
}

# math: the float functions and constants; functions that can take unbounded time on integers
# (factorial, comb, perm, prod, isqrt on huge numbers) are left out or bounded.
_MATH_NAMES = [
    "acos",
    "acosh",
    "asin",
    "asinh",
    "atan",
    "atan2",
    "atanh",
    "cbrt",
    "ceil",
    "copysign",
    "cos",
    "cosh",
    "degrees",
    "dist",
    "erf",
    "erfc",
    "exp",
    "exp2",
    "expm1",
    "fabs",
    "floor",
    "fmod",
    "frexp",
    "fsum",
    "gamma",
    "hypot",
    "isclose",
    "isfinite",
    "isinf",
    "isnan",
    "ldexp",
    "lgamma",
    "log",
    "log10",
    "log1p",
    "log2",
    "modf",
    "radians",
    "remainder",
    "sin",
    "sinh",
    "sqrt",
    "tan",
    "tanh",
    "trunc",
    "gcd",
    "lcm",
    "nextafter",
    "ulp",
]
_MATH: dict[str, Any] = {name: getattr(math, name) for name in _MATH_NAMES if hasattr(math, name)}
_MATH_FUNCTIONS: dict[str, Any] = {**_MATH, "factorial": _factorial, "pow": lambda a, b: math.pow(a, b)}
_MATH_CONSTANTS: dict[str, float] = {"pi": math.pi, "e": math.e, "tau": math.tau, "inf": math.inf, "nan": math.nan}

PYTHON_REFUSAL = (
    "the 'python' namespace is not available: robodesc evaluates xacro expressions without Python "
    "(--trust-xacro restores upstream xacro's evaluation for files you trust)"
)


def _functions(table: Mapping[str, Callable[..., Any]]) -> dict[str, Function]:
    return {name: Function(name, impl) for name, impl in table.items()}


def base_symbols(xacro_members: Mapping[str, Callable[..., Any]]) -> dict[str, Any]:
    """The names an expression sees besides properties: builtins, ``math`` (also unqualified, as in
    upstream xacro), the ``xacro`` helpers given, and ``python`` (which refuses every use)."""
    math_ns = Namespace("math", {**_functions(_MATH_FUNCTIONS), **_MATH_CONSTANTS})
    xacro_ns = Namespace("xacro", dict(_functions(xacro_members)))
    symbols: dict[str, Any] = {**_functions(_BUILTINS), "True": True, "False": False, "None": None}
    symbols.update(math_ns.members)
    symbols["math"] = math_ns
    symbols["xacro"] = xacro_ns
    symbols["python"] = Namespace("python", refusal=PYTHON_REFUSAL)
    # Upstream also exposes these xacro helpers unqualified (deprecated there).
    for name in ("load_yaml", "abs_filename", "dotify"):
        if name in xacro_ns.members:
            symbols[name] = xacro_ns.members[name]
    return symbols


# ---- the interpreter ------------------------------------------------------------------------

Lookup = Callable[[str], Any]


def evaluate(expression: str, lookup: Lookup) -> Any:
    """Evaluate ``expression``. ``lookup(name)`` answers names (properties first, then
    :func:`base_symbols`) and raises ``NameError`` for unknown ones."""
    text = expression.strip()
    if len(text) > MAX_EXPRESSION:
        raise EvalError(f"expression of {len(text)} characters; the limit is {MAX_EXPRESSION}")
    try:
        tree = ast.parse(text, mode="eval")
    except SyntaxError as exc:
        raise SyntaxError(f"invalid expression: {exc.msg}") from None
    except (RecursionError, MemoryError):
        raise EvalError("expression is nested too deeply") from None
    try:
        value = _Interpreter(lookup).run(tree.body)
    except RecursionError:
        raise EvalError("expression is nested too deeply") from None
    if isinstance(value, Function | Namespace):
        raise EvalError(f"an expression's value must be data, not {value!r}")
    return value


class _Interpreter:
    def __init__(self, lookup: Lookup) -> None:
        self.lookup = lookup
        self.scopes: list[dict[str, Any]] = []

    def run(self, node: ast.expr) -> Any:
        method = getattr(self, "_" + type(node).__name__, None)
        if method is None:
            raise EvalError(f"{_describe(node)} is not allowed in a xacro expression")
        return method(node)

    # literals and names
    def _Constant(self, node: ast.Constant) -> Any:
        if isinstance(node.value, bytes | complex) or node.value is Ellipsis:
            raise EvalError(f"{type(node.value).__name__} literals are not allowed")
        return bounded(node.value, "a literal")

    def _Name(self, node: ast.Name) -> Any:
        name = node.id
        if name.startswith("_"):
            raise EvalError(f"name {name!r} is refused (names starting with '_' reach Python internals)")
        for scope in reversed(self.scopes):
            if name in scope:
                return scope[name]
        return self.lookup(name)

    def _List(self, node: ast.List) -> Any:
        return bounded([self.run(e) for e in node.elts])

    def _Tuple(self, node: ast.Tuple) -> Any:
        return bounded(tuple(self.run(e) for e in node.elts))

    def _Set(self, node: ast.Set) -> Any:
        return bounded({self.run(e) for e in node.elts})

    def _Dict(self, node: ast.Dict) -> Any:
        out: dict[Any, Any] = {}
        for key, value in zip(node.keys, node.values, strict=True):
            if key is None:
                raise EvalError("'**' unpacking is not allowed")
            out[self.run(key)] = self.run(value)
        return bounded(out)

    def _JoinedStr(self, node: ast.JoinedStr) -> Any:
        parts: list[str] = []
        for value in node.values:
            parts.append(self.run(value) if isinstance(value, ast.FormattedValue) else str(self._Constant(value)))  # type: ignore[arg-type]
        return bounded("".join(parts))

    def _FormattedValue(self, node: ast.FormattedValue) -> Any:
        value = self.run(node.value)
        if node.conversion == ord("r"):
            value = repr(value)
        elif node.conversion in (ord("s"), ord("a")):
            value = str(value)
        spec = self.run(node.format_spec) if node.format_spec is not None else ""
        _format_spec_ok(spec)
        return bounded(format(value, spec))

    # operators
    def _BinOp(self, node: ast.BinOp) -> Any:
        op = _BINARY.get(type(node.op))
        if op is None:
            raise EvalError(f"operator {type(node.op).__name__} is not allowed")
        return bounded(op(self.run(node.left), self.run(node.right)))

    def _UnaryOp(self, node: ast.UnaryOp) -> Any:
        return bounded(_UNARY[type(node.op)](self.run(node.operand)))

    def _BoolOp(self, node: ast.BoolOp) -> Any:
        value: Any = None
        for operand in node.values:
            value = self.run(operand)
            if isinstance(node.op, ast.And) and not value:
                return value
            if isinstance(node.op, ast.Or) and value:
                return value
        return value

    def _Compare(self, node: ast.Compare) -> Any:
        left = self.run(node.left)
        for op, comparator in zip(node.ops, node.comparators, strict=True):
            right = self.run(comparator)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True

    def _IfExp(self, node: ast.IfExp) -> Any:
        return self.run(node.body) if self.run(node.test) else self.run(node.orelse)

    # access
    def _Attribute(self, node: ast.Attribute) -> Any:
        name = node.attr
        if name.startswith("_"):
            raise EvalError(f"attribute {name!r} is refused (names starting with '_' reach Python internals)")
        obj = self.run(node.value)
        if isinstance(obj, Namespace):
            if obj.refusal is not None:
                raise EvalError(obj.refusal)
            if name not in obj.members:
                raise NameError(f"name '{obj.name}.{name}' is not defined")
            return obj.members[name]
        methods = _methods_of(obj)
        if methods is not None and name in methods:
            impl = methods[name]
            return Function(f"{type(obj).__name__}.{name}", lambda *a, **k: impl(obj, *a, **k))
        if isinstance(obj, dict):  # xacro's YAML dictionaries give their keys as attributes
            if name in obj:
                return obj[name]
            raise AttributeError(f"the dictionary has no key '{name}'")
        raise EvalError(f"attribute '{name}' of a {type(obj).__name__} is not allowed")

    def _Subscript(self, node: ast.Subscript) -> Any:
        obj = self.run(node.value)
        if not isinstance(obj, str | list | tuple | dict):
            raise EvalError(f"a {type(obj).__name__} cannot be indexed")
        return bounded(obj[self.run(node.slice)])

    def _Slice(self, node: ast.Slice) -> Any:
        return slice(
            self.run(node.lower) if node.lower is not None else None,
            self.run(node.upper) if node.upper is not None else None,
            self.run(node.step) if node.step is not None else None,
        )

    def _Call(self, node: ast.Call) -> Any:
        fn = self.run(node.func)
        if not isinstance(fn, Function):
            raise EvalError(f"{_source(node.func)} is not a function an expression may call")
        args: list[Any] = []
        for arg in node.args:
            if isinstance(arg, ast.Starred):
                args.extend(self._iterable(self.run(arg.value)))
            else:
                args.append(self.run(arg))
        kwargs: dict[str, Any] = {}
        for keyword in node.keywords:
            if keyword.arg is None:
                raise EvalError("'**' unpacking is not allowed")
            kwargs[keyword.arg] = self.run(keyword.value)
        return bounded(fn.impl(*args, **kwargs), f"{fn.name}(...)")

    # comprehensions
    def _iterable(self, value: Any) -> list[Any]:
        if isinstance(value, str | list | tuple | dict | set | frozenset):
            items = list(value)
            if len(items) > MAX_ITEMS:
                raise EvalError(f"iterating over {len(items)} items; the limit is {MAX_ITEMS}")
            return items
        raise EvalError(f"a {type(value).__name__} cannot be iterated")

    def _comprehension(self, generators: list[ast.comprehension], emit: Callable[[], None]) -> None:
        def loop(index: int) -> None:
            if index == len(generators):
                emit()
                return
            gen = generators[index]
            if gen.is_async:
                raise EvalError("async comprehensions are not allowed")
            for item in self._iterable(self.run(gen.iter)):
                self._bind(gen.target, item)
                if all(self.run(cond) for cond in gen.ifs):
                    loop(index + 1)

        self.scopes.append({})
        try:
            loop(0)
        finally:
            self.scopes.pop()

    def _bind(self, target: ast.expr, value: Any) -> None:
        if isinstance(target, ast.Name):
            if target.id.startswith("_"):
                raise EvalError(f"name {target.id!r} is refused")
            self.scopes[-1][target.id] = value
        elif isinstance(target, ast.Tuple | ast.List):
            items = self._iterable(value)
            if len(items) != len(target.elts):
                raise ValueError(f"cannot unpack {len(items)} values into {len(target.elts)} names")
            for sub, item in zip(target.elts, items, strict=True):
                self._bind(sub, item)
        else:
            raise EvalError(f"{_describe(target)} is not allowed as a loop target")

    def _collect(self, node: ast.ListComp | ast.GeneratorExp | ast.SetComp) -> list[Any]:
        out: list[Any] = []

        def emit() -> None:
            if len(out) >= MAX_ITEMS:
                raise EvalError(f"a comprehension of more than {MAX_ITEMS} items")
            out.append(self.run(node.elt))

        self._comprehension(node.generators, emit)
        return out

    def _ListComp(self, node: ast.ListComp) -> Any:
        return self._collect(node)

    def _GeneratorExp(self, node: ast.GeneratorExp) -> Any:
        return self._collect(node)

    def _SetComp(self, node: ast.SetComp) -> Any:
        return set(self._collect(node))

    def _DictComp(self, node: ast.DictComp) -> Any:
        out: dict[Any, Any] = {}

        def emit() -> None:
            if len(out) >= MAX_ITEMS:
                raise EvalError(f"a comprehension of more than {MAX_ITEMS} items")
            out[self.run(node.key)] = self.run(node.value)

        self._comprehension(node.generators, emit)
        return out


def _methods_of(obj: Any) -> dict[str, Callable[..., Any]] | None:
    if isinstance(obj, str):
        return _STR_METHODS
    if isinstance(obj, list):
        return _LIST_METHODS
    if isinstance(obj, tuple):
        return _TUPLE_METHODS
    if isinstance(obj, dict):
        return _DICT_METHODS
    return None


def _describe(node: ast.AST) -> str:
    kinds = {
        "Lambda": "a lambda",
        "NamedExpr": "an assignment expression (:=)",
        "Await": "await",
        "Yield": "yield",
        "YieldFrom": "yield",
        "Starred": "'*' unpacking",
    }
    return kinds.get(type(node).__name__, f"a {type(node).__name__} node")


def _source(node: ast.AST) -> str:
    try:
        return repr(ast.unparse(node))
    except Exception:  # ast.unparse on odd trees: describing the node is enough
        return _describe(node)
