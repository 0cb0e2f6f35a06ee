#!/usr/bin/env python3
"""Fails when a lower layer of cgdem includes a higher one.

    scripts/check_layers.py [SOURCE_DIR]      check the tree (default: this script's repository)
    scripts/check_layers.py --self-test       show that a planted violation is caught

The layers, lowest first (a file may include its own folder and any lower rank):

    0  src/core
    1  src/geometry, src/io
    2  src/particles, src/contact   (one module, cgdem_dem's building blocks: they may
                                    include each other)
    3  src/fluid
    4  src/coupling, src/diagnostics
                                   (the drag and exchange between parcels and air; the
                                    observables of a run, such as the die-filling
                                    diagnostics: neither includes the other)
    5  src/parallel                 (decomposition, migration, and the MPI exchanges)
    6  solvers/*                    (everything that advances time; any solvers/ folder
                                    may include another, the graph between them must be
                                    acyclic)
    7  src/app                      (case readers, the phases and outputs of a run; the
                                    run driver is solvers/run)
    8  scaling, bench               (analysis commands and benchmarks; neither includes
                                    the other)
    9  src/app/main.cpp             (the command line: may include everything)

Only quoted includes of files that exist in the tree are looked at; tests/ may include
anything. Prints every violation with file and line, and any cycle between folders.
"""
import os
import re
import sys
import tempfile

RANK = {
    "src/core": 0,
    "src/geometry": 1, "src/io": 1,
    "src/particles": 2, "src/contact": 2,
    "src/fluid": 3,
    "src/coupling": 4, "src/diagnostics": 4,
    "src/parallel": 5,
    "solvers": 6,
    "src/app": 7,
    "scaling": 8, "bench": 8,
    "cli": 9,
}
# Folders of one rank that may include each other.
SAME_RANK_OK = [{"src/particles", "src/contact"}]
ROOTS = ("src", "solvers", "scaling", "bench")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"')


def layer_of(rel):
    """The layer of a repository-relative path, or None when it is in none."""
    if rel == "src/app/main.cpp":
        return "cli"
    parts = rel.split("/")
    if parts[0] == "src" and len(parts) > 2:
        return "src/" + parts[1]
    if parts[0] in ("solvers", "scaling", "bench"):
        return parts[0]
    return None


def folder_of(rel):
    """The folder used for cycle detection: src/<mod>, solvers/<mod>, scaling, bench."""
    parts = rel.split("/")
    if parts[0] in ("src", "solvers") and len(parts) > 2:
        return parts[0] + "/" + parts[1]
    return parts[0]


def resolve(root, inc):
    """The repository-relative path of an include ("core/x.hpp" is src/core/x.hpp)."""
    for cand in (os.path.join("src", inc), inc):
        if os.path.isfile(os.path.join(root, cand)):
            return cand.replace(os.sep, "/")
    return None


def check(root):
    violations, edges = [], {}
    for top in ROOTS:
        for dirpath, _, files in os.walk(os.path.join(root, top)):
            for name in sorted(files):
                if not name.endswith((".cpp", ".hpp", ".h")):
                    continue
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, root).replace(os.sep, "/")
                a = layer_of(rel)
                if a is None:
                    continue
                with open(path, errors="replace") as f:
                    for lineno, line in enumerate(f, 1):
                        m = INCLUDE.match(line)
                        if not m:
                            continue
                        tgt = resolve(root, m.group(1))
                        if tgt is None:
                            continue
                        b = layer_of(tgt)
                        if b is None:
                            continue
                        fa, fb = folder_of(rel), folder_of(tgt)
                        if fa != fb and a != "cli":
                            edges.setdefault(fa, set()).add(fb)
                        if a == b or a == "cli":
                            continue
                        unknown = [x for x in (a, b) if x not in RANK]
                        if unknown:
                            violations.append(f"{rel}:{lineno}: folder {unknown[0]} has no layer "
                                              f"(give it a rank in scripts/check_layers.py)")
                            continue
                        ok = RANK[b] < RANK[a] or any({a, b} <= s for s in SAME_RANK_OK)
                        if not ok:
                            violations.append(f"{rel}:{lineno}: layer {a} (rank {RANK[a]}) includes "
                                              f"{tgt} of layer {b} (rank {RANK[b]})")
    # Cycles between folders other than the allowed same-rank pairs.
    allowed = {frozenset(s) for s in SAME_RANK_OK}
    cycles, state = [], {}

    def visit(n, stack):
        state[n] = 1
        stack.append(n)
        for m in sorted(edges.get(n, ())):
            if frozenset((n, m)) in allowed:
                continue
            if state.get(m) == 1:
                cycles.append(" -> ".join(stack[stack.index(m):] + [m]))
            elif m not in state:
                visit(m, stack)
        stack.pop()
        state[n] = 2

    for n in sorted(edges):
        if n not in state:
            visit(n, [])
    return violations, cycles


def self_test():
    """A tree with one upward include and one cycle must give exactly those."""
    with tempfile.TemporaryDirectory() as d:
        def write(rel, text):
            os.makedirs(os.path.dirname(os.path.join(d, rel)), exist_ok=True)
            with open(os.path.join(d, rel), "w") as f:
                f.write(text)
        write("src/core/a.hpp", '#include "fluid/b.hpp"\n')           # upward: violation
        write("src/fluid/b.hpp", "\n")
        write("src/core/c.hpp", "\n")
        write("solvers/x/x.hpp", '#include "solvers/y/y.hpp"\n')       # solvers x <-> y: cycle
        write("solvers/y/y.hpp", '#include "solvers/x/x.hpp"\n')
        write("src/app/main.cpp", '#include "scaling/s.hpp"\n')         # the command line: fine
        write("scaling/s.hpp", '#include "app/r.hpp"\n')
        write("src/app/r.hpp", "\n")
        v, c = check(d)
    print("self-test: violations:", v)
    print("self-test: cycles:", c)
    ok = (len(v) == 1 and v[0].startswith("src/core/a.hpp:1:") and len(c) == 1 and "solvers/x" in c[0])
    print("self-test:", "passed" if ok else "FAILED")
    return 0 if ok else 1


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    root = argv[1] if len(argv) > 1 else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    violations, cycles = check(root)
    for v in violations:
        print(v)
    for c in cycles:
        print("cycle between folders:", c)
    print(f"check_layers: {len(violations)} upward includes, {len(cycles)} folder cycles")
    return 1 if violations or cycles else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
