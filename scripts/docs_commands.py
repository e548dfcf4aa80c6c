#!/usr/bin/env python3
"""docs_commands.py SRC BIN [--only FILE[:LINE]] [--list] [--keep]: the commands the documentation shows, run.

ctest docs.commands. Every ```sh, ```bash, ```shell and ```console block of SRC/README.md and SRC/docs/*.md
runs in a scratch folder with BIN's restir and restir_bench first on the PATH (also as build/restir and
build/restir_bench there): as written, or as the annotations right above the block rewrite it. The test
fails when a block fails (naming its file and line, showing it as run and its output) and when an annotation
is malformed: a block with no annotation runs as written, so one that cannot must say why with skip or drop.

Annotations are HTML comments (invisible on the rendered page), one per line, directly above the fence:

  <!-- test: skip REASON -->        the block is not run; REASON (required) says why (hours of jobs, Slurm, a
                                    window, root). Listed with its reason in the test's output.
  <!-- test: sed s/RE/TEXT/[g] -->  rewrites each line before it runs: RE is a Python regular expression, TEXT
                                    a re.sub replacement (\\1), any delimiter after the s; g: every match, else
                                    the first. Shrinks a command for the test: --res 1920x1080 to --res 32x18.
  <!-- test: drop RE REASON -->     leaves out the lines RE matches (with their \\ continuation lines);
                                    REASON (required) says why those lines do not run.
  <!-- test: env NAME=VALUE... -->  environment of the block (shell words).
  <!-- test: setup COMMAND -->      runs before the block, in the same shell (input files, cd).
  <!-- test: check COMMAND -->      runs after the block, in the same shell; the block fails if it fails (run
                                    the program a documented compile line built).
  <!-- test: expect TEXT -->        the block's output must contain TEXT (a count the page states).
  <!-- test: file PATH -->          the block (of any language: cmake, c, json) is not run but written to PATH,
                                    for the blocks after it; PATH is relative to the block's folder.
  <!-- test: cwd copy -->           runs in a copy of SRC's files (one copy for all pages), for commands that
                                    build the project itself (cmake -S . -B build); the default folder is one
                                    scratch folder per page, shared by its blocks in order.
  <!-- test: timeout SECONDS -->    the block's time limit instead of 120 s.
  <!-- test: synopsis -->           the block is a usage synopsis, not run: every --option it shows after
                                    `restir CMD` (or CMD1|CMD2) must appear in `restir CMD --help`.

Blocks run with `bash -e -o pipefail`; in ```console blocks only the `$ ` lines run. $DOCS_SRC is SRC and
$DOCS_TMP the page's scratch folder (rewrite an absolute path such as /opt/restir to $DOCS_TMP/opt/restir).
An unlabelled block (```) whose lines look like restir commands fails the test: label it sh or text.
--only README.md:338 runs that block (or a page's blocks); --list prints the blocks and their annotations;
--keep leaves the scratch folders and names them."""
import os
import pathlib
import re
import resource
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

SHELL_LANGS = {"sh", "bash", "shell", "console"}
FENCE = re.compile(r"^(\s*)(`{3,}|~{3,})\s*([\w+-]*)\s*$")
ANNOTATION = re.compile(r"^\s*<!--\s*test:\s*(\w[\w-]*)\s*(.*?)\s*-->\s*$")
KEYWORDS = {"skip", "sed", "drop", "env", "setup", "check", "expect", "file", "cwd", "timeout", "synopsis"}
LOOKS_LIKE_COMMAND = re.compile(r"^\s*(\$ )?(build/)?(restir|restir_bench|cmake|make|scripts/\S+)( |$)")


class DocError(Exception):
    pass


class Block:
    def __init__(self, page, line, lang, text, notes):
        self.page, self.line, self.lang, self.text, self.notes = page, line, lang, text, notes

    @property
    def where(self):
        return f"{self.page}:{self.line}"

    def notes_of(self, key):
        return [value for k, value in self.notes if k == key]


def parse_sed(expr, where):
    if len(expr) < 4 or expr[0] != "s":
        raise DocError(f"{where}: sed wants s/RE/TEXT/[g], not {expr!r}")
    delim, parts, cur, i = expr[1], [], "", 2
    while i < len(expr):
        c = expr[i]
        if c == "\\" and i + 1 < len(expr) and expr[i + 1] == delim:
            cur += delim
            i += 2
            continue
        if c == delim:
            parts.append(cur)
            cur = ""
        else:
            cur += c
        i += 1
    parts.append(cur)
    if len(parts) != 3 or parts[2] not in ("", "g"):
        raise DocError(f"{where}: sed wants s/RE/TEXT/[g], not {expr!r}")
    try:
        return re.compile(parts[0]), parts[1], 0 if parts[2] == "g" else 1
    except re.error as e:
        raise DocError(f"{where}: sed {expr!r}: {e}") from e


def split_reason(value, key, where):
    words = value.split(None, 1)
    if len(words) < 2:
        raise DocError(f"{where}: `{key} RE REASON` needs a reason")
    return words[0], words[1]


def read_blocks(src, page):
    lines = (src / page).read_text().split("\n")
    blocks, problems, i = [], [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, fence, lang = m.groups()
        start, j = i, i + 1
        while j < len(lines):
            close = re.match(r"^\s*(`{3,}|~{3,})\s*$", lines[j])
            if close and close.group(1)[0] == fence[0] and len(close.group(1)) >= len(fence):
                break
            j += 1
        body = [line[len(indent):] if line.startswith(indent) else line.lstrip() for line in lines[start + 1:j]]
        notes, k = [], start - 1
        while k >= 0 and ANNOTATION.match(lines[k]):
            a = ANNOTATION.match(lines[k])
            notes.insert(0, (a.group(1), a.group(2)))
            k -= 1
        where = f"{page}:{start + 1}"
        for key, value in notes:
            if key not in KEYWORDS:
                problems.append(f"{where}: unknown annotation `test: {key}` (known: {', '.join(sorted(KEYWORDS))})")
            elif key == "skip" and not value:
                problems.append(f"{where}: `test: skip` needs a reason")
        if not lang and not notes and any(LOOKS_LIKE_COMMAND.match(line) for line in body):
            problems.append(f"{where}: an unlabelled block of commands: label it ```sh (then it runs here) or "
                            "```text")
        blocks.append(Block(page, start + 1, lang, "\n".join(body), notes))
        i = j + 1
    return blocks, problems


def script_of(block):
    """The block's text after its sed and drop annotations, as the shell runs it."""
    lines = block.text.split("\n")
    if block.lang == "console":
        lines = [line[2:] for line in lines if line.startswith("$ ")]
    for expr in block.notes_of("sed"):
        pattern, repl, count = parse_sed(expr, block.where)
        lines = [pattern.sub(repl, line, count=count) for line in lines]
    for value in block.notes_of("drop"):
        pattern = re.compile(split_reason(value, "drop", block.where)[0])
        kept, dropping = [], False
        for line in lines:
            if dropping or pattern.search(line):
                dropping = line.rstrip().endswith("\\")
                continue
            kept.append(line)
        lines = kept
    return "\n".join(lines)


def copy_source(src, dest):
    """SRC's files as git sees them (tracked and untracked, not ignored), else all but build folders."""
    try:
        names = subprocess.run(["git", "-C", str(src), "ls-files", "-co", "--exclude-standard", "-z"],
                               check=True, capture_output=True).stdout.decode().split("\0")
    except (OSError, subprocess.CalledProcessError):
        shutil.copytree(src, dest, symlinks=True, ignore=shutil.ignore_patterns(".git", "build*"))
        return
    for name in filter(None, names):
        path = src / name
        if path.is_file() or path.is_symlink():
            (dest / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(path, dest / name, follow_symlinks=False)


class Runner:
    def __init__(self, src, bindir, root):
        self.src, self.root = src, root
        self.links = root / "bin"
        self.links.mkdir()
        for name in ("restir", "restir_bench"):
            if (bindir / name).exists():
                (self.links / name).symlink_to(bindir / name)
        self.copy = None
        self.pages = {}

    def page_dir(self, page):
        if page not in self.pages:
            d = self.root / re.sub(r"[^A-Za-z0-9_.-]", "_", page)
            d.mkdir()
            (d / "build").symlink_to(self.links)
            self.pages[page] = d
        return self.pages[page]

    def cwd_of(self, block):
        where = self.page_dir(block.page)
        for value in block.notes_of("cwd"):
            if value != "copy":
                raise DocError(f"{block.where}: `cwd` knows only `copy`, not {value!r}")
            if self.copy is None:
                self.copy = self.root / "source"
                self.copy.mkdir()
                copy_source(self.src, self.copy)
            where = self.copy
        return where

    def synopsis(self, block):
        """Every --option of each `restir CMD ...` entry of the block, against `restir CMD --help`."""
        entries, last = [], []  # [column, text]; last: the entries of the latest line that had one
        for line in block.text.split("\n"):
            starts = [m.start() for m in re.finditer(r"(?<![\w/-])restir\s+\S", line)]
            if starts:
                last = [[a, line[a:b]] for a, b in zip(starts, starts[1:] + [len(line)])]
                entries += last
                continue
            indent = len(line) - len(line.lstrip())
            owner = [e for e in last if e[0] <= indent]
            if owner:  # a continuation line: the entry it stands under
                owner[-1][1] += " " + line.strip()
        helps, missing = {}, []
        for _, text in entries:
            words = text.split()
            if len(words) < 2 or words[1].startswith("-"):
                continue
            for cmd in words[1].split("|"):
                if cmd not in helps:
                    p = subprocess.run([str(self.links / "restir"), cmd, "--help"], capture_output=True)
                    helps[cmd] = set(re.findall(r"--[a-z][a-z-]*", (p.stdout + p.stderr).decode(errors="replace")))
                for opt in sorted(set(re.findall(r"(?<![\w-])--[a-z][a-z-]*", text)) - helps[cmd]):
                    missing.append(f"restir {cmd} {opt}: `restir {cmd} --help` does not show it")
        return not missing, (0.0, 0.0), "\n".join(missing)

    def run(self, block):
        """(passed, seconds, output) of one block."""
        if block.notes_of("synopsis"):
            return self.synopsis(block)
        cwd = self.cwd_of(block)
        text = script_of(block)
        for path in block.notes_of("file"):
            target = cwd / path
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(text + "\n")
            return True, (0.0, 0.0), f"wrote {target}"
        env = dict(os.environ)
        env["PATH"] = f"{self.links}:{env.get('PATH', '/usr/bin:/bin')}"
        env["DOCS_SRC"] = str(self.src)
        env["DOCS_TMP"] = str(self.page_dir(block.page))
        for value in block.notes_of("env"):
            for word in shlex.split(value):
                name, eq, v = word.partition("=")
                if not eq:
                    raise DocError(f"{block.where}: env wants NAME=VALUE, not {word!r}")
                env[name] = v
        script = "\n".join(block.notes_of("setup") + [text] + block.notes_of("check")) + "\n"
        timeout = float((block.notes_of("timeout") or ["120"])[-1])
        t0, c0 = time.monotonic(), cpu_seconds()
        try:
            p = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", script], cwd=cwd, env=env,
                               stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                               timeout=timeout, start_new_session=True)
            out, rc = p.stdout.decode(errors="replace"), p.returncode
        except subprocess.TimeoutExpired as e:
            out, rc = (e.stdout or b"").decode(errors="replace") + f"\n[timed out after {timeout:g} s]", -1
        seconds = (time.monotonic() - t0, cpu_seconds() - c0)
        passed = rc == 0
        if passed:
            missing = [t for t in block.notes_of("expect") if t not in out]
            if missing:
                passed = False
                out += "\n[the output does not contain " + ", ".join(repr(t) for t in missing) + "]"
        else:
            out += f"\n[exit status {rc}]"
        return passed, seconds, f"$ cd {cwd}\n{script}---\n{out}"


def cpu_seconds():
    """User and system time of the finished children: the blocks' processes and theirs."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def pages_of(src):
    return ["README.md"] + sorted(f"docs/{p.name}" for p in (src / "docs").glob("*.md"))


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    flags = [a for a in argv if a.startswith("--")]
    only = None
    if "--only" in argv:
        only = argv[argv.index("--only") + 1]
        args.remove(only)
    if len(args) != 2:
        print(__doc__)
        return 2
    src, bindir = pathlib.Path(args[0]).resolve(), pathlib.Path(args[1]).resolve()
    if not (bindir / "restir").exists():
        print(f"docs_commands: no restir in {bindir}")
        return 2
    blocks, problems = [], []
    for page in pages_of(src):
        b, p = read_blocks(src, page)
        blocks += b
        problems += p
    if only:
        page, _, line = only.partition(":")
        blocks = [b for b in blocks if b.page == page and (not line or b.line == int(line))]
        problems = [p for p in problems if p.startswith(f"{page}:")]
        if not blocks:
            print(f"docs_commands: no block {only}")
            return 2
    if "--list" in flags:
        for b in blocks:
            print(f"{b.where} [{b.lang or '-'}] " + "; ".join(f"{k} {v}" for k, v in b.notes))
        return 0
    root = pathlib.Path(tempfile.mkdtemp(prefix="docs_commands."))
    runner = Runner(src, bindir, root)
    failed, ran, skipped, t0, c0 = [], 0, [], time.monotonic(), cpu_seconds()
    try:
        for b in blocks:
            if b.lang not in SHELL_LANGS and not b.notes_of("file"):
                continue
            if b.notes_of("skip"):
                skipped.append(f"{b.where}: skipped: {b.notes_of('skip')[0]}")
                continue
            try:
                for value in b.notes_of("drop"):
                    skipped.append(f"{b.where}: left out `{split_reason(value, 'drop', b.where)[0]}`: "
                                   f"{split_reason(value, 'drop', b.where)[1]}")
                passed, seconds, out = runner.run(b)
            except DocError as e:
                problems.append(str(e))
                continue
            ran += 1
            print(f"docs_commands: {b.where}: {'ok' if passed else 'FAILED'} ({seconds[0]:.1f} s, "
                  f"{seconds[1]:.1f} CPU-s)", flush=True)
            if not passed:
                failed.append(b.where)
                print(f"---- {b.where}: the block, as run, and its output:\n{out}\n----", flush=True)
    finally:
        if "--keep" in flags:
            print(f"docs_commands: scratch folders kept in {root}")
        else:
            shutil.rmtree(root, ignore_errors=True)
    for line in skipped:
        print("docs_commands:", line)
    for p in problems:
        print("docs_commands: PROBLEM:", p)
    print(f"docs_commands: {ran} blocks run in {time.monotonic() - t0:.0f} s ({cpu_seconds() - c0:.0f} CPU-s), "
          f"{len(failed)} failed"
          f"{' (' + ', '.join(failed) + ')' if failed else ''}, {len(problems)} problem(s) with the annotations")
    return 1 if failed or problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
