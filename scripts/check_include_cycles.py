#!/usr/bin/env python3
"""Fail when #include directives form a cycle between units or between libraries.

A unit is a header and its source counted as one: X/foo.cpp, X/foo.h and the
public header X/trackbed/X/foo.h are all unit X/foo (X being the library
folder). A unit U depends on a unit V when any file of U includes a file of V;
foo.cpp including foo.h is no dependency. A library A depends on a library B
when a file of A includes a header of B.

Includes are resolved as the compiler does for the quoted form: first next to
the including file, then against every library folder as an include root (so
"trackbed/<lib>/<name>.h" finds <lib>/trackbed/<lib>/<name>.h). Includes that
resolve to no library file (the standard library, third-party or generated
headers) are ignored; lines in comments or in #if 0 blocks are not includes.

Every strongly connected component of either graph is reported as cycles that,
together, use every edge of the component; each cycle is printed as the chain
of units (or libraries) with the include lines (file:line) that make each step.

Usage: check_include_cycles.py [--root DIR] [--verbose]
Exit status: 0 when there is no cycle, 1 otherwise.
"""

import argparse
import collections
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import lint_common  # noqa: E402

_INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*([<"])([^>"\n]+)[>"]', re.M)
_IF = re.compile(r"^[ \t]*#[ \t]*(if|ifdef|ifndef|elif|else|endif)\b(.*)$", re.M)

Include = collections.namedtuple("Include", "src line text target")


def unit_of(rel):
    """Unit name of a library file: X/trackbed/X/foo.h -> X/foo, X/foo.cpp -> X/foo."""
    parts = rel.split("/")
    lib, rest = parts[0], parts[1:]
    if len(rest) >= 3 and rest[0] == "trackbed":  # also while a folder and its namespace differ
        rest = rest[2:]
    stem = os.path.splitext("/".join(rest))[0]
    return f"{lib}/{stem}"


def _disabled_lines(text):
    """Line numbers inside #if 0 ... (#else/#elif/#endif) blocks."""
    disabled, depth_stack = set(), []
    lines = text.split("\n")
    for number, line in enumerate(lines, start=1):
        m = _IF.match(line)
        if m:
            _update_if_stack(depth_stack, m.group(1), m.group(2).strip())
        elif any(depth_stack):
            disabled.add(number)
    return disabled


def _update_if_stack(stack, directive, argument):
    """Track, per open #if, whether it is an #if 0 branch that is switched off."""
    if directive.startswith("if"):
        stack.append(directive == "if" and argument == "0")
    elif directive in ("else", "elif") and stack:
        stack[-1] = False
    elif directive == "endif" and stack:
        stack.pop()


def parse_includes(text):
    """Yield (line, quote, path, directive text) for the live #include lines of text."""
    code = lint_common.blank_literals(text, keep_strings=True)
    index = lint_common.LineIndex(code)
    disabled = _disabled_lines(code)
    raw_lines = text.split("\n")
    for m in _INCLUDE.finditer(code):
        line = index.line(m.start())
        if line not in disabled:
            yield line, m.group(1), m.group(2).strip(), raw_lines[line - 1].strip()


def resolve(rel, quote, path, files, by_root_path):
    """Library file that an include of rel names, or None."""
    if quote == '"':
        local = os.path.normpath(os.path.join(os.path.dirname(rel), path)).replace(os.sep, "/")
        if local in files:
            return local
    candidates = by_root_path.get(path, [])
    return candidates[0] if candidates else None


def collect_includes(root, verbose=False):
    """All includes between library files, as Include records."""
    lib_of = dict((rel, lib) for lib, rel in lint_common.library_files(root))
    by_root_path = collections.defaultdict(list)
    for rel, lib in lib_of.items():
        by_root_path[rel[len(lib) + 1:]].append(rel)
    includes = []
    for rel in lib_of:
        text = lint_common.read_text(root, rel)
        for line, quote, path, directive in parse_includes(text):
            target = resolve(rel, quote, path, lib_of, by_root_path)
            if target:
                includes.append(Include(rel, line, directive, target))
            elif verbose and quote == '"':
                print(f"note: {rel}:{line}: {directive} resolves to no library file")
    return includes, lib_of


def build_graph(includes, key):
    """Graph {node: {neighbour: [Include, ...]}} with node = key(file); self-edges dropped."""
    graph = collections.defaultdict(lambda: collections.defaultdict(list))
    for inc in includes:
        a, b = key(inc.src), key(inc.target)
        if a != b:
            graph[a][b].append(inc)
    return graph


def strongly_connected(graph):
    """Strongly connected components (Tarjan, iterative) of size > 1, each sorted."""
    nodes = sorted(set(graph) | {b for a in graph for b in graph[a]})
    index, low, on_stack, stack, comps = {}, {}, set(), [], []
    for start in nodes:
        if start in index:
            continue
        work = [(start, iter(sorted(graph.get(start, {}))))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, neighbours = work[-1]
            nxt = next(neighbours, None)
            if nxt is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    comp = _pop_component(stack, on_stack, node)
                    if len(comp) > 1:
                        comps.append(sorted(comp))
            elif nxt not in index:
                index[nxt] = low[nxt] = len(index)
                stack.append(nxt)
                on_stack.add(nxt)
                work.append((nxt, iter(sorted(graph.get(nxt, {})))))
            elif nxt in on_stack:
                low[node] = min(low[node], index[nxt])
    return sorted(comps)


def _pop_component(stack, on_stack, root):
    """Pop one strongly connected component, rooted at root, off Tarjan's stack."""
    comp = []
    while True:
        node = stack.pop()
        on_stack.discard(node)
        comp.append(node)
        if node == root:
            return comp


def shortest_path(graph, src, dst, allowed):
    """Shortest node path src -> dst inside allowed (breadth first), or None."""
    previous = {src: None}
    queue = collections.deque([src])
    while queue:
        node = queue.popleft()
        if node == dst:
            path = []
            while node is not None:
                path.append(node)
                node = previous[node]
            return path[::-1]
        for nxt in sorted(graph.get(node, {})):
            if nxt in allowed and nxt not in previous:
                previous[nxt] = node
                queue.append(nxt)
    return None


def cycles_of_component(graph, comp):
    """Cycles covering every edge of one component, each as a node list (first == last)."""
    allowed, seen, cycles = set(comp), set(), []
    for a in comp:
        for b in sorted(graph[a]):
            if b not in allowed:
                continue
            back = shortest_path(graph, b, a, allowed)
            cycle = [a] + back
            ring = cycle[:-1]
            k = ring.index(min(ring))
            canonical = tuple(ring[k:] + ring[:k])
            if canonical not in seen:
                seen.add(canonical)
                cycles.append(list(canonical) + [canonical[0]])
    return sorted(cycles, key=lambda c: (len(c), c))


def report(graph, kind):
    """Print every cycle of graph; return how many were found."""
    count = 0
    for comp in strongly_connected(graph):
        print(f"{kind}s in one include cycle: {', '.join(comp)}")
        for cycle in cycles_of_component(graph, comp):
            count += 1
            print(f"  cycle of {len(cycle) - 1}: " + " -> ".join(cycle))
            for a, b in zip(cycle, cycle[1:]):
                for inc in graph[a][b]:
                    print(f"    {inc.src}:{inc.line}: {inc.text}   [{a} -> {b}]")
    return count


def main(argv=None):
    """Parse arguments, check both graphs, print offenders, return the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=lint_common.default_root(),
                        help="source tree to check (default: this repository)")
    parser.add_argument("--verbose", action="store_true",
                        help="also list quoted includes that resolve to no library file")
    args = parser.parse_args(argv)
    includes, lib_of = collect_includes(args.root, args.verbose)
    units = build_graph(includes, unit_of)
    libs = build_graph(includes, lambda rel: lib_of[rel])
    count = report(units, "unit") + report(libs, "library")
    print(f"checked {len(lib_of)} files in libraries: {' '.join(lint_common.discover_libraries(args.root))}")
    return lint_common.fail_summary("check_include_cycles", count, "include cycle(s)")


if __name__ == "__main__":
    sys.exit(main())
