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
        return name in ("stdout", "t")

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
    args = parser.parse_args()
    if args.reps < 1:
        parser.error("--reps must be at least 1")

    result = {"version": clips_version(), "fired": [], "run_ns": [], "whole_ns": []}
    for _ in range(args.reps):
        fired, run_ns, whole_ns, output, mem_used = one_repetition(args.program, args.phase)
        result["fired"].append(fired)
        result["run_ns"].append(run_ns)
        result["whole_ns"].append(whole_ns)
        result["output"] = output
        result["mem_used"] = mem_used
    sys.stdout.write(json.dumps(result) + "\n")


if __name__ == "__main__":
    main()
