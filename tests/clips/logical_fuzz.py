#!/usr/bin/env python3
"""One random CLIPS program of logical support over self joins, for a seed.

Rules take `(logical ...)` over one to three patterns of two templates (so most join a
node to itself, and many share their first joins), some with a join test; some rules
are defined after the facts (primed). The facts are asserted, the rules run, then
facts are retracted (now and then another asserted and run) under `watch facts`: the
order of the logical retractions is what is compared (`order_fuzz.sh BIN A B logical`).
Usage: logical_fuzz.py SEED
"""
import random
import sys


def program(seed):
    r = random.Random(seed)
    out = ["(deftemplate a (slot y))", "(deftemplate b (slot y))"]
    rules = []
    for i in range(r.randint(2, 4)):
        n = r.randint(1, 3)
        pats, names = [], []
        for k in range(n):
            names.append("?v%d" % k)
            pats.append("(%s (y %s))" % (r.choice("aab"), names[k]))
        logical = r.randint(1, n)
        lhs = "(logical %s) %s" % (" ".join(pats[:logical]), " ".join(pats[logical:]))
        if n >= 2 and r.random() < 0.4:
            lhs += " (test (<= %s %s))" % (names[0], names[1])
        rules.append("(defrule r%d %s => (assert (s%d %s)))" % (i, lhs, i, " ".join(names)))
    facts = ["(assert (%s (y %d)))" % (r.choice("aab"), r.randint(1, 3)) for _ in range(r.randint(2, 4))]
    before = r.randint(0, len(rules))
    out += rules[:before] + facts + rules[before:]
    out += ["(watch facts)", "(run)"]
    for f in r.sample(range(1, len(facts) + 1), k=min(len(facts), r.randint(1, 3))):
        out.append("(retract %d)" % f)
        if r.random() < 0.3:
            out.append("(assert (%s (y %d)))" % (r.choice("ab"), r.randint(1, 3)))
            out.append("(run)")
    out += ["(facts)", "(exit)"]
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    sys.stdout.write(program(int(sys.argv[1])))
