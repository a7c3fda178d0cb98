#!/usr/bin/env python3
"""Fail when a C++ file in a library folder is longer than 900 lines.

Length is the file's number of lines as `wc -l` counts them, plus one when the
last line has no newline. Exceptions are made in the file itself, never in this
script: a comment in its first 5 lines reading

    // trackbed-lint: long-file (REASON)

for instance `(generated table)` or `(procedural texture recipes)`, exempts
that file. The reason is required; a marker without one is itself an offence.
Every marked file is listed, with its length, so exceptions stay visible; a
marker on a file that is within the limit is pointed out but does not fail.

Usage: check_file_length.py [--root DIR] [--max-lines 900]
Exit status: 0 when every file is within the limit or marked, 1 otherwise.
"""

import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lint_common  # noqa: E402

MAX_LINES = 900
MARKER_LINES = 5
_MARKER = re.compile(r"trackbed-lint:\s*long-file\b(?:\s*\(([^)]*)\))?")


def count_lines(text):
    """Lines of text: newlines, plus one for a last line without newline."""
    return text.count("\n") + (1 if text and not text.endswith("\n") else 0)


def find_marker(text):
    """(line, reason) of the long-file marker in the first lines, reason '' if none given."""
    for number, line in enumerate(text.split("\n")[:MARKER_LINES], start=1):
        m = _MARKER.search(line)
        if m:
            return number, (m.group(1) or "").strip()
    return None


def check(root, max_lines):
    """Return (offences, marked) lists of printable lines for the tree at root."""
    offences, marked = [], []
    for _, rel in lint_common.library_files(root):
        text = lint_common.read_text(root, rel)
        lines, marker = count_lines(text), find_marker(text)
        if marker and not marker[1]:
            offences.append(f"{rel}:{marker[0]}: long-file marker gives no reason in (...)")
        elif marker:
            note = "" if lines > max_lines else "  (within the limit: marker not needed)"
            marked.append(f"{rel}:{marker[0]}: {lines} lines, marked: {marker[1]}{note}")
        elif lines > max_lines:
            offences.append(f"{rel}:{max_lines + 1}: {lines} lines, over the limit of {max_lines}")
    return offences, marked


def main(argv=None):
    """Parse arguments, check every library file, print offenders and marked files."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=lint_common.default_root(),
                        help="source tree to check (default: this repository)")
    parser.add_argument("--max-lines", type=int, default=MAX_LINES,
                        help=f"longest file allowed without a marker (default {MAX_LINES})")
    args = parser.parse_args(argv)
    offences, marked = check(args.root, args.max_lines)
    for line in offences:
        print(line)
    print(f"files carrying the long-file marker: {len(marked)}")
    for line in marked:
        print(f"  {line}")
    return lint_common.fail_summary("check_file_length", len(offences),
                                    f"file(s) over {args.max_lines} lines without a marker")


if __name__ == "__main__":
    sys.exit(main())
