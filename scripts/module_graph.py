#!/usr/bin/env python3
"""Import graph of a crate's modules, and its cycles.

Usage: module_graph.py SRC_DIR [--files] [--print]

Reads every path a file names outside comments and outside `mod tests` (unit tests may reach up
the graph; files named tests.rs are skipped): `crate::...`, `super::...`, `self::...` and paths
that start with a child module of the file (`thermo::new` in the file that declares `mod
thermo`), with `{...}` groups expanded. By default a node is a top-level module (`a/b.rs` ->
`a`, `a.rs` -> `a`); with --files it is every file's module (`a/b.rs` -> `a::b`, `a/mod.rs` ->
`a`), so that a parent and its children are checked too. A path is mapped to the longest module
it names; crate-root re-exports such as `crate::System` are resolved through the root's `pub
use` lines. A `mod x;` declaration is not an import. Exits 1 and names the modules of every
cycle (strongly connected component) it finds; `--print` lists the edges. A text scan, not a
compiler: a path built by a macro or a glob re-export is not seen.
"""

import os
import re
import sys

IDENT = r"[A-Za-z_][A-Za-z_0-9]*"
START = re.compile(r"(?<![A-Za-z_0-9:])(crate|super|self|" + IDENT + r")::")
NAME = re.compile(r"(?:^|[{,]\s*)([A-Za-z_0-9]+)")
REEXPORT = re.compile(r"^pub use ([a-z_0-9]+)::(\{[^;]*\}|[A-Za-z_0-9]+);", re.M)
MOD = re.compile(r"^\s*(?:pub(?:\([a-z]+\))?\s+)?mod (" + IDENT + r")\s*;", re.M)


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


def module_of(relative):
    """`a/b.rs` -> ("a", "b"), `a/mod.rs` -> ("a",), `lib.rs` -> ()."""
    parts = relative[:-3].split(os.sep)
    if parts[-1] in ("mod", "lib", "main"):
        parts = parts[:-1]
    return tuple(parts)


def expand(text, i):
    """The paths of the use tree that starts at text[i] (after a `::`), as lists of segments,
    and the index after it."""
    if text.startswith("{", i):
        paths, depth, start, j = [], 0, i + 1, i
        while j < len(text):
            c = text[j]
            if c == "{":
                depth += 1
            elif c == "}":
                depth -= 1
                if depth == 0:
                    break
            if c == "," and depth == 1:
                paths.extend(expand_item(text[start:j]))
                start = j + 1
            j += 1
        paths.extend(expand_item(text[start:j]))
        return paths, j + 1
    m = re.compile(IDENT + r"(?:::" + IDENT + r")*").match(text, i)
    if not m:
        return [[]], i
    segments = m.group(0).split("::")
    end = m.end()
    if text.startswith("::{", end):
        inner, end = expand(text, end + 2)
        return [segments + p for p in inner], end
    return [segments], end


def expand_item(item):
    item = item.strip()
    if not item:
        return []
    paths, _ = expand(item, 0)
    return paths


def graph(src, files=False):
    aliases = root_aliases(src)
    sources = {}
    for folder, _, names in os.walk(src):
        for f in names:
            if f.endswith(".rs") and f != "tests.rs":
                path = os.path.join(folder, f)
                sources[module_of(os.path.relpath(path, src))] = path
    modules = set(sources)
    edges = {}
    for here, path in sources.items():
        code = code_of(path)
        children = set(MOD.findall(code))
        code_without_mods = MOD.sub("", code)
        out = set()
        for m in START.finditer(code_without_mods):
            first = m.group(1)
            if first == "crate":
                base = ()
            elif first == "self":
                base = here
            elif first == "super":
                base = here[:-1]
            elif first in children:
                base = here + (first,)
            else:
                continue
            tails, _ = expand(code_without_mods, m.end())
            for tail in tails:
                # Leading `super::super::...` climbs further.
                b = base
                while tail and tail[0] == "super":
                    b, tail = b[:-1], tail[1:]
                if first == "crate" and tail and tail[0] in aliases and (tail[0],) not in modules:
                    tail = [aliases[tail[0]]] + tail[1:]
                target = b + tuple(tail)
                while target and target not in modules:
                    target = target[:-1]
                if target in modules:
                    out.add(target)
        node = here if files else here[:1]
        targets = {t if files else t[:1] for t in out}
        edges.setdefault(node, set()).update(t for t in targets if t != node and t)
    names = {n for n in edges if n}
    return {
        "::".join(m): sorted("::".join(d) for d in out if d in names)
        for m, out in edges.items()
        if m
    }


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
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    if len(args) != 1:
        sys.exit("usage: module_graph.py SRC_DIR [--files] [--print]")
    files = "--files" in sys.argv
    edges = graph(args[0], files)
    if "--print" in sys.argv:
        for m in sorted(edges):
            print(f"{m} -> {', '.join(edges[m])}")
    found = cycles(edges)
    for component in found:
        print(f"import cycle among {', '.join(component)}", file=sys.stderr)
    if found:
        sys.exit(1)
    unit = "files" if files else "modules"
    print(f"{args[0]}: {len(edges)} {unit}, no import cycle")


if __name__ == "__main__":
    main()
