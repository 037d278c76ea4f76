"""A syntax tree for the robotics subset of HoloScript (see docs/compositions.md).

Grammar, informally::

    file      := item*
    item      := NAME ':' value                       -- a property
               | '@' NAME [ '{' entries '}' | '(' entries ')' ]   -- a trait
               | NAME [STRING|NAME] ['using' STRING] '{' item* '}' -- a block
               | NAME NAME* ['(' ... ')'] '{' ... '}' -- any other block: skipped, balanced
    value     := STRING | ['-'|'+'] NUMBER | true | false | null | NAME
               | '[' (value [','])* ']' | '{' entries '}'
    entries   := ((NAME|STRING) ':' value [','|';'])*

Blocks whose kind is in :data:`STRUCTURAL` are parsed; any other block (``logic``, ``state``,
``system``, ``function f(x) { ... }``) is skipped by brace matching and listed in ``skipped``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from robodesc.compose.holo_lexer import Kind, Token, tokenize
from robodesc.ir.diagnostics import ParseError, SourceLoc

STRUCTURAL = frozenset(
    {"composition", "environment", "template", "object", "orb", "spatial_group", "group", "behavior"}
)

Data = float | str | bool | None | list["Value"] | dict[str, "Value"]


@dataclass(slots=True)
class Value:
    data: Data
    loc: SourceLoc
    # For object values, where each key was written (for messages about one entry).
    key_locs: dict[str, SourceLoc] = field(default_factory=dict)


@dataclass(slots=True)
class Trait:
    name: str
    params: dict[str, Value]
    loc: SourceLoc
    key_locs: dict[str, SourceLoc] = field(default_factory=dict)


@dataclass(slots=True)
class Block:
    kind: str
    name: str | None
    loc: SourceLoc
    name_loc: SourceLoc
    using: str | None = None
    using_loc: SourceLoc | None = None
    props: dict[str, Value] = field(default_factory=dict)
    prop_locs: dict[str, SourceLoc] = field(default_factory=dict)
    traits: list[Trait] = field(default_factory=list)
    children: list[Block] = field(default_factory=list)


@dataclass(slots=True)
class Skipped:
    kind: str
    loc: SourceLoc


@dataclass(slots=True)
class Document:
    body: Block
    skipped: list[Skipped]
    duplicate_keys: list[tuple[str, SourceLoc]]


def parse(text: str, file: str) -> Document:
    parser = _Parser(tokenize(text, file), file)
    root = Block("file", None, SourceLoc(file, 1, 1), SourceLoc(file, 1, 1))
    parser.items(root, top=True)
    return Document(root, parser.skipped, parser.duplicates)


class _Parser:
    def __init__(self, tokens: list[Token], file: str) -> None:
        self.toks = tokens
        self.pos = 0
        self.file = file
        self.skipped: list[Skipped] = []
        self.duplicates: list[tuple[str, SourceLoc]] = []

    # ---- token helpers ---------------------------------------------------------------------
    @property
    def tok(self) -> Token:
        return self.toks[self.pos]

    def peek(self, ahead: int = 1) -> Token:
        return self.toks[min(self.pos + ahead, len(self.toks) - 1)]

    def loc(self, tok: Token | None = None) -> SourceLoc:
        t = tok or self.tok
        return SourceLoc(self.file, t.line, t.column)

    def take(self) -> Token:
        t = self.tok
        if t.kind is not Kind.EOF:
            self.pos += 1
        return t

    def is_punct(self, text: str, tok: Token | None = None) -> bool:
        t = tok or self.tok
        return t.kind is Kind.PUNCT and t.text == text

    def expect(self, text: str, what: str) -> Token:
        if not self.is_punct(text):
            raise self.error(f"expected '{text}' {what}, found {self.tok.describe()}")
        return self.take()

    def error(self, message: str, tok: Token | None = None) -> ParseError:
        return ParseError(message, loc=self.loc(tok))

    # ---- items -----------------------------------------------------------------------------
    def items(self, block: Block, *, top: bool = False) -> None:
        while True:
            t = self.tok
            if t.kind is Kind.EOF:
                if not top:
                    raise ParseError(
                        f"unbalanced braces: {block.kind} {block.name or ''} opened here is never closed".replace(
                            "  ", " "
                        ),
                        loc=block.loc,
                    )
                return
            if self.is_punct("}"):
                if top:
                    raise self.error("unbalanced braces: '}' without a matching '{'")
                self.take()
                return
            if self.is_punct(",") or self.is_punct(";"):
                self.take()
                continue
            if self.is_punct("@"):
                block.traits.append(self.trait())
                continue
            if t.kind in (Kind.IDENT, Kind.STRING) and self.is_punct(":", self.peek()):
                key = self.take()
                self.take()
                if key.text in block.props:
                    self.duplicates.append((key.text, self.loc(key)))
                block.props[key.text] = self.value()
                block.prop_locs[key.text] = self.loc(key)
                continue
            if t.kind is Kind.IDENT:
                self.block(block)
                continue
            raise self.error(f"unexpected {t.describe()}")

    def block(self, parent: Block) -> None:
        kw = self.take()
        if kw.text not in STRUCTURAL:
            self.skip_block(kw)
            return
        name: str | None = None
        name_tok = kw
        if self.tok.kind in (Kind.STRING, Kind.IDENT) and not (
            self.tok.kind is Kind.IDENT and self.tok.text == "using"
        ):
            name_tok = self.take()
            name = name_tok.text
        block = Block(kw.text, name, self.loc(kw), self.loc(name_tok))
        if self.tok.kind is Kind.IDENT and self.tok.text == "using":
            self.take()
            after = self.tok
            if after.kind is not Kind.STRING and after.kind is not Kind.IDENT:
                raise self.error(f"expected a template name after 'using', found {after.describe()}")
            using = self.take()
            block.using, block.using_loc = using.text, self.loc(using)
        self.expect("{", f"to open {kw.text} {name or ''}".rstrip())
        self.items(block)
        parent.children.append(block)

    def skip_block(self, kw: Token) -> None:
        """Step over ``kw [names] [( ... )] { ... }`` by matching brackets, without reading it."""
        while self.tok.kind in (Kind.IDENT, Kind.STRING):
            self.take()
        if self.is_punct("("):
            self.skip_balanced("(", ")")
        if not self.is_punct("{"):
            if self.tok.kind is Kind.NUMBER or self.tok.kind is Kind.OTHER or self.is_punct("["):
                raise self.error(f"expected ':' after {kw.text!r}, found {self.tok.describe()}", self.tok)
            raise self.error(f"expected ':' or '{{' after {kw.text!r}, found {self.tok.describe()}")
        self.skip_balanced("{", "}")
        self.skipped.append(Skipped(kw.text, self.loc(kw)))

    def skip_balanced(self, open_: str, close: str) -> None:
        start = self.tok
        stack = [close]
        self.take()
        pairs = {"{": "}", "(": ")", "[": "]"}
        while stack:
            t = self.take()
            if t.kind is Kind.EOF:
                raise self.error(f"unbalanced braces: '{open_}' opened here is never closed", start)
            if t.kind is Kind.PUNCT and t.text in pairs:
                stack.append(pairs[t.text])
            elif t.kind is Kind.PUNCT and t.text in ")]}":
                if t.text != stack[-1]:
                    raise self.error(f"unbalanced braces: found '{t.text}' where '{stack[-1]}' was expected", t)
                stack.pop()

    def trait(self) -> Trait:
        at = self.take()
        if self.tok.kind is not Kind.IDENT:
            raise self.error(f"expected a trait name after '@', found {self.tok.describe()}")
        name = self.take().text
        trait = Trait(name, {}, self.loc(at))
        if self.is_punct("{"):
            obj = self.object_value("{", "}")
            assert isinstance(obj.data, dict)
            trait.params, trait.key_locs = obj.data, obj.key_locs
        elif self.is_punct("("):
            obj = self.object_value("(", ")")
            assert isinstance(obj.data, dict)
            trait.params, trait.key_locs = obj.data, obj.key_locs
        return trait

    # ---- values ----------------------------------------------------------------------------
    def value(self) -> Value:
        t = self.tok
        loc = self.loc(t)
        if t.kind is Kind.STRING:
            self.take()
            return Value(t.text, loc)
        if t.kind is Kind.NUMBER:
            return Value(self.number(1.0), loc)
        if t.kind is Kind.OTHER and t.text in "+-" and self.peek().kind is Kind.NUMBER:
            self.take()
            return Value(self.number(-1.0 if t.text == "-" else 1.0), loc)
        if t.kind is Kind.IDENT:
            self.take()
            if t.text == "true":
                return Value(True, loc)
            if t.text == "false":
                return Value(False, loc)
            if t.text in ("null", "undefined"):
                return Value(None, loc)
            return Value(t.text, loc)
        if self.is_punct("["):
            self.take()
            items: list[Value] = []
            while not self.is_punct("]"):
                if self.tok.kind is Kind.EOF:
                    raise ParseError("unbalanced brackets: '[' opened here is never closed", loc=loc)
                items.append(self.value())
                if self.is_punct(","):
                    self.take()
            self.take()
            return Value(items, loc)
        if self.is_punct("{"):
            return self.object_value("{", "}")
        raise self.error(f"expected a value, found {t.describe()}")

    def number(self, sign: float) -> float:
        t = self.take()
        try:
            return sign * float(t.text.replace("_", ""))
        except ValueError:
            raise self.error(f"bad number {t.text!r}", t) from None

    def object_value(self, open_: str, close: str) -> Value:
        start = self.take()
        loc = self.loc(start)
        data: dict[str, Value] = {}
        key_locs: dict[str, SourceLoc] = {}
        while not self.is_punct(close):
            t = self.tok
            if t.kind is Kind.EOF:
                raise ParseError(f"unbalanced braces: '{open_}' opened here is never closed", loc=loc)
            if self.is_punct(",") or self.is_punct(";"):
                self.take()
                continue
            if t.kind not in (Kind.IDENT, Kind.STRING):
                raise self.error(f"expected a key, found {t.describe()}")
            self.take()
            self.expect(":", f"after key {t.text!r}")
            if t.text in data:
                self.duplicates.append((t.text, self.loc(t)))
            data[t.text] = self.value()
            key_locs[t.text] = self.loc(t)
        self.take()
        return Value(data, loc, key_locs)
