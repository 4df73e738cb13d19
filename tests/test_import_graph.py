"""No import circles inside tumble, not even through ``TYPE_CHECKING`` or imports inside functions.

grimp (installed with import-linter) builds the graph of tumble's imports, and counts an import
under ``if TYPE_CHECKING:`` and one inside a function as edges like any other. A cycle is a
strongly connected component of more than one module (Tarjan's algorithm); on failure each is
shown as a chain of modules that leads back to its start, every link with the line that makes
it. A hint-only import is broken by a small ``typing.Protocol`` in the lower module that lists
what it reads (as ``tumble.mass._display`` does for ``Body``), or by moving the shared thing down.
"""

from __future__ import annotations

from collections import deque

import grimp

PACKAGE = "tumble"


def strongly_connected(graph: grimp.ImportGraph) -> list[list[str]]:
    """The strongly connected components of more than one module, each sorted, in sorted order
    (Tarjan's algorithm, iterative: no recursion limit on a long chain)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    for root in sorted(graph.modules):
        if root in index:
            continue
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        work = [(root, iter(sorted(graph.find_modules_directly_imported_by(root))))]
        while work:
            v, successors = work[-1]
            for w in successors:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(sorted(graph.find_modules_directly_imported_by(w)))))
                    break
                if w in on_stack:
                    low[v] = min(low[v], index[w])
            else:  # every successor of v seen: v is done
                work.pop()
                if work:
                    parent = work[-1][0]
                    low[parent] = min(low[parent], low[v])
                if low[v] == index[v]:
                    component = []
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        component.append(w)
                        if w == v:
                            break
                    if len(component) > 1:
                        found.append(sorted(component))
    return sorted(found)


def _shortest_chain(graph: grimp.ImportGraph, members: set[str], source: str, target: str) -> list[str]:
    """A shortest chain of direct imports from ``source`` to ``target`` inside ``members``
    (breadth first), both ends included."""
    came_from: dict[str, str | None] = {source: None}
    queue = deque([source])
    while queue:
        v = queue.popleft()
        if v == target:
            chain = [v]
            while (previous := came_from[chain[-1]]) is not None:
                chain.append(previous)
            return chain[::-1]
        for w in sorted(graph.find_modules_directly_imported_by(v)):
            if w in members and w not in came_from:
                came_from[w] = v
                queue.append(w)
    raise AssertionError(f"no chain from {source} to {target}")  # in a component there always is one


def cycles_through(graph: grimp.ImportGraph, component: list[str]) -> list[list[str]]:
    """Chains of imports round ``component`` that use each of its imports at least once: for each
    import ``a -> b`` not yet used, ``a -> b`` and a shortest chain from ``b`` back to ``a``."""
    members = set(component)
    links = [(a, b) for a in component for b in sorted(graph.find_modules_directly_imported_by(a)) if b in members]
    used: set[tuple[str, str]] = set()
    chains = []
    for a, b in links:
        if (a, b) not in used:
            chain = [a, *_shortest_chain(graph, members, b, a)]
            used.update(zip(chain, chain[1:]))
            chains.append(chain)
    return chains


def describe(graph: grimp.ImportGraph, cycles: list[list[str]]) -> str:
    """The cycles as readable text: per component its modules, chains round it (every import in
    it on one at least), and each of those imports with the lines that make it."""
    lines = [f"{len(cycles)} import cycle{'' if len(cycles) == 1 else 's'} in {PACKAGE} (none allowed, not even "
             "through TYPE_CHECKING or imports inside functions):"]
    for k, component in enumerate(cycles, 1):
        lines += ["", f"cycle {k}, {len(component)} modules: {', '.join(component)}"]
        chains = cycles_through(graph, component)
        lines += ["    " + " -> ".join(chain) for chain in chains]
        lines.append("  its imports:")
        for importer, imported in sorted({link for chain in chains for link in zip(chain, chain[1:])}):
            details = graph.get_import_details(importer=importer, imported=imported)
            where = "; ".join(f"line {d['line_number']}: {d['line_contents']}" for d in details)
            lines.append(f"    {importer} -> {imported}    {where or '(no line recorded)'}")
    lines += ["", "Break each cycle: a typing.Protocol in the lower module listing what it reads (instead of "
              "a hint-only import of the class), or move the shared thing to the lower module."]
    return "\n".join(lines)


def test_tumble_has_no_import_cycles():
    graph = grimp.build_graph(PACKAGE, exclude_type_checking_imports=False, cache_dir=None)
    assert len(graph.modules) > 50  # the graph is tumble's, not an empty one
    cycles = strongly_connected(graph)
    assert not cycles, describe(graph, cycles)


def test_the_check_finds_cycles_and_names_their_chains():
    graph = grimp.ImportGraph()
    for name in ("pkg", "pkg.a", "pkg.b", "pkg.c", "pkg.d", "pkg.e", "pkg.f"):
        graph.add_module(name)
    for importer, imported in [("pkg.a", "pkg.b"), ("pkg.b", "pkg.c"), ("pkg.c", "pkg.a"), ("pkg.c", "pkg.d"),
                               ("pkg.e", "pkg.f"), ("pkg.f", "pkg.e"), ("pkg.d", "pkg.e"), ("pkg", "pkg.a")]:
        graph.add_import(importer=importer, imported=imported)
    cycles = strongly_connected(graph)
    assert cycles == [["pkg.a", "pkg.b", "pkg.c"], ["pkg.e", "pkg.f"]]
    assert cycles_through(graph, cycles[0]) == [["pkg.a", "pkg.b", "pkg.c", "pkg.a"]]
    text = describe(graph, cycles)
    assert "2 import cycles" in text
    assert "pkg.a -> pkg.b -> pkg.c -> pkg.a" in text and "pkg.e -> pkg.f -> pkg.e" in text
    assert "pkg.c -> pkg.d" not in text  # not on a cycle
    graph.add_import(importer="pkg.b", imported="pkg.a")  # a second cycle in the first component
    assert cycles_through(graph, cycles[0]) == [["pkg.a", "pkg.b", "pkg.a"], ["pkg.b", "pkg.c", "pkg.a", "pkg.b"]]
    graph.remove_import(importer="pkg.b", imported="pkg.a")
    graph.remove_import(importer="pkg.c", imported="pkg.a")
    graph.remove_import(importer="pkg.f", imported="pkg.e")
    assert strongly_connected(graph) == []


def test_a_long_chain_needs_no_recursion():
    graph = grimp.ImportGraph()
    names = [f"pkg.m{i}" for i in range(5000)]
    for name in names:
        graph.add_module(name)
    for importer, imported in zip(names, names[1:]):
        graph.add_import(importer=importer, imported=imported)
    assert strongly_connected(graph) == []
    graph.add_import(importer=names[-1], imported=names[0])
    assert [len(c) for c in strongly_connected(graph)] == [5000]
