#!/usr/bin/env python3
"""Fail when a file of the repository cites a tracker issue by its number.

Readers of the code and the docs have no tracker: a comment, a doc or a message
that says "issue N", "issue #N" or "issues N and M" (any case, N a number)
points nowhere. Cite what it means instead: the paper, the docs/ page, the
docs/results/ entry, or just say the fact. Every file git tracks is checked,
the dated results entries in docs/results/ included, and binary files (a NUL
byte in their first 8 KiB) are skipped; outside a git checkout every file under
the root is, but for hidden and build* folders. A link to another project's
public tracker (github.com/OWNER/REPO/issues/N) is a citation and passes.

Usage: check_no_issue_numbers.py [--root DIR]
Exit status: 0 when no file cites an issue number, 1 otherwise.
"""

import argparse
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lint_common  # noqa: E402

# "issue N", "Issue N's", "issue #N", "issues N and M" (N, M numbers); not "tissue N", not a
# link ".../issues/N". This comment cannot show a real one: the check would fail on itself.
ISSUE_NUMBER = re.compile(r"\bissues?[ \t]*#?[ \t]*[0-9]+", re.IGNORECASE)
_BINARY_PROBE = 8192


def tracked_files(root):
    """Paths relative to root, with '/', of the files to check, sorted."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], check=True,
                             capture_output=True).stdout
        return sorted(p for p in out.decode("utf-8", "replace").split("\0") if p)
    except (OSError, subprocess.CalledProcessError):
        return sorted(_walk(root))


def _walk(root):
    """Every file under root but in hidden and build* folders (no git checkout)."""
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames if not d.startswith((".", "build"))]
        for name in filenames:
            yield os.path.relpath(os.path.join(dirpath, name), root).replace(os.sep, "/")


def find_citations(text):
    """(line, matched text, the line stripped) for each issue number cited in text."""
    index = lint_common.LineIndex(text)
    lines = text.split("\n")
    found = []
    for m in ISSUE_NUMBER.finditer(text):
        line = index.line(m.start())
        found.append((line, m.group(0), lines[line - 1].strip()))
    return found


def check(root):
    """Return printable offences 'path:line: "issue N" in: …' for the tree at root."""
    offences = []
    for rel in tracked_files(root):
        path = os.path.join(root, rel)
        if not os.path.isfile(path):  # deleted in the worktree, not yet committed
            continue
        with open(path, "rb") as f:
            data = f.read()
        if b"\0" in data[:_BINARY_PROBE]:
            continue
        text = data.decode("utf-8", "replace")
        for line, cited, context in find_citations(text):
            offences.append(f'{rel}:{line}: "{cited}" in: {context[:160]}')
    return offences


def main(argv=None):
    """Parse arguments, check every file, print each citation of an issue number."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=lint_common.default_root(),
                        help="source tree to check (default: this repository)")
    args = parser.parse_args(argv)
    offences = check(args.root)
    for line in offences:
        print(line)
    if offences:
        print("cite the paper, the docs/ page or the docs/results/ entry instead, "
              "or just say the fact")
    return lint_common.fail_summary("check_no_issue_numbers", len(offences),
                                    "citation(s) of a tracker issue number")


if __name__ == "__main__":
    sys.exit(main())
