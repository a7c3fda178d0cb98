#!/usr/bin/env python3
"""Fail when a function definition in a library folder is longer than 120 lines.

How length is measured: from the line on which the function's declaration
starts (its first token after the previous declaration, so a `template <...>`
line, attributes and the return type count, comments above it do not) to the
line of the body's closing brace, both inclusive. Lambdas, local classes and
nested blocks inside a function count toward that function.

How functions are found, without a compiler:
  1. comments, string and char literals (raw strings R"d(...)d" and prefixed
     literals included; 1'000 is a number) and preprocessor lines are blanked,
     keeping line breaks, so that braces in them are not seen;
  2. braces are matched with a stack of scopes. At namespace or class scope the
     text since the previous `;`, `{`, `}` or access specifier is the head of
     whatever the `{` opens:
       - `namespace ...` and `extern "C"` open a namespace scope;
       - a head ending in `)` -- possibly followed by const, volatile, &, &&,
         noexcept(...), override, final, mutable, try, a trailing `-> type`, or a
         constructor's initializer list `: a_(x), b_{y}` -- opens a function
         body; so does a lambda assigned or passed to a call at namespace or
         class scope (`= [...](...) {`, `Make([] {`);
       - `class`/`struct`/`union` heads open a class scope, in which inline
         member functions are found the same way;
       - anything else (enum bodies, brace initializers) is no function.
     Inside a function every brace just nests.
A file whose braces do not balance (say, through #if branches that each open a
brace) is reported as an error rather than silently measured wrong.

Usage: check_function_length.py [--root DIR] [--max-lines 120] [--top 10]
Exit status: 0 when every function is within the limit, 1 otherwise.
"""

import argparse
import collections
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lint_common  # noqa: E402

MAX_LINES = 120

Function = collections.namedtuple("Function", "path start end name")
Frame = collections.namedtuple("Frame", "kind start_line name")

_EVENTS = re.compile(r"[{};]|(?<!:):(?!:)")
_QUAL = r"(?:const|volatile|noexcept|override|final|mutable|constexpr|try|throw|&&|&|\(\))"
_FUNC_END = re.compile(r"\)\s*(?:" + _QUAL + r"\s*)*(?:->[^;{}=]*)?$")
_LAMBDA_END = re.compile(r"(?:^|=|,)\s*\[\]\s*(?:mutable\s*)?(?:->[^;{}=]*)?$")
_INIT_LIST = re.compile(r"\)\s*(?:" + _QUAL + r"\s*)*:(?!:)")
_TEMPLATE_PREFIX = re.compile(r"^template\s*<")
_CLASS_HEAD = re.compile(r"^(?:typedef\s+)?(?:class|struct|union)\b")
_ENUM_HEAD = re.compile(r"^(?:typedef\s+)?enum\b")
_NAMESPACE_HEAD = re.compile(r'^(?:inline\s+)?namespace\b|^extern\s*"\s*"$')
_ACCESS = re.compile(r"^(?:public|private|protected)$")
_NAME = re.compile(r"((?:[\w~]+\s*(?:<[^<>]*>)?\s*::\s*)*(?:operator\b.*|~?\w+))\s*$")
_LAMBDA_NAME = re.compile(r"(\w+)\s*=\s*\[\]")


def collapse(head):
    """Head with each outermost (), [] or {} group emptied and whitespace squeezed."""
    out, depth = [], 0
    for c in head:
        if c in "([{":
            if depth == 0:
                out.append(c)
            depth += 1
        elif c in ")]}":
            depth = max(depth - 1, 0)
            if depth == 0:
                out.append(c)
        elif depth == 0:
            out.append(c)
    return re.sub(r"\s+", " ", "".join(out)).strip()


def open_tail(head):
    """Text after the last (, [ or { of head left open, or None when all are closed."""
    opened = []
    for k, c in enumerate(head):
        if c in "([{":
            opened.append(k)
        elif c in ")]}" and opened:
            opened.pop()
    return head[opened[-1] + 1:] if opened else None


def _is_function_head(h):
    """True when collapsed text ends like a function's or a lambda's signature."""
    return bool(_FUNC_END.search(h) or _LAMBDA_END.search(h))


def _strip_template_prefix(head):
    """Head without a leading `template <...>` (angle brackets balanced)."""
    if not _TEMPLATE_PREFIX.match(head):
        return head
    depth = 0
    for k, c in enumerate(head):
        if c == "<":
            depth += 1
        elif c == ">":
            depth -= 1
            if depth == 0:
                return _strip_template_prefix(head[k + 1:].strip())
    return head


def classify(head):
    """What a `{` after head opens: 'namespace', 'class', 'function', 'init' or 'other'.

    'init' is a member's brace initializer inside a constructor's initializer list
    (`Foo() : a_{1}`): the head goes on after its closing brace.
    """
    h = collapse(head)
    init = _INIT_LIST.search(h)
    if init:
        rest = h[init.end():].strip()
        return "function" if rest.endswith((")", "}")) else "init"
    tail = open_tail(head)
    if tail is not None:  # inside a call's parentheses: only a lambda is a function
        return "function" if _is_function_head(collapse(tail)) else "other"
    bare = _strip_template_prefix(h)
    if _ENUM_HEAD.match(bare):
        return "other"
    if _NAMESPACE_HEAD.match(bare):
        return "namespace"
    if _is_function_head(h):
        return "function"
    if _CLASS_HEAD.match(bare):
        return "class"
    return "other"


def function_name(head):
    """A readable name for the function whose head is given."""
    h = collapse(head)
    if open_tail(head) is not None:
        owner = re.search(r"(\w+)\s*[=(]", h)
        return f"{owner.group(1) if owner else ''} (lambda)".strip()
    lam = _LAMBDA_NAME.search(h)
    if lam and "(" not in h[:lam.start()]:
        return f"{lam.group(1)} (lambda)"
    pre = h.split("(", 1)[0].rstrip()
    if pre.endswith("operator"):
        pre += "()"
    m = _NAME.search(pre)
    return re.sub(r"\s+", "", m.group(1)) if m else "(unnamed)"


class Scanner:
    """Finds function definitions in one blanked file by matching braces."""

    def __init__(self, path, code):
        self.path, self.code = path, code
        self.lines = lint_common.LineIndex(code)
        self.stack = [Frame("namespace", 0, "")]
        self.head_start = 0
        self.functions = []

    def run(self):
        """Scan the whole file; return its functions or raise ValueError on bad braces."""
        for m in _EVENTS.finditer(self.code):
            self._event(m.group(), m.start())
        if len(self.stack) != 1:
            raise ValueError(f"{self.path}: {len(self.stack) - 1} brace(s) never closed")
        return self.functions

    def _event(self, c, pos):
        """Handle one `{`, `}`, `;` or `:` at pos."""
        kind = self.stack[-1].kind
        if c == "}":
            self._close(pos)
        elif kind in ("function", "block", "other", "init"):
            if c == "{":
                child = {"function": "block", "block": "block"}.get(kind, kind)
                self.stack.append(Frame(child, 0, ""))
        elif c == "{":
            self._open(pos)
        elif c == ";" or _ACCESS.match(self.code[self.head_start:pos].strip()):
            self.head_start = pos + 1

    def _open(self, pos):
        """A `{` at namespace or class scope: push what it opens."""
        head = self.code[self.head_start:pos]
        kind = classify(head)
        if kind == "function":
            offset = self.head_start + len(head) - len(head.lstrip())
            self.stack.append(Frame(kind, self.lines.line(offset), function_name(head)))
            return
        self.stack.append(Frame(kind, 0, ""))
        if kind != "init":
            self.head_start = pos + 1

    def _close(self, pos):
        """A `}`: pop its scope, recording a function that ends here."""
        if len(self.stack) == 1:
            raise ValueError(f"{self.path}:{self.lines.line(pos)}: unmatched closing brace")
        frame = self.stack.pop()
        if frame.kind == "function":
            end = self.lines.line(pos)
            self.functions.append(Function(self.path, frame.start_line, end, frame.name))
        if frame.kind != "init" and self.stack[-1].kind in ("namespace", "class"):
            self.head_start = pos + 1


def find_functions(path, text):
    """All function definitions of one file's text."""
    code = lint_common.blank_preprocessor(lint_common.blank_literals(text))
    return Scanner(path, code).run()


def length(fn):
    """Lines of a function, signature start and closing brace included."""
    return fn.end - fn.start + 1


def main(argv=None):
    """Parse arguments, measure every library function, print offenders and the longest."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=lint_common.default_root(),
                        help="source tree to check (default: this repository)")
    parser.add_argument("--max-lines", type=int, default=MAX_LINES,
                        help=f"longest function allowed (default {MAX_LINES})")
    parser.add_argument("--top", type=int, default=10, metavar="N",
                        help="how many of the longest functions to list (default 10)")
    args = parser.parse_args(argv)
    functions, errors = [], 0
    for _, rel in lint_common.library_files(args.root):
        try:
            functions += find_functions(rel, lint_common.read_text(args.root, rel))
        except ValueError as e:
            print(f"error: {e}")
            errors += 1
    ranked = sorted(functions, key=lambda f: (-length(f), f.path, f.start))
    over = [f for f in ranked if length(f) > args.max_lines]
    for f in over:
        print(f"{f.path}:{f.start}: {f.name} is {length(f)} lines (limit {args.max_lines}),"
              f" lines {f.start}-{f.end}")
    print(f"longest {min(args.top, len(ranked))} of {len(ranked)} functions:")
    for f in ranked[:args.top]:
        print(f"  {length(f):5d}  {f.path}:{f.start}  {f.name}")
    return lint_common.fail_summary("check_function_length", len(over) + errors,
                                    f"function(s) over {args.max_lines} lines or unparsable files")


if __name__ == "__main__":
    sys.exit(main())
