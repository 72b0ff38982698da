#!/usr/bin/env python3
"""Random CLIPS programs that stress activation order through shared alpha nodes and
joins: 1-3 templates (single and multislots) and ordered facts, rules whose patterns come
from a small per-program pool so that they often share prefixes, nodes and joins (slots
left out, `$?`, `$?m`, `?v` inside a multislot, constants, `~c`, `a|b`, `:` tests local and
referring to earlier patterns, shared variables, slots named in other orders, `not`,
`exists`, `test`, `or`, salience), rule files written by the program itself and loaded
under `(watch compilations)` before and after facts exist, then asserts, retracts,
modify, duplicate, agenda listings and runs under `(watch activations)` and
`(watch rules)`. Values are small integers, so no test can fail with an error.
For differential runs against CLIPS 6.30 (order_fuzz.sh).
Usage: order_fuzz.py SEED > program.clp"""
import random
import sys

SINGLE_VARS = ["?x", "?y", "?z"]
MULTI_VARS = ["?m", "?n"]


def gen(seed):
    r = random.Random(seed)
    # templates: name -> list of (slot, is_multi)
    pool_slots = [("x", False), ("y", False), ("m", True), ("z", False), ("k", True)]
    templates = {}
    for t in ["a", "b", "c"][: r.randint(1, 3)]:
        slots = r.sample(pool_slots, r.randint(2, 4))
        if not any(m for _, m in slots) and r.random() < 0.8:
            slots[r.randrange(len(slots))] = ("m", True)
            slots = list(dict.fromkeys(slots))
        templates[t] = slots
    ordered = ["o", "p"]
    out = []
    for t, slots in templates.items():
        out.append(f"(deftemplate {t} " + " ".join(
            f"(multislot {s})" if m else f"(slot {s} (default 0))" for s, m in slots) + ")")

    def val():
        return str(r.randint(1, 3))

    # ---- patterns -------------------------------------------------------------------
    def single_constraint(bound_here, bound):
        """constraint text for a single-field slot, and the variables it binds"""
        known = sorted(w for w in bound | bound_here if w in SINGLE_VARS)
        p = r.random()
        v = r.choice(SINGLE_VARS)
        if p < 0.3:
            return v, {v}
        if p < 0.45:
            return val(), set()
        if p < 0.52:
            return "~" + val(), set()
        if p < 0.6:
            a, b = r.sample(["1", "2", "3"], 2)
            return f"{a}|{b}", set()
        if p < 0.67:
            return f"{v}&~{val()}", {v}
        if p < 0.75:
            return f"{v}&:(> {v} 1)", {v}
        if p < 0.85 and known:
            w = r.choice(known)
            if w != v:
                return f"{v}&:(>= {v} {w})", {v}
        if p < 0.9 and known:
            w = r.choice(known)
            return f":(> {w} 1)", set()
        if p < 0.95:
            a, b = r.sample(["1", "2", "3"], 2)
            return f"{v}&{a}|{b}", {v}
        return v, {v}

    def multi_constraint(bound_here, bound):
        """list of field constraints for a multislot, the single and multi vars bound"""
        p = r.random()
        v = r.choice(SINGLE_VARS)
        m = r.choice(MULTI_VARS)
        if p < 0.22:
            return ["$?"], set(), set()
        if p < 0.42:
            return [f"$?{m[1:]}"], set(), {m}
        if p < 0.5:
            return [v], {v}, set()
        if p < 0.6:
            return [v, "$?"], {v}, set()
        if p < 0.66:
            return ["$?", v, "$?"], {v}, set()
        if p < 0.72:
            return [val(), "$?"], set(), set()
        if p < 0.76:
            return ["$?", val()], set(), set()
        if p < 0.8:
            return [], set(), set()
        if p < 0.86:
            return [f"$?{m[1:]}&:(> (length$ {m}) {r.randint(0, 2)})"], set(), {m}
        if p < 0.9:
            return [f"{v}&:(> {v} 1)", "$?"], {v}, set()
        if p < 0.95:
            return [f"$?{m[1:]}", v], {v}, {m}
        return [f"~{val()}", "$?"], set(), set()

    def template_pattern(bound):
        t = r.choice(list(templates))
        slots = list(templates[t])
        if r.random() < 0.4:
            r.shuffle(slots)
        parts, sbind, mbind = [], set(), set()
        for s, multi in slots:
            if r.random() < 0.35:
                continue  # left out
            if multi:
                fields, sv, mv = multi_constraint(sbind, bound)
                # a multi var of the same name twice in one pattern is a test: fine
                parts.append(f"({s}" + "".join(" " + f for f in fields) + ")")
                sbind |= sv
                mbind |= mv
            else:
                c, sv = single_constraint(sbind, bound)
                parts.append(f"({s} {c})")
                sbind |= sv
        return f"({t}" + "".join(" " + q for q in parts) + ")", sbind, mbind

    def ordered_pattern(bound):
        v = r.choice(SINGLE_VARS)
        w = r.choice(SINGLE_VARS)
        forms = [
            (f"(o {v} {w})", {v, w}),
            (f"(o {val()} {v})", {v}),
            (f"(o {v} $?)", {v}),
            (f"(o $? {v})", {v}),
            ("(o $?)", set()),
            (f"(o {v}&~{val()} {w})", {v, w}),
            (f"(p {v})", {v}),
            (f"(p {val()})", set()),
            (f"(p ~{val()})", set()),
        ]
        return r.choice(forms) + (set(),)

    def fresh_pattern(bound):
        if r.random() < 0.7:
            return template_pattern(bound)
        return ordered_pattern(bound)

    pool = []
    for _ in range(r.randint(3, 7)):
        pool.append(fresh_pattern(set()))

    def uses(text):
        return {w for w in SINGLE_VARS + MULTI_VARS if w + ")" in text or w + " " in text or w + "&" in text}

    def valid(text, sv, mv, bound_s, bound_m):
        # multi vars are multi everywhere, single ones single everywhere (distinct names);
        # a `:` test may only name variables bound before it (checked when generated for
        # fresh patterns; pool patterns are checked here: every test variable is bound
        # in the pattern itself or before)
        for chunk in text.split(":(")[1:]:
            body = chunk.split(")")[0]
            for w in SINGLE_VARS + MULTI_VARS:
                if w in body.split() or w + ")" in body:
                    if w not in (sv | mv | bound_s | bound_m):
                        return False
        return True

    def pattern(bound_s, bound_m):
        for _ in range(10):
            if r.random() < 0.75:
                text, sv, mv = r.choice(pool)
            else:
                text, sv, mv = fresh_pattern(bound_s | bound_m)
            if valid(text, sv, mv, bound_s, bound_m):
                return text, sv, mv
        return "(p 1)", set(), set()

    def test_ce(bound_s, bound_m):
        if bound_m and (r.random() < 0.4 or not bound_s):
            m = r.choice(sorted(bound_m))
            return f"(test (> (length$ {m}) {r.randint(0, 2)}))"
        vs = sorted(bound_s)
        if len(vs) >= 2 and r.random() < 0.5:
            a, b = r.sample(vs, 2)
            return f"(test (>= {a} {b}))"
        a = r.choice(vs)
        return f"(test (> {a} {r.randint(1, 2)}))"

    def rule(name):
        ces = []
        bs, bm = set(), set()
        for _ in range(r.randint(1, 4)):
            p = r.random()
            if p < 0.62:
                text, sv, mv = pattern(bs, bm)
                ces.append(text)
                bs |= sv
                bm |= mv
            elif p < 0.75:
                text, _, _ = pattern(bs, bm)
                ces.append(f"(not {text})")
            elif p < 0.83:
                text, _, _ = pattern(bs, bm)
                ces.append(f"(exists {text})")
            elif p < 0.9 and (bs or bm):
                ces.append(test_ce(bs, bm))
            elif p < 0.95:
                t1, s1, m1 = pattern(bs, bm)
                t2, s2, m2 = pattern(bs, bm)
                ces.append(f"(or {t1} {t2})")
                # variables bound in both branches are bound after the `or`
                bs |= s1 & s2
                bm |= m1 & m2
            else:
                t1, s1, m1 = pattern(bs, bm)
                t2, _, _ = pattern(bs | s1, bm | m1)
                ces.append(f"(not (and {t1} {t2}))")
        sal = ""
        if r.random() < 0.25:
            sal = f"(declare (salience {r.choice([-5, 5, 10])})) "
        acts = ""
        if r.random() < 0.25:
            if bs:
                acts = f" (assert (p {r.choice(sorted(bs))}))"
            else:
                acts = f" (assert (p {val()}))"
        return f"(defrule {name} {sal}" + " ".join(ces) + " =>" + acts + ")"

    # ---- facts and operations ---------------------------------------------------
    def fact():
        if r.random() < 0.7:
            t = r.choice(list(templates))
            parts = []
            for s, multi in templates[t]:
                if r.random() < 0.15:
                    continue  # default
                if multi:
                    parts.append(f"({s}" + "".join(" " + val() for _ in range(r.randint(0, 3))) + ")")
                else:
                    parts.append(f"({s} {val()})")
            return f"({t}" + "".join(" " + q for q in parts) + ")"
        if r.random() < 0.6:
            return f"(o {val()} {val()})"
        return f"(p {val()})"

    def op():
        p = r.random()
        if p < 0.45:
            return "(assert " + " ".join(fact() for _ in range(r.randint(1, 3))) + ")"
        t = r.choice(list(templates))
        slots = templates[t]
        s, multi = r.choice(slots)
        cond = "TRUE" if r.random() < 0.4 else f"(= (nth$ 1 (create$ ?f:{s} 0)) {val()})"
        if p < 0.6:
            known = [o for o in ordered if any(f"({o} " in line for line in out)]
            if known and r.random() < 0.3:
                # (only once a fact or pattern made the implied template: no error)
                return f"(do-for-fact ((?f {r.choice(known)})) TRUE (retract ?f))"
            return f"(do-for-fact ((?f {t})) {cond} (retract ?f))"
        new = ("(" + s + "".join(" " + val() for _ in range(r.randint(0, 2))) + ")") if multi \
            else f"({s} {val()})"
        if p < 0.8:
            return f"(do-for-fact ((?f {t})) {cond} (modify ?f {new}))"
        if p < 0.9:
            return f"(do-for-fact ((?f {t})) {cond} (duplicate ?f {new}))"
        if p < 0.95:
            return "(agenda)"
        return f"(run {r.randint(1, 3)})"

    names = iter(f"r{k}" for k in range(100))
    files = [0]

    def load_rules(k):
        files[0] += 1
        fname = f"rules{files[0]}.clp"
        lines = [f'(open "{fname}" out "w")']
        for _ in range(k):
            lines.append(f'(printout out "{rule(next(names))}" crlf)')
        lines.append("(close out)")
        comp = r.random() < 0.7
        if comp:
            lines.append("(watch compilations)")
        lines.append(f'(load "{fname}")')
        if comp:
            lines.append("(unwatch compilations)")
        return lines

    if r.random() < 0.5:
        out.append("(deffacts start " + " ".join(fact() for _ in range(r.randint(1, 4))) + ")")
    if r.random() < 0.6:
        out.append("(reset)")
    out.append("(watch activations)")
    out.append("(watch rules)")
    if r.random() < 0.3:
        out.append("(watch facts)")
    total = r.randint(4, 10)
    first = total if r.random() < 0.3 else r.randint(1, total)
    if r.random() < 0.5:
        for _ in range(r.randint(1, 4)):
            out.append(op())
    out += load_rules(first)
    for _ in range(r.randint(2, 8)):
        out.append(op())
    if total > first:
        out += load_rules(total - first)
        for _ in range(r.randint(1, 6)):
            out.append(op())
    out.append("(agenda)")
    out.append("(run 40)")
    if r.random() < 0.4:
        out.append("(reset)")
        out.append("(agenda)")
        out.append("(run 40)")
    out.append("(facts)")
    out.append("(exit)")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    print(gen(int(sys.argv[1])), end="")
