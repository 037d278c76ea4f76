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

    def add(kind: Kind, value: str, at_line: int, at_col: int) -> None:
        nonlocal newline
        out.append(Token(kind, value, at_line, at_col, newline))
        newline = False

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
            start = (line, col)
            end = text.find("*/", i + 2)
            if end < 0:
                raise ParseError("unterminated /* comment", loc=SourceLoc(file, *start))
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
        start_line, start_col = line, col
        if ch == "\\" and i + 1 < n and text[i + 1] == "`":
            # An escaped back quote outside a string (JavaScript pasted into a block): HoloScript
            # drops both characters.
            add(Kind.OTHER, "\\`", start_line, start_col)
            advance(2)
            continue
        if text.startswith(("'''", '"""'), i):
            quote3 = text[i : i + 3]
            end = text.find(quote3, i + 3)
            if end < 0:
                raise ParseError(
                    f"unterminated string (opened with {quote3})", loc=SourceLoc(file, start_line, start_col)
                )
            add(Kind.STRING, text[i + 3 : end], start_line, start_col)
            advance(end + 3 - i)
            continue
        if ch in "\"'`":
            quote = ch
            advance(1)
            chars: list[str] = []
            while True:
                if i >= n:
                    raise ParseError(
                        f"unterminated string (opened with {quote})", loc=SourceLoc(file, start_line, start_col)
                    )
                c = text[i]
                if c == quote:
                    advance(1)
                    break
                if c == "\\" and i + 1 < n:
                    chars.append(_ESCAPES.get(text[i + 1], text[i + 1]))
                    advance(2)
                    continue
                chars.append(c)
                advance(1)
            add(Kind.STRING, "".join(chars), start_line, start_col)
            continue
        if ch.isdigit() or (ch == "." and i + 1 < n and text[i + 1].isdigit()):
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
            add(Kind.NUMBER, text[i:j], start_line, start_col)
            advance(j - i)
            continue
        if ch.isalpha() or ch in "_$":
            j = i
            while j < n and (text[j].isalnum() or text[j] in "_$"):
                j += 1
            add(Kind.IDENT, text[i:j], start_line, start_col)
            advance(j - i)
            continue
        if ch in PUNCT and not text.startswith("...", i):
            add(Kind.PUNCT, ch, start_line, start_col)
            advance(1)
            continue
        for op in OPERATORS:
            if text.startswith(op, i):
                add(Kind.OP, op, start_line, start_col)
                advance(len(op))
                break
        else:
            add(Kind.OTHER, ch, start_line, start_col)
            advance(1)
    out.append(Token(Kind.EOF, "", line, col, True))
    return out
