#!/usr/bin/env python3
"""CLIPS programs written by others, measured in three engines (no program is copied here).

    python3 tests/bench/others.py OURS_BIN [PROGRAM ...] [--list FILE] [--no-c64]
                                  [--min-run N] [--keep DIR]

A PROGRAM is a batch file (`.clp` or `.bat`, or such a file gzipped) run as `clips -f2
PROGRAM`, the way tests/clips/NOTES.md's rounds of "CLIPS programs by others" ran them:
  stdin   PROGRAM with its extension replaced by `.in` when that file exists, else /dev/null
  files   the contents of the directory PROGRAM-without-extension + `.aux`, when it exists,
          are copied next to it (files the program opens)
A line of a list file (`#` starts a comment) is a PROGRAM followed by options, shell-quoted:
  in=FILE          stdin
  copy=PATH        a file (`.gz` unpacked) or a directory's contents copied next to it; repeatable
  drive=COMMANDS   PROGRAM holds constructs only: the batch run is
                   `(load "PROGRAM")` COMMANDS `(exit)` (e.g. drive="(reset) (run)")
  in=-             the answers the program reads are in the batch file (CLIPS's `read`
                   takes the batch's next lines), stdin is /dev/null
  name=NAME        the row's name (default: the last two parts of PROGRAM's path)
--examples adds CLIPS's example programs from Debian's clips-common, driven by
tests/clips/examples/ (COOL ones left out, `heavy` ones only with --heavy).
`(exit)` is appended when the batch does not end with it.

Each program runs in a scratch directory, twice per engine under callgrind: the batch as
it is (whole process) and the batch without its top-level `(run ...)` commands; run phase
= the difference, as tests/bench/shapes.py measures. Engines:
  CLIPS 6.30   `clips -f2 BATCH`
  CLIPS 6.4.2  clipspy's library driven by tests/bench/c64run.c with CLIPS 6.4's own main
               (`c64run -f2 BATCH`: RerouteStdin, CommandLoop)
  ours         `OURS_BIN clips -f2 BATCH`
A program whose run phase in CLIPS 6.30 is below --min-run instructions (default 1 M) is
listed as noise and not measured further. The printed text (stdout and stderr, our
`--> FILE:L:C` pointer lines dropped) of ours must equal CLIPS 6.30's. Ratio = the better
CLIPS / ours (above 1: we use fewer instructions); CLIPS 6.4.2 counts when it printed
CLIPS 6.30's text but for what 6.4 changed by design (no `initial-fact`, `load`'s
messages: `as_in_64`), else the ratio is against 6.30
alone and the one counting 6.4.2 anyway follows in parentheses (the output column says
which).
"""

import argparse
import concurrent.futures
import gzip
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from shapes import build_c64, callgrind  # noqa: E402

TIMEOUT = 3600
PLAIN_TIMEOUT = 120
EXAMPLES = "/usr/share/doc/clips-common/examples"


class Program:
    def __init__(self, path, stdin=None, copies=None, drive=None, name=None):
        self.path = os.path.abspath(path)
        stem = re.sub(r"\.(clp|bat)(\.gz)?$", "", self.path)
        if stdin is None and os.path.exists(stem + ".in"):
            stdin = stem + ".in"
        if copies is None:
            copies = [stem + ".aux"] if os.path.isdir(stem + ".aux") else []
        self.stdin = os.path.abspath(stdin) if stdin and stdin != "-" else stdin
        self.copies = [os.path.abspath(c) for c in copies]
        self.drive = drive
        parts = [p for p in self.path.split(os.sep) if p != "progs"]
        self.name = name or "/".join(parts[-2:])


def read_list(path):
    progs = []
    base = os.path.dirname(os.path.abspath(path))
    with open(path) as f:
        for line in f:
            words = shlex.split(line, comments=True)
            if not words:
                continue
            opts = {"copy": []}
            for w in words[1:]:
                key, _, val = w.partition("=")
                if key == "copy":
                    opts["copy"].append(os.path.join(base, val))
                elif key in ("in", "drive", "name"):
                    opts[key] = os.path.join(base, val) if key == "in" and val != "-" else val
                else:
                    raise SystemExit("%s: unknown option %r" % (path, w))
            progs.append(Program(os.path.join(base, words[0]), opts.get("in"),
                                 opts["copy"] or None, opts.get("drive"), opts.get("name")))
    return progs


def read_text(path):
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rb") as f:
        return f.read()


def copy_into(src, dst_dir):
    """A file (`.gz` unpacked) into dst_dir, or a directory's tree (its subdirectories kept)."""
    if os.path.isdir(src):
        for entry in os.listdir(src):
            sub = os.path.join(src, entry)
            if os.path.isdir(sub):
                os.makedirs(os.path.join(dst_dir, entry), exist_ok=True)
                copy_into(sub, os.path.join(dst_dir, entry))
            else:
                copy_into(sub, dst_dir)
        return
    name = os.path.basename(src)
    if name.endswith(".gz"):
        with open(os.path.join(dst_dir, name[:-3]), "wb") as f:
            f.write(read_text(src))
    else:
        shutil.copy(src, dst_dir)


def examples(heavy):
    """CLIPS's example programs as tests/clips/examples/MANIFEST drives them (no COOL)."""
    drivers = os.path.join(HERE, "..", "clips", "examples")
    progs = []
    with open(os.path.join(drivers, "MANIFEST")) as f:
        for line in f:
            words = line.split("#")[0].split()
            if len(words) < 4 or words[3] == "objects" or ("heavy" in words[4:] and not heavy):
                continue
            progs.append(Program(os.path.join(drivers, words[0] + ".bat"), os.devnull,
                                 [os.path.join(EXAMPLES, words[1])], None,
                                 "examples/" + words[0]))
    return progs


def top_forms(text):
    """(start, end) of each top-level parenthesised form; strings and `;` comments skipped."""
    forms, depth, start, i, n = [], 0, 0, 0, len(text)
    while i < n:
        c = text[i]
        if c == 59:  # ;
            while i < n and text[i] != 10:
                i += 1
            continue
        if c == 34:  # "
            i += 1
            while i < n and text[i] != 34:
                i += 2 if text[i] == 92 else 1
        elif c == 40:  # (
            if depth == 0:
                start = i
            depth += 1
        elif c == 41 and depth > 0:  # )
            depth -= 1
            if depth == 0:
                forms.append((start, i + 1))
        i += 1
    return forms


RUN = re.compile(rb"^\(\s*run(\s+[^()\s]+)?\s*\)$")
EXIT = re.compile(rb"^\(\s*exit(\s+[^()\s]+)?\s*\)$")


def batches(prog):
    """The batch file's bytes as run (full) and without its top-level `(run ...)`."""
    if prog.drive:
        load = os.path.basename(prog.path)
        if load.endswith(".gz"):
            load = load[:-3]
        text = ('(load "%s")\n%s\n' % (load, prog.drive)).encode()
    else:
        text = read_text(prog.path)
    forms = top_forms(text)
    if not forms or not EXIT.match(text[forms[-1][0]:forms[-1][1]]):
        text += b"\n(exit)\n"
        forms = top_forms(text)
    norun, last = [], 0
    for s, e in forms:
        if RUN.match(text[s:e]):
            norun.append(text[last:s])
            last = e
    norun.append(text[last:])
    return text, b"".join(norun), len(forms) - len(top_forms(b"".join(norun)))


def scratch(prog, batch, root, tag):
    d = os.path.join(root, tag)
    os.makedirs(d)
    if prog.drive:
        copy_into(prog.path, d)
    for c in prog.copies:
        copy_into(c, d)
    with open(os.path.join(d, "run.bat"), "wb") as f:
        f.write(batch)
    return d


def run_in(cmd, d, stdin, valgrind):
    with open(stdin if stdin and stdin != "-" else os.devnull, "rb") as inp:
        if valgrind:
            res = subprocess.run(
                ["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null"] + cmd,
                cwd=d, stdin=inp, capture_output=True, timeout=TIMEOUT)
            found = re.search(rb"Collected : (\d+)", res.stderr)
            if not found:
                raise RuntimeError("no callgrind count for %s" % cmd)
            return int(found.group(1))
        res = subprocess.run(cmd, cwd=d, stdin=inp, stdout=subprocess.PIPE,
                             stderr=subprocess.STDOUT, timeout=PLAIN_TIMEOUT)
        return res.stdout


READS_STDIN = re.compile(rb"\((read|readline)(\s+t)?\s*\)|\((read-number|get-char)[\s)]")


def ours_text(out):
    return b"".join(l for l in out.splitlines(True) if not re.match(rb"^--> \S+:\d+:\d+: ", l))


def measure(prog, engines, min_run, keep, startup):
    full, norun, removed = batches(prog)
    if removed == 0:
        return ("skip", "no top-level (run)")
    if prog.stdin is None and READS_STDIN.search(full if not prog.drive else read_text(prog.path)):
        return ("skip", "reads stdin and no input is given")
    root = tempfile.mkdtemp(prefix="others-", dir=keep)
    try:
        counts, texts = {}, {}
        for label, cmd in engines:
            out = run_in(cmd, scratch(prog, full, root, label + "-t"), prog.stdin, False)
            texts[label] = ours_text(out) if label == "ours" else out
            f = run_in(cmd, scratch(prog, full, root, label + "-f"), prog.stdin, True)
            if label == "6.30" and f - startup < min_run:
                return ("skip", "whole %.2f M in CLIPS 6.30, %.2f M of it start-up"
                        % (f / 1e6, startup / 1e6))
            n = run_in(cmd, scratch(prog, norun, root, label + "-n"), prog.stdin, True)
            counts[label] = (f - n, f)
            if label == "6.30" and f - n < min_run:
                return ("skip", "run %.2f M in CLIPS 6.30" % ((f - n) / 1e6))
        return ("row", counts, texts)
    finally:
        if not keep:
            shutil.rmtree(root, ignore_errors=True)


def as_in_64(text):
    """A transcript blurred where CLIPS 6.4 differs from 6.30 by design: no
    `initial-fact` (its lines dropped, its `f-0` in activations is 6.4's `*`), fact
    numbers (6.4's `modify` keeps the fact's) and totals, `load`'s messages (6.30's
    `Defining ...` lines, 6.4's character per construct) and 6.30's warning on
    `(defmodule MAIN)`."""
    text = re.sub(rb"(?m)^.*\(initial-fact\).*\n?", b"", text)
    text = re.sub(rb"(?m)^(Re)?[Dd]efining .*\n?", b"", text)
    text = re.sub(rb"(?m)^[%$*!#:&^~+]+\n?", b"", text)
    text = re.sub(rb"(?m)^\n?\[CSTRCPSR1\] WARNING: Redefining defmodule: MAIN\n?", b"", text)
    text = re.sub(rb"For a total of \d+ facts?\.", b"For a total of N facts.", text)
    text = re.sub(rb"(?<=[:,] )f-0\b|(?<=,)f-0\b|\bf-0(?=,)", b"*", text)
    return re.sub(rb"(?<=f-)\d+|(?<=<Fact-)\d+", b"N", text)


def row(name, counts, texts):
    """A markdown table row: instructions per engine and ratio, run phase then whole.
    CLIPS 6.4.2 counts in the ratio when its text is CLIPS 6.30's but for `as_in_64`;
    otherwise it ran another program (a function 6.4 dropped, another message) and the
    ratio is against 6.30 alone, the strict one after it in parentheses."""
    fmt = lambda v: "%.2f M" % (v / 1e6)
    get = lambda k, i: counts[k][i] if k in counts else 0
    has64 = "6.4.2" in texts
    like64 = has64 and as_in_64(texts["6.4.2"]) == as_in_64(texts["6.30"])
    cells = []
    for i in (0, 1):
        fair = min(v[i] for k, v in counts.items() if k == "6.30" or (k == "6.4.2" and like64))
        strict = min(v[i] for k, v in counts.items() if k != "ours")
        ratio = "%.2f" % (fair / max(counts["ours"][i], 1))
        if strict != fair:
            ratio += " (%.2f)" % (strict / max(counts["ours"][i], 1))
        cells.append((fmt(get("6.30", i)), fmt(get("6.4.2", i)), fmt(get("ours", i)), ratio))
    out = "same" if texts["ours"] == texts["6.30"] else "DIFFERS from 6.30"
    if has64 and texts["6.4.2"] != texts["6.30"]:
        out += "; 6.4.2: " + ("same but by design" if like64 else "other text, not counted")
    return "| %s | %s | %s | %s |" % (name, " | ".join(cells[0]), " | ".join(cells[1]), out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("ours")
    parser.add_argument("programs", nargs="*")
    parser.add_argument("--list", action="append", default=[])
    parser.add_argument("--examples", action="store_true",
                        help="also CLIPS's example programs (tests/clips/examples/MANIFEST)")
    parser.add_argument("--heavy", action="store_true", help="with --examples: the heavy ones too")
    parser.add_argument("--no-c64", action="store_true")
    parser.add_argument("--min-run", type=float, default=1e6)
    parser.add_argument("--jobs", type=int, default=1, help="programs measured at once")
    parser.add_argument("--keep", help="keep the scratch directories under this directory")
    args = parser.parse_args()
    progs = [Program(p) for p in args.programs]
    for lst in args.list:
        progs += read_list(lst)
    if args.examples:
        progs += examples(args.heavy)
    ours = os.path.abspath(args.ours)
    with tempfile.TemporaryDirectory() as tmp:
        c64 = None if args.no_c64 else build_c64(tmp)
        engines = [("6.30", ["clips", "-f2", "run.bat"])]
        if c64:
            engines.append(("6.4.2", [c64, "-f2", "run.bat"]))
        engines.append(("ours", [ours, "clips", "-f2", "run.bat"]))
        print("| program | 6.30 run | 6.4.2 run | ours run | run ratio | 6.30 whole "
              "| 6.4.2 whole | ours whole | whole ratio | output |")
        print("|---|---|---|---|---|---|---|---|---|---|")
        skipped = []
        with open(os.path.join(tmp, "run.bat"), "w") as f:
            f.write("(exit)\n")
        startup = run_in(engines[0][1], tmp, None, True)

        def one(prog):
            try:
                return measure(prog, engines, args.min_run, args.keep, startup)
            except (RuntimeError, subprocess.TimeoutExpired, OSError) as err:
                return ("skip", "failed: %s" % err)

        with concurrent.futures.ThreadPoolExecutor(max_workers=max(args.jobs, 1)) as pool:
            for prog, res in zip(progs, pool.map(one, progs)):
                if res[0] == "skip":
                    skipped.append((prog.name, res[1]))
                else:
                    print(row(prog.name, res[1], res[2]), flush=True)
        if skipped:
            print("\nNot measured:\n")
            for name, why in skipped:
                print("- %s: %s" % (name, why))


if __name__ == "__main__":
    main()
