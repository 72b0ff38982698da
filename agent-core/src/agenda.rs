//! The agenda: activations ordered by salience, then by CLIPS's depth strategy (newer
//! activations first). Refraction comes from the network: a fired activation is gone,
//! and only a new partial match can activate the rule again.

use crate::engine::{cap, watch, Core};
use crate::error::{CapacityError, Pool};
use crate::rule::Activation;
use crate::value::Ix;
use crate::value::NONE;

/// How many removed activations one modify can put back in place.
pub const JOURNAL_LEN: usize = 16;

/// An activation a modify's retract removed: what it was, and what followed it on
/// the agenda then (identified by creation number, as slots get reused).
#[derive(Clone, Copy, Debug)]
pub struct JournalEntry {
    pub rule: Ix,
    /// Hash of the fact numbers the activation matched.
    pub basis: u32,
    pub seq: u32,
    /// The next activation's `seq`, `None` for the end of the agenda.
    pub next_seq: Option<u32>,
}

/// The activations removed while `on` (see `JournalEntry`); `overflow` once more than
/// `JOURNAL_LEN` were.
#[derive(Clone, Copy, Debug)]
pub struct ActJournal {
    pub on: bool,
    pub overflow: bool,
    pub len: u8,
    pub entries: [JournalEntry; JOURNAL_LEN],
}

impl ActJournal {
    pub const EMPTY: ActJournal = ActJournal {
        on: false,
        overflow: false,
        len: 0,
        entries: [JournalEntry {
            rule: NONE,
            basis: 0,
            seq: 0,
            next_seq: None,
        }; JOURNAL_LEN],
    };
}

impl Core<'_> {
    pub(crate) fn add_activation(&mut self, rule: Ix, token: Ix) -> Result<(), CapacityError> {
        let a = if self.st.act_free != NONE {
            let a = self.st.act_free;
            self.st.act_free = self.acts[a as usize].next;
            a
        } else {
            let n = self.st.acts_used as usize;
            if n >= self.acts.len() || n >= NONE as usize {
                return Err(cap(Pool::Activations, self.acts.len()));
            }
            self.st.acts_used += 1;
            n as Ix
        };
        self.note_hw(Pool::Activations, self.st.acts_used as usize);
        self.st.act_seq = self.st.act_seq.wrapping_add(1);
        let salience = self.rules[rule as usize].salience;
        let next_of_token = self.tokens[token as usize].extra;
        self.acts[a as usize] = Activation {
            rule,
            token,
            salience,
            seq: self.st.act_seq,
            next: NONE,
            prev: NONE,
            next_of_token,
        };
        self.tokens[token as usize].extra = a;
        self.agenda_insert(a);
        if self.st.watch & watch::ACTIVATIONS != 0 {
            self.print_activation_line("==> Activation ", a);
        }
        Ok(())
    }

    /// A rule's salience now (global-based saliences are evaluated again).
    pub(crate) fn rule_salience(&mut self, rule: Ix) -> i32 {
        let e = self.rules[rule as usize].salience_expr;
        if e == NONE {
            return self.rules[rule as usize].salience;
        }
        let (scratch, sp, pm) = (self.st.scratch_top, self.st.sp, self.st.pm_rhs);
        let v = self.eval(e);
        (self.st.scratch_top, self.st.sp, self.st.pm_rhs) = (scratch, sp, pm);
        match v {
            Ok(crate::value::Value::Int(i)) => i.clamp(-10000, 10000) as i32,
            _ => self.rules[rule as usize].salience,
        }
    }

    /// Inserts before the first activation of lower or equal salience.
    fn agenda_insert(&mut self, a: Ix) {
        let sal = self.acts[a as usize].salience;
        let mut prev = NONE;
        let mut cur = self.st.agenda_head;
        while cur != NONE && self.acts[cur as usize].salience > sal {
            prev = cur;
            cur = self.acts[cur as usize].next;
        }
        self.acts[a as usize].prev = prev;
        self.acts[a as usize].next = cur;
        if cur != NONE {
            self.acts[cur as usize].prev = a;
        }
        if prev != NONE {
            self.acts[prev as usize].next = a;
        } else {
            self.st.agenda_head = a;
        }
        self.st.agenda_len += 1;
    }

    fn agenda_unlink(&mut self, a: Ix) {
        let x = self.acts[a as usize];
        self.st.agenda_len -= 1;
        if x.prev != NONE {
            self.acts[x.prev as usize].next = x.next;
        } else {
            self.st.agenda_head = x.next;
        }
        if x.next != NONE {
            self.acts[x.next as usize].prev = x.prev;
        }
    }

    pub(crate) fn remove_activation(&mut self, a: Ix) {
        if self.st.act_journal.on {
            self.journal_activation(a);
        }
        if self.st.watch & watch::ACTIVATIONS != 0 {
            self.print_activation_line("<== Activation ", a);
        }
        self.agenda_unlink(a);
        self.free_activation(a);
    }

    fn free_activation(&mut self, a: Ix) {
        // unlink from the token's activation chain
        let t = self.acts[a as usize].token;
        if t != NONE {
            let mut p = self.tokens[t as usize].extra;
            if p == a {
                self.tokens[t as usize].extra = self.acts[a as usize].next_of_token;
            } else {
                while p != NONE {
                    let n = self.acts[p as usize].next_of_token;
                    if n == a {
                        self.acts[p as usize].next_of_token = self.acts[a as usize].next_of_token;
                        break;
                    }
                    p = n;
                }
            }
        }
        self.acts[a as usize] = Activation {
            next: self.st.act_free,
            ..Activation::EMPTY
        };
        self.st.act_free = a;
    }

    /// Takes the top activation off the agenda (it fires; refraction keeps it gone).
    pub(crate) fn pop_activation(&mut self) -> Option<(Ix, Ix)> {
        let a = self.st.agenda_head;
        if a == NONE {
            return None;
        }
        let x = self.acts[a as usize];
        self.agenda_unlink(a);
        self.free_activation(a);
        Some((x.rule, x.token))
    }

    /// `refresh-agenda`: global-based saliences are evaluated again (CLIPS's
    /// when-defined evaluation otherwise keeps them), then the agenda is re-sorted.
    pub fn reorder_agenda(&mut self) {
        for r in 0..self.st.nrules {
            if self.rules[r as usize].salience_expr != NONE {
                let s = self.rule_salience(r);
                self.rules[r as usize].salience = s;
            }
        }
        let mut list = self.st.agenda_head;
        self.st.agenda_head = NONE;
        self.st.agenda_len = 0;
        // re-insert oldest first so newer stay ahead among equals
        let mut tail = list;
        while tail != NONE && self.acts[tail as usize].next != NONE {
            tail = self.acts[tail as usize].next;
        }
        list = tail;
        while list != NONE {
            let prev = self.acts[list as usize].prev;
            let rule = self.acts[list as usize].rule;
            self.acts[list as usize].salience = self.rules[rule as usize].salience;
            self.agenda_insert(list);
            list = prev;
        }
    }

    pub fn agenda_len(&self) -> usize {
        let mut n = 0;
        let mut a = self.st.agenda_head;
        while a != NONE {
            n += 1;
            a = self.acts[a as usize].next;
        }
        n
    }

    /// Hash of the fact numbers an activation matched (its identity across a rebuild).
    fn activation_basis(&self, a: Ix) -> u32 {
        // walks the partial match up to the root: (depth, fact number) pairs
        let mut h = 0x9E37_79B9u32;
        let mut t = self.acts[a as usize].token;
        while t != NONE {
            let tk = self.tokens[t as usize];
            let j = self.joins[tk.owner as usize];
            if j.kind == crate::rete::JoinKind::Root {
                break;
            }
            let num = if tk.am != NONE {
                self.facts[self.tokens[tk.am as usize].fact as usize].num
            } else {
                u32::MAX
            };
            h = (h ^ j.depth as u32).wrapping_mul(0x0100_0193);
            h = (h ^ num).wrapping_mul(0x0100_0193).rotate_left(5);
            t = tk.parent;
        }
        h
    }

    fn journal_activation(&mut self, a: Ix) {
        let j = &self.st.act_journal;
        if j.len as usize >= JOURNAL_LEN {
            self.st.act_journal.overflow = true;
            return;
        }
        let x = self.acts[a as usize];
        let entry = JournalEntry {
            rule: x.rule,
            basis: self.activation_basis(a),
            seq: x.seq,
            next_seq: (x.next != NONE).then(|| self.acts[x.next as usize].seq),
        };
        let j = &mut self.st.act_journal;
        j.entries[j.len as usize] = entry;
        j.len += 1;
    }

    /// Starts recording the activations removed from now on (see `JournalEntry`).
    pub(crate) fn journal_start(&mut self) {
        self.st.act_journal = ActJournal {
            on: true,
            ..ActJournal::EMPTY
        };
    }

    pub(crate) fn journal_stop(&mut self) {
        self.st.act_journal.on = false;
    }

    /// After a failed modify rebuilt the old fact's matches: gives each activation
    /// created since `mark` that the journal recorded its creation number back and
    /// puts it where it was, before the activation that followed it. Latest removed
    /// first, so a follower that was itself removed is already back in place.
    /// Activations that cannot be matched up stay where the rebuild put them.
    pub(crate) fn journal_restore(&mut self, mark: u32) {
        let j = self.st.act_journal;
        if j.overflow {
            return;
        }
        for e in j.entries[..j.len as usize].iter().rev() {
            let mut a = self.st.agenda_head;
            while a != NONE {
                let x = self.acts[a as usize];
                if x.seq.wrapping_sub(mark) as i32 > 0
                    && x.rule == e.rule
                    && self.activation_basis(a) == e.basis
                {
                    break;
                }
                a = x.next;
            }
            if a == NONE {
                continue;
            }
            // the follower, or the last activation for the end of the agenda
            let mut after = NONE;
            let mut before = NONE;
            let mut c = self.st.agenda_head;
            let mut found = e.next_seq.is_none();
            while c != NONE {
                if c != a && Some(self.acts[c as usize].seq) == e.next_seq {
                    before = c;
                    found = true;
                    break;
                }
                if c != a {
                    after = c;
                }
                c = self.acts[c as usize].next;
            }
            if !found {
                continue;
            }
            self.acts[a as usize].seq = e.seq;
            self.agenda_unlink(a);
            // between `after` (last one before the follower, or the tail) and `before`
            let prev = if before != NONE {
                self.acts[before as usize].prev
            } else {
                after
            };
            let sal = self.acts[a as usize].salience;
            if (prev != NONE && self.acts[prev as usize].salience < sal)
                || (before != NONE && self.acts[before as usize].salience > sal)
            {
                // salience changed meanwhile: the old place is no longer valid
                self.agenda_insert(a);
                continue;
            }
            self.acts[a as usize].prev = prev;
            self.acts[a as usize].next = before;
            if prev != NONE {
                self.acts[prev as usize].next = a;
            } else {
                self.st.agenda_head = a;
            }
            if before != NONE {
                self.acts[before as usize].prev = a;
            }
            self.st.agenda_len += 1;
        }
    }
}
