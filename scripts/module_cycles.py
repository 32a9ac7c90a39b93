#!/usr/bin/env python3
"""Module cycles in each Rust crate of the workspace: which modules' `use`s and paths reach each
other round in a loop (a imports b, b imports a, or longer). Reads the sources as text, each
file a module; a path is resolved to the deepest module file it names (`crate::a::b::Item` is
module a::b when a/b.rs or a/b/mod.rs exists, else a). A parent module reaching into its own
children (re-exports, `mod` items) is how Rust nests modules and is left out; a child reaching
back to its parent's items, and any two modules that are not nested, count.

Usage: scripts/module_cycles.py [CRATE_SRC ...]   (default: crates/*/src and python/src)
Exit status: 0 when no crate has a cycle, 1 otherwise (each cycle printed).
"""

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def modules(src: Path):
    """{module path tuple: file} for every .rs file under src (lib.rs/main.rs the root)."""
    out = {}
    for f in src.rglob("*.rs"):
        rel = f.relative_to(src).with_suffix("")
        parts = list(rel.parts)
        if parts[-1] == "mod":
            parts = parts[:-1]
        if parts in (["lib"], ["main"]):
            parts = []
        if "tests" in parts and f.name != "tests.rs" and parts[0] == "tests":
            continue
        out[tuple(parts)] = f
    return out


def strip(text: str) -> str:
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r'"(\\.|[^"\\])*"', '""', text)
    # Test modules reach everywhere by design: leave `#[cfg(test)] mod tests { ... }` out.
    return text


def code_without_tests(text: str) -> str:
    i = text.find("#[cfg(test)]")
    return text if i < 0 else text[:i]


def paths(text: str):
    """Every `crate::…`, `super::…`, `self::…` path, with use-tree braces expanded."""
    found = []
    for m in re.finditer(r"\buse\s+([^;]+);", text):
        found.extend(expand(m.group(1).replace("\n", " ")))
    for m in re.finditer(r"\b((?:crate|super|self)(?:::\w+)+)", text):
        found.append(m.group(1))
    return found


def expand(tree: str):
    tree = re.sub(r"\s+", "", tree)
    m = re.match(r"^(.*?)\{(.*)\}$", tree)
    if not m:
        return [tree.split(" as ")[0]]
    prefix, inner = m.group(1), m.group(2)
    depth, start, parts = 0, 0, []
    for i, c in enumerate(inner):
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
        elif c == "," and depth == 0:
            parts.append(inner[start:i])
            start = i + 1
    parts.append(inner[start:])
    return [p for part in parts if part for p in expand(prefix + part)]


def resolve(here, path, mods):
    segs = path.split("::")
    if segs[0] == "crate":
        base, rest = [], segs[1:]
    elif segs[0] in ("super", "self"):
        base = list(here)
        rest = segs
        while rest and rest[0] in ("super", "self"):
            if rest[0] == "super" and base:
                base.pop()
            rest = rest[1:]
    else:
        return None
    best = tuple(base)
    cur = list(base)
    for s in rest:
        cur.append(s)
        if tuple(cur) in mods:
            best = tuple(cur)
        else:
            break
    return best


def cycles(src: Path):
    mods = modules(src)
    edges = {m: set() for m in mods}
    for m, f in mods.items():
        text = code_without_tests(strip(f.read_text()))
        for p in paths(text):
            t = resolve(m, p, mods)
            if t is None or t == m or t not in mods:
                continue
            if t[: len(m)] == m:  # a parent reaching into its own children
                continue
            edges[m].add(t)
    # Tarjan's strongly connected components.
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in mods:
        if v not in index:
            visit(v)
    return out, edges


def main():
    srcs = [Path(a) for a in sys.argv[1:]] or sorted(ROOT.glob("crates/*/src")) + [ROOT / "python/src"]
    total = 0
    for src in srcs:
        found, edges = cycles(src)
        for comp in found:
            total += 1
            names = ["::".join(c) or "(root)" for c in comp]
            print(f"{src.relative_to(ROOT) if src.is_absolute() else src}: {' ↔ '.join(names)}")
            for c in comp:
                inside = sorted("::".join(t) or "(root)" for t in edges[c] if t in comp)
                print(f"    {'::'.join(c) or '(root)'} → {', '.join(inside)}")
    print(f"{total} module cycles")
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main())
