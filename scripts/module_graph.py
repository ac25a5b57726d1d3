#!/usr/bin/env python3
"""Import graph of a crate's top-level modules, and its cycles.

Usage: module_graph.py SRC_DIR [--print]

Reads every `crate::...` path in SRC_DIR's .rs files outside comments and outside `mod tests`
(unit tests may reach up the graph), maps each file to its top-level module (`a/b.rs` -> `a`,
`a.rs` -> `a`) and each path to the module it names (crate-root re-exports such as
`crate::System` are resolved through the root's `pub use` lines). Exits 1 and names the
modules of every cycle (strongly connected component) it finds; `--print` lists the edges.
A text scan, not a compiler: a path built by a macro or a glob re-export is not seen.
"""

import os
import re
import sys

PATH = re.compile(r"crate::(\{[^;]*?\}|[A-Za-z_0-9]+)")
NAME = re.compile(r"(?:^|[{,]\s*)([A-Za-z_0-9]+)")
REEXPORT = re.compile(r"^pub use ([a-z_0-9]+)::(\{[^;]*\}|[A-Za-z_0-9]+);", re.M)


def code_of(path):
    """The file's text without comment lines and without a trailing `mod tests`."""
    text = open(path, encoding="utf-8").read()
    cut = text.find("#[cfg(test)]\nmod tests")
    if cut >= 0:
        text = text[:cut]
    return "\n".join(l for l in text.split("\n") if not l.strip().startswith("//"))


def root_aliases(src):
    """`Name -> module` for the crate root's `pub use module::Name` re-exports."""
    aliases = {}
    for module, names in REEXPORT.findall(code_of(os.path.join(src, "lib.rs"))):
        for name in NAME.findall(names) if names.startswith("{") else [names]:
            aliases[name] = module
    return aliases


def graph(src):
    aliases = root_aliases(src)
    edges = {}
    for folder, _, files in os.walk(src):
        for f in files:
            if not f.endswith(".rs") or f == "tests.rs":
                continue
            path = os.path.join(folder, f)
            module = os.path.relpath(path, src)[:-3].split(os.sep)[0]
            out = edges.setdefault(module, set())
            for group in PATH.findall(code_of(path)):
                names = NAME.findall(group) if group.startswith("{") else [group]
                out.update(aliases.get(n, n) for n in names)
    modules = set(edges)
    return {m: sorted(d for d in out if d in modules and d != m) for m, out in edges.items()}


def cycles(edges):
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    sys.setrecursionlimit(10_000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return found


def main():
    if len(sys.argv) < 2:
        sys.exit("usage: module_graph.py SRC_DIR [--print]")
    edges = graph(sys.argv[1])
    if "--print" in sys.argv:
        for m in sorted(edges):
            print(f"{m} -> {', '.join(edges[m])}")
    found = cycles(edges)
    for component in found:
        print(f"import cycle among {', '.join(component)}", file=sys.stderr)
    if found:
        sys.exit(1)
    print(f"{sys.argv[1]}: {len(edges)} modules, no import cycle")


if __name__ == "__main__":
    main()
