# SPDX-License-Identifier: GPL-2.0-or-later
"""Character-level scanner for the declaration section of a .comp file.

The declaration language mixes HAL names (``out-#``), C expressions
(``personality & 0xff``) and documentation strings, so it is read with a
cursor over the text rather than a context-free tokenizer; every error
carries the file, line and column where it was found.
"""

from __future__ import annotations

import bisect
import re

from .model import Pos

_IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
_HALNAME = re.compile(r"[A-Za-z_#][A-Za-z0-9_.#-]*")
_NUMBER = re.compile(r"0[xX][0-9a-fA-F]+|[0-9]+")


class CompError(Exception):
    """An error in a .comp file, reported as FILE:LINE:COL: error: MESSAGE."""

    def __init__(self, pos: Pos, message: str) -> None:
        super().__init__(f"{pos}: error: {message}")
        self.pos = pos
        self.message = message


class Scanner:
    def __init__(self, text: str, filename: str) -> None:
        self.text = text
        self.file = filename
        self.i = 0
        self._line_starts = [0] + [m.end() for m in re.finditer(r"\n", text)]

    # ---- positions -------------------------------------------------------

    def pos(self, index: int | None = None) -> Pos:
        idx = self.i if index is None else index
        line = bisect.bisect_right(self._line_starts, idx) - 1
        return Pos(self.file, line + 1, idx - self._line_starts[line] + 1)

    def error(self, message: str, index: int | None = None) -> CompError:
        return CompError(self.pos(index), message)

    def at_end(self) -> bool:
        return self.i >= len(self.text)

    # ---- whitespace and comments ------------------------------------------

    def skip(self) -> None:
        t = self.text
        while self.i < len(t):
            c = t[self.i]
            if c in " \t\r\n\f\v":
                self.i += 1
            elif t.startswith("//", self.i):
                nl = t.find("\n", self.i)
                self.i = len(t) if nl < 0 else nl + 1
            elif t.startswith("/*", self.i):
                end = t.find("*/", self.i + 2)
                if end < 0:
                    raise self.error("unterminated /* comment")
                self.i = end + 2
            else:
                break

    def here(self) -> Pos:
        """Skip blanks and comments; the position of the next token."""
        self.skip()
        return self.pos()

    def at(self, s: str) -> bool:
        return self.text.startswith(s, self.i)

    def at_word(self, word: str) -> bool:
        """True when the next token is exactly the keyword `word`."""
        if not self.at(word):
            return False
        j = self.i + len(word)
        return j >= len(self.text) or not (self.text[j].isalnum() or self.text[j] == "_")

    def expect(self, s: str, what: str) -> None:
        self.skip()
        if not self.at(s):
            raise self.error(f"expected {what}, found {self.describe_next()}")
        self.i += len(s)

    def describe_next(self) -> str:
        if self.at_end():
            return "end of file"
        m = re.compile(r"\S+").match(self.text, self.i)
        tok = m.group(0) if m else self.text[self.i]
        if len(tok) > 20:
            tok = tok[:20] + "..."
        return f"'{tok}'"

    # ---- tokens ------------------------------------------------------------

    def match(self, rx: re.Pattern[str]) -> str | None:
        self.skip()
        m = rx.match(self.text, self.i)
        if not m:
            return None
        self.i = m.end()
        return m.group(0)

    def ident(self, what: str) -> str:
        s = self.match(_IDENT)
        if s is None:
            raise self.error(f"expected {what}, found {self.describe_next()}")
        return s

    def halname(self, what: str) -> str:
        s = self.match(_HALNAME)
        if s is None:
            raise self.error(f"expected {what}, found {self.describe_next()}")
        return s

    def number(self, what: str) -> int:
        s = self.match(_NUMBER)
        if s is None:
            raise self.error(f"expected {what} (a number), found {self.describe_next()}")
        return int(s, 0)

    def at_string(self) -> bool:
        self.skip()
        return self.at('"')

    def string(self, what: str) -> str:
        """A "C-style" or \"\"\"triple-quoted\"\"\" string, escapes interpreted."""
        self.skip()
        start = self.i
        t = self.text
        if t.startswith('"""', start):
            end = t.find('"""', start + 3)
            if end < 0:
                raise self.error('unterminated """ string', start)
            raw = t[start + 3 : end]
            self.i = end + 3
            return unescape(raw)
        if not self.at('"'):
            raise self.error(f"expected {what} (a quoted string), found {self.describe_next()}")
        j = start + 1
        while j < len(t) and t[j] != '"':
            if t[j] == "\n":
                raise self.error(
                    'unterminated string (a "string" ends on its line; use """...""" '
                    "for more lines)",
                    start,
                )
            j += 2 if t[j] == "\\" else 1
        if j >= len(t):
            raise self.error("unterminated string", start)
        self.i = j + 1
        return unescape(t[start + 1 : j])

    def expr(self, what: str, stop: str, stop_at_assign: bool = False) -> str:
        """Raw C expression text up to a character of `stop` at bracket depth
        0 (outside strings); with `stop_at_assign` also up to a lone `=` or
        the start of a documentation string."""
        self.skip()
        t = self.text
        start = j = self.i
        depth = 0
        opened: list[str] = []
        while j < len(t):
            c = t[j]
            if depth == 0 and c in stop:
                break
            if c in "([{":
                opened.append(")]}"["([{".index(c)])
                depth += 1
            elif c in ")]}":
                if depth == 0 or opened.pop() != c:
                    raise self.error(f"unbalanced '{c}' in {what}", j)
                depth -= 1
            elif c == '"':
                if depth == 0 and stop_at_assign:
                    break
                k = j + 1
                while k < len(t) and t[k] != '"':
                    k += 2 if t[k] == "\\" else 1
                j = k
            elif c == "'":
                k = j + 1
                while k < len(t) and t[k] != "'":
                    k += 2 if t[k] == "\\" else 1
                j = k
            elif c == "=" and stop_at_assign and depth == 0:
                prev = t[j - 1] if j > start else ""
                nxt = t[j + 1] if j + 1 < len(t) else ""
                if prev not in "=!<>" and nxt != "=":
                    break
                if nxt == "=":
                    j += 1
            elif c == ";" and depth > 0:
                raise self.error(f"';' inside brackets in {what}", j)
            elif c == ";":
                raise self.error(f"expected '{stop[0]}' to end the {what}, found ';'", j)
            j += 1
        if j >= len(t):
            raise self.error(f"unterminated {what}", start)
        text = t[start:j].strip()
        if not text:
            raise self.error(f"empty {what}", start)
        self.i = j
        return text


_ESCAPES = {
    "n": "\n",
    "t": "\t",
    "r": "\r",
    "\\": "\\",
    '"': '"',
    "'": "'",
    "a": "\a",
    "b": "\b",
    "f": "\f",
    "v": "\v",
    "0": "\0",
    "\n": "",
}


def unescape(raw: str) -> str:
    """Backslash escapes as a C (or Python) string literal reads them."""
    out = []
    i = 0
    while i < len(raw):
        c = raw[i]
        if c == "\\" and i + 1 < len(raw):
            n = raw[i + 1]
            if n in _ESCAPES:
                out.append(_ESCAPES[n])
                i += 2
                continue
            out.append("\\")  # unknown escape: kept as written, like Python
            i += 1
            continue
        out.append(c)
        i += 1
    return "".join(out)
