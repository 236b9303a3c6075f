#!/usr/bin/env python3
"""Who uses whom among the modules of each crate, and the circles (docs/ARCHITECTURE.md).

A module A uses a sibling B when A's file names `crate::B`, `super::B` (from a child of the same parent) or
`B::` after a `use crate::{...B...}`. Text-level, so a mention in a comment counts too: it errs on the side of
reporting a circle. Also counts the lines of crates/cli/src and which CLI command modules import another.

    python3 tools/module_graph.py            # circles per crate, CLI size and cross-imports; exit 1 on any
    python3 tools/module_graph.py --edges    # and every edge
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def crate_modules(src: Path):
    """Top-level module name -> list of files (the module's file and everything below it)."""
    mods = {}
    for f in sorted(src.rglob("*.rs")):
        rel = f.relative_to(src)
        if rel.parts[0] in ("main.rs", "lib.rs", "bin"):
            continue
        name = rel.parts[0].removesuffix(".rs")
        mods.setdefault(name, []).append(f)
    return mods


def strip_comments(text: str) -> str:
    return "\n".join(line.split("//")[0] if not line.lstrip().startswith("//") else "" for line in text.splitlines())


def top_level_edges(src: Path, prefix: str = "crate::"):
    mods = crate_modules(src)
    names = set(mods)
    edges = {m: set() for m in mods}
    for m, files in mods.items():
        for f in files:
            text = strip_comments(f.read_text())
            for target in re.findall(re.escape(prefix) + r"([a-z_][a-z0-9_]*)", text):
                if target in names and target != m:
                    edges[m].add(target)
            # `use crate::{a, b::c}` groups
            for group in re.findall(re.escape(prefix) + r"\{([^}]*)\}", text, flags=re.S):
                for target in re.findall(r"(?:^|[,{\s])([a-z_][a-z0-9_]*)", group):
                    if target in names and target != m:
                        edges[m].add(target)
            # `super::x` from a top-level module file means a sibling
            depth = len(f.relative_to(src).parts)
            if depth == 1 or f.name == "mod.rs" and depth == 2:
                for target in re.findall(r"super::([a-z_][a-z0-9_]*)", text):
                    if target in names and target != m:
                        edges[m].add(target)
    return edges


def circles(edges):
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, on, stack, out, counter = {}, {}, set(), [], [], [0]

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
    for v in edges:
        if v not in index:
            visit(v)
    return out


def main():
    show_edges = "--edges" in sys.argv
    bad = False
    for crate in sorted((ROOT / "crates").iterdir()):
        src = crate / "src"
        if not src.is_dir():
            continue
        edges = top_level_edges(src)
        if crate.name == "cli" and (src / "cmd").is_dir():
            cmd_edges = top_level_edges(src / "cmd", "crate::cmd::")
            for m, t in top_level_edges(src / "cmd").items():
                cmd_edges[m] |= t
            for m, targets in sorted(cmd_edges.items()):
                for t in sorted(targets):
                    print(f"cli: command module {m} imports command module {t}")
                    bad = True
            for c in circles(cmd_edges):
                print(f"cli/cmd: circle {' <-> '.join(c)}")
            lines = sum(len(f.read_text().splitlines()) for f in src.rglob("*.rs"))
            print(f"cli: crates/cli/src is {lines} lines")
        for c in circles(edges):
            print(f"{crate.name}: circle {' <-> '.join(c)}")
            bad = True
        if show_edges:
            for m, targets in sorted(edges.items()):
                if targets:
                    print(f"  {crate.name}::{m} -> {', '.join(sorted(targets))}")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
