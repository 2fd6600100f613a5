#!/usr/bin/python3
"""Checks that the includes of slam/ point one way (run by scripts/check_docs.py).

A unit is a header with its source and its JSON codec: slam/io/publish.h,
slam/io/publish.cc and slam/io/publish_json.h are the unit slam/io/publish.
Unit A uses unit B when a file of A has `#include "slam/.../B.h"` (quoted
includes only; system and third-party headers are not followed). A source
without a header of its name (vocabulary_export.cc) is a unit of its own.

1. No cycle between units: for each set of units that reach each other, one
   cycle through them and the includes that make it are listed.
2. Modules: no include runs up the module list, the order of the module
   table's rows in docs/architecture.md (`| `io/` | ...`): a file of
   slam/<a>/ includes only slam/<a>/ and modules listed above <a>.
3. Sub-modules of slam/synthetic/: no include runs back up the order that
   docs/architecture.md gives in the line "`raster ──► assets ──► ...
   ──► synthetic/`" (the generator, the files directly in synthetic/, last).

Usage: check_includes.py     exit 1 with one line per problem
"""
import collections
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
INCLUDE = re.compile(r'^\s*#\s*include\s+"(slam/[^"]+)"', re.M)
MODULE_ROW = re.compile(r"^\| `([A-Za-z0-9_]+)/` \|", re.M)
SUBMODULE_ORDER = re.compile(r"`((?:[a-z_]+/? ──► )+synthetic/)`")


def include_edges():
    """(file, included file) for every quoted slam/ include in a file under slam/."""
    edges = []
    for folder, dirs, files in os.walk(os.path.join(ROOT, "slam")):
        dirs.sort()
        for name in sorted(files):
            if not name.endswith((".h", ".cc")):
                continue
            path = os.path.relpath(os.path.join(folder, name), ROOT).replace(os.sep, "/")
            with open(os.path.join(ROOT, path), encoding="utf-8") as text:
                for included in INCLUDE.findall(text.read()):
                    edges.append((path, included))
    return edges


def unit_of(path):
    return re.sub(r"(_json)?\.(h|cc)$", "", path)


def strongly_connected(graph):
    """Tarjan's algorithm, iterative: the components of more than one node."""
    index, low, on_stack, stack, components = {}, {}, set(), [], []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, successors = work[-1]
            advanced = False
            for succ in successors:
                if succ not in index:
                    index[succ] = low[succ] = len(index)
                    stack.append(succ)
                    on_stack.add(succ)
                    work.append((succ, iter(sorted(graph.get(succ, ())))))
                    advanced = True
                    break
                if succ in on_stack:
                    low[node] = min(low[node], index[succ])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    components.append(sorted(component))
    return components


def cycle_through(start, graph, members):
    """A shortest path start -> ... -> start inside `members` (breadth first)."""
    previous = {start: None}
    queue = collections.deque([start])
    while queue:
        node = queue.popleft()
        for succ in sorted(graph[node]):
            if succ not in members:
                continue
            if succ == start:
                path = [node]
                while previous[path[-1]] is not None:
                    path.append(previous[path[-1]])
                return list(reversed(path)) + [start]
            if succ not in previous:
                previous[succ] = node
                queue.append(succ)
    return [start]


def cycle_problems(edges):
    graph = collections.defaultdict(set)
    files_of_edge = collections.defaultdict(list)
    for path, included in edges:
        a, b = unit_of(path), unit_of(included)
        if a != b:
            graph[a].add(b)
            graph[b]
            files_of_edge[(a, b)].append(f"{path} includes {included}")
    problems = []
    for component in strongly_connected(graph):
        cycle = cycle_through(component[0], graph, set(component))
        because = "; ".join(files_of_edge[(a, b)][0] for a, b in zip(cycle, cycle[1:]))
        extra = f" (units in the cycles: {', '.join(component)})" if len(component) > len(cycle) - 1 else ""
        problems.append(f"include cycle: {' -> '.join(cycle)}{extra}: {because}")
    return problems


def direction_problems(edges, order, part_of, what):
    """Includes from a part to a part later in `order` (parts None are not checked)."""
    rank = {part: i for i, part in enumerate(order)}
    problems = []
    for path, included in edges:
        a, b = part_of(path), part_of(included)
        if a is None or b is None or a == b:
            continue
        if a not in rank or b not in rank:
            missing = a if a not in rank else b
            problems.append(f"{path}: includes {included}, but {what} lists no {missing}")
        elif rank[b] > rank[a]:
            problems.append(f"{path}: includes {included}: {b} is listed after {a} ({what})")
    return problems


def module_of(path):
    return path.split("/")[1]


def synthetic_part_of(path):
    parts = path.split("/")
    if parts[1] != "synthetic":
        return None
    return parts[2] + "/" if len(parts) > 3 else "synthetic/"


def problems():
    edges = include_edges()
    found = cycle_problems(edges)
    with open(os.path.join(ROOT, "docs", "architecture.md"), encoding="utf-8") as text:
        architecture = text.read()
    modules = MODULE_ROW.findall(architecture)
    if not modules:
        found.append("docs/architecture.md: no module table (`| `m/` | ...` rows) to check includes against")
    else:
        found += direction_problems(edges, modules, module_of,
                                    "the module table of docs/architecture.md, top to bottom")
    order = SUBMODULE_ORDER.search(architecture)
    if not order:
        found.append("docs/architecture.md: no \"`raster ──► ... ──► synthetic/`\" line giving the "
                     "order of synthetic/'s sub-modules")
    else:
        parts = [p.strip().rstrip("/") + "/" for p in order.group(1).split("──►")]
        found += direction_problems(edges, parts, synthetic_part_of,
                                    "docs/architecture.md's order of synthetic/'s sub-modules")
    return found


def main():
    found = problems()
    for problem in found:
        print(problem)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
