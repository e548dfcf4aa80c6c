#!/usr/bin/env python3
"""registry.py BIN QUERY...: what `BIN list --json` says about the scenes and the method registry, for the
scripts that would otherwise keep their own lists of methods (render_hashes.sh, tsan.sh, demo.sh):

  scenes             the built-in scenes' names, one per line, in `restir list` order
  methods            the registered methods' names, one per line, in `restir list` order
  variants           "METHOD SETTINGS" per line: every method's variants (its row's .variants), in order
  role ROLE          the one method with that role (reference, demo)
  first CAP...       the first method, in `restir list` order, with every capability CAP (direct-only, ...)

Exits 1 naming the problem when BIN fails, a role is held by no method or by several, no method has the
capabilities, or a capability is not one `restir list --json` names (a typo would otherwise pick nothing).
scripts/check_lists.py imports load() from here.
"""
import json
import subprocess
import sys


def load(bin_path):
    """The document `bin_path list --json` prints, as Python objects."""
    out = subprocess.run([bin_path, "list", "--json"], check=True, stdout=subprocess.PIPE, text=True).stdout
    return json.loads(out)


def query(doc, args):
    """The lines QUERY args prints; raises ValueError naming the problem."""
    methods = doc["methods"]
    if args == ["scenes"]:
        return [s["name"] for s in doc["scenes"]]
    if args == ["methods"]:
        return [m["name"] for m in methods]
    if args == ["variants"]:
        return [m["name"] + " " + v for m in methods for v in m["variants"]]
    if len(args) == 2 and args[0] == "role":
        held = [m["name"] for m in methods if args[1] in m["roles"]]
        if len(held) != 1:
            raise ValueError("role %s is held by %d methods (%s), not 1" % (args[1], len(held), ", ".join(held)))
        return held
    if len(args) >= 2 and args[0] == "first":
        unknown = [c for c in args[1:] if c not in doc["capabilities"]]
        if unknown:
            raise ValueError("no capability is called %s (restir list --json names: %s)" %
                             (", ".join(unknown), ", ".join(doc["capabilities"])))
        for m in methods:
            if all(c in m["capabilities"] for c in args[1:]):
                return [m["name"]]
        raise ValueError("no method has the capabilities %s" % " ".join(args[1:]))
    raise ValueError("unknown query '%s' (scenes, methods, variants, role ROLE, first CAP...)" % " ".join(args))


def main(argv):
    if len(argv) < 3:
        sys.stderr.write(__doc__)
        return 2
    try:
        lines = query(load(argv[1]), argv[2:])
    except (ValueError, OSError, subprocess.CalledProcessError, json.JSONDecodeError, KeyError) as e:
        sys.stderr.write("registry.py: %s\n" % e)
        return 1
    for line in lines:
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
