#!/usr/bin/env python3
"""check_lists.py ROOT BIN | --self-test ROOT BIN: checks every list that people keep by hand against what the
restir command BIN says of itself (`BIN list --json`, `BIN render --help`), and exits 1 on any finding,
naming each one:

- README.md's method tables ("What is implemented today": every table whose first column is "method")
  name every registered method, and only those;
- docs/FUZZING.md's list of the methods scripts/tsan.sh renders is the registry's;
- fuzz/dict/params.dict holds every setting key of `restir render --help` and nothing that is neither a key,
  a registered method nor a JSON or value token;
- the registry itself: each method's settings (and the common ones) name keys that exist, every key is
  read by some method, each variant sets keys its method reads, each role is held by exactly one method
  (and demo.sh's "direct-lighting reference" needs a direct-only demo method);
- no script in scripts/ names a method (they read the registry through scripts/registry.py).

--self-test plants one problem of each kind in a copy of those files and fails unless every one is found
and the unchanged copy passes.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import registry  # noqa: E402  (scripts/registry.py: the one reader of `restir list --json`)

ROLES = ("reference", "demo")
# Tokens of a dictionary that are JSON syntax or values rather than names.
DICT_VALUE_TOKENS = {"{", "}", "[", "]", ":", ",", r'\\"', "true", "false", "null", "on", "off", "1e309", "-0", "NaN"}
COPIED = ["README.md", "docs/FUZZING.md", "fuzz/dict/params.dict"]


def render_keys(bin_path):
    """The setting keys `restir render --help` lists under "Parameters", in its order."""
    text = subprocess.run([bin_path, "render", "--help"], check=True, stdout=subprocess.PIPE, text=True).stdout
    keys, inside = [], False
    for line in text.splitlines():
        if line.startswith("Parameters (--set"):
            inside = True
        elif inside and not line.strip():
            break
        elif inside and line.startswith("  [") and "] read by " in line:
            continue  # a block's heading: which methods read the keys below it
        elif inside and line.startswith("  "):
            keys.append(line.split()[0])
    if not keys:
        raise RuntimeError("restir render --help lists no settings under 'Parameters (--set'")
    return keys


def compare_names(where, listed, registered):
    """Findings for a hand list that misses or adds names."""
    out = ["%s: method %s is registered but not listed" % (where, m) for m in registered if m not in listed]
    out += ["%s: lists %s, which is not a registered method" % (where, m) for m in listed if m not in registered]
    return out


def readme_methods(root):
    """The first-column names of README.md's method tables in "What is implemented today"."""
    text = open(os.path.join(root, "README.md"), encoding="utf-8").read()
    start = text.find("\n## What is implemented today")
    if start < 0:
        return None
    end = text.find("\n## ", start + 1)
    names, in_table = [], False
    for line in text[start:end if end > 0 else len(text)].splitlines():
        if re.match(r"^\|\s*method\s*\|", line):
            in_table = True
        elif in_table and line.startswith("|"):
            m = re.match(r"^\|\s*`([^`]+)`\s*\|", line)
            if m:
                names.append(m.group(1))
        else:
            in_table = False
    return names


def fuzzing_methods(root):
    """The methods docs/FUZZING.md says scripts/tsan.sh renders."""
    text = open(os.path.join(root, "docs/FUZZING.md"), encoding="utf-8").read()
    m = re.search(r"runs `scripts/tsan.sh`: every method of `restir render`[^(]*\(([^)]*)\)", text)
    return [n.strip() for n in m.group(1).split(",")] if m else None


def check_docs(root, names):
    out = []
    listed = readme_methods(root)
    if not listed:
        out.append("README.md: no method table under '## What is implemented today'")
    else:
        out += compare_names("README.md's method tables", listed, names)
    listed = fuzzing_methods(root)
    if listed is None:
        out.append("docs/FUZZING.md: the list of methods scripts/tsan.sh renders is not found (\"runs "
                   "`scripts/tsan.sh`: every method of `restir render` ... (NAME, ...)\")")
    else:
        out += compare_names("docs/FUZZING.md's scripts/tsan.sh methods", listed, names)
    return out


def check_dict(root, names, keys):
    path = "fuzz/dict/params.dict"
    tokens = []
    for line in open(os.path.join(root, path), encoding="utf-8"):
        line = line.strip()
        if line and not line.startswith("#"):
            tokens.append(line[1:-1] if len(line) >= 2 and line[0] == line[-1] == '"' else line)
    out = ["%s: setting %s (restir render --help) is missing" % (path, k) for k in keys if k not in tokens]
    out += ["%s: %s is neither a setting key of restir render --help, a registered method nor a JSON or value "
            "token" % (path, t) for t in tokens if t not in keys and t not in names and t not in DICT_VALUE_TOKENS]
    return out


def matches(pattern, key):
    """As method.c's setting_in: a key, or a family ending in '.' that key lies in."""
    return key.startswith(pattern) if pattern.endswith(".") else key == pattern


def check_registry(doc, keys):
    out, common = [], doc["common_settings"]
    for owner, patterns in [("common settings", common)] + [(m["name"], m["settings"]) for m in doc["methods"]]:
        out += ["registry: %s reads %s, which names no setting of restir render --help" % (owner, p)
                for p in patterns if not any(matches(p, k) for k in keys)]
    for k in keys:
        if not any(matches(p, k) for p in common) and \
           not any(matches(p, k) for m in doc["methods"] for p in m["settings"]):
            out.append("registry: setting %s is read by no method (no row's settings, nor the common ones)" % k)
    for m in doc["methods"]:
        for v in m["variants"]:
            for a in v.split(":"):
                key = a.split("=", 1)[0]
                if "=" not in a or key not in keys:
                    out.append("registry: %s's variant %s: %s is not key=value with a key of restir render --help" %
                               (m["name"], v, a))
                elif not any(matches(p, key) for p in common + m["settings"]):
                    out.append("registry: %s's variant %s sets %s, which %s does not read" % (m["name"], v, key,
                                                                                              m["name"]))
        out += ["registry: %s has role %s, which no script knows (%s)" % (m["name"], r, ", ".join(ROLES))
                for r in m["roles"] if r not in ROLES]
    for role in ROLES:
        held = [m for m in doc["methods"] if role in m["roles"]]
        if len(held) != 1:
            out.append("registry: role %s is held by %d methods (%s), not 1" %
                       (role, len(held), ", ".join(m["name"] for m in held)))
        elif role == "demo" and "direct-only" not in held[0]["capabilities"]:
            out.append("registry: the demo method %s is not direct-only, but scripts/demo.sh shows it against a "
                       "direct-lighting reference" % held[0]["name"])
    return out


def check_scripts(root, names):
    out, folder = [], os.path.join(root, "scripts")
    for n in sorted(os.listdir(folder)):
        if not n.endswith((".sh", ".py")):
            continue
        for i, line in enumerate(open(os.path.join(folder, n), encoding="utf-8", errors="replace"), 1):
            for m in names:
                if re.search(r"(?<![\w./-])" + re.escape(m) + r"(?![\w-])", line):
                    out.append("scripts/%s:%d names method %s (read it from the registry: scripts/registry.py)" %
                               (n, i, m))
    return out


def check(root, doc, keys):
    names = [m["name"] for m in doc["methods"]]
    return check_docs(root, names) + check_dict(root, names, keys) + check_registry(doc, keys) + \
        check_scripts(root, names)


def edit(path, old, new):
    text = open(path, encoding="utf-8").read()
    if old not in text:
        raise RuntimeError("self-test: %s no longer holds %r to plant a problem with" % (path, old))
    open(path, "w", encoding="utf-8").write(text.replace(old, new, 1))


def self_test(root, doc, keys):
    """0 when every planted problem is found and the unchanged copy passes."""
    names = [m["name"] for m in doc["methods"]]
    last, key = names[-1], keys[-1]

    def drop_readme_row(t):
        text = open(os.path.join(t, "README.md"), encoding="utf-8").read()
        row = re.search(r"^\| `%s` \|.*\n" % re.escape(last), text, re.M)
        edit(os.path.join(t, "README.md"), row.group(0), "")

    def drop_fuzzing_name(t):
        listed = fuzzing_methods(t)
        edit(os.path.join(t, "docs/FUZZING.md"), "(" + ", ".join(listed) + ")",
             "(" + ", ".join(n for n in listed if n != last) + ")")

    def scripts_name_one(t):
        with open(os.path.join(t, "scripts", "planted.sh"), "w") as f:
            f.write("restir render --method %s\n" % last)

    def role_twice(t):
        doc["methods"][0]["roles"].append("demo")

    plants = [
        ("a method missing from README's tables", drop_readme_row, "README.md's method tables: method " + last),
        ("a method missing from FUZZING.md", drop_fuzzing_name, "docs/FUZZING.md's scripts/tsan.sh methods"),
        ("a key missing from the dictionary", lambda t: edit(os.path.join(t, "fuzz/dict/params.dict"),
                                                             '"%s"\n' % key, ""), "setting %s" % key),
        ("a stray dictionary token", lambda t: edit(os.path.join(t, "fuzz/dict/params.dict"), '"spp"\n',
                                                    '"spp"\n"no-such-method"\n'), "no-such-method"),
        ("a script naming a method", scripts_name_one, "planted.sh:1 names method " + last),
        ("a role held twice", role_twice, "role demo is held by 2"),
    ]
    failed = 0
    for label, plant, want in [("the unchanged copy", lambda t: None, None)] + plants:
        saved = [list(m["roles"]) for m in doc["methods"]]
        with tempfile.TemporaryDirectory() as t:
            for rel in COPIED:
                os.makedirs(os.path.dirname(os.path.join(t, rel)) or t, exist_ok=True)
                shutil.copy(os.path.join(root, rel), os.path.join(t, rel))
            shutil.copytree(os.path.join(root, "scripts"), os.path.join(t, "scripts"))
            plant(t)
            found = check(t, doc, keys)
        for m, roles in zip(doc["methods"], saved):
            m["roles"] = roles
        ok = not found if want is None else any(want in f for f in found)
        print("%s: %s%s" % (label, "ok" if ok else "FAILED", "" if ok else " (found: %s)" % (found or "nothing")))
        failed += not ok
    return 1 if failed else 0


def main(argv):
    test = len(argv) == 4 and argv[1] == "--self-test"
    if len(argv) != 3 and not test:
        sys.stderr.write(__doc__)
        return 2
    root, bin_path = argv[-2], argv[-1]
    doc, keys = registry.load(bin_path), render_keys(bin_path)
    if test:
        return self_test(root, doc, keys)
    found = check(root, doc, keys)
    for f in found:
        print(f)
    print("check_lists.py: %d methods, %d settings; %s" % (len(doc["methods"]), len(keys),
                                                           "%d findings" % len(found) if found else "all lists agree"))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
