"""A typed syntax tree for HoloScript ``.holo`` files, the whole language (see docs/compositions.md).

The grammar is HoloScript's own (``HoloCompositionParser.ts``), read as one uniform shape::

    file      := item*
    item      := '@' NAME ['(' args ')' | '{' entries '}' | ':' value]     -- a trait
               | KEY (':' | '=') value                                     -- a property
               | KEY '{' entries '}'                                       -- physics { ... } and the like
               | KIND [NAME] [words] ['using' STRING] ['@' trait]* ['(' ... ')'] ['->' ...] '{' body '}'
                                                                           -- a block
               | NAME                                                      -- a flag (HoloScript: NAME: true)
    value     := ['-'|'+'|'!'] primary postfix* (OPERATOR value)?          -- on one line
    primary   := STRING | NUMBER | true | false | null | NAME | '@' NAME
               | '[' (value [','])* ']' | '{' entries '}' | '(' ... ')' ['=>' (block | value)]
    entries   := ((NAME|STRING|NUMBER) ':' value [','|';'])*   -- other content: code, skipped

A value that is not a literal (``a.b``, ``x * 2``, an arrow function) is kept as :class:`Expr`
(its text), never evaluated. Blocks of code (``logic``, ``function f(x) { }``, ``on event { }``,
``onClick: { }``, a block with parameters) are skipped by bracket matching and listed in
``Document.skipped``; every other block is parsed, whatever its kind: the lowering decides what
belongs to a robot. Tokens HoloScript's parser steps over silently (a stray ``;`` or operator
between items) are listed in ``Document.stray`` with their place.

Nesting is bounded (:data:`MAX_DEPTH`): deeper input is one :class:`ParseError` at the place
where the limit is crossed, never a ``RecursionError``. Skipping is iterative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from robodesc.frontends.holo.lexer import Kind, Token, tokenize
from robodesc.ir.diagnostics import ParseError, SourceLoc

MAX_DEPTH = 100

# Blocks whose body is code (statements), not declarations: HoloScript parses them as statements
# or skips them; robodesc skips them.
CODE_KINDS = frozenset(
    {
        "logic",
        "function",
        "action",
        "async",
        "on",
        "if",
        "else",
        "for",
        "foreach",
        "while",
        "switch",
        "try",
        "catch",
        "finally",
        "do",
        "handler",
        "lifecycle",
        "return",
        "emit",
        "let",
        "const",
        "var",
        "fn",
        "method",
        "export",
        "import",
        "class",
    }
)


@dataclass(slots=True, frozen=True)
class Expr:
    """A value that is not a literal: kept as its source text (``rate * 2``, ``(e) => { ... }``)."""

    text: str


Data = float | str | bool | None | Expr | list["Value"] | dict[str, "Value"]


@dataclass(slots=True)
class Value:
    data: Data
    loc: SourceLoc
    # For object values, where each key was written (for messages about one entry).
    key_locs: dict[str, SourceLoc] = field(default_factory=dict)
    # True when a bare word was written (``type: revolute``) rather than a string.
    bare: bool = False


@dataclass(slots=True)
class Trait:
    """``@name``, ``@name(key: v, ...)`` (positional arguments are ``_arg0``, ``_arg1`` ... as in
    HoloScript), ``@name { ... }`` or ``@name: value``."""

    name: str
    params: dict[str, Value]
    loc: SourceLoc
    key_locs: dict[str, SourceLoc] = field(default_factory=dict)
    in_header: bool = False


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
    # Words of the header after the name (``collider box { }``, ``extends Base``).
    words: list[str] = field(default_factory=list)


@dataclass(slots=True)
class Skipped:
    kind: str
    loc: SourceLoc
    why: str = "code"


@dataclass(slots=True)
class Document:
    body: Block
    skipped: list[Skipped]
    duplicate_keys: list[tuple[str, SourceLoc]]
    stray: list[tuple[str, SourceLoc]] = field(default_factory=list)
    equals_props: list[tuple[str, SourceLoc]] = field(default_factory=list)


def parse(text: str, file: str) -> Document:
    parser = _Parser(tokenize(text, file), file)
    root = Block("file", None, SourceLoc(file, 1, 1), SourceLoc(file, 1, 1))
    parser.items(root, top=True)
    return Document(root, parser.skipped, parser.duplicates, parser.stray, parser.equals)


_OPEN = {"{": "}", "(": ")", "[": "]"}
_VALUE_STOP = frozenset({",", ";", "}", "]", ")", ":"})


@dataclass(slots=True)
class _Header:
    """What a block's header says, before its ``{``: ``KIND [NAME] [words] ['using' STRING]
    ['@' trait]* ['(' ... ')'] ['->' ...]``."""

    name_tok: Token  # the name's token, else the keyword's (where the block's name is reported)
    name: str | None = None
    using: Token | None = None
    words: list[str] = field(default_factory=list)
    traits: list[Trait] = field(default_factory=list)
    params: bool = False  # a '(' ... ')' list: a function, unless the kind is a declaration
    code: bool = False  # a code kind, or an arrow in the header


class _Parser:
    def __init__(self, tokens: list[Token], file: str) -> None:
        self.toks = tokens
        self.pos = 0
        self.file = file
        self.depth = 0
        self.deepest = 0
        self.skipped: list[Skipped] = []
        self.duplicates: list[tuple[str, SourceLoc]] = []
        self.stray: list[tuple[str, SourceLoc]] = []
        self.equals: list[tuple[str, SourceLoc]] = []

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

    def is_op(self, text: str, tok: Token | None = None) -> bool:
        t = tok or self.tok
        return t.kind is Kind.OP and t.text == text

    def error(self, message: str, tok: Token | None = None) -> ParseError:
        return ParseError(message, loc=self.loc(tok))

    def enter(self, tok: Token) -> None:
        self.depth += 1
        self.deepest = max(self.deepest, self.depth)
        if self.depth > MAX_DEPTH:
            raise self.error(f"nesting deeper than {MAX_DEPTH} levels (blocks, values, lists or objects)", tok)

    def leave(self) -> None:
        self.depth -= 1

    # ---- items -----------------------------------------------------------------------------
    def items(self, block: Block, *, top: bool = False, opener: Token | None = None) -> None:
        while True:
            t = self.tok
            if t.kind is Kind.EOF:
                if not top:
                    what = f"{block.kind} {block.name or ''}".strip()
                    raise ParseError(
                        f"unbalanced braces: {what} opened here is never closed",
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
                trait = self.trait(header=False)
                if trait is not None:
                    block.traits.append(trait)
                continue
            if t.kind in (Kind.IDENT, Kind.STRING, Kind.NUMBER) and self.is_punct(":", self.peek()):
                self.property(block)
                continue
            if t.kind is Kind.IDENT and self.is_op("=", self.peek()):
                # HoloScript reports "Use ':' instead of '='" and reads the value anyway.
                self.equals.append((t.text, self.loc(t)))
                self.property(block)
                continue
            if t.kind is Kind.IDENT:
                self.block_or_flag(block)
                continue
            # Anything else between items (an operator, a stray bracket group): HoloScript's parser
            # steps over it; so does robodesc, and says where.
            self.stray.append((t.text, self.loc(t)))
            if t.kind is Kind.PUNCT and t.text in _OPEN:
                self.skip_balanced()
            else:
                self.take()

    def property(self, block: Block) -> None:
        key = self.take()
        self.take()  # ':' or '='
        name = key.text
        if name in block.props:
            self.duplicates.append((name, self.loc(key)))
        is_handler = name.startswith("on_") or (len(name) > 2 and name.startswith("on") and name[2].isupper())
        if self.is_punct("{") and (is_handler or name == "lifecycle"):
            start = self.tok
            self.skip_balanced()
            self.skipped.append(Skipped(name, self.loc(key)))
            value = Value(Expr("{ ... }"), self.loc(start))
        else:
            value = self.value()
        block.props[name] = value
        block.prop_locs[name] = self.loc(key)

    def block_or_flag(self, parent: Block) -> None:
        kw = self.take()
        kind = kw.text
        # `physics { mass: 2 }` (no colon): HoloScript reads it as the property physics: { ... }.
        if kind == "physics" and self.is_punct("{"):
            value = self.value()
            if kind in parent.props:
                self.duplicates.append((kind, self.loc(kw)))
            parent.props[kind] = value
            parent.prop_locs[kind] = self.loc(kw)
            return
        head = self.block_header(kw)
        if not self.is_punct("{"):
            if head.name is None and not head.words and not head.traits and not head.params:
                # A bare word: HoloScript reads `flag` as the property flag: true.
                parent.props[kind] = Value(True, self.loc(kw), bare=True)
                parent.prop_locs[kind] = self.loc(kw)
                return
            # A one-line statement (`import x from "y"`, `using "T"`, `let a = 1`): not a declaration.
            self.skipped.append(Skipped(kind, self.loc(kw), "statement"))
            return
        if head.code or (head.params and kind not in ("object", "template", "orb", "scene", "composition")):
            self.skip_balanced()
            self.skipped.append(Skipped(kind, self.loc(kw)))
            return
        block = Block(kind, head.name, self.loc(kw), self.loc(head.name_tok), words=head.words)
        if head.using is not None:
            block.using, block.using_loc = head.using.text, self.loc(head.using)
        for trait in head.traits:
            block.traits.append(trait)
        opener = self.take()
        self.enter(opener)
        self.items(block, opener=opener)
        self.leave()
        parent.children.append(block)

    def block_header(self, kw: Token) -> _Header:
        """The header of the statement ``kw`` opens: everything up to ``{``, the end of the line or
        a ``}``, ``;`` or ``,``."""
        head = _Header(kw, code=kw.text in CODE_KINDS)
        while True:
            t = self.tok
            if self.is_punct("{"):
                break
            if t.kind is Kind.EOF or self.is_punct("}") or self.is_punct(";") or self.is_punct(","):
                break
            if t.newline_before:
                break
            if t.kind is Kind.STRING or t.kind is Kind.IDENT:
                if t.kind is Kind.IDENT and t.text == "using" and self.peek().kind in (Kind.STRING, Kind.IDENT):
                    self.take()
                    head.using = self.take()
                    continue
                if head.name is None and not (t.kind is Kind.IDENT and t.text in ("extends", "from", "as")):
                    head.name_tok = self.take()
                    head.name = head.name_tok.text
                else:
                    head.words.append(self.take().text)
                continue
            if self.is_punct("@"):
                trait = self.trait(header=True)
                if trait is not None:
                    head.traits.append(trait)
                continue
            if self.is_punct("("):
                head.params = True
                self.skip_balanced()
                continue
            if self.is_punct("["):
                self.skip_balanced()
                continue
            if t.kind in (Kind.NUMBER, Kind.OP, Kind.OTHER) or self.is_punct("."):
                if self.is_op("=>") or self.is_op("->"):
                    head.code = True
                head.words.append(self.take().text)
                continue
            break
        return head

    def skip_balanced(self) -> None:
        """Step over ``( ... )``, ``[ ... ]`` or ``{ ... }`` by matching brackets (iteratively)."""
        start = self.tok
        stack = [_OPEN[start.text]]
        self.take()
        while stack:
            t = self.take()
            if t.kind is Kind.EOF:
                raise self.error(f"unbalanced braces: '{start.text}' opened here is never closed", start)
            if t.kind is Kind.PUNCT and t.text in _OPEN:
                stack.append(_OPEN[t.text])
            elif t.kind is Kind.PUNCT and t.text in ")]}":
                if t.text != stack[-1]:
                    raise self.error(f"unbalanced braces: found '{t.text}' where '{stack[-1]}' was expected", t)
                stack.pop()

    def trait(self, *, header: bool) -> Trait | None:
        at = self.take()
        if self.tok.kind not in (Kind.IDENT, Kind.STRING, Kind.NUMBER):
            raise self.error(f"expected a trait name after '@', found {self.tok.describe()}")
        name = self.take().text if self.tok.kind is Kind.STRING else self._glued_word()
        while self.is_punct(".") and self.peek().kind is Kind.IDENT and not self.peek().newline_before:
            self.take()
            name += "." + self.take().text
        trait = Trait(name, {}, self.loc(at), in_header=header)
        if self.is_punct("(") and not self.tok.newline_before:
            trait.params, trait.key_locs = self.arguments()
        elif self.is_punct("{") and (not header or self._brace_followed_by_brace()):
            obj = self.object_value()
            if isinstance(obj.data, dict):
                trait.params, trait.key_locs = obj.data, obj.key_locs
        elif self.is_punct(":") and not header:
            self.take()
            if self.is_punct("{"):
                obj = self.object_value()
                if isinstance(obj.data, dict):
                    trait.params, trait.key_locs = obj.data, obj.key_locs
            else:
                trait.params = {"_arg0": self.value()}
        return trait

    def _brace_followed_by_brace(self) -> bool:
        """HoloScript's rule for ``object "A" @t { ... } { ... }``: a header trait owns a brace
        block only when another '{' (the object's body) follows it."""
        depth = 0
        for index in range(self.pos, len(self.toks)):
            t = self.toks[index]
            if t.kind is Kind.PUNCT and t.text in "{[(":
                depth += 1
            elif t.kind is Kind.PUNCT and t.text in "}])":
                depth -= 1
                if depth == 0:
                    following = self.toks[min(index + 1, len(self.toks) - 1)]
                    return following.kind is Kind.PUNCT and following.text == "{"
        return False

    def arguments(self) -> tuple[dict[str, Value], dict[str, SourceLoc]]:
        opener = self.take()
        self.enter(opener)
        params: dict[str, Value] = {}
        locs: dict[str, SourceLoc] = {}
        index = 0
        while not self.is_punct(")"):
            t = self.tok
            if t.kind is Kind.EOF:
                raise self.error("unbalanced brackets: '(' opened here is never closed", opener)
            if self.is_punct(","):
                self.take()
                continue
            if t.kind in (Kind.IDENT, Kind.STRING) and self.is_punct(":", self.peek()):
                self.take()
                self.take()
                if t.text in params:
                    self.duplicates.append((t.text, self.loc(t)))
                params[t.text] = self.value()
                locs[t.text] = self.loc(t)
            else:
                key = f"_arg{index}"
                index += 1
                params[key] = self.value()
                locs[key] = params[key].loc
        self.take()
        self.leave()
        return params, locs

    # ---- values ----------------------------------------------------------------------------
    def value(self) -> Value:
        # Values nest through lists, objects, arrow functions and conditionals: count them all.
        self.enter(self.tok)
        start = self.pos
        first = self.tok
        loc = self.loc(first)
        value = self.unary()
        while self.tok.kind is Kind.OTHER and self._adjacent(self.pos - 1):
            self.take()  # a unit glued to a number (15°): kept in the text
            value = Value(Expr(self._text(start)), loc)
        # Binary operators continue the value on the same line (HoloScript reads one primary and
        # steps over the rest; robodesc keeps the whole expression as text).
        while (
            self.tok.kind is Kind.OP
            and not self.tok.newline_before
            and self.tok.text not in ("=>", "->", "++", "--", "!", "~", "#")
        ):
            op = self.take()
            value = Value(Expr(self._text(start)), loc)
            nxt: Token = self.toks[self.pos]
            if nxt.kind is Kind.EOF or (nxt.kind is Kind.PUNCT and nxt.text in _VALUE_STOP):
                # A type annotation (`array<string>,`) ends with an operator; HoloScript steps over it.
                break
            if op.text == "?" and not self.tok.newline_before:
                self.value()
                if self.is_punct(":"):
                    self.take()
                    self.value()
            else:
                self.unary()
            value = Value(Expr(self._text(start)), loc)
        self.leave()
        return value

    def unary(self) -> Value:
        t = self.tok
        loc = self.loc(t)
        if t.kind is Kind.OP and t.text in ("-", "+") and self.peek().kind is Kind.NUMBER:
            self.take()
            number = self.number(-1.0 if t.text == "-" else 1.0)
            return self.postfix(Value(number, loc), self.pos - 2)
        start = self.pos
        prefixed = False
        # Prefix operators and keywords (`- x`, `!!x`, `new f()`, `await g()`), read in a loop.
        while (self.tok.kind is Kind.OP and self.tok.text in ("-", "+", "!", "~", "...")) or (
            self.tok.kind is Kind.IDENT
            and self.tok.text in ("new", "await", "typeof")
            and not self.peek().newline_before
            and self.peek().kind in (Kind.IDENT, Kind.PUNCT, Kind.OP, Kind.NUMBER, Kind.STRING)
            and not (self.peek().kind is Kind.PUNCT and self.peek().text in _VALUE_STOP)
        ):
            self.take()
            prefixed = True
        inner = self.primary()
        if prefixed:
            return Value(Expr(self._text(start)), loc)
        return inner

    def primary(self) -> Value:
        t = self.tok
        loc = self.loc(t)
        start = self.pos
        if t.kind is Kind.STRING:
            self.take()
            return self.postfix(Value(t.text, loc), start)
        if t.kind is Kind.NUMBER:
            return self.postfix(Value(self.number(1.0), loc), start)
        if t.kind is Kind.IDENT:
            self.take()
            if t.text in ("true", "True", "TRUE"):
                return Value(True, loc)
            if t.text in ("false", "False", "FALSE"):
                return Value(False, loc)
            if t.text in ("null", "undefined", "none"):
                return Value(None, loc)
            if t.text == "function" and not self.tok.newline_before:
                while not self.is_punct("{") and self.tok.kind is not Kind.EOF and not self.is_punct("}"):
                    if self.tok.kind is Kind.PUNCT and self.tok.text in "([":
                        self.skip_balanced()
                    else:
                        self.take()
                if self.is_punct("{"):
                    self.skip_balanced()
                return Value(Expr(self._text(start)), loc)
            return self.postfix(Value(t.text, loc, bare=True), start)
        if self.is_punct("@"):
            self.take()
            if self.tok.kind not in (Kind.IDENT, Kind.NUMBER):
                raise self.error(f"expected a trait name after '@', found {self.tok.describe()}")
            name = "@" + self._glued_word()
            if (self.is_punct("(") or self.is_punct("{")) and not self.tok.newline_before:
                self.skip_balanced()  # a trait with its configuration, as a value (traits: [@a { }])
                return Value(Expr(self._text(start)), loc)
            return Value(name, loc)
        if self.is_op("#") and self.is_punct("{", self.peek()) and self._adjacent(self.pos):
            self.take()
            self.skip_balanced()  # #{name}: a value injected by a template engine
            return Value(Expr(self._text(start)), loc)
        if self.is_op("#") and self.peek().kind in (Kind.NUMBER, Kind.IDENT) and self._adjacent(self.pos):
            # An unquoted colour, #888888 or #ff00aa (HoloScript's parser stops here; robodesc reads it).
            self.take()
            return Value("#" + self._glued_word(), loc)
        if self.is_punct("["):
            return self.postfix(self.list_value(), start)
        if self.is_punct("{"):
            return self.object_value()
        if self.is_punct("("):
            self.skip_balanced()
            if self.is_op("=>"):
                self.take()
                if self.is_punct("{"):
                    self.skip_balanced()
                else:
                    self.value()
            return self.postfix(Value(Expr(self._text(start)), loc), start)
        raise self.error(f"expected a value, found {t.describe()}")

    def postfix(self, value: Value, start: int) -> Value:
        """``a.b``, ``f(x)``, ``a[0]``, ``x => ...``: the value becomes an expression."""
        changed = False
        while not self.tok.newline_before or self.is_punct("."):
            if (self.is_punct(".") and self.peek().kind in (Kind.IDENT, Kind.NUMBER)) or (
                self.is_op("?.") and self.peek().kind is Kind.IDENT
            ):
                self.take()
                self.take()
            elif (self.is_punct("(") or self.is_punct("[")) and not self.tok.newline_before:
                if isinstance(value.data, list) and self.is_punct("["):
                    break
                self.skip_balanced()
            elif self.is_op("=>") and not self.tok.newline_before:
                self.take()
                if self.is_punct("{"):
                    self.skip_balanced()
                else:
                    self.value()
            else:
                break
            changed = True
        if changed:
            return Value(Expr(self._text(start)), value.loc)
        return value

    def _adjacent(self, index: int) -> bool:
        """Whether token ``index + 1`` starts right where token ``index`` ends (no space between)."""
        a, b = self.toks[index], self.toks[min(index + 1, len(self.toks) - 1)]
        return a.kind is not Kind.STRING and b.line == a.line and b.column == a.column + len(a.text)

    def _glued_word(self) -> str:
        """A word the lexer split (``2d_canvas``, ``1a2b3c``): the tokens written without a space."""
        word = self.take().text
        while self.tok.kind in (Kind.IDENT, Kind.NUMBER) and self._adjacent(self.pos - 1):
            word += self.take().text
        return word

    def _text(self, start: int) -> str:
        parts: list[str] = []
        for t in self.toks[start : self.pos]:
            parts.append(repr(t.text) if t.kind is Kind.STRING else t.text)
        return " ".join(parts)

    def number(self, sign: float) -> float:
        t = self.take()
        raw = t.text.replace("_", "")
        try:
            return sign * (float(int(raw, 16)) if raw.lower().startswith("0x") else float(raw))
        except ValueError:
            raise self.error(f"bad number {t.text!r}", t) from None
        except OverflowError:
            # A hex literal beyond the float range; 1e999 reads as inf the same way. The lowering's
            # finite check refuses it, naming the element that reads it.
            return sign * math.inf

    def list_value(self) -> Value:
        opener = self.take()
        loc = self.loc(opener)
        self.enter(opener)
        items: list[Value] = []
        while not self.is_punct("]"):
            if self.tok.kind is Kind.EOF:
                raise ParseError("unbalanced brackets: '[' opened here is never closed", loc=loc)
            if self.is_punct(",") or self.is_punct(";"):
                self.take()
                continue
            if self.tok.newline_before and self.tok.kind is Kind.IDENT and self.is_punct(":", self.peek()):
                raise ParseError("unbalanced brackets: '[' opened here is never closed", loc=loc)
            if self.is_punct("}") or self.is_punct(")"):
                raise self.error(
                    f"unbalanced brackets: '[' opened at {loc.line}:{loc.column} is closed by '{self.tok.text}'"
                )
            items.append(self.value())
            if not (self.is_punct(",") or self.is_punct("]") or self.is_punct(";")) and not self.tok.newline_before:
                raise self.error(f"expected ',' or ']' in a list, found {self.tok.describe()}")
        self.take()
        self.leave()
        return Value(items, loc)

    def object_value(self) -> Value:
        opener = self.take()
        loc = self.loc(opener)
        self.enter(opener)
        data: dict[str, Value] = {}
        key_locs: dict[str, SourceLoc] = {}
        code = False
        while not self.is_punct("}"):
            t = self.tok
            if t.kind is Kind.EOF:
                raise ParseError("unbalanced braces: '{' opened here is never closed", loc=loc)
            if self.is_punct(",") or self.is_punct(";"):
                self.take()
                continue
            if t.kind in (Kind.IDENT, Kind.STRING, Kind.NUMBER) and self.is_punct(":", self.peek()):
                self.take()
                self.take()
                if t.text in data:
                    self.duplicates.append((t.text, self.loc(t)))
                data[t.text] = self.value()
                key_locs[t.text] = self.loc(t)
                continue
            if t.kind is Kind.IDENT and self.is_punct("{", self.peek()):
                # A nested declaration block inside an object value (physics { collider { ... } }).
                self.take()
                data[t.text] = self.object_value()
                key_locs[t.text] = self.loc(t)
                continue
            # Code, a spread, a shorthand entry: HoloScript skips the rest of the object; so does robodesc.
            code = True
            depth = 0
            while True:
                u = self.tok
                if u.kind is Kind.EOF:
                    raise ParseError("unbalanced braces: '{' opened here is never closed", loc=loc)
                if u.kind is Kind.PUNCT and u.text in _OPEN:
                    self.skip_balanced()
                    continue
                if u.kind is Kind.PUNCT and u.text == "}" and depth == 0:
                    break
                if u.kind is Kind.PUNCT and u.text in ")]":
                    raise self.error(f"unbalanced braces: found '{u.text}' where '}}' was expected", u)
                self.take()
            break
        self.take()
        self.leave()
        if code and not data:
            return Value(Expr("{ ... }"), loc)
        return Value(data, loc, key_locs)
