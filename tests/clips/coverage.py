#!/usr/bin/env python3
"""Coverage of the CLIPS 6.30 Basic Programming Guide by the differential programs.

Usage: tests/clips/coverage.py [--items] [--uncovered-only]

The BPG's items (constructs, conditional elements, constraint attributes, every function
and command of sections 12 and 13 and of Appendix H, the watch items, the seven
strategies, the I/O router's logical names and functions) are listed below as data,
grouped by the section numbers of the 6.30 BPG (March 17th 2015). Objects (COOL,
sections 9, 12.16, 13.11) and generic functions (sections 8, 12.15, 13.10) are left
out, as issue 21 leaves them out; `type` (12.15.4) is kept: it is not COOL's.

Each tests/clips/NNN-*.clp is read with a small CLIPS reader (comments, strings,
nesting) and walked with the meaning of each position: a construct's keyword, a CE in a
rule's conditions (a pattern's own fields are not calls), a call in an expression (also
inside the strings `eval`, `build` and `check-syntax` read, and the function `funcall`
and `sort` call), a `watch` item, a `set-strategy` argument, a logical name given to an
I/O function. A name is an item only where it stands in such a position, so `not` the CE
and `not` the function, or `facts` the command and a fact `(facts 1)`, are told apart.

It prints (a) per BPG section the number of programs using at least one of its items
(every program's frame, `(watch facts)`, `(watch rules)`, `(watch activations)` and
`(exit)`, covers those items but counts no program for its section),
(b) the items no program uses, (c) the items README.md lists as not implemented (with a
check that README names each one). Exit status 1 if an item is uncovered and not
listed as not implemented.
"""
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))

# (section, title, kind, names). kind: construct, ce, rule (rule property), slot (slot
# attribute), attr (constraint attribute), module, strategy, watch, lname (logical
# name), mode (`open`'s mode string), fn (function or command called).
SECTIONS = [
    ("3", "Deftemplate construct", "construct", ["deftemplate"]),
    ("3", "Deftemplate construct: slots and defaults", "slot",
     ["slot", "multislot", "default", "default-dynamic", "?DERIVE", "?NONE"]),
    ("4", "Deffacts construct", "construct", ["deffacts"]),
    ("5", "Defrule construct", "construct", ["defrule"]),
    ("5.3", "Conflict resolution strategies", "strategy",
     ["depth", "breadth", "simplicity", "complexity", "lex", "mea", "random"]),
    ("5.4.1", "Pattern CE (and its field constraints)", "ce",
     ["pattern", "<-", "&", "|", "~", ":", "="]),
    ("5.4.2", "Test CE", "ce", ["test"]),
    ("5.4.3", "Or CE", "ce", ["or"]),
    ("5.4.4", "And CE", "ce", ["and"]),
    ("5.4.5", "Not CE", "ce", ["not"]),
    ("5.4.6", "Exists CE", "ce", ["exists"]),
    ("5.4.7", "Forall CE", "ce", ["forall"]),
    ("5.4.8", "Logical CE", "ce", ["logical"]),
    ("5.4.10", "Rule properties", "rule", ["salience", "auto-focus"]),
    ("6", "Defglobal construct", "construct", ["defglobal"]),
    ("7", "Deffunction construct", "construct", ["deffunction"]),
    ("10", "Defmodule construct", "construct", ["defmodule"]),
    ("10", "Defmodule: imports, exports, module specifiers", "module",
     ["import", "export", "::"]),
    ("11", "Constraint attributes", "attr",
     ["type", "allowed-symbols", "allowed-strings", "allowed-lexemes",
      "allowed-integers", "allowed-floats", "allowed-numbers", "allowed-instance-names",
      "allowed-classes", "allowed-values", "range", "cardinality"]),
    ("12.1", "Predicate functions", "fn",
     ["numberp", "floatp", "integerp", "lexemep", "stringp", "symbolp", "evenp", "oddp",
      "multifieldp", "pointerp", "eq", "neq", "=", "<>", ">", ">=", "<", "<=", "and",
      "or", "not"]),
    ("12.2", "Multifield functions", "fn",
     ["create$", "nth$", "member$", "subsetp", "delete$", "explode$", "implode$",
      "subseq$", "replace$", "insert$", "first$", "rest$", "length$", "delete-member$",
      "replace-member$"]),
    ("12.3", "String functions", "fn",
     ["str-cat", "sym-cat", "sub-string", "str-index", "eval", "build", "upcase",
      "lowcase", "str-compare", "str-length", "check-syntax", "string-to-field"]),
    ("12.4.1", "I/O logical names", "lname",
     ["t", "stdin", "stdout", "wclips", "wdialog", "wdisplay", "werror", "wwarning",
      "wtrace"]),
    ("12.4.2", "Common I/O functions", "fn",
     ["open", "close", "printout", "read", "readline", "format", "rename", "remove",
      "get-char", "read-number", "set-locale"]),
    ("12.4.2", "Common I/O functions: open's modes", "mode",
     ["r", "w", "a", "rb", "wb", "ab"]),
    ("12.5.1", "Standard math functions", "fn",
     ["+", "-", "*", "/", "div", "max", "min", "abs", "float", "integer"]),
    ("12.5.2", "Extended math functions", "fn",
     ["acos", "acosh", "acot", "acoth", "acsc", "acsch", "asec", "asech", "asin", "asinh",
      "atan", "atanh", "cos", "cosh", "cot", "coth", "csc", "csch", "sec", "sech", "sin",
      "sinh", "tan", "tanh", "deg-grad", "deg-rad", "grad-deg", "rad-deg", "pi", "sqrt",
      "**", "exp", "log", "log10", "round", "mod"]),
    ("12.6", "Procedural functions", "fn",
     ["bind", "if", "while", "loop-for-count", "progn", "progn$", "return", "break",
      "switch", "foreach"]),
    ("12.7", "Miscellaneous functions", "fn",
     ["gensym", "gensym*", "setgen", "random", "seed", "time", "length",
      "get-function-restrictions", "sort", "funcall", "timer", "operating-system"]),
    ("12.8", "Deftemplate functions", "fn",
     ["deftemplate-module", "deftemplate-slot-allowed-values",
      "deftemplate-slot-cardinality", "deftemplate-slot-defaultp",
      "deftemplate-slot-default-value", "deftemplate-slot-existp",
      "deftemplate-slot-multip", "deftemplate-slot-names", "deftemplate-slot-range",
      "deftemplate-slot-singlep", "deftemplate-slot-types", "get-deftemplate-list"]),
    ("12.9", "Fact functions", "fn",
     ["assert", "retract", "modify", "duplicate", "assert-string", "fact-index",
      "fact-existp", "fact-relation", "fact-slot-names", "fact-slot-value",
      "get-fact-list"]),
    ("12.9.12", "Fact-set queries and distributed actions", "fn",
     ["any-factp", "find-fact", "find-all-facts", "do-for-fact", "do-for-all-facts",
      "delayed-do-for-all-facts"]),
    ("12.10", "Deffacts functions", "fn", ["get-deffacts-list", "deffacts-module"]),
    ("12.11", "Defrule functions", "fn", ["get-defrule-list", "defrule-module"]),
    ("12.12", "Agenda functions", "fn", ["get-focus", "get-focus-stack", "pop-focus"]),
    ("12.13", "Defglobal functions", "fn", ["get-defglobal-list", "defglobal-module"]),
    ("12.14", "Deffunction functions", "fn",
     ["get-deffunction-list", "deffunction-module"]),
    ("12.15.4", "Type determination", "fn", ["type"]),
    ("12.17", "Defmodule functions", "fn",
     ["get-defmodule-list", "set-current-module", "get-current-module"]),
    ("12.18", "Sequence expansion", "fn",
     ["expand$", "set-sequence-operator-recognition",
      "get-sequence-operator-recognition"]),
    ("13.1", "Environment commands", "fn",
     ["load", "load*", "save", "bload", "bsave", "clear", "exit", "reset", "batch",
      "batch*", "options", "system", "set-auto-float-dividend",
      "get-auto-float-dividend", "set-dynamic-constraint-checking",
      "get-dynamic-constraint-checking", "set-static-constraint-checking",
      "get-static-constraint-checking", "apropos"]),
    ("13.2", "Debugging commands", "fn",
     ["dribble-on", "dribble-off", "watch", "unwatch", "list-watch-items"]),
    ("13.2.3", "Watch items", "watch",
     ["all", "compilations", "statistics", "focus", "deffunctions", "globals", "rules",
      "activations", "facts"]),
    ("13.3", "Deftemplate commands", "fn",
     ["ppdeftemplate", "list-deftemplates", "undeftemplate"]),
    ("13.4", "Fact commands", "fn",
     ["facts", "load-facts", "save-facts", "set-fact-duplication",
      "get-fact-duplication", "ppfact"]),
    ("13.5", "Deffacts commands", "fn", ["ppdeffacts", "list-deffacts", "undeffacts"]),
    ("13.6", "Defrule commands", "fn",
     ["ppdefrule", "list-defrules", "undefrule", "matches", "set-break", "remove-break",
      "show-breaks", "refresh", "set-incremental-reset", "get-incremental-reset"]),
    ("13.6.11", "Truth maintenance commands", "fn", ["dependencies", "dependents"]),
    ("13.7", "Agenda commands", "fn",
     ["agenda", "run", "focus", "halt", "set-strategy", "get-strategy",
      "list-focus-stack", "clear-focus-stack", "set-salience-evaluation",
      "get-salience-evaluation", "refresh-agenda"]),
    ("13.8", "Defglobal commands", "fn",
     ["ppdefglobal", "list-defglobals", "undefglobal", "show-defglobals",
      "set-reset-globals", "get-reset-globals"]),
    ("13.9", "Deffunction commands", "fn",
     ["ppdeffunction", "list-deffunctions", "undeffunction"]),
    ("13.12", "Defmodule commands", "fn", ["ppdefmodule", "list-defmodules"]),
    ("13.13", "Memory management commands", "fn",
     ["mem-used", "mem-requests", "release-mem", "conserve-mem"]),
    ("13.14", "External text manipulation", "fn",
     ["fetch", "toss", "print-region", "get-region"]),
    ("13.15", "Profiling commands", "fn",
     ["set-profile-percent-threshold", "get-profile-percent-threshold", "profile-reset",
      "profile-info", "profile"]),
    # Appendix H names the body of the guide does not describe (older names, the
    # debugging extensions, the C code generator), COOL's and generic functions' left out.
    ("H", "Appendix H: older names, extensions", "fn",
     ["!=", "nth", "member", "subset", "mv-append", "mv-subseq", "mv-delete",
      "mv-replace", "str-explode", "str-implode", "str-assert", "wordp", "sequencep",
      "rules", "constructs-to-c", "edit", "primitives-info", "rule-complexity",
      "show-fht", "show-fpn", "show-joins", "show-opn"]),
    # Functions Debian's CLIPS 6.30 defines (get-function-list) that neither the body
    # nor Appendix H name, COOL's and external-language ones (call, new) left out.
    ("D", "Debian CLIPS 6.30 functions outside the BPG", "fn",
     ["put-char", "get-watch-item", "get-function-list", "timetag",
      "deftemplate-slot-facet-existp", "deftemplate-slot-facet-value",
      "get-beta-memory-resizing", "set-beta-memory-resizing", "join-activity",
      "join-activity-reset"]),
]

# Items README.md lists as not implemented, with the word README must contain.
NOT_IMPLEMENTED = {
    ("fn", "bload"): "`bload`",
    ("fn", "bsave"): "`bsave`",
    ("fn", "constructs-to-c"): "`constructs-to-c`",
    ("fn", "join-activity"): "`join-activity`",
    ("fn", "join-activity-reset"): "`join-activity-reset`",
}

# Every program's frame (`(watch facts)`, `(watch rules)`, `(watch activations)` first,
# `(exit)` last): these cover their items but do not count a program for a section.
FRAME = {("fn", "exit"), ("fn", "watch"), ("watch", "facts"), ("watch", "rules"),
         ("watch", "activations")}

CONSTRUCTS = {"deftemplate", "deffacts", "defrule", "defglobal", "deffunction",
              "defmodule", "defclass", "definstances", "defmessage-handler",
              "defgeneric", "defmethod"}
CE_HEADS = {"and", "or", "not", "exists", "forall", "logical"}
SLOT_ATTRS = {"default", "default-dynamic"}
CONSTRAINT_ATTRS = set(dict((n, 1) for s in SECTIONS if s[2] == "attr" for n in s[3]))
IO_FUNCS = {"printout", "format", "read", "readline", "get-char", "read-number",
            "put-char", "open", "close", "ppfact", "print-region"}
WATCH_FUNCS = {"watch", "unwatch", "list-watch-items", "get-watch-item"}

# ---------------------------------------------------------------- reader


class Sym(str):
    pass


class Str(str):
    pass


def tokens(text):
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if c in " \t\r\n\f\v":
            i += 1
        elif c == ";":
            while i < n and text[i] != "\n":
                i += 1
        elif c == '"':
            j, buf = i + 1, []
            while j < n and text[j] != '"':
                if text[j] == "\\" and j + 1 < n:
                    j += 1
                buf.append(text[j])
                j += 1
            yield Str("".join(buf))
            i = j + 1
        elif c in "()&|~":
            yield c
            i += 1
        else:
            j = i
            while j < n and text[j] not in " \t\r\n\f\v\"()&|~;":
                j += 1
            yield Sym(text[i:j])
            i = j


def read_forms(text):
    """The text's forms: a list is a Python list, a token a Sym or Str."""
    stack = [[]]
    for tok in tokens(text):
        if tok == "(":
            stack.append([])
        elif tok == ")":
            if len(stack) > 1:
                done = stack.pop()
                stack[-1].append(done)
        else:
            stack[-1].append(tok if isinstance(tok, (Sym, Str)) else Sym(tok))
    while len(stack) > 1:
        done = stack.pop()
        stack[-1].append(done)
    return stack[0]


# ---------------------------------------------------------------- walker


class Walker:
    def __init__(self):
        self.hits = set()
        self.extra_frame = set()
        self.templates = set()

    def frameless(self):
        """The hits that are not only the frame (`watch` of facts, rules and
        activations, `exit`): calls of `watch` and `exit` with other arguments count."""
        return (self.hits - FRAME) | self.extra_frame

    def hit(self, kind, name):
        self.hits.add((kind, str(name)))

    def program(self, text):
        forms = read_forms(text)
        for f in forms:
            if isinstance(f, list) and f and f[0] == "deftemplate" and len(f) > 1:
                self.templates.add(str(f[1]).split("::")[-1])
        for f in forms:
            self.top(f)

    def top(self, f):
        if not isinstance(f, list):
            self.token(f)
            return
        if f and isinstance(f[0], Sym) and f[0] in CONSTRUCTS:
            self.construct(f)
        else:
            self.expr(f)

    def token(self, t):
        if isinstance(t, Sym) and "::" in t and not t.startswith("::"):
            self.hit("module", "::")

    def construct(self, f):
        head = str(f[0])
        self.hit("construct", head)
        if len(f) > 1:
            self.token(f[1])
        body = f[2:]
        if body and isinstance(body[0], Str):
            body = body[1:]
        if head == "deftemplate":
            for s in body:
                if isinstance(s, list) and s and s[0] in ("slot", "multislot", "field",
                                                          "multifield"):
                    self.hit("slot", {"field": "slot", "multifield": "multislot"}
                             .get(str(s[0]), str(s[0])))
                    for a in s[2:]:
                        if not (isinstance(a, list) and a):
                            continue
                        if a[0] in SLOT_ATTRS:
                            self.hit("slot", a[0])
                            for v in a[1:]:
                                if v in ("?DERIVE", "?NONE"):
                                    self.hit("slot", v)
                                self.expr(v)
                        elif a[0] in CONSTRAINT_ATTRS:
                            self.hit("attr", a[0])
        elif head == "deffacts":
            for x in body:
                self.fact(x)
        elif head == "defrule":
            rhs = False
            for x in body:
                if x == "=>":
                    rhs = True
                elif rhs:
                    self.expr(x)
                elif isinstance(x, list) and x and x[0] == "declare":
                    for p in x[1:]:
                        if isinstance(p, list) and p and isinstance(p[0], Sym):
                            self.hit("rule", p[0])
                            for v in p[1:]:
                                self.expr(v)
                else:
                    self.ce(x)
        elif head == "deffunction":
            seen_params = False
            for x in body:
                if not seen_params and isinstance(x, list):
                    seen_params = True
                    continue
                self.expr(x)
        elif head == "defglobal":
            for x in body:
                self.expr(x)
        elif head == "defmodule":
            for x in body:
                if isinstance(x, list) and x and x[0] in ("import", "export"):
                    self.hit("module", x[0])
        else:  # COOL and generic functions: only calls in their bodies
            for x in body:
                if isinstance(x, list):
                    self.expr(x)

    def ce(self, x):
        if isinstance(x, Sym):
            if x == "<-":
                self.hit("ce", "<-")
            return
        if not isinstance(x, list) or not x:
            return
        h = x[0]
        if isinstance(h, Sym) and h in CE_HEADS:
            self.hit("ce", h)
            for c in x[1:]:
                self.ce(c)
        elif h == "test":
            self.hit("ce", "test")
            for c in x[1:]:
                self.expr(c)
        else:
            self.hit("ce", "pattern")
            self.pattern(x)

    def pattern(self, x):
        prev = None
        for t in x:
            if isinstance(t, list):
                if prev in (":", "="):
                    self.hit("ce", prev)
                    self.expr(t)
                else:
                    self.pattern(t)
            elif isinstance(t, Sym):
                if t in ("&", "|", "~"):
                    self.hit("ce", t)
                self.token(t)
            prev = t

    def fact(self, x):
        if not isinstance(x, list) or not x:
            return
        rel = str(x[0]).split("::")[-1]
        self.token(x[0])
        for c in x[1:]:
            if isinstance(c, list):
                if rel in self.templates and c and isinstance(c[0], Sym):
                    for v in c[1:]:
                        self.expr(v)
                else:
                    self.expr(c)

    def expr(self, x):
        if not isinstance(x, list):
            self.token(x)
            return
        if not x:
            return
        h = x[0]
        if not isinstance(h, Sym) or h.startswith("?") or h.startswith("$?"):
            for c in x:
                self.expr(c)
            return
        name = str(h)
        self.hit("fn", name)
        self.token(h)
        args = x[1:]
        if name in ("assert",):
            for c in args:
                self.fact(c)
            return
        if name in ("modify", "duplicate"):
            if args:
                self.expr(args[0])
            for c in args[1:]:
                if isinstance(c, list):
                    for v in c[1:]:
                        self.expr(v)
            return
        if name == "switch":
            for c in args:
                if isinstance(c, list) and c and c[0] in ("case", "default"):
                    for v in c[1:]:
                        self.expr(v)
                else:
                    self.expr(c)
            return
        if name in WATCH_FUNCS and args and isinstance(args[0], Sym):
            self.hit("watch", args[0])
            if name != "watch" or args[0] not in ("facts", "rules", "activations") or \
                    len(args) > 1:
                self.extra_frame.update({("fn", name), ("watch", str(args[0]))})
        if name == "exit" and args:
            self.extra_frame.add(("fn", "exit"))
        if name == "set-strategy" and args and isinstance(args[0], Sym):
            self.hit("strategy", args[0])
        if name in ("funcall", "sort") and args and isinstance(args[0], (Sym, Str)):
            self.hit("fn", str(args[0]))
        if name in IO_FUNCS and args:
            ln = args[1] if name in ("open", "ppfact") and len(args) > 1 else args[0]
            if isinstance(ln, Sym):
                self.hit("lname", ln)
        if name == "open" and len(args) > 2 and isinstance(args[2], Str):
            self.hit("mode", args[2])
        if name in ("eval", "build", "check-syntax"):
            for c in args:
                if isinstance(c, Str):
                    sub = read_forms(c)
                    for f in sub:
                        if name == "eval":
                            self.expr(f)
                        else:
                            self.top(f)
        for c in args:
            self.expr(c)


# ---------------------------------------------------------------- report


def main():
    show_items = "--items" in sys.argv
    progs = sorted(p for p in os.listdir(HERE) if re.match(r"\d{3}-.*\.clp$", p))
    uses = {}
    counted = {}
    for p in progs:
        with open(os.path.join(HERE, p), encoding="utf-8", errors="replace") as fh:
            text = fh.read()
        w = Walker()
        w.program(text)
        for key in w.hits:
            uses.setdefault(key, []).append(p[:3])
        for key in w.frameless():
            counted.setdefault(key, []).append(p[:3])
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as fh:
        readme = fh.read()

    print("(a) differential programs per BPG section (%d programs)" % len(progs))
    print()
    print("| section | title | items | covered | programs |")
    print("|---|---|---|---|---|")
    by_section = {}
    order = []
    for sec, title, kind, names in SECTIONS:
        if sec not in by_section:
            by_section[sec] = [title, 0, 0, set()]
            order.append(sec)
        row = by_section[sec]
        for n in names:
            row[1] += 1
            ps = uses.get((kind, n), [])
            if ps:
                row[2] += 1
            row[3].update(counted.get((kind, n), []))
    for sec in order:
        title, n, c, ps = by_section[sec]
        print("| %s | %s | %d | %d | %d |" % (sec, title, n, c, len(ps)))
    if show_items:
        print()
        for sec, title, kind, names in SECTIONS:
            for n in names:
                ps = uses.get((kind, n), [])
                print("%-8s %-10s %-34s %4d  %s" % (sec, kind, n, len(ps),
                                                    " ".join(ps[:8])))
    print()
    print("(b) items no program uses")
    missing = []
    for sec, title, kind, names in SECTIONS:
        for n in names:
            if not uses.get((kind, n)):
                listed = (kind, n) in NOT_IMPLEMENTED
                missing.append((sec, kind, n, listed))
                print("  %-8s %-10s %-30s%s" % (sec, kind, n,
                                                "  (not implemented, README)" if listed
                                                else ""))
    if not missing:
        print("  none")
    print()
    print("(c) items README.md lists as not implemented")
    for (kind, n), word in sorted(NOT_IMPLEMENTED.items()):
        ok = word in readme
        ps = uses.get((kind, n), [])
        print("  %-10s %-22s README %s; programs: %s" % (
            kind, n, "names it" if ok else "DOES NOT NAME IT",
            " ".join(ps) if ps else "none"))
    bad = [m for m in missing if not m[3]]
    bad += [k for k, w in NOT_IMPLEMENTED.items() if w not in readme]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
