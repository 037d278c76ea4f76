"""Typed reading of PyYAML nodes with ``file:line:col`` messages.

PyYAML's ``compose`` keeps every node's start mark; reading values through :class:`NodeReader`
turns a wrong type or an unknown key into one precise :class:`ParseError`::

    robot.yaml:12:5: joints.elbow.limits.lower: expected a number
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Collection, Iterator

import yaml
from yaml.nodes import MappingNode, Node, ScalarNode, SequenceNode

from robodesc.frontends.compose.numbers import finite
from robodesc.ir.diagnostics import ParseError, SourceLoc

MERGE_TAG = "tag:yaml.org,2002:merge"
# Aliases share nodes, so a hostile file can make a walk exponential; no real robot comes close.
NODE_BUDGET = 2_000_000


# Nesting depth of YAML collections. PyYAML's composer is recursive (a few hundred levels reach
# Python's recursion limit); its parser is a state machine, so the depth is checked on the parser's
# events first. Compositions nest five or six levels deep.
MAX_DEPTH = 100


def _check_depth(text: str, file: str) -> None:
    depth = 0
    for event in yaml.parse(text, Loader=yaml.SafeLoader):
        if isinstance(event, yaml.CollectionStartEvent):
            depth += 1
            if depth > MAX_DEPTH:
                mark = event.start_mark
                raise ParseError(
                    f"YAML nested more than {MAX_DEPTH} levels deep; refused",
                    loc=SourceLoc(file, mark.line + 1, mark.column + 1) if mark is not None else SourceLoc(file),
                )
        elif isinstance(event, yaml.CollectionEndEvent):
            depth -= 1


def compose_text(text: str, file: str) -> Node | None:
    try:
        _check_depth(text, file)
        return yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        loc = SourceLoc(file, mark.line + 1, mark.column + 1) if mark is not None else SourceLoc(file)
        problem = exc.problem or exc.context or "malformed YAML"
        raise ParseError(f"YAML syntax: {problem}", loc=loc) from None
    except yaml.YAMLError as exc:
        raise ParseError(f"YAML syntax: {exc}", loc=SourceLoc(file)) from None


class NodeReader:
    """Reads values from nodes of one file; every error names the path and the place."""

    def __init__(self, file: str) -> None:
        self.file = file
        self._visited = 0

    def loc(self, node: Node) -> SourceLoc:
        mark = node.start_mark
        return SourceLoc(self.file, mark.line + 1, mark.column + 1)

    def fail(self, node: Node, path: str, message: str) -> ParseError:
        return ParseError(message, element=path, loc=self.loc(node))

    def _tick(self, node: Node, path: str) -> None:
        self._visited += 1
        if self._visited > NODE_BUDGET:
            raise self.fail(node, path, "document too large once aliases are expanded")

    # ---- containers -----------------------------------------------------------------------
    def pairs(self, node: Node, path: str) -> list[tuple[ScalarNode, Node]]:
        """A mapping's entries with ``<<`` merge keys applied (explicit keys win), in order."""
        if not isinstance(node, MappingNode):
            raise self.fail(node, path, f"expected a mapping, got {describe(node)}")
        self._tick(node, path)
        merged: list[tuple[ScalarNode, Node]] = []
        explicit: list[tuple[ScalarNode, Node]] = []
        for key, value in node.value:
            if key.tag == MERGE_TAG:
                sources = value.value if isinstance(value, SequenceNode) else [value]
                for source in sources:
                    for k, v in self.pairs(source, path):
                        if not any(k.value == mk.value for mk, _ in merged):
                            merged.append((k, v))
                continue
            if not isinstance(key, ScalarNode):
                raise self.fail(key, path, "mapping keys must be plain names")
            for seen, _ in explicit:
                if seen.value == key.value:
                    raise self.fail(
                        key, path, f"duplicate key {key.value!r} (first at line {seen.start_mark.line + 1})"
                    )
            explicit.append((key, value))
        names = {k.value for k, _ in explicit}
        return [(k, v) for k, v in merged if k.value not in names] + explicit

    def mapping(
        self,
        node: Node,
        path: str,
        allowed: Collection[str] | None = None,
        required: Collection[str] = (),
    ) -> dict[str, Node]:
        """Entries by key; unknown keys are rejected with a suggestion, missing required ones named."""
        out: dict[str, Node] = {}
        for key, value in self.pairs(node, path):
            name = str(key.value)
            if allowed is not None and name not in allowed:
                close = difflib.get_close_matches(name, list(allowed), n=1)
                hint = f"; did you mean {close[0]!r}?" if close else f" (known keys: {', '.join(sorted(allowed))})"
                raise self.fail(key, path, f"unknown key {name!r}{hint}")
            out[name] = value
        for name in required:
            if name not in out:
                raise self.fail(node, path, f"missing required key {name!r}")
        return out

    def sequence(self, node: Node, path: str) -> list[Node]:
        if not isinstance(node, SequenceNode):
            raise self.fail(node, path, f"expected a list, got {describe(node)}")
        self._tick(node, path)
        return list(node.value)

    def items(self, node: Node, path: str) -> Iterator[tuple[str, Node, str]]:
        """``(name, value, path)`` of a mapping of named things."""
        for key, value in self.pairs(node, path):
            name = str(key.value)
            if not name:
                raise self.fail(key, path, "names may not be empty")
            yield name, value, f"{path}.{name}"

    # ---- scalars ----------------------------------------------------------------------------
    def number(self, node: Node, path: str) -> float:
        if isinstance(node, ScalarNode) and node.tag in ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float"):
            value = _to_float(node.value)
        elif isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:str" and node.style is None:
            # YAML 1.1 reads 1e-3 (no dot) as a string; it is a number to anyone writing a robot.
            value = _to_float(node.value)
        else:
            value = None
        if value is None:
            raise self.fail(node, path, f"expected a number, got {describe(node)}")
        return finite(value, path, self.loc(node), written=repr(node.value))

    def positive(self, node: Node, path: str, *, allow_zero: bool = False) -> float:
        value = self.number(node, path)
        if value < 0 or (value == 0 and not allow_zero):
            raise self.fail(
                node, path, f"expected a {'non-negative' if allow_zero else 'positive'} number, got {value:g}"
            )
        return value

    def integer(self, node: Node, path: str) -> int:
        value = self.number(node, path)
        if value != int(value):
            raise self.fail(node, path, f"expected a whole number, got {value:g}")
        return int(value)

    def string(self, node: Node, path: str) -> str:
        if not isinstance(node, ScalarNode) or node.tag == "tag:yaml.org,2002:null":
            raise self.fail(node, path, f"expected a string, got {describe(node)}")
        return str(node.value)

    def boolean(self, node: Node, path: str) -> bool:
        if isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:bool":
            return node.value.lower() in ("true", "yes", "on", "y")
        raise self.fail(node, path, f"expected true or false, got {describe(node)}")

    def choice(self, node: Node, path: str, options: Collection[str]) -> str:
        value = self.string(node, path)
        if value not in options:
            close = difflib.get_close_matches(value, list(options), n=1)
            hint = f"; did you mean {close[0]!r}?" if close else ""
            raise self.fail(node, path, f"expected one of {', '.join(options)}, got {value!r}{hint}")
        return value

    def numbers(self, node: Node, path: str, count: int | Collection[int]) -> list[float]:
        counts = (count,) if isinstance(count, int) else tuple(count)
        items = self.sequence(node, path)
        if len(items) not in counts:
            want = " or ".join(str(c) for c in counts)
            raise self.fail(node, path, f"expected {want} numbers, got {len(items)}")
        return [self.number(item, f"{path}[{i}]") for i, item in enumerate(items)]

    def vec3(self, node: Node, path: str) -> tuple[float, float, float]:
        a, b, c = self.numbers(node, path, 3)
        return (a, b, c)

    def is_null(self, node: Node) -> bool:
        return isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:null"


def describe(node: Node) -> str:
    if isinstance(node, MappingNode):
        return "a mapping"
    if isinstance(node, SequenceNode):
        return "a list"
    if isinstance(node, ScalarNode):
        if node.tag == "tag:yaml.org,2002:null":
            return "nothing (null)"
        if node.tag == "tag:yaml.org,2002:bool":
            return f"a boolean ({node.value})"
        if node.tag in ("tag:yaml.org,2002:int", "tag:yaml.org,2002:float"):
            return f"a number ({node.value})"
        return f"a string ({node.value!r})"
    return "something else"


def _to_float(text: str) -> float | None:
    try:
        return float(text.replace("_", ""))
    except ValueError:
        lowered = text.lower()
        if lowered in (".inf", "+.inf"):
            return math.inf
        if lowered == "-.inf":
            return -math.inf
        if lowered == ".nan":
            return math.nan
        return None


def merge_nodes(base: Node, over: Node, reader: NodeReader, path: str) -> Node:
    """``over`` deep-merged onto ``base``: mappings merge key by key, a null deletes, anything else replaces."""
    if isinstance(base, MappingNode) and isinstance(over, MappingNode):
        entries = list(reader.pairs(base, path))
        for key, value in reader.pairs(over, path):
            index = next((i for i, (k, _) in enumerate(entries) if k.value == key.value), None)
            if reader.is_null(value):
                if index is not None:
                    entries.pop(index)
                continue
            if index is None:
                entries.append((key, value))
            else:
                entries[index] = (
                    entries[index][0],
                    merge_nodes(entries[index][1], value, reader, f"{path}.{key.value}"),
                )
        return MappingNode(base.tag, list(entries), base.start_mark, base.end_mark)
    return over
