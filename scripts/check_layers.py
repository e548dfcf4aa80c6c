#!/usr/bin/env python3
"""check_layers.py [ROOT] | --self-test: checks the source tree's structure (docs/ARCHITECTURE.md) and exits 1 on
any finding, naming each one:

- layers: a file in folder A includes a header of folder B only where B is one of A's allowed
  folders below (the folders form a DAG, checked too);
- cycles: no include cycle between modules, where a module is X.c with X.h of one folder, and
  module A depends on B when A.c or A.h includes B.h;
- style: project headers by their path from src/ (or include/, or the file's own folder for app/,
  tests/, bench/), never with '../'; cJSON as <cjson/cJSON.h>; each file opens with a comment;
- size: no source file over 700 lines (tests are exempt: they may read as long sections).

--self-test builds small trees with one planted problem each and fails unless every one is found
and a clean tree passes (a check that cannot fail would prove nothing).
"""
import collections
import io
import os
import re
import sys
import tempfile
from contextlib import redirect_stdout

# Who may include whom, by folder. Lower layers come first; every folder may include itself.
ALLOWED = {
    "include/restir": [],
    "src/restir": ["include/restir"],
    "src/metrics": ["include/restir"],
    "src/recon": ["include/restir"],
    "src/core": [],
    "src/denoise": ["src/core"],
    "src/scene": ["src/core"],
    "src/shading": ["src/scene", "src/core"],
    "src/render": ["src/denoise", "src/shading", "src/scene", "src/core", "include/restir"],
    "src/methods": ["src/denoise", "src/render", "src/shading", "src/scene", "src/core", "include/restir"],
    "src/io": ["src/scene", "src/core", "include/restir"],
    "src/experiments": ["src/denoise", "src/methods", "src/render", "src/io", "src/shading", "src/scene", "src/core",
                        "include/restir"],
    "src/view": ["src/denoise", "src/methods", "src/render", "src/io", "src/scene", "src/core", "include/restir"],
    "app": ["src/denoise", "src/experiments", "src/view", "src/methods", "src/render", "src/io", "src/shading", "src/scene",
            "src/core", "include/restir"],
}
# Checked for style, size exemptions and cycles, but free to include any layer.
FREE = ["tests", "bench", "fuzz"]
MAX_LINES = 700
INCLUDE_RE = re.compile(r'^\s*#\s*include\s+([<"])([^">]+)[">]', re.M)


def folder_of(path):
    for f in sorted(list(ALLOWED) + FREE, key=len, reverse=True):
        if path == f or path.startswith(f + "/"):
            return f
    return None


def sources(root):
    out = []
    for top in ["src", "app", "include", "tests", "bench", "fuzz"]:
        for dirpath, _, names in os.walk(os.path.join(root, top)):
            for n in names:
                if n.endswith((".c", ".h")):
                    out.append(os.path.relpath(os.path.join(dirpath, n), root))
    return sorted(out)


def resolve(root, src, inc):
    """The header a quoted include names, relative to root, or None."""
    here = os.path.dirname(src)
    for base in [here, "src", "include", "tests"]:
        cand = os.path.normpath(os.path.join(base, inc))
        if os.path.exists(os.path.join(root, cand)):
            return cand
    return None


def find_cycles(graph):
    """Strongly connected components with more than one node (Tarjan's algorithm)."""
    index, low, stack, on_stack, comps = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                comps.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(graph):
        if v not in index:
            visit(v)
    return comps


def check(root):
    """Prints every problem of the tree at root; returns how many there are."""
    problems = []
    folder_graph = {f: set(a) for f, a in ALLOWED.items()}
    for comp in find_cycles(folder_graph):
        problems.append("layers: the allowed folders form a cycle: " + " -> ".join(comp))
    modules = collections.defaultdict(set)
    for path in sources(root):
        text = open(os.path.join(root, path), encoding="utf-8").read()
        src_folder = folder_of(path)
        module = os.path.splitext(path)[0]
        modules[module]
        if not text.lstrip().startswith(("/*", "//")):
            problems.append(f"style: {path} does not open with a comment saying what it holds")
        lines = text.count("\n")
        if lines > MAX_LINES and not path.startswith("tests/"):
            problems.append(f"size: {path} has {lines} lines (at most {MAX_LINES})")
        for kind, inc in INCLUDE_RE.findall(text):
            if "cJSON.h" in inc and not (kind == "<" and inc == "cjson/cJSON.h"):
                problems.append(f"style: {path} includes {kind}{inc}: spell it <cjson/cJSON.h>")
            if kind != '"':
                continue
            if ".." in inc.split("/"):
                problems.append(f"style: {path} includes \"{inc}\": name headers from src/, not with ../")
            target = resolve(root, path, inc)
            if target is None:
                problems.append(f"style: {path} includes \"{inc}\", which is not a project header")
                continue
            if (src_folder in ALLOWED and src_folder.startswith("src/") and "/" not in inc
                    and os.path.dirname(target) == os.path.dirname(path)):
                problems.append(f"style: {path} includes \"{inc}\": name it from src/ "
                                f"(\"{os.path.relpath(target, 'src')}\")")
            dst_folder = folder_of(target)
            if src_folder in ALLOWED and dst_folder != src_folder and dst_folder not in ALLOWED[src_folder]:
                problems.append(f"layers: {path} includes {target}: {src_folder} may not include {dst_folder}")
            dst_module = os.path.splitext(target)[0]
            if dst_module != module:
                modules[module].add(dst_module)
    for comp in find_cycles(modules):
        problems.append("cycles: these modules include each other: " + ", ".join(comp))
    for p in problems:
        print(p)
    print(f"check_layers: {len(modules)} modules, {len(problems)} problem(s)")
    return len(problems)


def self_test():
    clean = {
        "src/core/vec.h": '/* vec.h: x */\n#include <math.h>\n',
        "src/scene/scene.h": '/* scene.h: x */\n#include "core/vec.h"\n',
        "src/scene/scene.c": '/* scene.c: x */\n#include "scene/scene.h"\n\n#include <cjson/cJSON.h>\n',
        "app/cli.h": '/* cli.h: x */\n#include "scene/scene.h"\n',
        "app/main.c": '/* main.c: x */\n#include "cli.h"\n',
    }
    planted = {
        "upward include": ("src/core/vec.h", '/* vec.h: x */\n#include "scene/scene.h"\n', "layers:"),
        "module cycle": ("src/scene/light.h", '/* light.h: x */\n#include "scene/scene.h"\n', "cycles:"),
        "long file": ("src/scene/big.c", "/* big.c: x */\n" + "int x;\n" * 701, "size:"),
        "../ include": ("app/bad.c", '/* bad.c: x */\n#include "../src/core/vec.h"\n', "style:"),
        "bare src include": ("src/scene/other.c", '/* other.c: x */\n#include "scene.h"\n', "style:"),
        "cJSON spelling": ("src/scene/json.c", '/* json.c: x */\n#include <cJSON.h>\n', "style:"),
        "no opening comment": ("src/scene/plain.c", "int y;\n", "style:"),
    }
    failures = 0
    for name, (path, text, kind) in [("clean tree", (None, None, None))] + list(planted.items()):
        with tempfile.TemporaryDirectory() as root:
            files = dict(clean)
            if path:
                files[path] = text
            if name == "module cycle":  # scene.h includes light.h, which includes scene.h
                files["src/scene/scene.h"] += '#include "scene/light.h"\n'
            for rel, body in files.items():
                os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
                with open(os.path.join(root, rel), "w", encoding="utf-8") as f:
                    f.write(body)
            out = io.StringIO()
            with redirect_stdout(out):
                found = check(root)
            ok = found == 0 if path is None else found > 0 and kind in out.getvalue()
            print(f"{'ok  ' if ok else 'FAIL'} {name}: {found} problem(s)")
            failures += not ok
    print(f"self-test: {len(planted) + 1 - failures} passed, {failures} failed")
    return 1 if failures else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    return 1 if check(root) else 0


if __name__ == "__main__":
    sys.exit(main())
