#!/usr/bin/env python3
"""check_api_doc.py ROOT: docs/API.md's function reference against include/restir/*.h.

Every function declared or defined in a public header must have a row `| `name` | yes/no | ... |`
in docs/API.md, with "yes" exactly when the header defines it RESTIR_HD (inline, CUDA-callable);
every row must name a function that exists. Exits 1 listing the differences."""
import pathlib
import re
import sys

DECL = re.compile(r"^(RESTIR_HD\s+)?[A-Za-z_][A-Za-z0-9_ ]*?[\s*](restir_[a-z0-9_]+)\(", re.M)
ROW = re.compile(r"^\|\s*`(restir_[a-z0-9_]+)`\s*\|\s*(yes|no)\s*\|", re.M)


def header_functions(root):
    found = {}
    for header in sorted((root / "include" / "restir").glob("*.h")):
        for m in DECL.finditer(header.read_text()):
            found[m.group(2)] = (bool(m.group(1)), header.name)
    return found


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    headers = header_functions(root)
    doc = {m.group(1): m.group(2) == "yes" for m in ROW.finditer((root / "docs" / "API.md").read_text())}
    problems = []
    for name, (hd, header) in sorted(headers.items()):
        if name not in doc:
            problems.append(f"{name} ({header}) has no row in docs/API.md")
        elif doc[name] != hd:
            problems.append(f"{name}: docs/API.md says HD {'yes' if doc[name] else 'no'}, {header} says "
                            f"{'yes' if hd else 'no'}")
    for name in sorted(set(doc) - set(headers)):
        problems.append(f"docs/API.md lists {name}, which no public header declares")
    for p in problems:
        print("check_api_doc:", p)
    print(f"check_api_doc: {len(headers)} public functions, {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
