"""No import cycle in descgen, at module level or inside a function: every strongly connected
component of the import graph (grimp reads both kinds) is one module. The layers contract
(pyproject.toml, [tool.importlinter]) orders the folders; this also holds inside a folder.

Exit 0 when there is none; else each cycle's modules and the imports that close it, exit 1."""

from __future__ import annotations

import sys

import grimp


def cycles(package: str = "descgen") -> list[list[str]]:
    graph = grimp.build_graph(package)
    edges = {m: sorted(graph.find_modules_directly_imported_by(m)) for m in sorted(graph.modules)}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    for root in edges:  # Tarjan's algorithm, iterative: a deep chain must not hit the recursion limit
        if root in index:
            continue
        work = [(root, 0)]
        while work:
            node, i = work.pop()
            if i == 0:
                index[node] = low[node] = len(index)
                stack.append(node)
                on_stack.add(node)
            for j in range(i, len(edges[node])):
                nxt = edges[node][j]
                if nxt not in index:
                    work += [(node, j + 1), (nxt, 0)]
                    break
                if nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
            else:
                if low[node] == index[node]:
                    component = []
                    while True:
                        top = stack.pop()
                        on_stack.discard(top)
                        component.append(top)
                        if top == node:
                            break
                    if len(component) > 1:
                        found.append(sorted(component))
                if work:
                    parent = work[-1][0]
                    low[parent] = min(low[parent], low[node])
    return found


def main() -> int:
    found = cycles()
    graph = grimp.build_graph("descgen") if found else None
    for component in found:
        print(f"import cycle of {len(component)} modules:")
        for a in component:
            for b in component:
                if graph is not None and graph.direct_import_exists(importer=a, imported=b):
                    lines = sorted(d["line_number"] for d in graph.get_import_details(importer=a, imported=b))
                    print(f"  {a} -> {b} (line {', '.join(map(str, lines))})")
    if not found:
        print("no import cycle in descgen")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
