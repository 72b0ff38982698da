//! A deftemplate slot's attributes — `type`, `default`/`default-dynamic`, the
//! `allowed-...` lists, `range` and `cardinality` — with the checks CLIPS makes when it
//! parses them: each attribute once, values of the type an `allowed-...` attribute
//! names, bounds in order, a `type` that admits every allowed value and the range's
//! bounds, and a default that fits them all (reported at the offending value). COOL's
//! slot attributes (`visibility`, `storage`, ...) are refused as CLIPS refuses them in
//! a deftemplate.

use super::facts::expected;
use super::{PResult, Parser, Scope};
use crate::error::{EchoTail, LoadDetail, LoadError, Restriction};
use crate::expr::{Expr, Op};
use crate::lexer::{Lexer, Tok, Token};
use crate::template::{allowed, types, DefaultKind, SlotDef};
use crate::value::Ix;
use crate::value::{Value, NONE};

/// Reader position of the first value of an attribute, to point at a bad one later.
type ValuesAt<'s> = (Lexer<'s>, Option<Token<'s>>);

/// What a slot's attribute list has given so far.
struct Seen<'s> {
    types: bool,
    /// Whether a `default` or `default-dynamic` was read (`?NONE` and `?DERIVE` too),
    /// and where its values start (none for those two).
    default_given: bool,
    default: Option<(ValuesAt<'s>, &'static str)>,
    /// Where each `allowed-...` attribute's values start, by `ALLOWED` index.
    lists: [Option<ValuesAt<'s>>; 8],
    /// `allowed-classes` was given (with class names: `Some(true)`).
    classes: Option<bool>,
    /// The `range` attribute's name token.
    range: Option<Token<'s>>,
    cardinality: bool,
}

/// `e` with CLIPS's `ERROR:` text shown up to token `at`, joined by `tail`.
fn echoed(mut e: LoadError, at: Token<'_>, tail: EchoTail) -> LoadError {
    e.echo_end = at.end as u32;
    e.echo_tail = tail;
    e
}

impl Seen<'_> {
    /// Whether `allowed-...` attribute `name` was given.
    fn has(&self, name: &str) -> bool {
        ALLOWED
            .iter()
            .zip(self.lists.iter())
            .any(|(&(n, _), l)| n == name && l.is_some())
    }

    /// The attribute given before that `allowed-...` attribute `name` cannot be
    /// combined with, named as CLIPS names it (`allowed-number` is CLIPS's spelling).
    fn excluded_by(&self, name: &str) -> Option<&'static str> {
        let first_of = |names: &[&'static str]| names.iter().copied().find(|n| self.has(n));
        if name == "allowed-values" {
            let other = first_of(&[
                "allowed-symbols",
                "allowed-strings",
                "allowed-lexemes",
                "allowed-integers",
                "allowed-floats",
                "allowed-numbers",
            ]);
            if other.is_some() {
                return other;
            }
        }
        if self.range.is_some() && restricts_numbers(name) {
            return Some("range");
        }
        match name {
            "allowed-values" => None,
            _ if self.has("allowed-values") => Some("allowed-values"),
            "allowed-numbers" => first_of(&["allowed-floats", "allowed-integers"]),
            "allowed-integers" | "allowed-floats" if self.has("allowed-numbers") => {
                Some("allowed-number")
            }
            "allowed-lexemes" => first_of(&["allowed-symbols", "allowed-strings"]),
            "allowed-symbols" | "allowed-strings" if self.has("allowed-lexemes") => {
                Some("allowed-lexemes")
            }
            _ => None,
        }
    }
}

/// The `allowed-...` attributes that restrict numbers, which `range` excludes.
fn restricts_numbers(attribute: &str) -> bool {
    matches!(
        attribute,
        "allowed-values" | "allowed-integers" | "allowed-floats" | "allowed-numbers"
    )
}

/// The `allowed-...` attributes: name, kind, and whether a value fits the kind.
const ALLOWED: [(&str, u8); 8] = [
    ("allowed-values", allowed::VALUES),
    ("allowed-symbols", allowed::SYMBOLS),
    ("allowed-strings", allowed::STRINGS),
    ("allowed-lexemes", allowed::LEXEMES),
    ("allowed-integers", allowed::INTEGERS),
    ("allowed-floats", allowed::FLOATS),
    ("allowed-numbers", allowed::NUMBERS),
    ("allowed-instance-names", allowed::INSTANCE_NAMES),
];

/// Whether a value of type `bit` (`types::of`) fits an `allowed-...` list of `kind`.
fn fits_allowed_kind(kind: u8, bit: u8) -> bool {
    kind == allowed::VALUES || kind & bit != 0
}

impl<'s> Parser<'s, '_, '_> {
    /// The attributes of one slot, up to the slot's `)`; its facets (`facet`,
    /// `multifacet`, with `extras`) chained from `facets`.
    pub(super) fn slot_attributes(
        &mut self,
        mut def: SlotDef,
        facets: &mut Ix,
    ) -> PResult<SlotDef> {
        #[cfg(not(feature = "extras"))]
        let _ = facets;
        let mut seen = Seen {
            types: false,
            default_given: false,
            default: None,
            lists: [None, None, None, None, None, None, None, None],
            classes: None,
            range: None,
            cardinality: false,
        };
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => {
                    // CLIPS checks the slot once it is read, and shows it whole
                    self.check_slot(&def, &seen)
                        .map_err(|e| echoed(e, t, EchoTail::Normal))?;
                    return Ok(def);
                }
                Tok::LParen => {
                    let at = self.next();
                    let attr = match at.tok {
                        Tok::Symbol(s) => s,
                        _ => {
                            let e = self.err(at, "a slot attribute");
                            return Err(echoed(e, at, EchoTail::Normal));
                        }
                    };
                    match attr {
                        "default" | "default-dynamic" => {
                            if seen.default_given {
                                return Err(self.twice(at, "default"));
                            }
                            seen.default_given = true;
                            let attribute = if attr == "default" {
                                "default"
                            } else {
                                "default-dynamic"
                            };
                            seen.default = self.default_attribute(&mut def, at, attribute)?;
                        }
                        "type" => {
                            if seen.types {
                                return Err(self.twice(at, "type"));
                            }
                            seen.types = true;
                            def.types = self.type_attribute()?;
                        }
                        _ if ALLOWED.iter().any(|&(name, _)| name == attr) => {
                            let (name, kind) = ALLOWED
                                .iter()
                                .copied()
                                .find(|&(name, _)| name == attr)
                                .unwrap_or(ALLOWED[0]);
                            // (CLIPS 6.30 takes a second allowed-instance-names)
                            if seen.has(name) && name != "allowed-instance-names" {
                                return Err(self.twice(at, name));
                            }
                            if let Some(first) = seen.excluded_by(name) {
                                let mut e = self.err(
                                    at,
                                    "attributes that combine (allowed-values stands alone; no number list with range)",
                                );
                                e.detail = LoadDetail::AllowedCombined {
                                    first,
                                    second: name,
                                };
                                return Err(echoed(e, at, EchoTail::Normal));
                            }
                            let values_at = self.save();
                            self.allowed_attribute(&mut def, name, kind)?;
                            if let Some(k) = ALLOWED.iter().position(|&(n, _)| n == name) {
                                if seen.lists[k].is_none() {
                                    seen.lists[k] = Some(values_at);
                                }
                            }
                        }
                        #[cfg(feature = "extras")]
                        "facet" | "multifacet" => {
                            self.facet_attribute(attr == "multifacet", facets)?;
                        }
                        "allowed-classes" if cfg!(feature = "extras") => {
                            if seen.classes.is_some() {
                                return Err(self.twice(at, "allowed-classes"));
                            }
                            if seen.has("allowed-values") {
                                let mut e = self.err(
                                    at,
                                    "attributes that combine (allowed-values stands alone)",
                                );
                                e.detail = LoadDetail::AllowedCombined {
                                    first: "allowed-values",
                                    second: "allowed-classes",
                                };
                                return Err(echoed(e, at, EchoTail::Normal));
                            }
                            let named = self.classes_attribute()?;
                            seen.classes = Some(named);
                            if named {
                                def.allowed_kind |= allowed::CLASSES;
                            }
                        }
                        "range" => {
                            if seen.range.is_some() {
                                return Err(self.twice(at, "range"));
                            }
                            if let Some(first) = [
                                "allowed-values",
                                "allowed-integers",
                                "allowed-floats",
                                "allowed-numbers",
                            ]
                            .into_iter()
                            .find(|a| seen.has(a))
                            {
                                let mut e = self.err(at, "no range with allowed-... numbers");
                                e.detail = LoadDetail::AllowedCombined {
                                    first,
                                    second: "range",
                                };
                                return Err(echoed(e, at, EchoTail::Normal));
                            }
                            seen.range = Some(at);
                            def.range = self.bounds_attribute(false)?;
                        }
                        "cardinality" => {
                            if seen.cardinality {
                                return Err(self.twice(at, "cardinality"));
                            }
                            if !def.multi {
                                let mut e = self.err(at, "a multislot for a cardinality");
                                e.detail = LoadDetail::CardinalityOfSingle;
                                return Err(echoed(e, at, EchoTail::Normal));
                            }
                            seen.cardinality = true;
                            def.cardinality = self.bounds_attribute(true)?;
                        }
                        // the rest of CLIPS's slot attributes belong to COOL's classes;
                        // in a deftemplate CLIPS refuses them like an unknown one
                        _ => {
                            let e = self.attribute_syntax(
                                at,
                                "a slot attribute (type, default, allowed-values, range, ...)",
                                "slot attributes",
                            );
                            return Err(echoed(e, at, EchoTail::Normal));
                        }
                    }
                }
                _ => {
                    let e = self.err(t, "'(' starting a slot attribute or ')'");
                    return Err(echoed(e, t, EchoTail::Normal));
                }
            }
        }
    }

    /// `[PRNTUTIL5]`: an attribute given a second time (at its name).
    fn twice(&self, at: Token<'s>, attribute: &'static str) -> crate::error::LoadError {
        let mut e = self.err(at, "each slot attribute once");
        e.detail = LoadDetail::AttributeTwice { attribute };
        echoed(e, at, EchoTail::Normal)
    }

    /// `(default ...)`/`(default-dynamic ...)` after its name; None for `?NONE` and
    /// `?DERIVE`, else where the values start (to check them when the slot ends).
    fn default_attribute(
        &mut self,
        def: &mut SlotDef,
        at: Token<'s>,
        attribute: &'static str,
    ) -> PResult<Option<(ValuesAt<'s>, &'static str)>> {
        let what = if attribute == "default" {
            "default attribute"
        } else {
            "default-dynamic attribute"
        };
        let vt = self.peek();
        if let Tok::SfVar(v @ ("NONE" | "DERIVE")) = vt.tok {
            self.next();
            if attribute != "default" {
                // only a static default may be ?NONE or ?DERIVE
                let e = self.attribute_syntax(vt, "a value (not ?NONE or ?DERIVE)", what);
                return Err(echoed(e, vt, EchoTail::Normal));
            }
            def.default_kind = if v == "NONE" {
                DefaultKind::Required
            } else {
                DefaultKind::Derived
            };
            let close = self.peek();
            if !matches!(close.tok, Tok::RParen | Tok::Eof | Tok::Bad) {
                let e = self.attribute_syntax(close, "')' after the default", what);
                return Err(echoed(e, close, EchoTail::Normal));
            }
            self.expect_rparen("')' after the default")?;
            return Ok(None);
        }
        let save = self.scope;
        self.scope = Scope::Frame;
        // (a dynamic default reads an unseen global by name too, when it runs)
        self.evaluated_now = attribute == "default" || attribute == "default-dynamic";
        let holder = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
        let values_at = self.save();
        let mut n = 0 as Ix;
        // (a single-field slot's second value, where the error is placed)
        let mut second = at;
        let close = loop {
            let t = self.peek();
            match t.tok {
                Tok::RParen => {
                    self.next();
                    break t;
                }
                Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                // a default cannot read a variable (nothing binds one there)
                Tok::SfVar(_) | Tok::MfVar(_) => {
                    let e = self.attribute_syntax(t, "a constant, global or call", what);
                    return Err(echoed(e, t, EchoTail::Normal));
                }
                _ => {
                    if n == 1 {
                        second = t;
                    }
                    let a = self.parse_expr()?;
                    self.cx.append_child(holder, a);
                    n += 1;
                }
            }
        };
        self.scope = save;
        self.evaluated_now = false;
        // CLIPS reads the attribute whole first, and shows the deftemplate up to it; a
        // builtin call that returns a multifield (`create$`) is refused there as well,
        // whatever it would give
        let first = self.cx.exprs[holder as usize].first;
        if !def.multi && (n != 1 || self.returns_multifield(first)) {
            if n == 1 {
                second = self.value_at(values_at.clone(), 0)?;
            }
            let mut e = self.err(second, "exactly one default value for a single-field slot");
            e.detail = crate::error::LoadDetail::DefaultSingle;
            e.echo_end = close.end as u32;
            return Err(e);
        }
        def.default = self.cx.exprs[holder as usize].first;
        def.default_kind = if attribute == "default" {
            DefaultKind::Static
        } else {
            DefaultKind::Dynamic
        };
        if attribute == "default" {
            self.evaluate_static_default(def, &values_at, close)?;
        }
        Ok(Some((values_at, attribute)))
    }

    /// Whether expression `e` is a builtin call CLIPS's parser knows to return a
    /// multifield (return type `m`).
    fn returns_multifield(&self, e: Ix) -> bool {
        let x = self.cx.exprs[e as usize];
        x.op == Op::Call
            && x.aux == crate::expr::FnKind::Builtin as u8
            && matches!(
                crate::builtins::get(x.data).returns,
                crate::builtins::describe::Returns::Multifield
            )
    }

    /// CLIPS evaluates a static default's expressions once, when the deftemplate is
    /// defined (`(default (gensym))` is the same symbol in every fact): calls and
    /// globals become the constants they give, a multifield's fields spliced in. An
    /// expression that fails is reported as CLIPS reports it: its error, then the
    /// deftemplate up to the attribute's `)` (`close`).
    fn evaluate_static_default(
        &mut self,
        def: &mut SlotDef,
        values_at: &ValuesAt<'s>,
        close: Token<'s>,
    ) -> PResult<()> {
        let mut c = def.default;
        let mut any = false;
        while c != NONE {
            any |= !self.is_literal(c);
            c = self.cx.exprs[c as usize].next;
        }
        if !any {
            return Ok(());
        }
        let holder = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
        let mut c = def.default;
        let mut k = 0;
        let mut fields = 0;
        while c != NONE {
            let next = self.cx.exprs[c as usize].next;
            let v = if self.is_literal(c) {
                self.cx.const_value(c)
            } else {
                match self.eval_now(c) {
                    Ok(v) => v,
                    Err(err) => {
                        if err.is_capacity() {
                            let at = self.value_at(values_at.clone(), k)?;
                            return Err(self.err(at, "a default value that evaluates"));
                        }
                        self.cx.write_error_message(err);
                        let at = self.value_at(values_at.clone(), k)?;
                        let mut e = self.err(at, "a default value that evaluates");
                        e.detail = LoadDetail::DefaultEvaluation;
                        return Err(echoed(e, close, EchoTail::Normal));
                    }
                }
            };
            let push = |p: &mut Self, v: Value| -> PResult<()> {
                let e = cap!(p, p.cx.push_const(v))?;
                p.cx.append_child(holder, e);
                Ok(())
            };
            match v {
                Value::Multi(m) => {
                    for i in 0..m.len as usize {
                        let item = self.cx.mf_item(m, i);
                        push(self, item)?;
                        fields += 1;
                    }
                }
                Value::Int(_) | Value::Float(_) | Value::Sym(_) | Value::Str(_) => {
                    push(self, v)?;
                    fields += 1;
                }
                // a fact address or no value is no constant a fact can take
                _ => {
                    let at = self.value_at(values_at.clone(), k)?;
                    return Err(self.err(at, "a default value that evaluates to a field"));
                }
            }
            c = next;
            k += 1;
        }
        if !def.multi && fields != 1 {
            let at = self.value_at(values_at.clone(), 0)?;
            return Err(self.err(at, "exactly one default value for a single-field slot"));
        }
        def.default = self.cx.exprs[holder as usize].first;
        Ok(())
    }

    /// `(type T...)` after its name: the type mask (0 for any type).
    fn type_attribute(&mut self) -> PResult<u8> {
        let mut mask = 0u8;
        let mut variable = false;
        loop {
            let tt = self.next();
            let bits = match tt.tok {
                Tok::RParen if mask == 0 && !variable => {
                    let e = self.attribute_syntax(tt, "a type name", "type attribute");
                    return Err(echoed(e, tt, EchoTail::Normal));
                }
                Tok::RParen => return Ok(if variable { 0 } else { mask }),
                // ?VARIABLE stands alone
                Tok::SfVar("VARIABLE") if mask == 0 && !variable => {
                    variable = true;
                    continue;
                }
                Tok::SfVar("VARIABLE") => {
                    let e = self.attribute_syntax(tt, "?VARIABLE alone", "type attribute");
                    return Err(echoed(e, tt, EchoTail::SpaceAfter));
                }
                _ if variable => {
                    let e = self.attribute_syntax(tt, "')' after ?VARIABLE", "type attribute");
                    return Err(echoed(e, tt, EchoTail::SpaceAfter));
                }
                Tok::Symbol("SYMBOL") => types::SYMBOL,
                Tok::Symbol("STRING") => types::STRING,
                Tok::Symbol("LEXEME") => types::LEXEME,
                Tok::Symbol("INTEGER") => types::INTEGER,
                Tok::Symbol("FLOAT") => types::FLOAT,
                Tok::Symbol("NUMBER") => types::NUMBER,
                Tok::Symbol("FACT-ADDRESS") => types::FACT_ADDRESS,
                Tok::Symbol("INSTANCE-NAME") => types::INSTANCE_NAME,
                Tok::Symbol("INSTANCE-ADDRESS") => types::INSTANCE_ADDRESS,
                Tok::Symbol("INSTANCE") => types::INSTANCE,
                _ => {
                    // CLIPS saved a space after the name it did not know
                    let e = self.attribute_syntax(tt, "a type name", "type attribute");
                    return Err(echoed(e, tt, EchoTail::SpaceAfter));
                }
            };
            // (CLIPS refuses a type that overlaps one named before: `INTEGER NUMBER`)
            if mask & bits != 0 {
                let e = self.attribute_syntax(tt, "a type not named before", "type attribute");
                return Err(echoed(e, tt, EchoTail::SpaceAfter));
            }
            mask |= bits;
        }
    }

    /// `(range MIN MAX)` or, with `cardinality`, `(cardinality MIN MAX)` after its
    /// name: two numbers (integers for a cardinality, not below 0) or `?VARIABLE`,
    /// the minimum not above the maximum. Returns the chain of the two bounds.
    fn bounds_attribute(&mut self, cardinality: bool) -> PResult<Ix> {
        let what = if cardinality {
            "cardinality attribute"
        } else {
            "range attribute"
        };
        let holder = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
        let mut bounds = [Value::Void; 2];
        for (k, bound) in bounds.iter_mut().enumerate() {
            let t = self.next();
            let v = match t.tok {
                Tok::Int(i) | Tok::IntOverflow(i) => Value::Int(i),
                Tok::Float(f) if !cardinality => Value::Float(f),
                Tok::SfVar("VARIABLE") => {
                    let unbounded = match (k, cardinality) {
                        (0, true) => Value::Int(0),
                        (0, false) => Value::Sym(cap!(self, self.cx.intern("-oo"))?),
                        _ => Value::Sym(cap!(self, self.cx.intern("+oo"))?),
                    };
                    let c = cap!(self, self.cx.push_const(unbounded))?;
                    self.cx.append_child(holder, c);
                    *bound = unbounded;
                    continue;
                }
                _ => {
                    // CLIPS saved a space before reading the bound
                    let tail = if t.tok == Tok::RParen {
                        EchoTail::SpaceBefore
                    } else {
                        EchoTail::Normal
                    };
                    let e = self.attribute_syntax(t, "a number or ?VARIABLE", what);
                    return Err(echoed(e, t, tail));
                }
            };
            if cardinality && k == 0 && matches!(v, Value::Int(i) if i < 0) {
                let mut e = self.err(t, "a minimum cardinality of 0 or more");
                e.detail = LoadDetail::CardinalityBelowZero;
                return Err(echoed(e, t, EchoTail::Normal));
            }
            let c = match self.literal(t)? {
                Some(c) => c,
                None => return Err(self.attribute_syntax(t, "a number or ?VARIABLE", what)),
            };
            self.cx.append_child(holder, c);
            *bound = v;
        }
        let close = self.next();
        if close.tok != Tok::RParen {
            // CLIPS names the range attribute here, for a cardinality too
            let e = self.attribute_syntax(close, "')' after the two bounds", "range attribute");
            return Err(echoed(e, close, EchoTail::Glued));
        }
        if let (Some(min), Some(max)) = (bounds[0].as_number(), bounds[1].as_number()) {
            if min > max {
                let mut e = self.err(close, "a minimum not above the maximum");
                e.detail = LoadDetail::MinAboveMax { cardinality };
                return Err(echoed(e, close, EchoTail::Normal));
            }
        }
        Ok(self.cx.exprs[holder as usize].first)
    }

    /// `(allowed-KIND v...)` after its name: constants of the kind's type.
    fn allowed_attribute(
        &mut self,
        def: &mut SlotDef,
        name: &'static str,
        kind: u8,
    ) -> PResult<()> {
        let what = match name {
            "allowed-symbols" => "allowed-symbols attribute",
            "allowed-strings" => "allowed-strings attribute",
            "allowed-lexemes" => "allowed-lexemes attribute",
            "allowed-integers" => "allowed-integers attribute",
            "allowed-floats" => "allowed-floats attribute",
            "allowed-numbers" => "allowed-numbers attribute",
            "allowed-instance-names" => "allowed-instance-names attribute",
            _ => "allowed-values attribute",
        };
        let holder = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
        let mut any = false;
        let close = loop {
            let tt = self.next();
            if tt.tok == Tok::RParen {
                break tt;
            }
            // CLIPS saved a space after each value it read
            let constants = self.cx.exprs[holder as usize].first != NONE;
            if tt.tok == Tok::SfVar("VARIABLE") {
                if constants {
                    let e = self.attribute_syntax(tt, "constants or ?VARIABLE, not both", what);
                    return Err(echoed(e, tt, EchoTail::SpaceAfter));
                }
                any = true;
                continue;
            }
            let c = match self.literal(tt)? {
                Some(c) => c,
                None => {
                    let e = self.attribute_syntax(tt, "a constant allowed value", what);
                    return Err(echoed(e, tt, EchoTail::SpaceAfter));
                }
            };
            if !fits_allowed_kind(kind, self.cx.type_bit(self.cx.const_value(c))) {
                let mut e = self.err(tt, "a value of the type the allowed-... attribute names");
                e.detail = LoadDetail::AllowedValueType { attribute: name };
                return Err(echoed(e, tt, EchoTail::SpaceAfter));
            }
            if any {
                let e = self.attribute_syntax(tt, "constants or ?VARIABLE, not both", what);
                return Err(echoed(e, tt, EchoTail::SpaceAfter));
            }
            self.cx.append_child(holder, c);
        };
        let first = self.cx.exprs[holder as usize].first;
        if first == NONE && !any {
            let e = self.attribute_syntax(close, "at least one allowed value", what);
            return Err(echoed(e, close, EchoTail::SpaceBefore));
        }
        if first != NONE {
            // the values of every allowed-... attribute make one list, as in CLIPS
            if def.allowed == NONE {
                def.allowed = first;
            } else {
                let mut last = def.allowed;
                while self.cx.exprs[last as usize].next != NONE {
                    last = self.cx.exprs[last as usize].next;
                }
                self.cx.exprs[last as usize].next = first;
            }
            def.allowed_kind |= kind;
        }
        Ok(())
    }

    /// `(facet NAME VALUE)` or `(multifacet NAME VALUE...)` after its name, as CLIPS
    /// 6.30 reads them: a symbol naming a facet the slot does not have yet, then
    /// constants, exactly one for a facet. Put first in the chain at `facets`
    /// (`template::facet`).
    #[cfg(feature = "extras")]
    fn facet_attribute(&mut self, multi: bool, facets: &mut Ix) -> PResult<()> {
        let what = if multi {
            "multifacet attribute"
        } else {
            "facet attribute"
        };
        let nt = self.next();
        let Tok::Symbol(name) = nt.tok else {
            let e = self.attribute_syntax(nt, "a facet name (a symbol)", what);
            // (CLIPS saved a space before the token it read)
            let tail = if nt.tok == Tok::RParen {
                EchoTail::SpaceBefore
            } else {
                EchoTail::Normal
            };
            return Err(echoed(e, nt, tail));
        };
        let sym = cap!(self, self.cx.intern(name))?;
        let mut f = *facets;
        while f != NONE {
            let x = self.cx.exprs[f as usize];
            if x.data == sym {
                let mut e = self.err(nt, "a facet name not used before in this slot");
                e.detail = LoadDetail::FacetTwice { multi };
                return Err(echoed(e, nt, EchoTail::Normal));
            }
            f = x.next;
        }
        let aux = if multi {
            crate::template::facet::MULTI
        } else {
            0
        };
        let head = cap!(self, self.cx.push_expr(Expr::new(Op::Sym, aux, sym)))?;
        let mut n = 0;
        loop {
            let tt = self.next();
            if tt.tok == Tok::RParen && (multi || n == 1) {
                break;
            }
            let c = match self.literal(tt)? {
                Some(c) if multi || n == 0 => c,
                _ => {
                    let e = self.attribute_syntax(tt, "one constant value", what);
                    return Err(echoed(e, tt, EchoTail::Normal));
                }
            };
            self.cx.append_child(head, c);
            n += 1;
        }
        self.cx.exprs[head as usize].next = *facets;
        *facets = head;
        Ok(())
    }

    /// `(allowed-classes NAME...)` after its name, or `?VARIABLE` alone: whether
    /// class names were given (kept for nothing but the check: no classes here).
    fn classes_attribute(&mut self) -> PResult<bool> {
        const WHAT: &str = "allowed-classes attribute";
        let mut names = false;
        let mut any = false;
        loop {
            let tt = self.next();
            match tt.tok {
                Tok::RParen if names || any => return Ok(names),
                Tok::RParen => {
                    let e = self.attribute_syntax(tt, "at least one class name", WHAT);
                    return Err(echoed(e, tt, EchoTail::SpaceBefore));
                }
                Tok::Symbol(s) if crate::value::instance_name_body(s).is_some() => {
                    let mut e = self.err(tt, "a class name (a symbol)");
                    e.detail = LoadDetail::AllowedValueType {
                        attribute: "allowed-classes",
                    };
                    return Err(echoed(e, tt, EchoTail::SpaceAfter));
                }
                Tok::SfVar("VARIABLE") if !names && !any => any = true,
                Tok::Symbol(_) if !any => names = true,
                Tok::SfVar("VARIABLE") | Tok::Symbol(_) => {
                    let e = self.attribute_syntax(tt, "class names or ?VARIABLE, not both", WHAT);
                    return Err(echoed(e, tt, EchoTail::SpaceAfter));
                }
                _ if self.literal(tt)?.is_some() => {
                    let mut e = self.err(tt, "a class name (a symbol)");
                    e.detail = LoadDetail::AllowedValueType {
                        attribute: "allowed-classes",
                    };
                    return Err(echoed(e, tt, EchoTail::SpaceAfter));
                }
                _ => {
                    let e = self.attribute_syntax(tt, "a class name", WHAT);
                    return Err(echoed(e, tt, EchoTail::SpaceAfter));
                }
            }
        }
    }

    /// A syntax error CLIPS words as "Check appropriate syntax for `what`".
    fn attribute_syntax(
        &self,
        at: Token<'s>,
        expected: &'static str,
        what: &'static str,
    ) -> crate::error::LoadError {
        let mut e = self.err(at, expected);
        e.construct = what;
        e
    }

    /// Checks made when the slot is complete (its attributes come in any order): the
    /// `type` admits every allowed value, and the default's literals fit both.
    /// A default value the slot's constraints refuse (`[CSTRNCHK1]`; `call`: the value
    /// is a function call's return type, not a literal).
    fn default_error(
        &self,
        at: Token<'s>,
        attribute: &'static str,
        what: Restriction,
        def: &SlotDef,
        call: bool,
    ) -> LoadError {
        let mut e = self.err(at, expected(what));
        e.detail = LoadDetail::DefaultConstraint {
            attribute,
            what,
            slot: def.name,
            range: def.range,
            call,
        };
        e
    }

    fn check_slot(&mut self, def: &SlotDef, seen: &Seen<'s>) -> PResult<()> {
        // a default derived for an address type alone is CLIPS's `<Dummy Instance>` or
        // `<Dummy Fact>`, values only `extras` prints
        let addresses = types::INSTANCE_ADDRESS | types::FACT_ADDRESS;
        if cfg!(not(feature = "extras"))
            && def.default_kind == DefaultKind::Derived
            && def.types & addresses != 0
            && def.types & !addresses == 0
            && def.allowed == NONE
            && (!def.multi || self.cx.cardinality_of(def).0 > 0)
        {
            let at = self.peek();
            return Err(self.not_implemented(at, "a derived default of an address type"));
        }
        if def.types != 0 {
            // a type an allowed-... list restricts must be one the slot takes (CLIPS's
            // order and names); reported at the first value of that list
            let kinds: [(u8, &str, [usize; 2]); 5] = [
                (types::SYMBOL, "allowed-symbols", [1, 3]),
                (types::STRING, "allowed-strings", [2, 3]),
                (types::INTEGER, "allowed-integers/numbers", [4, 6]),
                (types::FLOAT, "allowed-floats/numbers", [5, 6]),
                (types::INSTANCE_NAME, "allowed-instance-names", [7, 7]),
            ];
            for (bit, attribute, lists) in kinds {
                if def.allowed_kind & bit != 0 && def.types & bit == 0 {
                    let list = lists.iter().find_map(|&k| seen.lists[k].clone());
                    let at = match list {
                        Some(values_at) => self.value_at(values_at, 0)?,
                        None => self.peek(),
                    };
                    let mut e = self.err(at, "allowed values of the slot's type");
                    e.detail = LoadDetail::TypeConflict { attribute };
                    return Err(e);
                }
            }
            if let (Some(named), true) = (seen.classes, def.types & types::INSTANCE == 0) {
                // (CLIPS names the attribute so when it has no class names)
                let attribute = if named {
                    "allowed-classes"
                } else {
                    "allowed-class"
                };
                let at = self.peek();
                let mut e = self.err(at, "a type an allowed class can be");
                e.detail = LoadDetail::TypeConflict { attribute };
                return Err(e);
            }
            if let (Some(values_at), true) = (
                seen.lists[0].clone(),
                def.allowed_kind & allowed::VALUES != 0,
            ) {
                let mut c = def.allowed;
                let mut k = 0;
                while c != NONE {
                    let v = self.cx.const_value(c);
                    if def.types & self.cx.type_bit(v) == 0 {
                        let at = self.value_at(values_at.clone(), k)?;
                        let mut e = self.err(at, "allowed values of the slot's type");
                        e.detail = LoadDetail::TypeConflict {
                            attribute: "allowed-values",
                        };
                        return Err(e);
                    }
                    c = self.cx.exprs[c as usize].next;
                    k += 1;
                }
            }
        }
        if let (Some(at), true) = (seen.range, def.types != 0) {
            // each bound's type must be one the slot takes
            let mut c = def.range;
            while c != NONE {
                let bound = self.cx.const_value(c);
                let number = matches!(bound, Value::Int(_) | Value::Float(_));
                if number && def.types & self.cx.type_bit(bound) == 0 {
                    let mut e = self.err(at, "a range of numbers of the slot's type");
                    e.detail = LoadDetail::TypeConflict { attribute: "range" };
                    return Err(e);
                }
                c = self.cx.exprs[c as usize].next;
            }
        }
        if let Some((values_at, attribute)) = &seen.default {
            let mut c = def.default;
            let mut k = 0;
            let mut literals = 0i64;
            let mut open = false;
            while c != NONE {
                if let Some(what) = self.literal_violation(def, c) {
                    let at = self.value_at(values_at.clone(), k)?;
                    return Err(self.default_error(at, attribute, what, def, false));
                }
                // a dynamic default's builtin call: its return type against the slot's
                let x = self.cx.exprs[c as usize];
                if *attribute == "default-dynamic"
                    && def.types != 0
                    && x.op == crate::expr::Op::Call
                    && x.aux == crate::expr::FnKind::Builtin as u8
                {
                    let returns = crate::builtins::get(x.data).returns;
                    if returns.slot_types().is_some_and(|t| t & def.types == 0) {
                        let at = self.value_at(values_at.clone(), k)?;
                        let what = Restriction::Type;
                        return Err(self.default_error(at, attribute, what, def, true));
                    }
                }
                if self.is_literal(c) {
                    literals += 1;
                } else {
                    open = true;
                }
                c = self.cx.exprs[c as usize].next;
                k += 1;
            }
            if def.multi && !self.count_fits(def, literals, open) {
                let at = self.value_at(values_at.clone(), 0)?;
                let what = Restriction::Cardinality;
                return Err(self.default_error(at, attribute, what, def, false));
            }
        }
        Ok(())
    }

    /// The first token of the `k`-th value from `values_at` (re-read, then the reader
    /// is put back where it was).
    fn value_at(&mut self, values_at: ValuesAt<'s>, k: usize) -> PResult<Token<'s>> {
        let resume = self.save();
        self.restore(values_at);
        for _ in 0..k {
            self.skip_balanced()?;
        }
        let at = self.peek();
        self.restore(resume);
        Ok(at)
    }
}
