#!/usr/bin/env python3
"""Who uses whom among the modules of each crate, and the circles (docs/ARCHITECTURE.md).

A module A uses a sibling B when A's file names `crate::B`, `super::B` (from a child of the same parent) or
`B::` after a `use crate::{...B...}`. Text-level: comments are left out, any other mention counts, so it errs
on the side of reporting a circle. Also counts the lines of crates/cli/src and which CLI command modules
import another.

Code under `#[cfg(test)]` (a module's unit tests, a test-only module) is left out of the graph by default: it
is built only for the crate's own tests and nothing depends on it, as Cargo leaves dev-dependencies out of its
check for circles between crates. A unit test of the snake's plates may cast rays with the BVH while the BVH's
test uses the snake as its mesh. `--tests` counts it too.

    python3 tools/module_graph.py            # circles per crate, CLI size and cross-imports; exit 1 on any
    python3 tools/module_graph.py --edges    # and every edge
    python3 tools/module_graph.py --tests    # with the edges of test code
"""
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
# The thin CLI's size (docs/ARCHITECTURE.md): parse, one library call, print.
CLI_MAX_LINES = 3500


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


RAW_STRING = re.compile(r'b?r(#*)"')
CHAR = re.compile(r"'(?:\\.|[^\\'])'")


def skip_item(text: str, start: int) -> int:
    """End of the item that starts at `start`: through its balanced `{...}` block, or its `;`. Braces inside
    comments, strings and character literals do not count."""
    depth, i, n = 0, start, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            i = text.find("\n", i)
            i = n if i < 0 else i
            continue
        if text.startswith("/*", i):
            i = text.find("*/", i + 2)
            i = n if i < 0 else i + 2
            continue
        raw = RAW_STRING.match(text, i) if c in "br" and not (text[i - 1].isalnum() or text[i - 1] == "_") else None
        if raw:
            end = text.find('"' + raw.group(1), raw.end())
            i = n if end < 0 else end + 1 + len(raw.group(1))
            continue
        if c == '"':
            i += 1
            while i < n and text[i] != '"':
                i += 2 if text[i] == "\\" else 1
            i += 1
            continue
        if c == "'":
            ch = CHAR.match(text, i)
            i = ch.end() if ch else i + 1  # else a lifetime
            continue
        if c == ";" and depth == 0:
            return i + 1
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                return i + 1
        i += 1
    return i


def strip_tests(text: str) -> str:
    """The text without the items under `#[cfg(test)]` (other attributes on them included)."""
    out, pos = [], 0
    for m in re.finditer(r"#\[cfg\(test\)\]", text):
        if m.start() < pos:
            continue
        out.append(text[pos : m.start()])
        item = m.end()
        while True:  # further attributes of the same item
            a = re.match(r"\s*#\[[^\]]*\]", text[item:])
            if not a:
                break
            item += a.end()
        pos = skip_item(text, item)
    out.append(text[pos:])
    return "".join(out)


def test_only_modules(src: Path):
    """Top-level modules declared `#[cfg(test)] mod x;` in lib.rs / main.rs."""
    names = set()
    for root in ("lib.rs", "main.rs"):
        f = src / root
        if f.is_file():
            names |= set(re.findall(r"#\[cfg\(test\)\]\s*(?:#\[[^\]]*\]\s*)*(?:pub(?:\([a-z]+\))?\s+)?mod\s+([a-z_][a-z0-9_]*)\s*;", f.read_text()))
    return names


def top_level_edges(src: Path, prefix: str = "crate::", tests: bool = False):
    mods = crate_modules(src)
    if not tests:
        for name in test_only_modules(src):
            mods.pop(name, None)
    names = set(mods)
    edges = {m: set() for m in mods}
    for m, files in mods.items():
        for f in files:
            text = f.read_text()
            text = strip_comments(text if tests else strip_tests(text))
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
    tests = "--tests" in sys.argv
    bad = False
    for crate in sorted((ROOT / "crates").iterdir()):
        src = crate / "src"
        if not src.is_dir():
            continue
        edges = top_level_edges(src, tests=tests)
        if crate.name == "cli" and (src / "cmd").is_dir():
            cmd_edges = top_level_edges(src / "cmd", "crate::cmd::", tests)
            for m, t in top_level_edges(src / "cmd", tests=tests).items():
                cmd_edges[m] |= t
            for m, targets in sorted(cmd_edges.items()):
                for t in sorted(targets):
                    print(f"cli: command module {m} imports command module {t}")
                    bad = True
            for c in circles(cmd_edges):
                print(f"cli/cmd: circle {' <-> '.join(c)}")
            lines = sum(len(f.read_text().splitlines()) for f in src.rglob("*.rs"))
            print(f"cli: crates/cli/src is {lines} lines")
            if lines > CLI_MAX_LINES:
                print(f"cli: more than {CLI_MAX_LINES} lines: move the computation into the library (issue 31)")
                bad = True
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
