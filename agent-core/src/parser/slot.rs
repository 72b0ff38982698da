//! A deftemplate slot's attributes — `type`, `default`/`default-dynamic`, the
//! `allowed-...` lists and the accepted-but-unenforced rest — with the checks CLIPS
//! makes when it parses them: each attribute once, values of the type an `allowed-...`
//! attribute names, a `type` that admits every allowed value, and a default that fits
//! both (reported at the offending value).

use super::facts::Violation;
use super::{PResult, Parser, Scope};
use crate::error::LoadDetail;
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
    default: Option<(ValuesAt<'s>, &'static str)>,
    allowed: Option<(ValuesAt<'s>, &'static str)>,
}

/// The `allowed-...` attributes: name, kind, and whether a value fits the kind.
const ALLOWED: [(&str, u8); 7] = [
    ("allowed-values", allowed::VALUES),
    ("allowed-symbols", allowed::SYMBOLS),
    ("allowed-strings", allowed::STRINGS),
    ("allowed-lexemes", allowed::LEXEMES),
    ("allowed-integers", allowed::INTEGERS),
    ("allowed-floats", allowed::FLOATS),
    ("allowed-numbers", allowed::NUMBERS),
];

fn fits_allowed_kind(kind: u8, v: Value) -> bool {
    match kind {
        allowed::SYMBOLS => matches!(v, Value::Sym(_)),
        allowed::STRINGS => matches!(v, Value::Str(_)),
        allowed::LEXEMES => matches!(v, Value::Sym(_) | Value::Str(_)),
        allowed::INTEGERS => matches!(v, Value::Int(_)),
        allowed::FLOATS => matches!(v, Value::Float(_)),
        allowed::NUMBERS => matches!(v, Value::Int(_) | Value::Float(_)),
        _ => true,
    }
}

fn type_bit(v: Value) -> u8 {
    match v {
        Value::Int(_) => types::INTEGER,
        Value::Float(_) => types::FLOAT,
        Value::Sym(_) => types::SYMBOL,
        Value::Str(_) => types::STRING,
        _ => 0,
    }
}

/// CLIPS's name of the restriction a `type` conflicts with, by allowed kind and value.
fn conflict_name(attribute: &'static str, kind: u8, v: Value) -> &'static str {
    match (kind, v) {
        (allowed::INTEGERS | allowed::NUMBERS, Value::Int(_)) => "allowed-integers/numbers",
        (allowed::FLOATS | allowed::NUMBERS, Value::Float(_)) => "allowed-floats/numbers",
        _ => attribute,
    }
}

impl<'s> Parser<'s, '_, '_> {
    /// The attributes of one slot, up to the slot's `)`.
    pub(super) fn slot_attributes(&mut self, mut def: SlotDef) -> PResult<SlotDef> {
        let mut seen = Seen {
            types: false,
            default: None,
            allowed: None,
        };
        loop {
            let t = self.next();
            match t.tok {
                Tok::RParen => {
                    self.check_slot(&def, &seen)?;
                    return Ok(def);
                }
                Tok::LParen => {
                    let at = self.next();
                    let attr = match at.tok {
                        Tok::Symbol(s) => s,
                        _ => return Err(self.err(at, "a slot attribute")),
                    };
                    match attr {
                        "default" | "default-dynamic" => {
                            if seen.default.is_some() {
                                return Err(self.twice(at, "default"));
                            }
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
                            if let Some((_, first)) = seen.allowed {
                                if first == name {
                                    return Err(self.twice(at, name));
                                }
                                if first == "allowed-values" || name == "allowed-values" {
                                    let mut e = self.err(
                                        at,
                                        "allowed-values alone (it cannot be combined with another allowed-... attribute)",
                                    );
                                    e.detail = LoadDetail::AllowedCombined {
                                        first,
                                        second: name,
                                    };
                                    return Err(e);
                                }
                            }
                            let values_at = self.save();
                            self.allowed_attribute(&mut def, name, kind)?;
                            seen.allowed = Some((values_at, name));
                        }
                        "range" | "cardinality" | "visibility" | "storage" | "pattern-match"
                        | "create-accessor" | "override-message" | "access" | "propagation"
                        | "source" => {
                            // accepted, not enforced
                            loop {
                                let tt = self.next();
                                match tt.tok {
                                    Tok::RParen => break,
                                    Tok::Eof | Tok::Bad => return Err(self.err(tt, "')'")),
                                    _ => {}
                                }
                            }
                        }
                        _ => {
                            return Err(self
                                .err(at, "a slot attribute (type, default, allowed-values, ...)"))
                        }
                    }
                }
                _ => return Err(self.err(t, "'(' starting a slot attribute or ')'")),
            }
        }
    }

    /// `[PRNTUTIL5]`: an attribute given a second time (at its name).
    fn twice(&self, at: Token<'s>, attribute: &'static str) -> crate::error::LoadError {
        let mut e = self.err(at, "each slot attribute once");
        e.detail = LoadDetail::AttributeTwice { attribute };
        e
    }

    /// `(default ...)`/`(default-dynamic ...)` after its name; None for `?NONE` and
    /// `?DERIVE`, else where the values start (to check them when the slot ends).
    fn default_attribute(
        &mut self,
        def: &mut SlotDef,
        at: Token<'s>,
        attribute: &'static str,
    ) -> PResult<Option<(ValuesAt<'s>, &'static str)>> {
        if let Tok::SfVar(v @ ("NONE" | "DERIVE")) = self.peek().tok {
            self.next();
            def.default_kind = if v == "NONE" {
                DefaultKind::Required
            } else {
                DefaultKind::Derived
            };
            self.expect_rparen("')' after the default")?;
            return Ok(None);
        }
        let save = self.scope;
        self.scope = Scope::Frame;
        let holder = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
        let values_at = self.save();
        let mut n = 0 as Ix;
        loop {
            let t = self.peek();
            match t.tok {
                Tok::RParen => {
                    self.next();
                    break;
                }
                Tok::Eof | Tok::Bad => return Err(self.err(t, "')'")),
                _ if !def.multi && n == 1 => {
                    return Err(self.err(t, "a single default value for a single-field slot"))
                }
                _ => {
                    let a = self.parse_expr()?;
                    self.cx.append_child(holder, a);
                    n += 1;
                }
            }
        }
        self.scope = save;
        if !def.multi && n != 1 {
            return Err(self.err(at, "exactly one default value for a single-field slot"));
        }
        def.default = self.cx.exprs[holder as usize].first;
        def.default_kind = if attribute == "default" {
            DefaultKind::Static
        } else {
            DefaultKind::Dynamic
        };
        Ok(Some((values_at, attribute)))
    }

    /// `(type T...)` after its name: the type mask (0 for any type).
    fn type_attribute(&mut self) -> PResult<u8> {
        let mut mask = 0u8;
        let mut variable = false;
        loop {
            let tt = self.next();
            let bits = match tt.tok {
                Tok::RParen if mask == 0 && !variable => {
                    return Err(self.attribute_syntax(tt, "a type name", "type attribute"))
                }
                Tok::RParen => return Ok(if variable { 0 } else { mask }),
                // ?VARIABLE stands alone
                Tok::SfVar("VARIABLE") if mask == 0 && !variable => {
                    variable = true;
                    continue;
                }
                Tok::SfVar("VARIABLE") => {
                    return Err(self.attribute_syntax(tt, "?VARIABLE alone", "type attribute"))
                }
                _ if variable => {
                    return Err(self.attribute_syntax(tt, "')' after ?VARIABLE", "type attribute"))
                }
                Tok::Symbol("SYMBOL") => types::SYMBOL,
                Tok::Symbol("STRING") => types::STRING,
                Tok::Symbol("LEXEME") => types::LEXEME,
                Tok::Symbol("INTEGER") => types::INTEGER,
                Tok::Symbol("FLOAT") => types::FLOAT,
                Tok::Symbol("NUMBER") => types::NUMBER,
                Tok::Symbol("FACT-ADDRESS") => types::FACT_ADDRESS,
                _ => return Err(self.err(tt, "a type name")),
            };
            if mask & bits == bits {
                return Err(self.attribute_syntax(tt, "a type not named before", "type attribute"));
            }
            mask |= bits;
        }
    }

    /// `(allowed-KIND v...)` after its name: constants of the kind's type.
    fn allowed_attribute(
        &mut self,
        def: &mut SlotDef,
        name: &'static str,
        kind: u8,
    ) -> PResult<()> {
        let holder = cap!(self, self.cx.push_expr(Expr::new(Op::Nop, 0, 0)))?;
        let mut any = false;
        let close = loop {
            let tt = self.next();
            if tt.tok == Tok::RParen {
                break tt;
            }
            if tt.tok == Tok::SfVar("VARIABLE") {
                any = true;
                continue;
            }
            let c = match self.literal(tt)? {
                Some(c) => c,
                None => return Err(self.err(tt, "a constant allowed value")),
            };
            if !fits_allowed_kind(kind, self.cx.const_value(c)) {
                let mut e = self.err(tt, "a value of the type the allowed-... attribute names");
                e.detail = LoadDetail::AllowedValueType { attribute: name };
                return Err(e);
            }
            self.cx.append_child(holder, c);
        };
        let first = self.cx.exprs[holder as usize].first;
        if first == NONE && !any {
            let what = match name {
                "allowed-symbols" => "allowed-symbols attribute",
                "allowed-strings" => "allowed-strings attribute",
                "allowed-lexemes" => "allowed-lexemes attribute",
                "allowed-integers" => "allowed-integers attribute",
                "allowed-floats" => "allowed-floats attribute",
                "allowed-numbers" => "allowed-numbers attribute",
                _ => "allowed-values attribute",
            };
            return Err(self.attribute_syntax(close, "at least one allowed value", what));
        }
        if first != NONE {
            def.allowed = first;
            def.allowed_kind = kind;
        }
        Ok(())
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
    fn check_slot(&mut self, def: &SlotDef, seen: &Seen<'s>) -> PResult<()> {
        if let Some((values_at, attribute)) = &seen.allowed {
            if def.types != 0 {
                let mut c = def.allowed;
                let mut k = 0;
                while c != NONE {
                    let v = self.cx.const_value(c);
                    if def.types & type_bit(v) == 0 {
                        let at = self.value_at(values_at.clone(), k)?;
                        let mut e = self.err(at, "allowed values of the slot's type");
                        e.detail = LoadDetail::TypeConflict {
                            attribute: conflict_name(attribute, def.allowed_kind, v),
                        };
                        return Err(e);
                    }
                    c = self.cx.exprs[c as usize].next;
                    k += 1;
                }
            }
        }
        if let Some((values_at, attribute)) = &seen.default {
            let mut c = def.default;
            let mut k = 0;
            while c != NONE {
                if let Some(violation) = self.literal_violation(def, c) {
                    let at = self.value_at(values_at.clone(), k)?;
                    let mut e = self.err(at, violation.expected());
                    e.detail = LoadDetail::DefaultConstraint {
                        attribute,
                        types: violation == Violation::Type,
                        slot: def.name,
                    };
                    return Err(e);
                }
                c = self.cx.exprs[c as usize].next;
                k += 1;
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
