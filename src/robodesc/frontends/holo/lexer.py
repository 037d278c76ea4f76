"""Tokens of HoloScript ``.holo`` files.

The token rules follow HoloScript's own lexer (``packages/core/src/parser/composition/lexer.ts``):
``//`` and ``/* */`` comments; strings in ``"`` or ``'`` that may run over several lines, with
backslash escapes; identifiers of letters, digits, ``_`` (and ``$``); numbers; the punctuation
``{ } [ ] ( ) : , . ; @`` and operators. Two deliberate differences, both more careful:
a back-quoted template string is one string token (HoloScript drops the back quote and reads its
text as code, where an apostrophe would open a string), and a number keeps its exponent or hex
digits (``1e-3``, ``0xff``). A character HoloScript's lexer drops silently (``%``, ``~``, ``\\``
...) becomes an ``other`` token, so that the parser can name it where it matters.

Every token records whether a line break comes before it: HoloScript ends a property's value at
the end of its line.

>>> [t.text for t in tokenize('object "A" { mass: -2.5 } // done', "a.holo")]
['object', 'A', '{', 'mass', ':', '-', '2.5', '}', '']
"""

from __future__ import annotations

import enum
from dataclasses import dataclass

from robodesc.ir.diagnostics import ParseError, SourceLoc


class Kind(enum.Enum):
    IDENT = "name"
    STRING = "string"
    NUMBER = "number"
    PUNCT = "punctuation"
    OP = "operator"
    OTHER = "character"
    EOF = "end of file"


PUNCT = frozenset("{}[]():,@;.")
# Longest first: HoloScript's multi-character operators, plus JavaScript's that code blocks use.
OPERATORS = (
    "===",
    "!==",
    "...",
    "**=",
    "=>",
    "->",
    "==",
    "!=",
    "<=",
    ">=",
    "+=",
    "-=",
    "*=",
    "/=",
    "%=",
    "++",
    "--",
    "&&",
    "||",
    "??",
    "?.",
    "**",
    "::",
    "=",
    "+",
    "-",
    "*",
    "/",
    "<",
    ">",
    "!",
    "?",
    "#",
    "%",
    "&",
    "|",
    "^",
    "~",
)


@dataclass(slots=True, frozen=True)
class Token:
    kind: Kind
    text: str  # for strings: the decoded value
    line: int
    column: int
    newline_before: bool = False

    def describe(self) -> str:
        if self.kind is Kind.EOF:
            return "end of file"
        if self.kind is Kind.STRING:
            return f"string {self.text!r}"
        return f"{self.kind.value} {self.text!r}"


_ESCAPES = {"n": "\n", "t": "\t", "r": "\r", "0": "\0", "\\": "\\", "'": "'", '"': '"', "`": "`"}


def tokenize(text: str, file: str) -> list[Token]:
    out: list[Token] = []
    i, line, col = 0, 1, 1
    n = len(text)
    newline = True

    def advance(count: int) -> None:
        nonlocal i, line, col
        for _ in range(count):
            if text[i] == "\n":
                line += 1
                col = 1
            else:
                col += 1
            i += 1

    while i < n:
        ch = text[i]
        if ch == "\n":
            newline = True
            advance(1)
            continue
        if ch in " \t\r\f\v\ufeff\u00a0":
            advance(1)
            continue
        if text.startswith("//", i):
            end = text.find("\n", i)
            advance((n if end < 0 else end) - i)
            continue
        if text.startswith("/*", i):
            end = text.find("*/", i + 2)
            if end < 0:
                raise ParseError("unterminated /* comment", loc=SourceLoc(file, line, col))
            if "\n" in text[i:end]:
                newline = True  # a comment over several lines ends the line as a line break does
            advance(end + 2 - i)
            continue
        if ch == "#" and newline and (i + 1 >= n or text[i + 1] in " \t\r\n#!"):
            # A '#' comment line (some HoloScript examples use them; HoloScript's lexer would read
            # the words as tokens and step over them).
            end = text.find("\n", i)
            advance((n if end < 0 else end) - i)
            continue
        kind, value, end = _token_at(text, i, file, line, col)
        out.append(Token(kind, value, line, col, newline))
        newline = False
        advance(end - i)
    out.append(Token(Kind.EOF, "", line, col, True))
    return out


def _token_at(text: str, i: int, file: str, line: int, col: int) -> tuple[Kind, str, int]:
    """The token that starts at ``text[i]`` (at ``line``:``col``): its kind, text and end index."""
    n = len(text)
    ch = text[i]
    if ch == "\\" and i + 1 < n and text[i + 1] == "`":
        # An escaped back quote outside a string (JavaScript pasted into a block): HoloScript
        # drops both characters.
        return Kind.OTHER, "\\`", i + 2
    if text.startswith(("'''", '"""'), i):
        quote3 = text[i : i + 3]
        end = text.find(quote3, i + 3)
        if end < 0:
            raise ParseError(f"unterminated string (opened with {quote3})", loc=SourceLoc(file, line, col))
        return Kind.STRING, text[i + 3 : end], end + 3
    if ch in "\"'`":
        return _string(text, i, file, line, col)
    if ch.isdigit() or (ch == "." and i + 1 < n and text[i + 1].isdigit()):
        end = _number_end(text, i)
        return Kind.NUMBER, text[i:end], end
    if ch.isalpha() or ch in "_$":
        j = i
        while j < n and (text[j].isalnum() or text[j] in "_$"):
            j += 1
        return Kind.IDENT, text[i:j], j
    if ch in PUNCT and not text.startswith("...", i):
        return Kind.PUNCT, ch, i + 1
    for op in OPERATORS:
        if text.startswith(op, i):
            return Kind.OP, op, i + len(op)
    return Kind.OTHER, ch, i + 1


def _string(text: str, i: int, file: str, line: int, col: int) -> tuple[Kind, str, int]:
    """A string in ``"``, ``'`` or a back quote opened at ``text[i]``: its decoded value and the
    index after its closing quote."""
    n = len(text)
    quote = text[i]
    i += 1
    chars: list[str] = []
    while True:
        if i >= n:
            raise ParseError(f"unterminated string (opened with {quote})", loc=SourceLoc(file, line, col))
        c = text[i]
        if c == quote:
            return Kind.STRING, "".join(chars), i + 1
        if c == "\\" and i + 1 < n:
            chars.append(_ESCAPES.get(text[i + 1], text[i + 1]))
            i += 2
            continue
        chars.append(c)
        i += 1


def _number_end(text: str, i: int) -> int:
    """The index after the number that starts at ``text[i]``: hex digits after ``0x``, else digits,
    a fraction and an exponent (``_`` separators allowed in the digits)."""
    n = len(text)
    j = i
    if text.startswith(("0x", "0X"), i):
        j = i + 2
        while j < n and (text[j] in "0123456789abcdefABCDEF_"):
            j += 1
    else:
        while j < n and (text[j].isdigit() or text[j] == "_"):
            j += 1
        if j < n and text[j] == "." and j + 1 < n and text[j + 1].isdigit():
            j += 1
            while j < n and (text[j].isdigit() or text[j] == "_"):
                j += 1
        if j < n and text[j] in "eE":
            k = j + 1
            if k < n and text[k] in "+-":
                k += 1
            if k < n and text[k].isdigit():
                j = k
                while j < n and text[j].isdigit():
                    j += 1
    return j
