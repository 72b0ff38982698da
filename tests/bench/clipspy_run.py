#!/usr/bin/env python3
"""Run one benchmark program in CLIPS 6.4 (PyPI `clipspy`) in-process.

Used by `robotino-agent bench`; also handy by hand:

    python3 tests/bench/clipspy_run.py PROGRAM.clp --reps 5
    python3 tests/bench/clipspy_run.py PROGRAM.clp --phase norun   # for callgrind

PROGRAM holds constructs only (deftemplates, defrules, deffacts): this driver
does the (load), (reset) and (run) itself so it can time run() alone.

Prints one JSON object on the last line of stdout:
  version     CLIPS version string found in the library, if any
  fired       rules fired per repetition (run() return value)
  run_ns      wall time of run() alone, per repetition
  whole_ns    wall time of load + reset + run, per repetition
  output      text the program printed to stdout in the last repetition
  mem_used    (mem-used) after the last run, in bytes
"""

import argparse
import json
import sys
import time

import clips


class CaptureRouter(clips.Router):
    """Collects what the program prints to stdout (`printout t`)."""

    def __init__(self):
        super().__init__("bench-capture", 30)
        self.text = []

    def query(self, name):
        # 6.4 sends `(watch statistics)` to stdout; older names kept for safety.
        return name in ("stdout", "t", "wdisplay")

    def write(self, _name, message):
        self.text.append(message)


def clips_version():
    """CLIPS and clipspy versions, read from the installed package."""
    import importlib.metadata
    import re

    clipspy = importlib.metadata.version("clipspy")
    # The library embeds its banner, e.g. "CLIPS (6.4.2 1/14/25)".
    library = "6.4"
    try:
        with open(clips._clips.__file__, "rb") as shared_object:
            found = re.search(rb"CLIPS \((6\.[0-9.]+)", shared_object.read())
        if found:
            library = found.group(1).decode()
    except OSError:
        pass
    return "CLIPS %s (clipspy %s)" % (library, clipspy)


def one_repetition(program, phase):
    env = clips.Environment()
    capture = CaptureRouter()
    env.add_router(capture)
    start = time.perf_counter_ns()
    env.load(program)
    env.reset()
    fired = 0
    run_ns = 0
    if phase == "full":
        run_start = time.perf_counter_ns()
        fired = env.run()
        run_ns = time.perf_counter_ns() - run_start
    whole_ns = time.perf_counter_ns() - start
    mem_used = int(env.eval("(mem-used)"))
    return fired, run_ns, whole_ns, "".join(capture.text), mem_used


def time_batch(path):
    """Runs a CLIPS batch file (without its `(exit)`, which would end Python) in a
    fresh environment; returns (wall ns, printed text, environment)."""
    import os
    import tempfile

    with open(path) as source:
        lines = [line for line in source if line.strip() != "(exit)"]
    handle, stripped = tempfile.mkstemp(suffix=".clp")
    with os.fdopen(handle, "w") as target:
        target.writelines(lines)
    env = clips.Environment()
    capture = CaptureRouter()
    env.add_router(capture)
    try:
        start = time.perf_counter_ns()
        env.batch_star(stripped)
        elapsed = time.perf_counter_ns() - start
    finally:
        os.unlink(stripped)
    return elapsed, "".join(capture.text), env


def batch_repetition(path, baseline):
    """Batch mode (LLSF games: many (reset)/(run) in one file): run = the batch minus
    the same batch without its (run) commands, both timed in-process."""
    import re

    whole_ns, output, env = time_batch(path)
    mem_used = int(env.eval("(mem-used)"))
    base_ns = time_batch(baseline)[0] if baseline else 0
    fired = sum(int(n) for n in re.findall(r"^(\d+) rules fired", output, re.M))
    return fired, max(whole_ns - base_ns, 0), whole_ns, output, mem_used


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("program", help="file with constructs only")
    parser.add_argument("--reps", type=int, default=1)
    parser.add_argument(
        "--phase",
        choices=("full", "norun"),
        default="full",
        help="norun stops after (reset): the baseline subtracted under callgrind",
    )
    parser.add_argument(
        "--batch",
        action="store_true",
        help="PROGRAM is a batch file (its (exit) is dropped) instead of constructs",
    )
    parser.add_argument(
        "--baseline",
        help="with --batch: the same batch without (run), timed and subtracted",
    )
    args = parser.parse_args()
    if args.reps < 1:
        parser.error("--reps must be at least 1")

    result = {"version": clips_version(), "fired": [], "run_ns": [], "whole_ns": []}
    for _ in range(args.reps):
        if args.batch:
            fired, run_ns, whole_ns, output, mem_used = batch_repetition(
                args.program, args.baseline
            )
        else:
            fired, run_ns, whole_ns, output, mem_used = one_repetition(
                args.program, args.phase
            )
        result["fired"].append(fired)
        result["run_ns"].append(run_ns)
        result["whole_ns"].append(whole_ns)
        result["output"] = output
        result["mem_used"] = mem_used
    sys.stdout.write(json.dumps(result) + "\n")


if __name__ == "__main__":
    main()
