#!/usr/bin/env python3
"""Small generated programs of shapes the main bench lacks, measured in three engines.

    python3 tests/bench/shapes.py emit DIR [--only SHAPE ...] [--sizes N ...]
    python3 tests/bench/shapes.py measure DIR OURS_BIN [--only SHAPE ...] [--no-c64] [--sizes N ...]
        [--cache CACHE_DIR] [--jobs N] [--ends-first] [--rows FILE]
    python3 tests/bench/shapes.py measure-dirs DIR ... OURS_BIN [--no-c64] [--cache CACHE_DIR]
        [--jobs N] [--ends-first] [--rows FILE]
    python3 tests/bench/shapes.py table FILE ...

`emit` writes DIR/<shape>-<size>/ with program.clp (constructs only, as the bench's
clipspy driver wants them), full.bat.clp (load*, reset, run, exit) and norun.bat.clp
(the same without run). The batches load `program.clp` by its relative name and every
engine is run in the row's directory with relative arguments, so no path's length enters
a measurement (it moved ours' string-output rows by up to 1.3 %, SHAPES.md).

`measure` counts instructions with callgrind, run phase = full - norun and whole process:
  CLIPS 6.30   `clips -f2 full.bat.clp` / `norun.bat.clp`
  CLIPS 6.4.2  clipspy's own library (`_clips.abi3.so`) driven by a 20-line C program
               (tests/bench/c64run.c): CreateEnvironment, Load, Reset, Run, the calls the
               bench's clipspy driver makes, without the 288 M instructions and the
               minute per run of starting Python under valgrind. Its whole-process
               figure is therefore lower than the bench's (harder for us, never easier).
  ours         `OURS_BIN clips -f2 full.bat.clp` / `norun.bat.clp`
and checks that the three engines print the same text. Prints a markdown table; ratio =
best CLIPS / ours (above 1 means we use fewer instructions). Then a growth table: per
shape and engine, run-phase instructions per rule fired at the largest size over the same
at the smallest (issue 22: ours may grow no faster than CLIPS's); the firings are CLIPS
6.4.2's Run() result (or CLIPS 6.30's FIRE lines without the 6.4 driver).

`--cache CACHE_DIR` keeps the CLIPS 6.30 and 6.4.2 figures (run, whole, rules fired and a
hash of the printed text) as one small JSON file per row and engine, named
`<shape>-<size>-<engine>-<hash>.json`; the hash covers the program text, both batch texts
(with DIR replaced by a placeholder, so any DIR hits the same entries) and the engine's
identity (sha256 of /usr/bin/clips and its libclips, or of clipspy's `_clips.abi3.so` and
c64run.c; valgrind's version). A changed shape, size or CLIPS build misses and is
measured again; ours is never cached. Files are written to a temporary name and renamed,
so several processes may share the directory, and a killed run keeps every finished row.
No cache by default. `--jobs N` measures N rows at once; every row is printed to stderr as
it completes (with the seconds since the start) and stdout keeps the table in row order.
`--ends-first` starts every shape's smallest and largest sizes before the sizes between
them (what the growth table needs first); rows are started in the order `--only` names
the shapes (list the cheap ones first to have most shapes by a deadline). `--rows FILE`
appends each finished row's exact figures to FILE as a JSON line; `shapes.py table
FILE ...` prints both tables from such files (the rows of an interrupted run, or of
several runs put together; a row in several: its last line).

`measure-dirs` measures rows already on disk in the same layout (program.clp,
full.bat.clp, norun.bat.clp), such as `robotino-agent bench --emit-only --work-dir DIR`
writes them: each DIR is a row directory or holds row directories, named
`<shape>-<size>` (a name without a size is size 0). The engines, cache, `--rows` and tables
are `measure`'s. The bench's batches `(watch statistics)`, whose lines 6.30 and ours print
and the 6.4.2 driver does not, so for such rows the same-output check leaves out those
lines (`N rules fired`, `... mean number of ...`, run time); the run-phase counts keep
them, as the bench's own 6.30 figures do.

Every program's data is asserted by rules during the run (an init rule or a chain of
firings), so the run phase matches and fires; `deffacts` loads its data at reset.
"""

import argparse
import concurrent.futures
import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
CLIPS64_SO_HINT = "clips/_clips.abi3.so"

COLORS = ["red", "green", "blue", "yellow", "black", "white", "plum"]


def lcg(seed):
    """Deterministic pseudo-random numbers (the same in every Python)."""
    state = seed & 0xFFFFFFFF
    while True:
        state = (state * 1103515245 + 12345) & 0x7FFFFFFF
        yield state >> 8


def report_rule(*globals_):
    parts = " ".join('"%s=" ?*%s* " "' % (g, g) for g in globals_)
    return "(defrule zz-report (declare (salience -1000)) => (printout t %s crlf))\n" % parts


def defglobals(*names):
    return "".join("(defglobal ?*%s* = 0)\n" % n for n in names)


# --- shapes -----------------------------------------------------------------------------


def mfwild(n):
    """Multifield slots and ordered facts with `$?` wildcards, member$ and length$ tests."""
    rnd = lcg(n)
    out = [defglobals("red", "redblue", "green", "ends", "long", "pos", "pair")]
    out.append("(deftemplate bag (slot id) (multislot items))\n")
    asserts = []
    for i in range(n):
        items = [COLORS[next(rnd) % len(COLORS)] for _ in range(3 + next(rnd) % 6)]
        asserts.append("(assert (bag (id %d) (items %s)))" % (i, " ".join(items)))
        asserts.append("(assert (tag %d %s))" % (i, " ".join(items[:3])))
    out.append("(defrule init => %s)\n" % "\n  ".join(asserts))
    out.append(
        """(defrule has-red (bag (id ?i) (items $? red $?)) => (bind ?*red* (+ ?*red* 1)))
(defrule red-then-blue (bag (id ?i) (items $? red $? blue $?)) => (bind ?*redblue* (+ ?*redblue* 1)))
(defrule member-green (bag (id ?i) (items $?all)) (test (member$ green ?all)) => (bind ?*green* (+ ?*green* 1)))
(defrule same-ends (bag (id ?i) (items ?x $? ?x)) => (bind ?*ends* (+ ?*ends* 1)))
(defrule long-bag (bag (id ?i) (items $?a&:(> (length$ ?a) 5))) => (bind ?*long* (+ ?*long* 1)))
(defrule yellow-pos (bag (id ?i) (items $?b yellow $?)) => (bind ?*pos* (+ ?*pos* (length$ ?b))))
(defrule tag-pair (tag ?i ?x $?) (bag (id ?i) (items $? ?x ?x $?)) => (bind ?*pair* (+ ?*pair* 1)))
"""
    )
    out.append(report_rule("red", "redblue", "green", "ends", "long", "pos", "pair"))
    return "".join(out)


def testce(n):
    """`test` CEs with arithmetic and string functions over a join of every pair."""
    out = [defglobals("pairs", "words", "tri")]
    asserts = ["(assert (num %d))" % i for i in range(1, n + 1)]
    words = ["alpha", "beta", "gamma", "delta", "apple", "anchor", "zeta", "axe", "omega"]
    asserts += ['(assert (word "%s%d"))' % (words[i % len(words)], i) for i in range(n)]
    out.append("(defrule init => %s)\n" % "\n  ".join(asserts))
    out.append(
        """(defrule pair (num ?x) (num ?y&:(> ?y ?x)) (test (= (mod (+ (* ?x ?x) ?y) 7) 0))
  => (bind ?*pairs* (+ ?*pairs* 1)))
(defrule tri (num ?x) (num ?y&:(> ?y ?x)) (test (and (< (+ ?x ?y) 40) (evenp (+ ?x ?y))))
  => (bind ?*tri* (+ ?*tri* 1)))
(defrule a-word (word ?w) (test (eq (sub-string 1 1 ?w) "a")) (test (> (str-length ?w) 5))
  => (bind ?*words* (+ ?*words* (str-length ?w))))
"""
    )
    out.append(report_rule("pairs", "words", "tri"))
    return "".join(out)


def deffunc(n):
    """Deffunctions with while and loop-for-count loops called from a right-hand side."""
    return (
        defglobals("acc", "steps")
        + """(deffunction collatz (?n)
  (bind ?s 0)
  (while (> ?n 1) do
    (if (evenp ?n) then (bind ?n (div ?n 2)) else (bind ?n (+ (* 3 ?n) 1)))
    (bind ?s (+ ?s 1)))
  ?s)
(deffunction sumsq (?n)
  (bind ?t 0)
  (loop-for-count (?i 1 ?n) do (bind ?t (+ ?t (* ?i ?i))))
  ?t)
(deffunction classify (?k)
  (switch (mod ?k 4)
    (case 0 then zero)
    (case 1 then one)
    (case 2 then two)
    (default other)))
(deffacts start (count 1))
(defrule step
  ?f <- (count ?k&:(<= ?k %d))
  =>
  (retract ?f)
  (bind ?*steps* (+ ?*steps* (collatz ?k)))
  (bind ?*acc* (+ ?*acc* (sumsq (mod ?k 13))))
  (if (eq (classify ?k) two) then (bind ?*acc* (- ?*acc* 1)))
  (assert (count (+ ?k 1))))
"""
        % n
        + report_rule("acc", "steps")
    )


def modify(n):
    """Heavy modify of a 12-slot template; other rules watch single slots."""
    out = [defglobals("low", "far", "zone")]
    out.append(
        """(deftemplate robot (slot name) (slot steps (default 0)) (slot x (default 0)) (slot y (default 0))
  (slot heading (default 0)) (slot battery (default 100)) (slot zone (default z0))
  (slot load (default none)) (slot state (default idle)) (slot speed (default 1))
  (slot errors (default 0)) (slot goal (default none)))
(deftemplate zone-info (slot id) (slot cost))
"""
    )
    asserts = ["(assert (robot (name r%d) (x %d)))" % (i, i) for i in range(4)]
    asserts += ["(assert (zone-info (id z%d) (cost %d)))" % (i, i * 3) for i in range(5)]
    out.append("(defrule init => %s)\n" % "\n  ".join(asserts))
    out.append(
        """(defrule move
  ?r <- (robot (name ?n) (steps ?s&:(< ?s %d)) (x ?x) (y ?y) (battery ?b&:(>= ?b 10)))
  =>
  (modify ?r (steps (+ ?s 1)) (x (+ ?x 1)) (y (- ?y 1)) (battery (- ?b 3))
             (zone (sym-cat z (mod (+ ?x ?s) 5))) (heading (mod (* ?s 30) 360))))
(defrule recharge
  ?r <- (robot (battery ?b&:(< ?b 10)))
  =>
  (bind ?*low* (+ ?*low* 1))
  (modify ?r (battery 100) (state charging)))
(defrule far-away (robot (name ?n) (x ?x&:(> ?x 100)) (state ?st&~far))
  => (bind ?*far* (+ ?*far* 1)))
(defrule in-zone (robot (name ?n) (zone ?z)) (zone-info (id ?z) (cost ?c&:(> ?c 6)))
  => (bind ?*zone* (+ ?*zone* ?c)))
"""
        % (n // 4)
    )
    out.append(report_rule("low", "far", "zone"))
    return "".join(out)


def existsforall(n):
    """`exists` and `forall` over tasks finished one by one."""
    groups = max(n // 10, 1)
    out = [defglobals("done", "groups", "busy")]
    asserts = ["(assert (group g%d))" % g for g in range(groups)]
    asserts += [
        "(assert (task (id %d) (group g%d) (skill %s)))" % (i, i % groups, ["a", "b", "c"][i % 3])
        for i in range(n)
    ]
    asserts += ["(assert (worker w%d %s))" % (w, ["a", "b", "c"][w % 3]) for w in range(6)]
    out.append("(deftemplate task (slot id) (slot group) (slot skill) (slot state (default open)))\n")
    out.append("(defrule init => %s)\n" % "\n  ".join(asserts))
    out.append(
        """(defrule finish
  ?t <- (task (id ?i) (state open))
  =>
  (modify ?t (state done))
  (assert (done ?i))
  (bind ?*done* (+ ?*done* 1)))
(defrule group-done
  (group ?g)
  (forall (task (group ?g) (id ?i)) (done ?i))
  =>
  (bind ?*groups* (+ ?*groups* 1)))
(defrule worker-busy
  (declare (salience 10))
  (worker ?w ?s)
  (exists (task (skill ?s) (state open)))
  =>
  (bind ?*busy* (+ ?*busy* 1)))
(defrule all-open (declare (salience 20)) (not (task (state done))) (exists (task)) =>
  (printout t "all open" crlf))
"""
    )
    out.append(report_rule("done", "groups", "busy"))
    return "".join(out)


def strout(n):
    """Output per firing built with str-cat, sym-cat and format."""
    return (
        defglobals("len")
        + """(deffacts start (count 1))
(defrule step
  ?f <- (count ?k&:(<= ?k %d))
  =>
  (retract ?f)
  (bind ?s (str-cat "item-" ?k "-" (mod ?k 7)))
  (bind ?*len* (+ ?*len* (str-length ?s)))
  (printout t ?s " " (sym-cat a ?k b) (format nil " %%5d %%-8s|%%6.2f" ?k ?s (/ ?k 3)) crlf)
  (printout t (upcase ?s) " " (str-index "-" ?s) " " (sub-string 2 4 ?s) crlf)
  (assert (count (+ ?k 1))))
"""
        % n
        + report_rule("len")
    )


def factquery(n):
    """Fact-set queries (do-for-all-facts, find-all-facts, any-factp, find-fact) in a RHS."""
    rnd = lcg(n + 7)
    asserts = [
        "(assert (item (id %d) (w %d) (kind %s)))" % (i, next(rnd) % 100, "abc"[next(rnd) % 3])
        for i in range(n)
    ]
    return (
        defglobals("sum", "cnt", "any", "first")
        + "(deftemplate item (slot id) (slot w) (slot kind))\n"
        + "(defrule init => %s (assert (query 1)))\n" % "\n  ".join(asserts)
        + """(defrule query
  ?q <- (query ?k&:(<= ?k 40))
  =>
  (retract ?q)
  (do-for-all-facts ((?f item)) (> ?f:w (* ?k 2)) (bind ?*sum* (+ ?*sum* ?f:w)))
  (bind ?*cnt* (+ ?*cnt* (length$ (find-all-facts ((?f item)) (eq ?f:kind (nth$ (+ 1 (mod ?k 3)) (create$ a b c)))))))
  (if (any-factp ((?f item)) (= ?f:w ?k)) then (bind ?*any* (+ ?*any* 1)))
  (bind ?ff (find-fact ((?f item)) (> ?f:w (- 99 ?k))))
  (if (> (length$ ?ff) 0) then (bind ?*first* (+ ?*first* (fact-slot-value (nth$ 1 ?ff) id))))
  (assert (query (+ ?k 1))))
"""
        + report_rule("sum", "cnt", "any", "first")
    )


def salience(n):
    """A deep salience chain: 20 rules per tick, each updating a global."""
    out = [defglobals("a", "b"), "(deffacts start (tick 1))\n"]
    for level in range(20):
        out.append(
            "(defrule s%02d (declare (salience %d)) (tick ?k) => (bind ?*a* (+ ?*a* %d)) (bind ?*b* (mod (+ ?*b* ?k) 1000)))\n"
            % (level, 100 - level * 5, level)
        )
    out.append(
        "(defrule next (declare (salience -50)) ?f <- (tick ?k&:(< ?k %d)) => (retract ?f) (assert (tick (+ ?k 1))))\n"
        % max(n // 21, 1)
    )
    out.append(report_rule("a", "b"))
    return "".join(out)


def ordered(n):
    """Ordered facts with 12 fields; rules test constants on different fields and join."""
    rnd = lcg(n + 3)
    syms = ["a", "b", "c", "d"]
    asserts = []
    for i in range(n):
        fields = [syms[next(rnd) % 4] for _ in range(6)] + [str(next(rnd) % 50) for _ in range(5)]
        asserts.append("(assert (rec %d %s))" % (i, " ".join(fields)))
    out = [defglobals("r1", "r2", "r3", "r4", "r5", "j")]
    out.append("(defrule init => %s)\n" % "\n  ".join(asserts))
    out.append(
        """(defrule o1 (rec ?i a ? ? b ? ? $?) => (bind ?*r1* (+ ?*r1* 1)))
(defrule o2 (rec ?i ? c ? ? d ? ?n&:(> ?n 25) $?) => (bind ?*r2* (+ ?*r2* 1)))
(defrule o3 (rec ?i ?x ?x ?x ? ? ? $?) => (bind ?*r3* (+ ?*r3* 1)))
(defrule o4 (rec ?i ? ? ? ? ? a ? ? ? ? 7) => (bind ?*r4* (+ ?*r4* 1)))
(defrule o5 (rec ?i b ? ? ? ? ? ?v ?v $?) => (bind ?*r5* (+ ?*r5* 1)))
(defrule oj (rec ?i d d ? ? ? ? ?v $?) (rec ?j&:(< ?i ?j) ? ? d d ? ? ?v $?) => (bind ?*j* (+ ?*j* 1)))
"""
    )
    out.append(report_rule("r1", "r2", "r3", "r4", "r5", "j"))
    return "".join(out)


def deffacts(n):
    """A large deffacts load (at reset), then rules over it."""
    rnd = lcg(n + 11)
    out = [defglobals("hot", "pair")]
    out.append("(deftemplate reading (slot sensor) (slot t) (slot value))\n")
    facts = []
    for i in range(n):
        facts.append("(reading (sensor s%d) (t %d) (value %d))" % (i % 50, i // 50, next(rnd) % 1000))
        if i % 4 == 0:
            facts.append("(link s%d s%d)" % (i % 50, (i * 7) % 50))
    for start in range(0, len(facts), 500):
        out.append("(deffacts data%d\n  %s)\n" % (start // 500, "\n  ".join(facts[start:start + 500])))
    out.append(
        """(defrule hot (reading (sensor ?s) (value ?v&:(> ?v 990))) => (bind ?*hot* (+ ?*hot* 1)))
(defrule linked-hot (link ?a ?b&~?a) (reading (sensor ?a) (t 0) (value ?v&:(> ?v 900)))
  => (bind ?*pair* (+ ?*pair* 1)))
"""
    )
    out.append(report_rule("hot", "pair"))
    return "".join(out)


def countdown(n):
    """A bare loop: retract and assert one counter per firing, a switch on the right."""
    return (
        defglobals("x")
        + """(deffacts start (count %d))
(defrule down
  ?f <- (count ?n&:(> ?n 0))
  =>
  (retract ?f)
  (switch (mod ?n 3)
    (case 0 then (bind ?*x* (+ ?*x* 1)))
    (case 1 then (bind ?*x* (- ?*x* 2)))
    (default (bind ?*x* (* ?*x* 1))))
  (assert (count (- ?n 1))))
"""
        % n
        + report_rule("x")
    )


def agenda(n):
    """Many activations created and withdrawn: a control fact gates a wide join."""
    out = [defglobals("fired", "seen")]
    asserts = ["(assert (part %d %s))" % (i, "abcd"[i % 4]) for i in range(n)]
    out.append("(defrule init => %s (assert (phase 1)))\n" % "\n  ".join(asserts))
    out.append(
        """(defrule look (phase ?p&:(<= ?p 10)) (part ?i ?k) (not (seen ?i ?p))
  => (bind ?*seen* (+ ?*seen* 1)) (assert (seen ?i ?p)))
(defrule advance (declare (salience -10)) ?f <- (phase ?p&:(<= ?p 10))
  => (bind ?*fired* (+ ?*fired* 1)) (retract ?f) (assert (phase (+ ?p 1))))
"""
    )
    out.append(report_rule("fired", "seen"))
    return "".join(out)


# --- round 2 ----------------------------------------------------------------------------


def logical(n):
    """`logical` support chains: derived facts lose their support as sources are retracted."""
    groups = 10
    out = [defglobals("d1", "d3", "gone")]
    out.append("(deftemplate src (slot id) (slot grp))\n")
    asserts = ["(assert (grp-on %d))" % g for g in range(groups)]
    asserts += ["(assert (src (id %d) (grp %d)))" % (i, i % groups) for i in range(n)]
    out.append("(defrule init => %s)\n" % "\n  ".join(asserts))
    out.append(
        """(defrule derive1 (logical (src (id ?i) (grp ?g))) => (assert (d1 ?i ?g)) (bind ?*d1* (+ ?*d1* 1)))
(defrule derive2 (logical (d1 ?i ?g) (grp-on ?g)) => (assert (d2 ?i)))
(defrule derive3 (logical (d2 ?i) (not (veto ?i))) => (assert (d3 ?i)))
(defrule count-d3 (d3 ?i) => (bind ?*d3* (+ ?*d3* 1)))
(defrule veto (declare (salience -5)) (d3 ?i&:(= (mod ?i 7) 0)) (not (veto ?i)) => (assert (veto ?i)))
(defrule drop (declare (salience -10)) ?s <- (src (id ?i&:(= (mod ?i 3) 0))) => (retract ?s))
(defrule group-off (declare (salience -20)) ?g <- (grp-on ?x&:(< ?x 5)) => (retract ?g))
(defrule lost (declare (salience -30)) (src (id ?i)) (not (d2 ?i)) => (bind ?*gone* (+ ?*gone* 1)))
(defrule zz-count (declare (salience -900)) =>
  (printout t (length$ (find-all-facts ((?f d1)) TRUE)) " " (length$ (find-all-facts ((?f d2)) TRUE))
     " " (length$ (find-all-facts ((?f d3)) TRUE)) crlf))
"""
    )
    out.append(report_rule("d1", "d3", "gone"))
    return "".join(out)


def modules(n):
    """Modules with focus, return, auto-focus and per-module agendas over job stages."""
    rounds = 10
    rnd = lcg(n + 5)
    asserts = [
        "(assert (job (id %d) (round %d) (v %d)))" % (i, i % rounds, next(rnd) % 100) for i in range(n)
    ]
    return (
        """(defmodule MAIN (export ?ALL))
(deftemplate job (slot id) (slot round) (slot stage (default 0)) (slot v))
(defglobal ?*sense* = 0 ?*plan* = 0 ?*act* = 0 ?*ret* = 0 ?*alarm* = 0 ?*h* = 0)
"""
        + "(defrule init => %s (assert (round 0)))\n" % "\n  ".join(asserts)
        + """(defrule next-round ?r <- (round ?k&:(< ?k %d)) =>
  (retract ?r) (assert (round (+ ?k 1))) (focus SENSE PLAN ACT))
(defrule zz-report (declare (salience -1000)) =>
  (printout t ?*sense* " " ?*plan* " " ?*act* " " ?*ret* " " ?*alarm* " " ?*h* crlf))
(defmodule SENSE (import MAIN ?ALL))
(defrule SENSE::see ?j <- (job (id ?i) (round ?k) (stage 0)) (round ?r&:(= ?k (- ?r 1))) =>
  (bind ?*sense* (+ ?*sense* 1)) (bind ?*h* (mod (+ (* ?*h* 31) ?i) 1000003)) (modify ?j (stage 1)))
(defmodule PLAN (import MAIN ?ALL))
(defrule PLAN::plan ?j <- (job (id ?i) (stage 1) (v ?v)) =>
  (bind ?*plan* (+ ?*plan* 1)) (bind ?*h* (mod (+ (* ?*h* 17) ?i) 1000003)) (modify ?j (stage 2)))
(defrule PLAN::hurry (declare (salience 10)) ?j <- (job (id ?i&:(= (mod ?i 13) 0)) (stage 1))
  (round ?r&:(= (mod ?r 3) 0)) =>
  (bind ?*ret* (+ ?*ret* 1)) (modify ?j (stage 2)) (return))
(defmodule ACT (import MAIN ?ALL))
(defrule ACT::act ?j <- (job (id ?i) (stage 2)) =>
  (bind ?*act* (+ ?*act* 1)) (bind ?*h* (mod (+ (* ?*h* 7) ?i) 1000003)) (modify ?j (stage 3)))
(defmodule ALARM (import MAIN ?ALL))
(defrule ALARM::alarm (declare (auto-focus TRUE)) (job (id ?i) (stage 3) (v ?v&:(> ?v 90))) =>
  (bind ?*alarm* (+ ?*alarm* 1)) (bind ?*h* (mod (+ (* ?*h* 3) ?i) 1000003)))
"""
        % rounds
    )


def strategy(name):
    def make(n):
        """A large agenda under one conflict resolution strategy; the firing order is hashed."""
        rnd = lcg(n + 13)
        asserts = ["(set-strategy %s)" % name]
        asserts += ["(assert (item %d %d))" % (i, next(rnd) % 100) for i in range(n)]
        asserts += ["(assert (kind %s))" % k for k in ("a", "b", "c")]
        return (
            defglobals("h", "pick", "pair", "hit")
            + "(defrule init (declare (salience 100)) => %s)\n" % "\n  ".join(asserts)
            + """(defrule pick (item ?i ?w) (kind ?k) (test (> ?w 30)) =>
  (bind ?*pick* (+ ?*pick* 1)) (bind ?*h* (mod (+ (* ?*h* 31) ?i) 1000003)))
(defrule pair (item ?i ?w) (item ?j&:(> ?j ?i) ?w) =>
  (bind ?*pair* (+ ?*pair* 1)) (bind ?*h* (mod (+ (* ?*h* 7) ?j) 1000003)))
(defrule hit ?f <- (item ?i ?w&:(> ?w 70)) =>
  (retract ?f) (assert (hit ?i)) (bind ?*hit* (+ ?*hit* 1)) (bind ?*h* (mod (+ (* ?*h* 3) ?i) 1000003)))
(defrule rehit (hit ?i) (kind a) => (bind ?*h* (mod (+ (* ?*h* 5) ?i) 1000003)))
"""
            + report_rule("h", "pick", "pair", "hit")
        )

    make.__doc__ = "A large agenda under the %s strategy; the firing order is hashed." % name
    return make


def orce(n):
    """`or` CEs, alone, inside `and`, under `not`, with facts retracted as the run goes."""
    rnd = lcg(n + 17)
    asserts = []
    for i in range(n):
        kind = ["smoke", "heat", "water", "none"][next(rnd) % 4]
        asserts.append("(assert (sensor (id %d) (kind %s) (v %d)))" % (i, kind, next(rnd) % 100))
        r = next(rnd) % 6
        if r == 0:
            asserts.append("(assert (ok %d))" % i)
        elif r == 1:
            asserts.append("(assert (maybe %d))" % i)
        elif r == 2:
            asserts.append("(assert (maybe %d) (confirm %d))" % (i, i))
        elif r == 3:
            asserts.append("(assert (bad %d))" % i)
    return (
        defglobals("alarm", "either", "clean", "gone")
        + "(deftemplate sensor (slot id) (slot kind) (slot v))\n"
        + "(defrule init => %s)\n" % "\n  ".join(asserts)
        + """(defrule alarm (or (sensor (kind smoke) (v ?v&:(> ?v 50))) (sensor (kind heat) (v ?v&:(> ?v 80))))
  => (bind ?*alarm* (+ ?*alarm* ?v)))
(defrule either (sensor (id ?i)) (or (ok ?i) (and (maybe ?i) (confirm ?i))) => (bind ?*either* (+ ?*either* 1)))
(defrule clean (sensor (id ?i) (kind ~none)) (not (or (bad ?i) (maybe ?i))) => (bind ?*clean* (+ ?*clean* 1)))
(defrule drop (declare (salience -10)) (or ?f <- (ok ?i) ?f <- (confirm ?i)) (test (= (mod ?i 2) 0)) =>
  (retract ?f) (bind ?*gone* (+ ?*gone* 1)))
(defrule unbad (declare (salience -20)) ?f <- (bad ?i&:(= (mod ?i 3) 0)) => (retract ?f))
"""
        + report_rule("alarm", "either", "clean", "gone")
    )


def notand(n):
    """Nested `not (and ...)` over a graph whose marks are set one firing at a time."""
    rnd = lcg(n + 19)
    nodes = max(n // 4, 4)
    asserts = ["(assert (node %d))" % i for i in range(nodes)]
    edges = set()
    for _ in range(n):
        a, b = next(rnd) % nodes, next(rnd) % nodes
        if a != b and (a, b) not in edges:
            edges.add((a, b))
            asserts.append("(assert (edge %d %d))" % (a, b))
    return (
        defglobals("lonely", "nocycle", "allmarked", "marks")
        + "(defrule init => %s (assert (mark-next 0)))\n" % "\n  ".join(asserts)
        + """(defrule lonely (node ?a) (not (and (edge ?a ?b) (node ?b))) => (bind ?*lonely* (+ ?*lonely* 1)))
(defrule no-cycle (node ?a) (not (and (edge ?a ?b) (edge ?b ?a))) => (bind ?*nocycle* (+ ?*nocycle* 1)))
(defrule all-marked (node ?a) (mark ?a) (not (and (edge ?a ?b) (not (mark ?b)))) =>
  (bind ?*allmarked* (+ ?*allmarked* 1)))
(defrule mark (declare (salience -10)) ?f <- (mark-next ?k) (node ?k) =>
  (retract ?f) (assert (mark ?k) (mark-next (+ ?k 1))) (bind ?*marks* (+ ?*marks* 1)))
"""
        + report_rule("lonely", "nocycle", "allmarked", "marks")
    )


def mflist(n):
    """Multifield functions in actions on lists of 60-120 fields (explode$, subseq$, ...)."""
    return (
        "(defglobal ?*l* = (create$ 1 2 3 4 5) ?*sum* = 0 ?*hits* = 0 ?*len* = 0)\n"
        + """(deffacts start (count 1))
(defrule step ?f <- (count ?k&:(<= ?k %d)) =>
  (retract ?f)
  (bind ?*l* (insert$ ?*l* 1 (mod (* ?k 7) 101)))
  (if (> (length$ ?*l*) 120) then (bind ?*l* (subseq$ ?*l* 1 60)))
  (bind ?s (implode$ ?*l*))
  (bind ?m (explode$ ?s))
  (bind ?*len* (+ ?*len* (str-length ?s)))
  (bind ?*sum* (+ ?*sum* (nth$ (+ 1 (mod ?k (length$ ?m))) ?m)))
  (if (member$ (mod ?k 101) ?m) then (bind ?*hits* (+ ?*hits* 1)))
  (bind ?r (replace$ (rest$ ?m) 1 2 (first$ ?m)))
  (bind ?*sum* (+ ?*sum* (length$ (delete$ ?r 1 1)) (nth$ 1 (subseq$ ?m 2 3))))
  (assert (count (+ ?k 1))))
"""
        % n
        + report_rule("sum", "hits", "len")
    )


def strbuild(n):
    """Strings built in a while loop with str-cat, sym-cat and sub-string, then matched."""
    return (
        defglobals("long", "a0", "cmp", "n")
        + """(deffacts start (count 1))
(defrule step ?f <- (count ?k&:(<= ?k %d)) =>
  (retract ?f)
  (bind ?s "") (bind ?i 0)
  (while (< ?i (+ 2 (mod ?k 9))) do
    (bind ?s (str-cat ?s (sub-string (+ 1 (mod (+ ?i ?k) 8)) (+ 1 (mod (+ ?i ?k) 8)) "abcdefgh") ?i))
    (bind ?i (+ ?i 1)))
  (assert (word ?k (sym-cat w ?s) ?s))
  (assert (count (+ ?k 1))))
(defrule long (word ?k ?w ?s&:(> (str-length ?s) 12)) => (bind ?*long* (+ ?*long* 1)))
(defrule a0 (word ?k ?w ?s) (test (str-index "a0" ?s)) => (bind ?*a0* (+ ?*a0* (str-index "a0" ?s))))
(defrule cmp (word ?k ?w ?s) (word ?j&:(= ?j (+ ?k 1)) ?w2 ?s2&:(< (str-compare ?s ?s2) 0)) =>
  (bind ?*cmp* (+ ?*cmp* 1)))
(defrule up (word ?k ?w ?s) (test (eq (upcase (sub-string 1 1 ?s)) "C")) =>
  (bind ?*n* (+ ?*n* (str-length (str-cat (upcase ?s) (lowcase ?w))))))
"""
        % n
        + report_rule("long", "a0", "cmp", "n")
    )


def partials(n):
    """Many partial matches in a 3-pattern join, then the middle facts retracted one by one."""
    heads = 20
    out = [defglobals("tri", "pairs", "gone")]
    asserts = ["(assert (a %d))" % i for i in range(heads)]
    asserts += ["(assert (b %d %d))" % (i % heads, i) for i in range(n)]
    asserts += ["(assert (c %d %d))" % (j, j % 3) for j in range(0, n, 5)]
    out.append("(defrule init => %s)\n" % "\n  ".join(asserts))
    out.append(
        """(defrule tri (a ?x) (b ?x ?y) (c ?y ?z) => (bind ?*tri* (+ ?*tri* 1)))
(defrule pairs (a ?x) (b ?x ?y) (b ?x ?z&:(= ?z (+ ?y %d))) => (bind ?*pairs* (+ ?*pairs* 1)))
(defrule kill (declare (salience -10)) ?f <- (b ?x ?y) => (retract ?f) (bind ?*gone* (+ ?*gone* 1)))
(defrule kill-a (declare (salience -20)) ?f <- (a ?x) => (retract ?f))
"""
        % heads
    )
    out.append(report_rule("tri", "pairs", "gone"))
    return "".join(out)


def widemod(n):
    """A 24-slot template; each firing modifies one slot; rules watch other slots."""
    rnd = lcg(n + 23)
    slots = " ".join("(slot s%d)" % k for k in range(1, 23))
    out = [defglobals("w5", "pair", "hi")]
    out.append("(deftemplate rec (slot id) %s (slot n (default 0)))\n" % slots)
    asserts = []
    for i in range(16):
        vals = " ".join("(s%d %s)" % (k, "abc"[next(rnd) % 3]) for k in range(1, 23))
        asserts.append("(assert (rec (id %d) %s))" % (i, vals))
    out.append("(defrule init => %s)\n" % "\n  ".join(asserts))
    out.append(
        """(defrule bump ?r <- (rec (id ?i) (n ?n&:(< ?n %d))) => (modify ?r (n (+ ?n 1))))
(defrule watch-s5 (declare (salience 5)) (rec (id ?i) (s5 a) (s9 ?x&~c)) => (bind ?*w5* (+ ?*w5* 1)))
(defrule pair (declare (salience 5)) (rec (id ?i) (s1 ?x) (s2 b)) (rec (id ?j&:(< ?i ?j)) (s1 ?x) (s3 ~a)) => (bind ?*pair* (+ ?*pair* 1)))
(defrule hi (declare (salience 5)) (rec (id ?i) (s20 c) (n ?n&:(= (mod ?n 10) 0))) => (bind ?*hi* (+ ?*hi* 1)))
"""
        % (n // 16)
    )
    out.append(report_rule("w5", "pair", "hi"))
    return "".join(out)


def dftest(n):
    """`test` CEs calling deffunctions with while loops; globals updated on every firing."""
    asserts = ["(assert (num %d))" % i for i in range(2, n + 2)]
    return (
        defglobals("primes", "twins", "dig", "calls")
        + """(deffunction prime (?n)
  (bind ?*calls* (+ ?*calls* 1))
  (bind ?d 2)
  (while (<= (* ?d ?d) ?n) do
    (if (= (mod ?n ?d) 0) then (return FALSE))
    (bind ?d (+ ?d 1)))
  TRUE)
(deffunction digsum (?n)
  (bind ?s 0)
  (while (> ?n 0) do (bind ?s (+ ?s (mod ?n 10))) (bind ?n (div ?n 10)))
  ?s)
"""
        + "(defrule init => %s)\n" % "\n  ".join(asserts)
        + """(defrule prime (num ?x) (test (prime ?x)) => (bind ?*primes* (+ ?*primes* 1)) (assert (prime ?x)))
(defrule twin (prime ?x) (prime ?y&:(= ?y (+ ?x 2))) => (bind ?*twins* (+ ?*twins* 1)))
(defrule dig (num ?x) (test (= (digsum ?x) 10)) => (bind ?*dig* (+ ?*dig* ?x)))
"""
        + report_rule("primes", "twins", "dig", "calls")
    )


def nestquery(n):
    """Nested do-for-all-facts and a two-template fact-set query in a right-hand side."""
    rnd = lcg(n + 29)
    asserts = [
        "(assert (item (id %d) (w %d) (kind %d)))" % (i, next(rnd) % 100, next(rnd) % 4) for i in range(n)
    ]
    asserts += ["(assert (link (from %d) (to %d)))" % (i, (i * 7) % n) for i in range(0, n, 3)]
    return (
        defglobals("c", "l", "m")
        + "(deftemplate item (slot id) (slot w) (slot kind))\n(deftemplate link (slot from) (slot to))\n"
        + "(defrule init => %s (assert (query 1)))\n" % "\n  ".join(asserts)
        + """(defrule query ?q <- (query ?k&:(<= ?k 12)) =>
  (retract ?q)
  (do-for-all-facts ((?a item)) (= ?a:kind (mod ?k 4))
    (do-for-all-facts ((?b item)) (and (= ?b:kind ?a:kind) (> ?b:w (+ ?a:w 40)))
      (bind ?*c* (+ ?*c* 1))))
  (do-for-all-facts ((?a item) (?l link)) (and (= ?l:from ?a:id) (> ?a:w (* ?k 7)))
    (bind ?*l* (+ ?*l* ?l:to)))
  (bind ?*m* (+ ?*m* (length$ (find-all-facts ((?a item)) (= ?a:w ?k)))))
  (assert (query (+ ?k 1))))
"""
        + report_rule("c", "l", "m")
    )


# --- round 4 (p35) ----------------------------------------------------------------------


def recurse(n):
    """Recursive deffunctions (fib, gcd, an accumulator) called from a right-hand side."""
    return (
        defglobals("fib", "g", "d")
        + """(deffunction fib (?n) (if (< ?n 2) then ?n else (+ (fib (- ?n 1)) (fib (- ?n 2)))))
(deffunction gcd (?a ?b) (if (= ?b 0) then ?a else (gcd ?b (mod ?a ?b))))
(deffunction walk (?n ?acc)
  (if (= ?n 0) then (return ?acc))
  (walk (- ?n 1) (+ ?acc (mod (* ?n ?n) 7))))
(deffacts start (count 1))
(defrule step ?f <- (count ?k&:(<= ?k %d)) =>
  (retract ?f)
  (bind ?*fib* (+ ?*fib* (fib (mod ?k 11))))
  (bind ?*g* (+ ?*g* (gcd (* ?k 12) (+ ?k 18))))
  (bind ?*d* (+ ?*d* (walk (mod ?k 30) 0)))
  (assert (count (+ ?k 1))))
"""
        % n
        + report_rule("fib", "g", "d")
    )


def rhsloop(n):
    """Right-hand sides with nested loop-for-count, while and if, and many local binds."""
    return (
        defglobals("a", "b", "c")
        + """(deffacts start (count 1))
(defrule step ?f <- (count ?k&:(<= ?k %d)) =>
  (retract ?f)
  (bind ?x 0) (bind ?y 1) (bind ?z (mod ?k 5))
  (loop-for-count (?i 1 (+ 2 (mod ?k 4))) do
    (loop-for-count (?j ?i 4) do
      (if (evenp (+ ?i ?j)) then (bind ?x (+ ?x (* ?i ?j)))
       else (if (> ?j 2) then (bind ?y (mod (* ?y 3) 101)) else (bind ?z (+ ?z 1))))))
  (bind ?w ?k)
  (while (> ?w 9) do (bind ?w (div ?w 3)) (bind ?z (+ ?z 1)))
  (bind ?*a* (+ ?*a* ?x)) (bind ?*b* (mod (+ ?*b* ?y) 100003)) (bind ?*c* (+ ?*c* ?z ?w))
  (assert (count (+ ?k 1))))
"""
        % n
        + report_rule("a", "b", "c")
    )


def globals_(n):
    """Globals read in pattern and test CEs while the right-hand sides change them."""
    rnd = lcg(n + 31)
    return (
        """(defglobal ?*lo* = 20 ?*hi* = 80 ?*step* = 3 ?*mode* = fast ?*off* = 5)
(defglobal ?*band* = 0 ?*fast* = 0 ?*sum* = 0 ?*t* = 0)
(deftemplate reading (slot id) (slot v) (slot mode))
(deffacts start (tick 0))
(defrule tick ?f <- (tick ?k&:(< ?k %d)) =>
  (retract ?f)
  (bind ?v (mod (+ (* ?k 7) %d) 100))
  (bind ?m (if (evenp ?k) then fast else slow))
  (assert (reading (id ?k) (v ?v) (mode ?m)))
  (if (= (mod ?k 10) 0) then (bind ?*lo* (+ 15 (mod ?k 11))) (bind ?*mode* (if (eq ?*mode* fast) then slow else fast)))
  (bind ?*t* (+ ?*t* ?*step*))
  (assert (tick (+ ?k 1))))
(defrule in-band (reading (id ?i) (v ?v&:(>= ?v ?*lo*)&:(<= ?v ?*hi*))) =>
  (bind ?*band* (+ ?*band* 1)))
(defrule mode (reading (id ?i) (mode ?m&:(eq ?m ?*mode*))) => (bind ?*fast* (+ ?*fast* 1)))
(defrule near (reading (id ?i) (v ?v)) (reading (id ?j&:(= ?j (+ ?i 1))) (v ?w))
  (test (< (abs (- ?v ?w)) (+ ?*off* ?*step*))) =>
  (bind ?*sum* (+ ?*sum* ?v ?w ?*off*)))
"""
        % (n, next(rnd) % 50)
        + report_rule("band", "fast", "sum", "t", "lo")
    )


def dynsal(n):
    """Salience from globals re-evaluated every cycle (set-salience-evaluation every-cycle)."""
    return (
        defglobals("pa", "pb", "pc", "h", "na", "nb", "nc")
        + """(deftemplate job (slot id) (slot kind))
(defrule init (declare (salience 1000)) =>
  (set-salience-evaluation every-cycle)
  (loop-for-count (?i 1 %d) do (assert (job (id ?i) (kind (nth$ (+ 1 (mod ?i 3)) (create$ a b c)))))))
(defrule do-a (declare (salience ?*pa*)) ?j <- (job (id ?i) (kind a)) =>
  (retract ?j) (bind ?*na* (+ ?*na* 1)) (bind ?*h* (mod (+ (* ?*h* 31) ?i) 1000003))
  (bind ?*pa* (- ?*pa* 2)) (bind ?*pb* (+ ?*pb* 1)))
(defrule do-b (declare (salience (+ ?*pb* 1))) ?j <- (job (id ?i) (kind b)) =>
  (retract ?j) (bind ?*nb* (+ ?*nb* 1)) (bind ?*h* (mod (+ (* ?*h* 17) ?i) 1000003))
  (bind ?*pb* (- ?*pb* 3)) (bind ?*pc* (+ ?*pc* 2)))
(defrule do-c (declare (salience ?*pc*)) ?j <- (job (id ?i) (kind c)) =>
  (retract ?j) (bind ?*nc* (+ ?*nc* 1)) (bind ?*h* (mod (+ (* ?*h* 7) ?i) 1000003))
  (bind ?*pc* (- ?*pc* 4)) (bind ?*pa* (+ ?*pa* 3)))
"""
        % n
        + report_rule("h", "na", "nb", "nc", "pa", "pb", "pc")
    )


def assertstr(n):
    """Facts built as text with str-cat and asserted with assert-string, then matched."""
    return (
        defglobals("obs", "pair", "len")
        + """(deftemplate note (slot id) (slot tag) (slot text))
(deffacts start (count 1))
(defrule step ?f <- (count ?k&:(<= ?k %d)) =>
  (retract ?f)
  (assert-string (str-cat "(obs " ?k " s" (mod ?k 5) " \\"t" (mod (* ?k 7) 13) "\\")"))
  (assert-string (str-cat "(note (id " ?k ") (tag " (sym-cat g (mod ?k 4)) ") (text \\"n" ?k "\\"))"))
  (assert (count (+ ?k 1))))
(defrule obs (obs ?k s3 ?t) => (bind ?*obs* (+ ?*obs* 1)))
(defrule pair (obs ?k ?s ?t) (note (id ?k) (tag g1) (text ?x)) =>
  (bind ?*pair* (+ ?*pair* 1)) (bind ?*len* (+ ?*len* (str-length ?x) (str-length ?t))))
"""
        % n
        + report_rule("obs", "pair", "len")
    )


def defaults(n):
    """Many templates with default and default-dynamic slots, asserted with few slots given."""
    kinds = 12
    out = [defglobals("seq", "sum", "hit")]
    for t in range(kinds):
        out.append(
            "(deftemplate t%d (slot id) (slot a (default %d)) (slot b (default-dynamic (+ ?*seq* %d)))\n"
            "  (slot c (type SYMBOL) (default k%d)) (multislot m (default x%d y z)) (slot d (type INTEGER)))\n"
            % (t, t * 3, t, t % 3, t)
        )
    out.append("(deffacts start (count 1))\n")
    cases = "\n    ".join("(case %d then (assert (t%d (id ?k))))" % (t, t) for t in range(kinds))
    out.append(
        """(defrule step ?f <- (count ?k&:(<= ?k %d)) =>
  (retract ?f)
  (bind ?*seq* (+ ?*seq* 1))
  (switch (mod ?k %d)
    %s)
  (assert (count (+ ?k 1))))
"""
        % (n, kinds, cases)
    )
    for t in range(kinds):
        out.append(
            "(defrule r%d (t%d (id ?i) (a ?a) (b ?b) (c k%d) (m x%d $?r) (d ?d)) =>\n"
            "  (bind ?*sum* (+ ?*sum* ?a ?b ?d (length$ ?r))) (bind ?*hit* (+ ?*hit* 1)))\n"
            % (t, t, t % 3, t)
        )
    out.append(report_rule("seq", "sum", "hit"))
    return "".join(out)


def chain(n):
    """A cycle of 8 rules, each firing asserting what the next matches, 4 tokens in flight."""
    stages = 8
    out = [defglobals("laps", "h")]
    out += ["(deftemplate s%d (slot id) (slot lap) (slot v))\n" % s for s in range(stages)]
    out.append("(deffacts start %s)\n" % " ".join("(s0 (id %d) (lap 0) (v %d))" % (t, t) for t in range(4)))
    for s in range(stages):
        nxt = (s + 1) % stages
        lap = "(+ ?l 1)" if nxt == 0 else "?l"
        guard = "&:(< ?l %d)" % (n // 4) if s == 0 else ""
        out.append(
            "(defrule st%d ?f <- (s%d (id ?i) (lap ?l%s) (v ?v)) =>\n"
            "  (retract ?f) (bind ?*h* (mod (+ (* ?*h* %d) ?v ?i) 1000003))\n"
            "  (assert (s%d (id ?i) (lap %s) (v (mod (+ ?v %d) 97)))))\n"
            % (s, s, guard, 3 + s * 2, nxt, lap, s + 1)
        )
    out.append("(defrule lap (declare (salience 5)) (s0 (id 0) (lap ?l&~0)) => (bind ?*laps* (+ ?*laps* 1)))\n")
    out.append(report_rule("laps", "h"))
    return "".join(out)


def manypat(n):
    """Rules of 6-10 patterns over the same 48 facts at every size; ticks re-join them."""
    rnd = lcg(237)
    facts = []
    for rel in "abcdefgh":
        seen = set()
        while len(seen) < 6:
            seen.add((next(rnd) % 6, next(rnd) % 6))
        facts += ["(%s %d %d)" % (rel, x, y) for x, y in sorted(seen)]
    return (
        defglobals("p6", "p8", "p10", "ticks")
        + "(deffacts data %s (tick 0))\n" % " ".join(facts)
        + """(defrule p6 (tick ?t) (a ?x1 ?x2) (b ?x2 ?x3) (c ?x3 ?x4) (d ?x4 ?x5) (e ?x5 ?x1) =>
  (bind ?*p6* (+ ?*p6* 1)))
(defrule p8 (a ?x1 ?x2) (b ?x2 ?x3) (c ?x3 ?x4) (d ?x4 ?x5) (e ?x5 ?x6) (f ?x6 ?x7) (g ?x7 ?x1) (tick ?t) =>
  (bind ?*p8* (+ ?*p8* ?t)))
(defrule p10 (tick ?t) (a ?x1 ?x2) (h ?x2 ?x1) (b ?x2 ?x3) (c ?x3 ?x4&~?x1) (d ?x4 ?x5) (f ?x5 ?x6)
  (g ?x6 ?x7) (h ?x7 ?x8) (e ?x8 ?x9&:(< ?x9 4)) =>
  (bind ?*p10* (+ ?*p10* 1)))
(defrule tick (declare (salience -10)) ?f <- (tick ?t&:(< ?t %d)) =>
  (retract ?f) (bind ?*ticks* (+ ?*ticks* 1)) (assert (tick (+ ?t 1))))
"""
        % n
        + report_rule("p6", "p8", "p10", "ticks")
    )


def testarith(n):
    """`test` CEs with arithmetic over variables of three joined patterns."""
    rnd = lcg(n + 41)
    asserts = ["(assert (pt (id %d) (x %d) (y %d)))" % (i, next(rnd) % 50, next(rnd) % 50) for i in range(n)]
    asserts += ["(assert (w %d %d))" % (i, next(rnd) % 9 + 1) for i in range(n // 2)]
    return (
        defglobals("tri", "near", "f")
        + "(deftemplate pt (slot id) (slot x) (slot y))\n"
        + "(defrule init => %s)\n" % "\n  ".join(asserts)
        + """(defrule near (pt (id ?i) (x ?x1) (y ?y1)) (pt (id ?j&:(> ?j ?i)) (x ?x2) (y ?y2))
  (test (< (+ (* (- ?x1 ?x2) (- ?x1 ?x2)) (* (- ?y1 ?y2) (- ?y1 ?y2))) 40)) =>
  (bind ?*near* (+ ?*near* 1)))
(defrule tri (pt (id ?i) (x ?a)) (w ?i ?k) (pt (id ?j&:(> ?j ?i)) (x ?b))
  (test (= (mod (+ ?a (* ?b ?k) (max ?a ?b)) 13) 0))
  (test (or (> (/ ?a ?k) 2.5) (< (min ?b ?k) 3))) =>
  (bind ?*tri* (+ ?*tri* 1)))
(defrule f (pt (id ?i) (x ?x) (y ?y)) (test (> (float (+ ?x ?y)) (* 1.5 (abs (- ?x ?y))))) =>
  (bind ?*f* (+ ?*f* 1)))
"""
        + report_rule("tri", "near", "f")
    )


def fmtout(n):
    """printout-heavy firings: format with widths, precisions, %e/%g/%x/%o, and crlf."""
    return (
        """(deffacts start (count 1))
(defrule step ?f <- (count ?k&:(<= ?k %d)) =>
  (retract ?f)
  (bind ?v (/ (* ?k 7.25) 3))
  (printout t (format nil "%%-6d|%%8.3f|%%10s|%%-5s|" ?k ?v (sym-cat n ?k) (str-cat "s" (mod ?k 9))) crlf)
  (format t "%%4d %%e %%g %%x %%o%%n" (mod ?k 1000) ?v (* ?v 1000) ?k ?k)
  (printout t "k=" ?k " v=" ?v " half=" (/ ?k 2) " int=" (integer ?v) tab "end" crlf)
  (assert (count (+ ?k 1))))
"""
        % n
    )


def mfslot(n):
    """Multislot templates changed by modify with replace$, insert$, subseq$, create$."""
    rnd = lcg(n + 43)
    asserts = [
        "(assert (queue (id %d) (items %s)))"
        % (q, " ".join(COLORS[next(rnd) % len(COLORS)] for _ in range(4 + q % 4)))
        for q in range(8)
    ]
    return (
        defglobals("rot", "red", "sum", "len")
        + "(deftemplate queue (slot id) (slot n (default 0)) (multislot items))\n"
        + "(defrule init => %s)\n" % "\n  ".join(asserts)
        + """(defrule rotate ?q <- (queue (id ?i) (n ?n&:(< ?n %d)) (items ?first $?rest)) =>
  (bind ?*rot* (+ ?*rot* 1))
  (bind ?new (create$ ?rest ?first))
  (if (> (length$ ?new) 9) then (bind ?new (subseq$ ?new 2 (length$ ?new))))
  (if (= (mod ?n 5) 0) then (bind ?new (insert$ ?new 2 (nth$ (+ 1 (mod ?n 7)) (create$ red green blue yellow black white plum)))))
  (if (member$ plum ?new) then (bind ?new (replace$ ?new (member$ plum ?new) (member$ plum ?new) red)))
  (modify ?q (n (+ ?n 1)) (items ?new)))
(defrule red-head (declare (salience 5)) (queue (id ?i) (items red $?)) => (bind ?*red* (+ ?*red* 1)))
(defrule text (declare (salience 5)) (queue (id ?i) (n ?n&:(= (mod ?n 10) 0)) (items $?all)) =>
  (bind ?s (implode$ ?all))
  (bind ?*len* (+ ?*len* (str-length ?s) (length$ (explode$ ?s)))))
(defrule middle (declare (salience 5)) (queue (id ?i) (items ? ?x $? ?x ?)) => (bind ?*sum* (+ ?*sum* ?i)))
"""
        % (n // 8)
        + report_rule("rot", "red", "sum", "len")
    )


def strfun(n):
    """String and symbol functions in patterns: str-compare, str-index, upcase, sym-cat."""
    rnd = lcg(n + 47)
    syll = ["ka", "lo", "mi", "ne", "ro", "su", "ta", "vi"]
    asserts = []
    for i in range(n):
        w = "".join(syll[next(rnd) % 8] for _ in range(2 + next(rnd) % 3))
        asserts.append('(assert (word %d "%s" %s))' % (i, w, w))
    return (
        defglobals("cmp", "idx", "up", "sym", "sub")
        + "(defrule init => %s)\n" % "\n  ".join(asserts)
        + """(defrule cmp (word ?i ?s ?) (word ?j&:(= ?j (+ ?i 1)) ?t&:(> (str-compare ?s ?t) 0) ?) =>
  (bind ?*cmp* (+ ?*cmp* 1)))
(defrule idx (word ?i ?s&:(str-index "ro" ?s) ?) => (bind ?*idx* (+ ?*idx* (str-index "ro" ?s))))
(defrule up (word ?i ?s ?y&:(eq (upcase ?y) (sym-cat (upcase (sub-string 1 2 ?s)) (upcase (sub-string 3 (str-length ?s) ?s))))) =>
  (bind ?*up* (+ ?*up* 1)))
(defrule sym (word ?i ?s ?y) (test (eq (sym-cat ?y -x) (string-to-field (str-cat ?s "-x")))) =>
  (bind ?*sym* (+ ?*sym* 1)))
(defrule sub (word ?i ?s ?) (word ?j&~?i ?t&:(eq (sub-string 1 4 ?s) (sub-string 1 4 ?t)) ?) =>
  (bind ?*sub* (+ ?*sub* 1)))
"""
        + report_rule("cmp", "idx", "up", "sym", "sub")
    )


def longmod(n):
    """A 14-slot template modified in 12 slots at a time by a pipeline of stage rules."""
    slots = ["a", "b", "c", "d", "e", "f", "g", "h", "i", "j", "k", "l"]
    tmpl = " ".join("(slot %s (default 0))" % s for s in slots)
    out = [defglobals("laps", "h")]
    out.append("(deftemplate part (slot id) (slot stage (default 0)) %s (slot lap (default 0)))\n" % tmpl)
    out.append("(deffacts start %s)\n" % " ".join("(part (id %d))" % p for p in range(6)))
    for st in range(4):
        binds = " ".join("(%s ?%s)" % (s, s) for s in slots)
        sets = " ".join("(%s (+ ?%s %d))" % (s, s, (k + st) % 5 + 1) for k, s in enumerate(slots))
        guard = "&:(< ?lap %d)" % (n // 6) if st == 0 else ""
        nxt = (st + 1) % 4
        lap = "(+ ?lap 1)" if nxt == 0 else "?lap"
        out.append(
            "(defrule stage%d ?p <- (part (id ?id) (stage %d) (lap ?lap%s) %s) =>\n"
            "  (modify ?p (stage %d) (lap %s) %s))\n" % (st, st, guard, binds, nxt, lap, sets)
        )
    out.append(
        """(defrule watch (part (id ?id) (stage 2) (a ?a) (l ?l&:(> ?l ?a))) =>
  (bind ?*h* (mod (+ (* ?*h* 31) ?l ?id) 1000003)))
(defrule lapped (part (id ?id) (stage 0) (lap ?lap&~0) (c ?c)) => (bind ?*laps* (+ ?*laps* 1)))
"""
    )
    out.append(report_rule("laps", "h"))
    return "".join(out)


def growforall(n):
    """`forall` and `exists` re-decided as the fact base grows one fact per firing."""
    return (
        defglobals("all", "ex", "none", "add")
        + """(deftemplate item (slot id) (slot grp) (slot ok))
(deffacts start (next 0))
(defrule add ?f <- (next ?k&:(< ?k %d)) =>
  (retract ?f) (bind ?*add* (+ ?*add* 1))
  (assert (item (id ?k) (grp (mod ?k 5)) (ok (if (= (mod ?k 7) 3) then no else yes))))
  (if (= (mod ?k 4) 0) then (assert (check ?k)))
  (assert (next (+ ?k 1))))
(defrule all-ok (check ?c) (forall (item (id ?i&:(< ?i ?c)) (grp 1)) (item (id ?i) (ok yes))) =>
  (bind ?*all* (+ ?*all* 1)))
(defrule some-bad (check ?c) (exists (item (id ?i&:(< ?i ?c)) (ok no))) =>
  (bind ?*ex* (+ ?*ex* 1)))
(defrule none-grp (check ?c) (not (item (grp 4) (id ?i&:(> ?i ?c)))) =>
  (bind ?*none* (+ ?*none* 1)))
"""
        % n
        + report_rule("all", "ex", "none", "add")
    )


def mfsort(n):
    """Sorting one list by swaps, `$?p ?x $?m ?y&:(> ?x ?y) $?f` (every pair of fields a
    segmentation), one swap per firing; then the sorted list read by `$?` around a
    variable with a predicate."""
    rnd = lcg(n)
    nums = " ".join(str(next(rnd) % 100) for _ in range(n))
    return (
        defglobals("swaps", "ups")
        + "(defrule init => (assert (v %s)))\n" % nums
        + """(defrule swap ?h <- (v $?p ?x $?m ?y&:(> ?x ?y) $?f) =>
  (retract ?h) (bind ?*swaps* (+ ?*swaps* 1)) (assert (v $?p ?y $?m ?x $?f)))
(defrule up (declare (salience -10)) (v $?a ?x ?y&:(< ?x ?y) $?b) =>
  (bind ?*ups* (+ ?*ups* (length$ ?a))))
(defrule show (declare (salience -20)) (v $?all) => (printout t (length$ ?all) crlf))
"""
        + report_rule("swaps", "ups")
    )


def mfscan(n):
    """Several `$?` in a template's multislot around constants, variables and
    predicates (pairs of rising error codes, rising triples, a repeated field), joined
    with probe facts on an element between two `$?`; the logs asserted by a chain."""
    rnd = lcg(n)
    logs = []
    for i in range(4):
        ev = []
        for _ in range(n):
            r = next(rnd) % 10
            if r < 2:
                ev.append("err %d" % (next(rnd) % 50))
            elif r < 4:
                ev.append("warn")
            else:
                ev.append(str(next(rnd) % 100))
        nums = " ".join(str(next(rnd) % 1000) for _ in range(n // 2))
        logs.append("(log (id %d) (ev %s) (nums %s))" % (i, " ".join(ev), nums))
    probes = " ".join("(probe %d)" % (next(rnd) % 100) for _ in range(n // 2))
    return (
        defglobals("rise", "tri", "rep", "hit", "warns")
        + "(deftemplate log (slot id) (multislot ev) (multislot nums))\n"
        + "(defrule init => (assert %s))\n" % " ".join(logs)
        + "(defrule probes (log (id 3)) => (assert %s))\n" % probes
        + """(defrule rise (log (id ?i) (ev $? err ?c $? err ?d&:(> ?d ?c) $?)) =>
  (bind ?*rise* (+ ?*rise* 1)))
(defrule tri (log (id ?i) (nums $? ?x $? ?y&:(> ?y ?x) $? ?z&:(> ?z ?y) $?)) =>
  (bind ?*tri* (+ ?*tri* 1)))
(defrule rep (log (id ?i) (ev $?a ?x $?b ?x $?)) (test (< (length$ ?b) 3)) =>
  (bind ?*rep* (+ ?*rep* 1)))
(defrule hit (probe ?q) (log (id ?i) (ev $?a ?q $?)) =>
  (bind ?*hit* (+ ?*hit* (length$ ?a))))
(defrule warns (log (id ?i) (ev $? warn ?w&:(neq ?w warn) $? warn $?)) =>
  (bind ?*warns* (+ ?*warns* 1)))
"""
        + report_rule("rise", "tri", "rep", "hit", "warns")
    )


# --- round 5 (branch g7) ----------------------------------------------------------------


def perm(rnd, n):
    """A pseudo-random permutation of 0..n-1 (Fisher-Yates over `lcg`)."""
    p = list(range(n))
    for i in range(n - 1, 0, -1):
        j = next(rnd) % (i + 1)
        p[i], p[j] = p[j], p[i]
    return p


def deepjoin(n):
    """A 7-pattern join chain linked by variables over n facts per relation (one full
    match per start), the relations asserted interleaved so every memory grows."""
    rnd = lcg(n + 7)
    perms = [perm(rnd, n) for _ in range(6)]
    asserts = []
    for i in range(n):
        asserts.append("(assert (e0 %d %d))" % (i, i))
        for k in range(6):
            asserts.append("(assert (e%d %d %d))" % (k + 1, i, perms[k][i]))
        # a dead end per relation: a key nothing else carries
        asserts.append("(assert (e%d %d %d))" % (1 + i % 6, n + i, i))
    return (
        defglobals("full", "odd", "h")
        + "(defrule init => %s)\n" % "\n  ".join(asserts)
        + """(defrule full (e0 ?s ?a) (e1 ?a ?b) (e2 ?b ?c) (e3 ?c ?d) (e4 ?d ?e) (e5 ?e ?f) (e6 ?f ?g) =>
  (bind ?*full* (+ ?*full* 1)) (bind ?*h* (mod (+ (* ?*h* 31) ?g) 1000003)))
(defrule odd (e1 ?a ?b) (e2 ?b ?c) (e3 ?c ?d&:(= (mod ?d 2) 1)) (e4 ?d ?a) =>
  (bind ?*odd* (+ ?*odd* 1)))
"""
        + report_rule("full", "odd", "h")
    )


def skewjoin(n):
    """Joins on a variable whose values are skewed: 7 of 8 items share key 0, so one
    hash bucket holds most facts; the second join variable (the id) decides."""
    asserts = []
    for i in range(n):
        key = 0 if i % 8 else i
        asserts.append("(assert (item %d %d))" % (i, key))
        if i % 3:
            asserts.append("(assert (tag %d %d %s))" % (key, i, COLORS[i % 4]))
    asserts += ["(assert (owner %d o%d))" % (k, k) for k in range(0, n, 8)]
    return (
        defglobals("tagged", "owned", "red", "untagged")
        + "(defrule init => %s)\n" % "\n  ".join(asserts)
        + """(defrule tagged (item ?i ?k) (tag ?k ?i ?c) => (bind ?*tagged* (+ ?*tagged* 1)))
(defrule owned (item ?i ?k) (owner ?k ?o) => (bind ?*owned* (+ ?*owned* 1)))
(defrule red (tag ?k ?i red) (item ?i ?k) (owner ?k ?o) => (bind ?*red* (+ ?*red* 1)))
(defrule untagged (declare (salience -10)) (item ?i ?k) (not (tag ?k ?i ?)) =>
  (bind ?*untagged* (+ ?*untagged* 1)))
"""
        + report_rule("tagged", "owned", "red", "untagged")
    )


def manyexists(n):
    """Eight rules of `exists` on different keys (a slot join, a constant, a
    predicate), decided as offers arrive and re-decided as they are withdrawn."""
    rnd = lcg(n + 3)
    asserts = ["(assert (ask (id %d) (kind k%d) (lvl %d)))" % (i, i % 5, next(rnd) % 10) for i in range(n)]
    asserts += [
        "(assert (offer (id %d) (kind k%d) (lvl %d) (by s%d)))" % (i % n, next(rnd) % 5, next(rnd) % 10, next(rnd) % 4)
        for i in range(3 * n)
    ]
    return (
        defglobals("e1", "e2", "e3", "e4", "e5", "e6", "e7", "e8", "gone")
        + "(deftemplate ask (slot id) (slot kind) (slot lvl))\n"
        + "(deftemplate offer (slot id) (slot kind) (slot lvl) (slot by))\n"
        + "(defrule init => %s (assert (drop 0)))\n" % "\n  ".join(asserts)
        + """(defrule e1 (ask (id ?i)) (exists (offer (id ?i))) => (bind ?*e1* (+ ?*e1* 1)))
(defrule e2 (ask (kind ?k)) (exists (offer (kind ?k) (by s0))) => (bind ?*e2* (+ ?*e2* 1)))
(defrule e3 (ask (id ?i) (kind ?k)) (exists (offer (id ?i) (kind ?k))) => (bind ?*e3* (+ ?*e3* 1)))
(defrule e4 (ask (id ?i) (lvl ?l)) (exists (offer (id ?i) (lvl ?m&:(> ?m ?l)))) => (bind ?*e4* (+ ?*e4* 1)))
(defrule e5 (ask (id ?i) (lvl 3)) (exists (offer (id ?i) (by s1))) => (bind ?*e5* (+ ?*e5* 1)))
(defrule e6 (ask (id ?i)) (exists (offer (id ?i) (by s2) (lvl ?m&:(< ?m 5)))) => (bind ?*e6* (+ ?*e6* 1)))
(defrule e7 (ask (id ?i) (kind k2)) (exists (offer (id ?i) (kind ~k2))) => (bind ?*e7* (+ ?*e7* 1)))
(defrule e8 (ask (id ?i)) (exists (offer (id ?i) (by s3)) (offer (id ?i) (by s0))) => (bind ?*e8* (+ ?*e8* 1)))
(defrule drop (declare (salience -10)) ?d <- (drop ?j) ?o <- (offer (id ?j)) =>
  (retract ?o) (bind ?*gone* (+ ?*gone* 1)))
(defrule next (declare (salience -20)) ?d <- (drop ?j&:(< ?j %d)) =>
  (retract ?d) (assert (drop (+ ?j 2))))
(defrule lost (declare (salience -30)) (ask (id ?i)) (not (offer (id ?i))) =>
  (bind ?*gone* (+ ?*gone* 100)))
"""
        % n
        + report_rule("e1", "e2", "e3", "e4", "e5", "e6", "e7", "e8", "gone")
    )


def rangejoin(n):
    """`test` CEs comparing numbers across joins: windows (lo < v < hi) and near
    pairs, which no hash can serve, over n values."""
    rnd = lcg(n + 11)
    asserts = ["(assert (val %d %d))" % (i, next(rnd) % (4 * n)) for i in range(n)]
    asserts += ["(assert (win %d %d))" % (w, w * 40) for w in range(n // 10)]
    return (
        defglobals("inwin", "near", "chain")
        + "(defrule init => %s)\n" % "\n  ".join(asserts)
        + """(defrule inwin (win ?w ?lo) (val ?i ?v) (test (and (>= ?v ?lo) (< ?v (+ ?lo 40)))) =>
  (bind ?*inwin* (+ ?*inwin* 1)))
(defrule near (val ?i ?a) (val ?j&:(> ?j ?i) ?b) (test (< (abs (- ?a ?b)) 2)) =>
  (bind ?*near* (+ ?*near* 1)))
(defrule chain (val ?i ?a) (val ?j ?b&:(> ?b ?a)) (test (< ?b (+ ?a 3))) (val ?k ?c&:(> ?c ?b))
  (test (< ?c (+ ?b 3))) => (bind ?*chain* (+ ?*chain* 1)))
"""
        + report_rule("inwin", "near", "chain")
    )


def reassert(n):
    """Retract and assert again the same fact content, and asserts of facts already
    present (duplicates: no new fact), as the fact base holds n facts."""
    asserts = ["(assert (data %d %s %d))" % (i, COLORS[i % 7], i * 3) for i in range(n)]
    asserts += ["(assert (rec (id %d) (c %s) (v %d)))" % (i, COLORS[i % 5], i) for i in range(n)]
    return (
        defglobals("dup", "again", "seen")
        + "(deftemplate rec (slot id) (slot c) (slot v))\n"
        + "(defrule init => %s (assert (step 0)))\n" % "\n  ".join(asserts)
        + """(defrule step ?s <- (step ?k&:(< ?k %d)) ?d <- (data ?k ?c ?v) ?r <- (rec (id ?k) (c ?rc) (v ?rv)) =>
  (retract ?s ?d ?r)
  (assert (data ?k ?c ?v))
  (assert (rec (id ?k) (c ?rc) (v ?rv)))
  (assert (data ?k ?c ?v))
  (assert (rec (id (div ?k 2)) (c ?rc) (v (div ?k 2))))
  (assert (data (div ?k 3) ?c (* 3 (div ?k 3))))
  (bind ?*dup* (+ ?*dup* 1))
  (assert (step (+ ?k 1))))
(defrule again (data ?k ?c ?v) (rec (id ?k) (c red)) => (bind ?*again* (+ ?*again* 1)))
(defrule seen (declare (salience -5)) (data ?k&:(= (mod ?k 5) 0) ?c ?v) => (bind ?*seen* (+ ?*seen* 1)))
(defrule zz-count (declare (salience -900)) =>
  (printout t (length$ (find-all-facts ((?f data)) TRUE)) " " (length$ (find-all-facts ((?f rec)) TRUE)) crlf))
"""
        % n
        + report_rule("dup", "again", "seen")
    )


def wideglobal(n):
    """A 20-slot template; rules test one slot each against a global (in a pattern
    predicate and in a `test` CE) while right-hand sides move the globals."""
    rnd = lcg(n + 17)
    slots = ["s%d" % i for i in range(20)]
    asserts = [
        "(assert (w (id %d) %s))" % (i, " ".join("(%s %d)" % (s, next(rnd) % 100) for s in slots))
        for i in range(n)
    ]
    rules = []
    for r in range(10):
        s = slots[2 * r + 1]
        if r % 2:
            rules.append(
                "(defrule g%d (w (id ?i) (%s ?v&:(> ?v ?*t%d*))) => (bind ?*c%d* (+ ?*c%d* 1)) (bind ?*t%d* (mod (+ ?*t%d* 7) 100)))\n"
                % (r, s, r, r, r, (r + 1) % 10, (r + 1) % 10)
            )
        else:
            rules.append(
                "(defrule g%d (w (id ?i) (%s ?v) (s0 ?z)) (test (< ?v (+ ?*t%d* ?z))) => (bind ?*c%d* (+ ?*c%d* 1)))\n"
                % (r, s, r, r, r)
            )
    return (
        defglobals(*(["t%d" % r for r in range(10)] + ["c%d" % r for r in range(10)]))
        + "(deftemplate w (slot id) %s)\n" % " ".join("(slot %s)" % s for s in slots)
        + "(defrule init => (bind ?*t1* 50) (bind ?*t4* 30) %s)\n" % "\n  ".join(asserts)
        + "".join(rules)
        + report_rule(*["c%d" % r for r in range(10)])
    )


def bigagenda(n):
    """Thousands of activations pending at once over 9 saliences; firings add more
    at every salience, so each insertion lands in a large agenda."""
    sal = [-40, -30, -20, -10, 0, 10, 20, 30, 40]
    asserts = ["(assert (p %d))" % i for i in range(n)]
    rules = []
    for k, s in enumerate(sal):
        rules.append(
            "(defrule r%d (declare (salience %d)) (p ?i&:(<> (mod ?i 9) %d)) => (bind ?*h* (mod (+ (* ?*h* 31) ?i %d) 1000003))%s)\n"
            % (k, s, k, k, " (assert (q ?i))" if k == 8 else "")
        )
    rules.append(
        "(defrule q1 (declare (salience 35)) (q ?i&:(= (mod ?i 3) 0)) => (bind ?*h* (mod (+ (* ?*h* 7) ?i) 1000003)))\n"
        "(defrule q2 (declare (salience -35)) (q ?i) => (bind ?*q* (+ ?*q* 1)))\n"
    )
    return (
        defglobals("h", "q")
        + "(defrule init (declare (salience 100)) => %s)\n" % "\n  ".join(asserts)
        + "".join(rules)
        + report_rule("h", "q")
    )


def heldmod(n):
    """`modify` of facts that many rules' joins hold: each object is joined by 8
    rules (with refs, tags, a control fact and each other); a walk modifies them."""
    asserts = []
    for i in range(n):
        asserts.append("(assert (obj (id %d) (grp %d) (val 0)))" % (i, i % 10))
        asserts.append("(assert (ref %d %d))" % (i, (i * 7) % n))
        asserts.append("(assert (tag %d %s))" % (i, COLORS[i % 3]))
    return (
        defglobals("h", "m")
        + "(deftemplate obj (slot id) (slot grp) (slot val))\n"
        + "(defrule init => %s (assert (walk 0)) (assert (mode on)))\n" % "\n  ".join(asserts)
        + """(defrule walk ?w <- (walk ?k&:(< ?k %d)) ?o <- (obj (id ?k) (val ?v)) =>
  (retract ?w) (modify ?o (val (+ ?v 1))) (bind ?*m* (+ ?*m* 1)) (assert (walk (+ ?k 1))))
(defrule h1 (obj (id ?i) (val 1)) (ref ?i ?j) (obj (id ?j) (val ?w)) => (bind ?*h* (mod (+ (* ?*h* 3) ?i ?w) 1000003)))
(defrule h2 (obj (id ?i) (grp ?g)) (tag ?i red) (mode on) => (bind ?*h* (mod (+ ?*h* ?g) 1000003)))
(defrule h3 (obj (id ?i) (grp ?g) (val ?v&:(> ?v 0))) (tag ?i ~blue) => (bind ?*h* (mod (+ (* ?*h* 5) ?i) 1000003)))
(defrule h4 (mode on) (obj (id ?i) (val ?v)) (not (tag ?i blue)) (ref ?i ?j&:(> ?j ?i)) => (bind ?*h* (mod (+ ?*h* ?j) 1000003)))
(defrule h5 (obj (id ?i) (grp 3) (val ?v)) (ref ?j ?i) => (bind ?*h* (mod (+ (* ?*h* 7) ?j) 1000003)))
(defrule h6 (obj (id ?i) (val ?v)) (exists (ref ?i ?)) (tag ?i green) => (bind ?*h* (mod (+ ?*h* 11) 1000003)))
(defrule h7 (obj (id ?i) (val 0)) (ref ?i ?j) => (bind ?*h* (mod (+ ?*h* 13) 1000003)))
(defrule h8 (obj (id ?i) (grp ?g) (val ?v)) (obj (id ?j&:(= ?j (+ ?i 1))) (grp ?g2) (val ?v)) => (bind ?*h* (mod (+ ?*h* ?g2) 1000003)))
"""
        % n
        + report_rule("h", "m")
    )


def mfgrow(n):
    """A multislot grown by one element per firing (modify with create$), matched by
    `$?` patterns around constants and variables against the growing list."""
    return (
        defglobals("a", "b", "c", "d")
        + "(deftemplate hist (slot id) (multislot xs))\n"
        + "(defrule init => (assert (hist (id 1))) (assert (hist (id 2))) (assert (want 3)) (assert (want 17)))\n"
        + """(defrule grow ?h <- (hist (id ?id) (xs $?x&:(< (length$ ?x) %d))) =>
  (modify ?h (xs (create$ $?x (mod (+ (* (length$ ?x) 7) ?id) 23)))))
(defrule has-want (hist (id ?id) (xs $? ?w $?)) (want ?w) => (bind ?*a* (+ ?*a* 1)))
(defrule ends (hist (id ?id) (xs ?f $? ?l&:(> ?l ?f))) => (bind ?*b* (+ ?*b* 1)))
(defrule last-two (hist (xs $? ?x ?x)) => (bind ?*c* (+ ?*c* 1)))
(defrule zero (hist (id 2) (xs $?p 0 $?)) => (bind ?*d* (+ ?*d* (length$ ?p))))
"""
        % n
        + report_rule("a", "b", "c", "d")
    )


def queryjoin(n):
    """Fact-set queries over two variables whose test compares slots of both (an audit
    of n employees against departments and against each other), run by a rule per
    round from a deffunction."""
    rnd = lcg(n + 23)
    asserts = [
        "(assert (emp (id %d) (dept %d) (pay %d) (age %d)))"
        % (i, i % 10, 1000 + next(rnd) % 8000, 20 + next(rnd) % 45)
        for i in range(n)
    ]
    asserts += ["(assert (dept (id %d) (cap %d)))" % (d, 3000 + next(rnd) % 5000) for d in range(10)]
    return (
        defglobals("over", "pairs")
        + "(deftemplate emp (slot id) (slot dept) (slot pay) (slot age))\n"
        + "(deftemplate dept (slot id) (slot cap))\n"
        + "(defrule init => %s (assert (round 30)))\n" % "\n  ".join(asserts)
        + """(deffunction audit (?limit)
  (do-for-all-facts ((?e emp) (?d dept)) (and (= ?e:dept ?d:id) (> ?e:pay ?d:cap) (< ?e:age ?limit))
    (bind ?*over* (+ ?*over* 1)))
  (do-for-all-facts ((?a emp) (?b emp)) (and (= ?a:dept ?b:dept) (< ?a:age ?b:age) (> ?a:pay ?b:pay))
    (bind ?*pairs* (+ ?*pairs* 1))))
(defrule round ?r <- (round ?k&:(<= ?k 60)) => (retract ?r) (audit ?k) (assert (round (+ ?k 10))))
"""
        + report_rule("over", "pairs")
    )


def modrules(n):
    """Five modules of n rules each (constant tests on a kind), focused in turn;
    jobs pass through every module, one rule per module matching each."""
    mods = ["M%d" % m for m in range(5)]
    jobs = 200
    out = [
        "(defmodule MAIN (export ?ALL))\n",
        "(deftemplate job (slot id) (slot kind) (slot stage (default 0)))\n",
        "(defglobal ?*h* = 0 ?*n* = 0)\n",
        "(defrule init => %s (assert (round 0)))\n"
        % " ".join("(assert (job (id %d) (kind k%d)))" % (i, (i * 37) % n) for i in range(jobs)),
        "(defrule next ?r <- (round ?k&:(< ?k 3)) => (retract ?r) (assert (round (+ ?k 1))) (focus %s))\n"
        % " ".join(mods),
        "(defrule zz-report (declare (salience -1000)) => (printout t ?*h* \" \" ?*n* crlf))\n",
    ]
    for m, mod in enumerate(mods):
        out.append("(defmodule %s (import MAIN ?ALL))\n" % mod)
        for r in range(n):
            out.append(
                "(defrule %s::r%d ?j <- (job (id ?i) (kind k%d) (stage %d)) (round ?k) =>"
                " (bind ?*n* (+ ?*n* 1)) (bind ?*h* (mod (+ (* ?*h* %d) ?i %d) 1000003)) (modify ?j (stage %d)))\n"
                % (mod, r, r, m + 5 * 0, 3 + m, r, (m + 1) % 5)
            )
    return "".join(out)


SHAPES = {
    "mfwild": (mfwild, [100, 400, 1600]),
    "testce": (testce, [30, 60, 120]),
    "deffunc": (deffunc, [200, 800, 3200]),
    "modify": (modify, [400, 1600, 6400]),
    "existsforall": (existsforall, [50, 200, 800]),
    "strout": (strout, [200, 800, 3200]),
    "factquery": (factquery, [50, 200, 800]),
    "salience": (salience, [500, 2000, 8000]),
    "ordered": (ordered, [200, 800, 3200]),
    "deffacts": (deffacts, [1000, 4000, 16000]),
    "countdown": (countdown, [1000, 4000, 16000]),
    "agenda": (agenda, [50, 200, 800]),
    # round 2
    "logical": (logical, [100, 400, 1600]),
    "modules": (modules, [100, 400, 1600]),
    "lex": (strategy("lex"), [50, 200, 800, 1600]),
    "mea": (strategy("mea"), [50, 200, 800, 1600]),
    "breadth": (strategy("breadth"), [50, 200, 800]),
    "orce": (orce, [100, 400, 1600]),
    "notand": (notand, [100, 400, 1600]),
    "mflist": (mflist, [200, 800, 3200]),
    "strbuild": (strbuild, [100, 200, 400]),
    "partials": (partials, [100, 400, 1600]),
    "widemod": (widemod, [400, 1600, 6400]),
    "dftest": (dftest, [200, 800, 3200]),
    "nestquery": (nestquery, [50, 150, 450]),
    # round 4 (p35)
    "recurse": (recurse, [100, 400, 1600]),
    "rhsloop": (rhsloop, [250, 1000, 4000]),
    "globals": (globals_, [100, 300, 900]),
    "dynsal": (dynsal, [50, 200, 600]),
    "assertstr": (assertstr, [100, 400, 1600]),
    "defaults": (defaults, [250, 1000, 4000]),
    "chain": (chain, [200, 800, 3200]),
    "manypat": (manypat, [50, 200, 800]),
    "testarith": (testarith, [30, 60, 120]),
    "fmtout": (fmtout, [100, 400, 1600]),
    "mfslot": (mfslot, [200, 800, 3200]),
    "strfun": (strfun, [50, 100, 200]),
    "longmod": (longmod, [120, 480, 1920]),
    "growforall": (growforall, [50, 200, 800]),
    # several `$?` in one multislot (branch p34)
    "mfsort": (mfsort, [8, 16, 24, 32]),
    "mfscan": (mfscan, [10, 20, 40, 80]),
    # round 5 (g7)
    "deepjoin": (deepjoin, [100, 200, 400, 800]),
    "skewjoin": (skewjoin, [100, 200, 400, 800]),
    "manyexists": (manyexists, [50, 100, 200, 400]),
    "rangejoin": (rangejoin, [50, 100, 200, 400]),
    "reassert": (reassert, [100, 200, 400, 800]),
    "wideglobal": (wideglobal, [50, 100, 200, 400]),
    "bigagenda": (bigagenda, [100, 200, 400, 800]),
    "heldmod": (heldmod, [50, 100, 200, 400]),
    "mfgrow": (mfgrow, [25, 50, 100, 200]),
    "modrules": (modrules, [10, 20, 40, 80]),
    # session 22: two-variable fact-set queries
    "queryjoin": (queryjoin, [50, 100, 200, 400]),
}


def emit(out_dir, only, sizes_=None):
    """Rows in SHAPES order, or in the order `only` names the shapes."""
    rows = []
    unknown = [name for name in only or [] if name not in SHAPES]
    if unknown:
        raise SystemExit("unknown shapes: %s" % " ".join(unknown))
    for name in dict.fromkeys(only or SHAPES):
        make, sizes = SHAPES[name]
        for size in sizes_ or sizes:
            row = "%s-%d" % (name, size)
            d = os.path.join(out_dir, row)
            os.makedirs(d, exist_ok=True)
            program = os.path.join(d, "program.clp")
            with open(program, "w") as f:
                f.write(make(size))
            # relative to the row's directory (every engine runs there): the same text,
            # so the same symbol arena layout, for every DIR and every size (see below)
            for phase, run in (("full", "(run)\n"), ("norun", "")):
                with open(os.path.join(d, phase + ".bat.clp"), "w") as f:
                    f.write('(load* "program.clp")\n(reset)\n%s(exit)\n' % run)
            rows.append((name, size, d))
    return rows


# --- measuring --------------------------------------------------------------------------


def callgrind_run(cmd, cwd):
    """(instructions, stdout, stderr) of one run under callgrind."""
    res = subprocess.run(
        ["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null"] + cmd,
        cwd=cwd, capture_output=True, text=True, timeout=3600,
    )
    found = re.search(r"Collected : (\d+)", res.stderr)
    if not found:
        raise RuntimeError("no callgrind count for %s: %s" % (cmd, res.stderr[-500:]))
    return int(found.group(1)), res.stdout, res.stderr


def callgrind(cmd, cwd):
    return callgrind_run(cmd, cwd)[0]


def plain(cmd, cwd):
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=600).stdout


def build_c64(scratch):
    """The C driver of clipspy's library; None when python, clipspy or gcc is missing."""
    try:
        info = subprocess.run(
            ["python3", "-c",
             "import sys, sysconfig, clips._clips as c; print(c.__file__); "
             "print(sysconfig.get_config_var('LIBDIR')); print(sysconfig.get_config_var('LDVERSION'))"],
            capture_output=True, text=True, check=True,
        ).stdout.split()
        so, libdir, ldversion = info
        exe = os.path.join(scratch, "c64run")
        subprocess.run(
            ["gcc", "-O2", '-DCLIPS_SO="%s"' % so, "-o", exe, os.path.join(HERE, "c64run.c"),
             "-ldl", "-L" + libdir, "-Wl,--no-as-needed", "-lpython" + ldversion,
             "-Wl,-rpath," + libdir],
            check=True,
        )
        build_c64.so = so
        return exe
    except (subprocess.CalledProcessError, OSError, ValueError) as err:
        print("no CLIPS 6.4 driver: %s" % err, file=sys.stderr)
        return None


def fired_watch(d):
    """Rules fired in the run by CLIPS 6.30's FIRE lines (when there is no 6.4 driver)."""
    batch = os.path.join(d, "watch.bat.clp")
    with open(batch, "w") as f:
        f.write('(load* "%s")\n(reset)\n(watch rules)\n(run)\n(exit)\n' % os.path.join(d, "program.clp"))
    out = plain(["clips", "-f2", batch], d)
    return sum(1 for line in out.splitlines() if line.startswith("FIRE"))


# --- cache of the CLIPS figures ---------------------------------------------------------


def file_digest(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def engine_ids(c64):
    """What makes a CLIPS engine's counts what they are: its binaries, its driver, valgrind."""
    vg = subprocess.run(["valgrind", "--version"], capture_output=True, text=True).stdout.strip()
    clips = shutil.which("clips") or "clips"
    ids = {"6.30": {"valgrind": vg, "clips": file_digest(os.path.realpath(clips))}}
    # The 6.30 binary is a small front end; the engine is its shared library.
    try:
        ldd = subprocess.run(["ldd", clips], capture_output=True, text=True).stdout
        lib = re.search(r"libclips\S*\s+=>\s+(\S+)", ldd)
        if lib:
            ids["6.30"]["libclips"] = file_digest(os.path.realpath(lib.group(1)))
    except OSError:
        pass
    if c64:
        ids["6.4.2"] = {"valgrind": vg, "so": file_digest(build_c64.so),
                        "driver": file_digest(os.path.join(HERE, "c64run.c"))}
    ids["fired"] = ids.get("6.4.2", ids["6.30"])
    return ids


class Cache:
    """CLIPS 6.30 and 6.4.2 results (deterministic) as one small JSON file per row and
    engine, named by a hash of the engine's identity, the program text and the batch
    texts. The emit directory's path is replaced by a placeholder before hashing, so the
    cache serves any DIR (the count differs from a run in another DIR by the few
    instructions of reading a longer or shorter path). Written as a temporary file then
    renamed, so processes sharing the directory never read half a file."""

    def __init__(self, path, ids):
        self.path = path
        self.ids = ids
        self.hits = self.misses = 0
        self.lock = threading.Lock()
        if path:
            os.makedirs(path, exist_ok=True)

    def key(self, label, d):
        texts = []
        for name in ("program.clp", "full.bat.clp", "norun.bat.clp"):
            with open(os.path.join(d, name)) as f:
                text = f.read().replace(d, "@DIR@")
            # `emit`'s relative load path: the key of the same batch with DIR's path,
            # so entries made before `emit` wrote relative paths still serve
            texts.append(text.replace('(load* "program.clp")', '(load* "@DIR@/program.clp")'))
        blob = json.dumps([label, self.ids[label], texts], sort_keys=True)
        return hashlib.sha256(blob.encode()).hexdigest()

    def get(self, label, d, compute):
        if not self.path:
            return compute()
        key = self.key(label, d)
        file = os.path.join(self.path, "%s-%s-%s.json" % (os.path.basename(d), label, key[:24]))
        try:
            with open(file) as f:
                entry = json.load(f)
            if entry.get("key") == key:
                with self.lock:
                    self.hits += 1
                return entry["result"]
        except (OSError, ValueError, KeyError):
            pass
        result = compute()
        entry = {"key": key, "engine": label, "row": os.path.basename(d), "dir": d,
                 "ids": self.ids[label], "result": result}
        fd, tmp = tempfile.mkstemp(dir=self.path, prefix=".tmp-", suffix=".json")
        with os.fdopen(fd, "w") as f:
            json.dump(entry, f, indent=1, sort_keys=True)
        os.replace(tmp, file)
        with self.lock:
            self.misses += 1
        return result


STATISTICS = re.compile(
    r"^(\d+ rules fired.*|\d+ mean number of .*|Run time is .*|[\d.]+ rules per second.*)$")


def text_summary(stdout, strip_statistics=False):
    if strip_statistics:
        stdout = "\n".join(line for line in stdout.splitlines() if not STATISTICS.match(line.strip()))
    text = stdout.strip()
    return {"sha256": hashlib.sha256(text.encode()).hexdigest(), "tail": text[-80:]}


def growth_table(results):
    """Instructions per firing (run phase) at the largest size over the smallest, per engine."""
    print()
    print("| shape | sizes | fired | 6.30 growth | 6.4.2 growth | ours growth | ours / better CLIPS growth |")
    print("|---|---|---|---|---|---|---|")
    by_shape = {}
    for name, size, fired, runs in results:
        by_shape.setdefault(name, []).append((size, fired, runs))
    for name, rows in by_shape.items():
        rows.sort()
        if len(rows) < 2:
            continue
        (s0, f0, r0), (s1, f1, r1) = rows[0], rows[-1]
        grow = {}
        for label in r0:
            small = r0[label] / max(f0, 1)
            grow[label] = (r1[label] / max(f1, 1)) / max(small, 1e-9)
        best = min(v for k, v in grow.items() if k != "ours")
        print(
            "| %s | %d-%d | %d-%d | %.2f | %s | %.2f | %.2f |"
            % (name, s0, s1, f0, f1, grow["6.30"],
               "%.2f" % grow["6.4.2"] if "6.4.2" in grow else "-", grow["ours"], grow["ours"] / best),
            flush=True,
        )


def watches_statistics(d):
    with open(os.path.join(d, "full.bat.clp")) as f:
        return "(watch statistics)" in f.read()


def measure_row(d, engines, c64, cache):
    runs, wholes, texts = {}, {}, {}
    fired = None
    strip = watches_statistics(d)
    for label, cmd in engines:
        def compute(cmd=cmd):
            full, out, err = callgrind_run(cmd(d, "full"), d)
            norun = callgrind(cmd(d, "norun"), d)
            result = {"run": full - norun, "whole": full, "output": text_summary(out, strip)}
            found = re.search(r"fired (\d+)", err)
            if found:
                result["fired"] = int(found.group(1))
            return result

        result = compute() if label == "ours" else cache.get(label, d, compute)
        runs[label], wholes[label] = result["run"], result["whole"]
        # CLIPS 6.30's command loop echoes nothing in -f2; compare the printed text.
        texts[label] = result["output"]
        if label == "6.4.2":
            fired = result.get("fired")
    if fired is None:
        fired = cache.get("fired", d, lambda: fired_watch(d))
    return fired, runs, wholes, texts


def format_row(name, size, fired, runs, wholes, texts):
    same = len(set(t["sha256"] for t in texts.values())) == 1
    best_run = min(v for k, v in runs.items() if k != "ours")
    best_whole = min(v for k, v in wholes.items() if k != "ours")
    fmt = lambda v: "%.2f M" % (v / 1e6)
    return "| %s | %d | %d | %s | %s | %s | %.2f | %s | %s | %s | %.2f | %s |" % (
        name, size, fired, fmt(runs["6.30"]), fmt(runs.get("6.4.2", 0)), fmt(runs["ours"]),
        best_run / max(runs["ours"], 1), fmt(wholes["6.30"]), fmt(wholes.get("6.4.2", 0)),
        fmt(wholes["ours"]), best_whole / max(wholes["ours"], 1),
        "yes" if same else "NO: " + " / ".join("%s %r" % (k, v["tail"]) for k, v in texts.items()))


def ends_first(rows):
    """Row indices: every shape's smallest size, then its largest, then the sizes between,
    so that an interrupted run has what the growth table needs."""
    sizes = {}
    for name, size, _ in rows:
        sizes.setdefault(name, []).append(size)
    rank = lambda name, size: 0 if size == min(sizes[name]) else 1 if size == max(sizes[name]) else 2
    return sorted(range(len(rows)), key=lambda i: (rank(rows[i][0], rows[i][1]), i))


def measure(rows, ours, c64, cache=None, jobs=1, order=None, rows_file=None):
    """Rows are measured by `jobs` workers (started in `order`, default as given); each row
    is printed to stderr as it completes and the table on stdout keeps the rows' order (a
    row as soon as all before it are done). With `rows_file`, each row's exact figures are
    appended to it as one JSON line as soon as the row is done (`table` prints them)."""
    cache = cache or Cache(None, {})
    # Every engine runs in the row's directory with relative file names: a path's length
    # is in no engine's memory layout (ours keeps the load path's text in its symbol
    # arena, so the strings made after it start at other offsets, and checking them as
    # UTF-8 costs per firing with their alignment; SHAPES.md).
    engines = [("6.30", lambda d, p: ["clips", "-f2", p + ".bat.clp"])]
    if c64:
        engines.append(("6.4.2", lambda d, p: [c64, "program.clp"] + ([] if p == "full" else ["norun"])))
    engines.append(("ours", lambda d, p: [ours, "clips", "-f2", p + ".bat.clp"]))
    print("| shape | size | fired | 6.30 run | 6.4.2 run | ours run | run ratio | 6.30 whole | 6.4.2 whole | ours whole | whole ratio | same output |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|", flush=True)
    results, lines = [None] * len(rows), [None] * len(rows)
    printed = 0
    started = time.time()
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(jobs, 1)) as pool:
        futures = {pool.submit(measure_row, rows[i][2], engines, c64, cache): i
                   for i in (order or range(len(rows)))}
        for future in concurrent.futures.as_completed(futures):
            i = futures[future]
            name, size, _ = rows[i]
            try:
                fired, runs, wholes, texts = future.result()
            except (RuntimeError, OSError, subprocess.TimeoutExpired) as err:
                lines[i] = "| %s | %d | failed: %s |" % (name, size, str(err)[:200].replace("\n", " "))
            else:
                results[i] = (name, size, fired, runs)
                lines[i] = format_row(name, size, fired, runs, wholes, texts)
                if rows_file:
                    with open(rows_file, "a") as f:
                        f.write(json.dumps({"shape": name, "size": size, "fired": fired, "runs": runs,
                                            "wholes": wholes, "texts": texts, "ours": ours}) + "\n")
            print("[%5.0f s] %s" % (time.time() - started, lines[i]), file=sys.stderr, flush=True)
            while printed < len(rows) and lines[printed] is not None:
                print(lines[printed], flush=True)
                printed += 1
    growth_table([r for r in results if r])
    if cache.path:
        print("cache %s: %d hits, %d new" % (cache.path, cache.hits, cache.misses), file=sys.stderr)


def table(files):
    """The two tables from JSON lines written by `measure --rows`, in SHAPES order; a row
    measured more than once: its last line."""
    latest = {}
    for path in files:
        with open(path) as f:
            for line in f:
                if line.strip():
                    r = json.loads(line)
                    latest[(r["shape"], r["size"])] = r
    names = list(SHAPES)
    key = lambda k: (names.index(k[0]) if k[0] in names else len(names), k[0], k[1])
    print("| shape | size | fired | 6.30 run | 6.4.2 run | ours run | run ratio | 6.30 whole | 6.4.2 whole | ours whole | whole ratio | same output |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    results = []
    for k in sorted(latest, key=key):
        r = latest[k]
        print(format_row(r["shape"], r["size"], r["fired"], r["runs"], r["wholes"], r["texts"]))
        results.append((r["shape"], r["size"], r["fired"], r["runs"]))
    growth_table(results)


def row_dirs(dirs):
    """(shape, size, dir) of row directories named <shape>-<size>: each of `dirs` is one or
    holds them; sorted by shape, then size."""
    rows = []
    for top in dirs:
        top = os.path.abspath(top)
        if os.path.exists(os.path.join(top, "program.clp")):
            candidates = [top]
        else:
            candidates = [os.path.join(top, n) for n in sorted(os.listdir(top))]
        for d in candidates:
            if not all(os.path.exists(os.path.join(d, n))
                       for n in ("program.clp", "full.bat.clp", "norun.bat.clp")):
                continue
            base = os.path.basename(d)
            found = re.match(r"^(.*)-(\d+)$", base)
            name, size = (found.group(1), int(found.group(2))) if found else (base, 0)
            rows.append((name, size, d))
    if not rows:
        raise SystemExit("no row directories (program.clp, full.bat.clp, norun.bat.clp) in %s" % " ".join(dirs))
    return sorted(rows, key=lambda r: (r[0], r[1]))


def add_measure_options(p):
    """The options `measure` and `measure-dirs` share."""
    p.add_argument("--no-c64", action="store_true")
    p.add_argument("--cache", metavar="CACHE_DIR",
                   help="keep and reuse CLIPS 6.30 and 6.4.2 results here (ours is always measured)")
    p.add_argument("--jobs", type=int, default=1, help="rows measured in parallel")
    p.add_argument("--ends-first", action="store_true",
                   help="start every shape's smallest and largest sizes before the others")
    p.add_argument("--rows", metavar="FILE", help="append each row's exact figures to FILE (JSON lines)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="cmd", required=True)
    e = sub.add_parser("emit")
    e.add_argument("dir")
    e.add_argument("--only", nargs="*")
    e.add_argument("--sizes", nargs="*", type=int, help="these sizes instead of the shape's own")
    m = sub.add_parser("measure")
    m.add_argument("dir")
    m.add_argument("ours")
    m.add_argument("--only", nargs="*")
    m.add_argument("--sizes", nargs="*", type=int, help="these sizes instead of the shape's own")
    add_measure_options(m)
    md = sub.add_parser("measure-dirs", help="measure rows already on disk (e.g. bench --emit-only)")
    md.add_argument("dirs", nargs="+", metavar="DIR")
    md.add_argument("ours")
    add_measure_options(md)
    t = sub.add_parser("table", help="print the tables from `measure --rows` files")
    t.add_argument("files", nargs="+")
    args = parser.parse_args()
    if args.cmd == "table":
        table(args.files)
        return
    if args.cmd == "measure-dirs":
        rows = row_dirs(args.dirs)
    else:
        rows = emit(os.path.abspath(args.dir), args.only, args.sizes)
    if args.cmd in ("measure", "measure-dirs"):
        with tempfile.TemporaryDirectory() as scratch:
            c64 = None if args.no_c64 else build_c64(scratch)
            cache = Cache(os.path.abspath(args.cache) if args.cache else None, engine_ids(c64))
            order = ends_first(rows) if args.ends_first else None
            measure(rows, os.path.abspath(args.ours), c64, cache, args.jobs, order, args.rows)


if __name__ == "__main__":
    main()
