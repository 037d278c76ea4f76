"""Tokens of HoloScript ``.holo`` files.

The lexer never guesses: strings (single, double or back quotes) and comments (``//``, ``/* */``)
are read exactly so that braces inside them do not count; any other character the robotics subset
does not use becomes an ``other`` token, which the parser rejects where a value is expected and
steps over inside blocks it skips (``logic`` holds JavaScript-like code).

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
    OTHER = "character"
    EOF = "end of file"


PUNCT = frozenset("{}[]():,@;")


@dataclass(slots=True, frozen=True)
class Token:
    kind: Kind
    text: str  # for strings: the decoded value
    line: int
    column: int

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
        if ch in " \t\r\n\ufeff":
            advance(1)
            continue
        if text.startswith("//", i):
            while i < n and text[i] != "\n":
                advance(1)
            continue
        if text.startswith("/*", i):
            start = (line, col)
            end = text.find("*/", i + 2)
            if end < 0:
                raise ParseError("unterminated /* comment", loc=SourceLoc(file, *start))
            advance(end + 2 - i)
            continue
        start_line, start_col = line, col
        if ch in "\"'`":
            quote = ch
            advance(1)
            chars: list[str] = []
            while True:
                if i >= n or (text[i] == "\n" and quote != "`"):
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
            out.append(Token(Kind.STRING, "".join(chars), start_line, start_col))
            continue
        if ch.isdigit() or (ch == "." and i + 1 < n and text[i + 1].isdigit()):
            j = i
            while j < n and (text[j].isdigit() or text[j] in "._"):
                j += 1
            if j < n and text[j] in "eE":
                k = j + 1
                if k < n and text[k] in "+-":
                    k += 1
                if k < n and text[k].isdigit():
                    j = k
                    while j < n and text[j].isdigit():
                        j += 1
            raw = text[i:j]
            out.append(Token(Kind.NUMBER, raw, start_line, start_col))
            advance(j - i)
            continue
        if ch.isalpha() or ch in "_$":
            j = i
            while j < n and (text[j].isalnum() or text[j] in "_$"):
                j += 1
            out.append(Token(Kind.IDENT, text[i:j], start_line, start_col))
            advance(j - i)
            continue
        out.append(Token(Kind.PUNCT if ch in PUNCT else Kind.OTHER, ch, start_line, start_col))
        advance(1)
    out.append(Token(Kind.EOF, "", line, col))
    return out
