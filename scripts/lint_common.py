"""Shared helpers of trackbed's architecture checks (check_*.py beside this file).

Library folders are found, not listed: every top-level directory of the source
tree that holds a C++ file (.cpp/.cc/.h/.hpp, at any depth) is a library,
except build*, tests, bench, scripts, docs, cmake and hidden folders. So the
checks keep working when libraries are split, renamed or added.

`blank_literals` turns C++ text into text of the same length and the same line
breaks in which comments (and, on request, string and char literals, raw
strings included) are spaces, so that later passes can match braces or read
#include lines without being fooled, and still report true line numbers.
"""

import bisect
import os
import re

SOURCE_SUFFIXES = (".cpp", ".cc", ".h", ".hpp")
EXCLUDED_DIRS = {"tests", "bench", "scripts", "docs", "cmake"}

_IDENT_START = re.compile(r"[A-Za-z_]")
_IDENT_WORD = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")
# A pp-number (C++ [lex.ppnumber]): digit separators ' and exponent signs included.
_PP_NUMBER = re.compile(r"\.?[0-9](?:[eEpP][+-]|'[0-9A-Za-z_]|[0-9A-Za-z_.])*")
_RAW_PREFIXES = {"R", "u8R", "uR", "UR", "LR"}
_STRING_PREFIXES = {"u8", "u", "U", "L"}


def default_root():
    """The repository root: the parent of the folder holding this file."""
    return os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def is_excluded_dir(name):
    """True for a top-level folder that is never a library."""
    return name in EXCLUDED_DIRS or name.startswith("build") or name.startswith(".")


def walk_sources(folder):
    """Yield the paths of the C++ files under folder, sorted, skipping hidden/build dirs."""
    for dirpath, dirnames, filenames in os.walk(folder):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith((".", "build")))
        for name in sorted(filenames):
            if name.endswith(SOURCE_SUFFIXES):
                yield os.path.join(dirpath, name)


def discover_libraries(root):
    """Return the sorted names of the top-level library folders under root."""
    libs = []
    for name in sorted(os.listdir(root)):
        path = os.path.join(root, name)
        if os.path.isdir(path) and not is_excluded_dir(name):
            if next(walk_sources(path), None) is not None:
                libs.append(name)
    return libs


def library_files(root):
    """Yield (library, path relative to root with '/') for every library C++ file."""
    for lib in discover_libraries(root):
        for path in walk_sources(os.path.join(root, lib)):
            yield lib, os.path.relpath(path, root).replace(os.sep, "/")


def read_text(root, rel):
    """Read a source file as UTF-8, replacing undecodable bytes."""
    with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
        return f.read()


def _spaces(text):
    """Text of the same length with every character but newlines turned to spaces."""
    return re.sub(r"[^\n]", " ", text)


def _end_of_line_comment(text, i):
    """Index just past a // comment starting at i (a backslash-newline continues it)."""
    n = len(text)
    while True:
        j = text.find("\n", i)
        if j < 0:
            return n
        if j > 0 and text[j - 1] == "\\":
            i = j + 1
            continue
        return j


def _end_of_quoted(text, i, quote):
    """Index just past a "..." or '...' literal whose opening quote is at i."""
    n = len(text)
    j = i + 1
    while j < n:
        c = text[j]
        if c == "\\":
            j += 2
            continue
        if c == quote or c == "\n":
            return j + 1
        j += 1
    return n


def _end_of_raw(text, i):
    """Index just past a raw string R"delim(...)delim" whose '"' is at i."""
    paren = text.find("(", i)
    if paren < 0:
        return len(text)
    delim = text[i + 1:paren]
    close = text.find(")" + delim + '"', paren + 1)
    return len(text) if close < 0 else close + len(delim) + 2


def _blank_literal(literal):
    """A literal's replacement: prefix and quotes kept, everything between them spaces."""
    first = min(k for k in (literal.find('"'), literal.find("'")) if k >= 0)
    if len(literal) - first < 2:
        return _spaces(literal)
    return literal[:first + 1] + _spaces(literal[first + 1:-1]) + literal[-1]


def _word_token_end(text, i):
    """(end, kind) of the identifier at i, or of the literal it prefixes (u8"", R"()")."""
    j = _IDENT_WORD.match(text, i).end()
    word, nxt = text[i:j], text[j:j + 1]
    if nxt == '"' and word in _RAW_PREFIXES:
        return _end_of_raw(text, j), "literal"
    if nxt in ('"', "'") and nxt and word in _STRING_PREFIXES:
        return _end_of_quoted(text, j, nxt), "literal"
    return j, "code"


def _next_token(text, i):
    """(end, kind) of the token starting at i; kind is 'comment', 'literal' or 'code'."""
    c = text[i]
    if text.startswith("//", i):
        return _end_of_line_comment(text, i), "comment"
    if text.startswith("/*", i):
        k = text.find("*/", i + 2)
        return (len(text) if k < 0 else k + 2), "comment"
    if c in "\"'":
        return _end_of_quoted(text, i, c), "literal"
    if c.isdigit() or (c == "." and text[i + 1:i + 2].isdigit()):
        return _PP_NUMBER.match(text, i).end(), "code"
    if _IDENT_START.match(c):
        return _word_token_end(text, i)
    return i + 1, "code"


def blank_literals(text, keep_strings=False):
    """Return text with comments (and, unless keep_strings, literals) blanked out.

    Length and newlines are preserved, so offsets and line numbers stay valid.
    Handles // and /* */ comments, "..." and '...' literals with escapes,
    encoding prefixes (u8, u, U, L), raw strings R"delim(...)delim" and digit
    separators (1'000'000 is a number, not a char literal).
    """
    out = []
    i = 0
    while i < len(text):
        j, kind = _next_token(text, i)
        token = text[i:j]
        if kind == "comment":
            token = _spaces(token)
        elif kind == "literal" and not keep_strings:
            token = _blank_literal(token)
        out.append(token)
        i = j
    return "".join(out)


def blank_preprocessor(text):
    """Blank every preprocessor directive line (and its backslash continuations)."""
    lines = text.split("\n")
    continuing = False
    for k, line in enumerate(lines):
        if continuing or line.lstrip().startswith("#"):
            continuing = line.rstrip().endswith("\\")
            lines[k] = " " * len(line)
    return "\n".join(lines)


class LineIndex:
    """Maps offsets of one text to 1-based line numbers."""

    def __init__(self, text):
        self._starts = [0] + [m.end() for m in re.finditer("\n", text)]

    def line(self, offset):
        """1-based line number of offset."""
        return bisect.bisect_right(self._starts, offset)


def fail_summary(name, count, what):
    """Print the closing line of a check and return its exit code."""
    if count:
        print(f"{name}: FAILED, {count} {what}")
        return 1
    print(f"{name}: OK")
    return 0
