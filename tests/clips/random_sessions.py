#!/usr/bin/env python3
"""Random CLIPS sessions that change the rule base while facts exist: rules defined,
redefined and removed between asserts and runs, tests that can fail on a symbol,
queries in tests, and conflict resolution strategies chosen at the start and changed
between steps (drawn from a generator of their own, so the rest of a seed's session is
what it was before strategies were added). For differential runs against CLIPS 6.30
(random_sessions.sh).
With `modules` after the seed, the session has modules: MAIN exports its templates,
modules A and B import them, rules go into any of the three (some with auto-focus and
actions that focus another module or return), and the stream focuses modules before
runs and lists every module's agenda and facts (drawn from a generator of its own too).
Usage: random_sessions.py SEED [modules] > program.clp"""
import random, sys

def gen(seed, modules=False):
    r = random.Random(seed)
    rm = random.Random(seed * 104723 + 7) if modules else None
    out = (["(defmodule MAIN (export ?ALL))"] if modules else []) + ["(deftemplate ctx (slot s))",
           "(deftemplate cnt (slot c))",
           "(deftemplate it (slot id) (slot v) (slot w))",
           "(deftemplate mk (slot id) (slot v))"]
    vals = ["x", "y", "z"]
    states = ["s0", "s1", "s2"]
    names = [f"r{k}" for k in range(4)]
    counter = [0]

    def pattern():
        p = r.random()
        if p < 0.3:
            counter[0] += 1
            fresh = f"?u{counter[0]}"
            v = r.choice(["?v", fresh + "&" + r.choice(vals), fresh + "&~" + r.choice(vals)])
            w = r.choice(["?w", "?w&:(> ?w 1)", "?w&:(eq ?w 2)", "?w"])
            return f"(it (id ?i) (v {v}) (w {w}))"
        if p < 0.45:
            return f"(ctx (s {r.choice(states + ['?s'])}))"
        if p < 0.6:
            return r.choice(["(cnt (c ?c))", "(cnt (c ?c&:(< ?c 4)))"])
        if p < 0.75:
            return r.choice(["(not (mk (id ?i)))", "(not (mk (v z)))", "(mk (id ?i) (v ?mv))"])
        if p < 0.85:
            return r.choice(["(exists (mk (v x)))", "(test (> ?w 0))", "(test (neq ?v y))"])
        return r.choice(["(test (any-factp ((?k mk)) (eq ?k:v ?v)))",
                         "(it (id ?j&:(any-factp ((?m mk)) (= ?m:id ?j))))"])

    def rule(name):
        ces = []
        bound = set()
        for _ in range(r.randint(1, 4)):
            p = pattern()
            needs = [v for v in ("?i", "?w", "?v", "?c") if v in p and not p.startswith(("(it (id ?i)", "(cnt"))]
            if any(v not in bound for v in needs):
                continue
            ces.append(p)
            if p.startswith("(it (id ?i)"):
                bound |= {"?i", "?w"} | ({"?v"} if "(v ?v)" in p else set())
            if p.startswith("(cnt"):
                bound.add("?c")
        if not ces or ces[0].startswith(("(not", "(test", "(exists")):
            ces.insert(0, "(it (id ?i) (v ?v) (w ?w))")
        acts = []
        if r.random() < 0.5:
            acts.append(f"(printout t \"{name} fired\" crlf)")
        sal = f"(declare (salience {r.randint(-1, 1)})) " if r.random() < 0.3 else ""
        if rm is not None:
            module = rm.choice(["MAIN", "A", "B"])
            if rm.random() < 0.3:
                sal = (sal[:-2] + " (auto-focus TRUE)) ") if sal else "(declare (auto-focus TRUE)) "
            if rm.random() < 0.3:
                acts.append(rm.choice(["(focus A)", "(focus B)", "(focus MAIN)", "(return)"]))
            name = f"{module}::{name}"
        return f"(defrule {name} {sal}" + " ".join(ces) + " => " + " ".join(acts) + ")"

    def fact():
        p = r.random()
        counter[0] += 1
        if p < 0.5:
            w = r.choice([str(r.randint(0, 3)), str(r.randint(0, 3)), "q"])
            return f"(it (id {r.randint(0, 4)}) (v {r.choice(vals)}) (w {w}))"
        if p < 0.7:
            return f"(mk (id {r.randint(0, 4)}) (v {r.choice(vals)}))"
        if p < 0.85:
            return f"(cnt (c {r.choice(['0', '2', '5', 'n'])}))"
        return f"(ctx (s {r.choice(states)}))"

    strategies = ["depth", "breadth", "lex", "mea", "complexity", "simplicity", "random"]
    rs = random.Random(seed * 7919 + 104729)
    if rs.random() < 0.7:
        out.append(f"(set-strategy {rs.choice(strategies)})")

    if rm is not None:
        out += ["(defmodule A (import MAIN ?ALL))", "(defmodule B (import MAIN ?ALL))"]
    if r.random() < 0.5:
        out.append("(watch activations)")
    out.append("(watch rules)")
    for _ in range(r.randint(6, 14)):
        p = r.random()
        if p < 0.35:
            out.append(rule(r.choice(names)))
        elif p < 0.65:
            out.append("(assert " + " ".join(fact() for _ in range(r.randint(1, 3))) + ")")
        elif p < 0.72:
            out.append(f"(undefrule {r.choice(names)})")
        elif p < 0.8:
            out.append(f"(retract {r.randint(1, max(1, counter[0]))})")
        elif p < 0.9:
            out.append(f"(run {r.randint(1, 4)})")
        else:
            out.append("(agenda)")
        if rs.random() < 0.15:
            out.append(f"(set-strategy {rs.choice(strategies)})")
        if rm is not None and rm.random() < 0.2:
            out.append(f"(focus {rm.choice(['A', 'B', 'MAIN', 'B A'])})")
    if rm is not None:
        out += ["(agenda *)", "(focus B A)", "(run)", "(facts *)", "(get-focus-stack)"]
        out.append("(exit)")
        return "\n".join(out) + "\n"
    out.append("(agenda)")
    out.append("(run)")
    out.append("(facts)")
    out.append("(exit)")
    return "\n".join(out) + "\n"

if __name__ == "__main__":
    print(gen(int(sys.argv[1]), len(sys.argv) > 2 and sys.argv[2] == "modules"), end="")
