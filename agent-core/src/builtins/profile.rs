//! CLIPS 6.30's profiler: `profile`, `profile-info`, `profile-reset`,
//! `get-`/`set-profile-percent-threshold` (agent-core feature `extras`; the agent image
//! has none of them). A rule's firing and a deffunction's call are timed with
//! [`Host::time`] and listed by `profile-info` in CLIPS's layout; the figures are the
//! host's clock's, so only their layout and what is listed can be compared with CLIPS.
//!
//! [`Host::time`]: crate::host::Host::time

use super::describe::{ArgType, Returns};
use super::{Args, Builtin};
use crate::engine::Core;
use crate::error::EvalError;
use crate::host::router;
use crate::value::{Ix, TextBuf, Value};
use core::fmt::Write;

#[rustfmt::skip]
pub const FUNCS: &[Builtin] = &[
    Builtin::eager("profile", 1, 1, profile).args(&[ArgType::Symbol], ArgType::Any).returns(Returns::Void),
    Builtin::eager("profile-info", 0, 1, profile_info).args(&[ArgType::Symbol], ArgType::Any).returns(Returns::Void),
    Builtin::eager("profile-reset", 0, 0, profile_reset).returns(Returns::Void),
    Builtin::eager("set-profile-percent-threshold", 1, 1, set_profile_percent_threshold).args(&[ArgType::Number], ArgType::Any).returns(Returns::Float),
    Builtin::eager("get-profile-percent-threshold", 0, 0, get_profile_percent_threshold).returns(Returns::Float),
];

pub const TABLE: super::Table = super::Table::new(FUNCS);

/// What the profiler counts (`profile`'s argument).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Off,
    Constructs,
    UserFunctions,
}

/// One construct's figures: how often it was entered, its time without and with what
/// it called that was profiled too.
#[derive(Clone, Copy)]
struct Info {
    entries: u32,
    own: f64,
    with_kids: f64,
}

impl Info {
    const ZERO: Info = Info {
        entries: 0,
        own: 0.0,
        with_kids: 0.0,
    };
}

/// A construct being run: which, when it started, when its own time last resumed.
#[derive(Clone, Copy)]
struct Frame {
    rule: bool,
    i: Ix,
    start: f64,
    resumed: f64,
}

/// Most rules and deffunctions profiled (those with a higher index are not): the
/// tables are part of every host engine's state, which `clear` builds afresh.
pub const MOST_PROFILED: usize = 64;
/// Deepest nesting of profiled constructs (deeper calls are not profiled).
const MOST_NESTED: usize = 32;

/// CLIPS's profiler state: its mode, its clock and the figures of each rule and
/// deffunction (by index). CLIPS also profiles COOL's message handlers and, in
/// `user-functions` mode, every builtin called; here `user-functions` mode counts the
/// deffunctions (the functions a program defines) and no builtin.
#[derive(Clone, Copy)]
pub struct Profile {
    mode: Mode,
    /// The mode `profile-info` reports (the last one `profile` set; none after
    /// `profile-reset`).
    last: Mode,
    threshold: f64,
    start: f64,
    total: f64,
    rules: [Info; MOST_PROFILED],
    funcs: [Info; MOST_PROFILED],
    frames: [Frame; MOST_NESTED],
    depth: u8,
    /// Calls nested deeper than `MOST_NESTED`, not profiled.
    skipped: u16,
    /// The host is polled at each deffunction call (`Engine::set_poll_calls`).
    poll_calls: bool,
    /// A deffunction's call goes out of line: profiled or polled (one test per call).
    calls_hooked: bool,
}

impl Default for Profile {
    fn default() -> Profile {
        Profile::new()
    }
}

impl Profile {
    pub const fn new() -> Profile {
        Profile {
            mode: Mode::Off,
            last: Mode::Off,
            threshold: 0.0,
            start: 0.0,
            total: 0.0,
            rules: [Info::ZERO; MOST_PROFILED],
            funcs: [Info::ZERO; MOST_PROFILED],
            frames: [Frame {
                rule: false,
                i: 0,
                start: 0.0,
                resumed: 0.0,
            }; MOST_NESTED],
            depth: 0,
            skipped: 0,
            poll_calls: false,
            calls_hooked: false,
        }
    }

    /// Whether the host is polled at each deffunction call.
    #[inline(always)]
    pub fn polls_calls(&self) -> bool {
        self.poll_calls
    }

    /// Polls the host at each deffunction call, or stops.
    pub fn set_poll_calls(&mut self, on: bool) {
        self.poll_calls = on;
        self.rehook();
    }

    /// After the mode or the poll changed: whether calls go out of line.
    fn rehook(&mut self) {
        self.calls_hooked = self.poll_calls || self.mode != Mode::Off;
    }

    /// After `clear`: the constructs are gone, with their figures.
    pub fn forget_constructs(&mut self) {
        self.rules = [Info::ZERO; MOST_PROFILED];
        self.funcs = [Info::ZERO; MOST_PROFILED];
    }
}

impl Core<'_> {
    /// Whether a deffunction's call goes out of line (`Core::call_deffunction_hooked`):
    /// profiled, or the host polled at it.
    #[inline(always)]
    pub(crate) fn calls_hooked(&self) -> bool {
        self.st.profile.calls_hooked
    }

    /// Whether a rule's firing (`rule`) or a deffunction's call is profiled now.
    #[inline(always)]
    pub(crate) fn profiling(&self, rule: bool) -> bool {
        match self.st.profile.mode {
            Mode::Off => false,
            Mode::Constructs => true,
            Mode::UserFunctions => !rule,
        }
    }

    /// Rule (`rule`) or deffunction `i` starts running, profiled.
    #[cold]
    #[inline(never)]
    pub(crate) fn profile_enter(&mut self, rule: bool, i: Ix) {
        let now = self.host.time();
        let p = &mut self.st.profile;
        let d = usize::from(p.depth);
        if d == MOST_NESTED || (i as usize) >= MOST_PROFILED {
            p.skipped += 1;
            return;
        }
        if d > 0 {
            let f = p.frames[d - 1];
            let parent = if f.rule { &mut p.rules } else { &mut p.funcs };
            parent[f.i as usize].own += now - f.resumed;
        }
        p.frames[d] = Frame {
            rule,
            i,
            start: now,
            resumed: now,
        };
        p.depth += 1;
    }

    /// The construct `profile_enter` started last stops.
    #[cold]
    #[inline(never)]
    pub(crate) fn profile_leave(&mut self, rule: bool, i: Ix) {
        let now = self.host.time();
        let p = &mut self.st.profile;
        if p.depth == 0
            || (i as usize) >= MOST_PROFILED
            || p.skipped > 0 && {
                let top = p.frames[usize::from(p.depth) - 1];
                top.rule != rule || top.i != i
            }
        {
            p.skipped = p.skipped.saturating_sub(1);
            return;
        }
        p.depth -= 1;
        let f = p.frames[usize::from(p.depth)];
        let info = if f.rule { &mut p.rules } else { &mut p.funcs };
        let info = &mut info[f.i as usize];
        info.entries += 1;
        info.own += now - f.resumed;
        // a recursive call's time is counted once, in its outermost call
        let outer = p.frames[..usize::from(p.depth)]
            .iter()
            .any(|o| o.rule == f.rule && o.i == f.i);
        if !outer {
            info.with_kids += now - f.start;
        }
        if p.depth > 0 {
            p.frames[usize::from(p.depth) - 1].resumed = now;
        }
    }
}

/// `(profile constructs|user-functions|off)`.
fn profile(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    let Value::Sym(s) = cx.arg(a, 0) else {
        return Err(EvalError::wrong_type(
            "profile",
            1,
            super::save_facts::T_SYMBOL,
        ));
    };
    let mode = match cx.sym_text(s) {
        "constructs" => Mode::Constructs,
        "user-functions" => Mode::UserFunctions,
        "off" => Mode::Off,
        _ => {
            cx.write(
                router::WERROR,
                "[ARGACCES5] Function profile expected argument #1 to be of type symbol with value constructs, user-functions, or off\n",
            );
            return Ok(Value::Void);
        }
    };
    let now = cx.host.time();
    let p = &mut cx.st.profile;
    if p.mode != Mode::Off {
        p.total += now - p.start;
    }
    if mode != Mode::Off {
        p.start = now;
        p.last = mode;
    }
    p.mode = mode;
    p.rehook();
    // the run loop times rules on its general path
    cx.note_run_slow();
    Ok(Value::Void)
}

/// `(profile-reset)`: every figure to zero; `profile-info` prints nothing until
/// `profile` runs again.
fn profile_reset(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    let now = cx.host.time();
    let p = &mut cx.st.profile;
    p.forget_constructs();
    p.total = 0.0;
    p.start = now;
    p.last = Mode::Off;
    Ok(Value::Void)
}

fn get_profile_percent_threshold(cx: &mut Core<'_>, _a: Args) -> Result<Value, EvalError> {
    Ok(Value::Float(cx.st.profile.threshold))
}

/// `(set-profile-percent-threshold <number>)`: the threshold before, or -1.0 for a
/// number outside 0..=100 (CLIPS's value after its error).
fn set_profile_percent_threshold(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    // (a computed value of another type: the threshold stays, returned)
    let current = Value::Float(cx.st.profile.threshold);
    let n = match cx.arg_num(a, 0, "set-profile-percent-threshold") {
        Ok(n) => n.as_f64(),
        Err(e) => {
            cx.set_error_fallback(current, None);
            return Err(e);
        }
    };
    if !(0.0..=100.0).contains(&n) {
        cx.write(
            router::WERROR,
            "[ARGACCES5] Function set-profile-percent-threshold expected argument #1 to be of type number in the range 0 to 100\n",
        );
        return Ok(Value::Float(-1.0));
    }
    let p = &mut cx.st.profile;
    let old = p.threshold;
    p.threshold = n;
    Ok(Value::Float(old))
}

/// `(profile-info)`: the elapsed time, then each profiled rule's and deffunction's
/// entries and times above the threshold, as CLIPS lays them out.
fn profile_info(cx: &mut Core<'_>, a: Args) -> Result<Value, EvalError> {
    if a.len == 1 && !matches!(cx.arg(a, 0), Value::Sym(_)) {
        return Err(EvalError::wrong_type(
            "profile-info",
            1,
            super::save_facts::T_SYMBOL,
        ));
    }
    let now = cx.host.time();
    let p = &mut cx.st.profile;
    if p.mode != Mode::Off {
        p.total += now - p.start;
        p.start = now;
    }
    let p = cx.st.profile;
    let what = match p.last {
        Mode::Off => return Ok(Value::Void),
        Mode::Constructs => "Construct",
        Mode::UserFunctions => "Function",
    };
    let mut b: TextBuf<256> = TextBuf::new();
    let _ = write!(b, "Profile elapsed time = ");
    let _ = super::format::write_general(&mut b, p.total, 6);
    let _ = writeln!(b, " seconds");
    let _ = writeln!(
        b,
        "{:<41}Entries         Time           %          Time+Kids     %+Kids",
        alloc_free_concat(what, " Name").as_str()
    );
    let dashes = if p.last == Mode::Constructs {
        "--------------"
    } else {
        "-------------"
    };
    let _ = writeln!(
        b,
        "{dashes:<41}-------        ------        -----        ---------     ------"
    );
    cx.write(router::WDISPLAY, b.as_str());
    let sections: [(&str, bool); 2] = [("Deffunctions", false), ("Defrules", true)];
    for (title, rule) in sections {
        if p.last == Mode::UserFunctions && rule {
            continue;
        }
        let mut banner = p.last == Mode::Constructs;
        let count = (if rule {
            cx.st.pools.nrules
        } else {
            cx.st.pools.nfuncs
        }) as usize;
        for i in 0..count.min(MOST_PROFILED) {
            let info = if rule { p.rules[i] } else { p.funcs[i] };
            if info.entries == 0 {
                continue;
            }
            let pct = |t: f64| match p.total {
                0.0 => 0.0,
                total => match t * 100.0 / total {
                    x if x < 0.005 => 0.0,
                    x => x,
                },
            };
            let (own, kids) = (pct(info.own), pct(info.with_kids));
            if own < p.threshold {
                continue;
            }
            let name = if rule {
                cx.rules[i].name
            } else {
                cx.funcs[i].name
            };
            if name == crate::value::NONE {
                continue;
            }
            let mut b: TextBuf<512> = TextBuf::new();
            if banner {
                let _ = write!(b, "\n*** {title} ***\n\n");
                banner = false;
            }
            let mut name = cx.sym_text(name);
            if name.len() >= 40 {
                let _ = writeln!(b, "{name}");
                name = "";
            }
            let _ = writeln!(
                b,
                "{name:<40} {:>7} {:>15.6}  {own:>8.2}%  {:>15.6}  {kids:>8.2}%",
                info.entries, info.own, info.with_kids
            );
            cx.write(router::WDISPLAY, b.as_str());
        }
    }
    Ok(Value::Void)
}

/// `a` then `b`, in a small buffer (for a padded column).
fn alloc_free_concat(a: &str, b: &str) -> TextBuf<32> {
    let mut t = TextBuf::new();
    let _ = write!(t, "{a}{b}");
    t
}

#[cfg(test)]
mod tests {
    extern crate std;
    use crate::engine::SmallEngine;
    use crate::host::Host;
    use std::string::String;

    /// A host whose clock advances one second at each reading.
    #[derive(Default)]
    struct Clock {
        out: String,
        now: f64,
    }

    impl Host for Clock {
        fn write_str(&mut self, _router: &str, text: &str) {
            self.out.push_str(text);
        }
        fn time(&mut self) -> f64 {
            let t = self.now;
            self.now += 1.0;
            t
        }
    }

    fn run(src: &str) -> String {
        let mut e = std::boxed::Box::new(SmallEngine::new());
        let mut h = Clock::default();
        e.batch_str(&mut h, src, false);
        h.out
    }

    #[test]
    fn profile_info_reports_entries_and_times_as_clips_lays_them_out() {
        // clock: profile 0; r enters 1; f enters 2, leaves 3; r leaves 4; info 5
        let out = run("(profile constructs)
             (deffunction f (?x) (* ?x 2))
             (defrule r => (f 3))
             (reset)
             (run)
             (profile-info)");
        let want = "Profile elapsed time = 5 seconds
Construct Name                           Entries         Time           %          Time+Kids     %+Kids
--------------                           -------        ------        -----        ---------     ------

*** Deffunctions ***

f                                              1        1.000000     20.00%         1.000000     20.00%

*** Defrules ***

r                                              1        2.000000     40.00%         3.000000     60.00%
";
        assert_eq!(out, want);
    }

    #[test]
    fn profile_info_drops_rows_under_the_threshold_and_after_a_reset() {
        let out = run("(set-profile-percent-threshold 30)
             (profile user-functions)
             (deffunction g () 1)
             (deffunction f () (g) (g))
             (f)
             (profile-info)
             (profile-reset)
             (profile-info)");
        // f: entered 1, g 2-3, g 4-5, left 6 (own 1+1+1 = 3 of 7); g: own 2 of 7
        assert!(out.contains("Function Name"), "{out}");
        assert!(out.contains("\nf   "), "{out}");
        assert!(!out.contains("\ng   "), "{out}");
        assert!(!out.contains("Deffunctions"), "{out}");
        assert_eq!(out.matches("Profile elapsed").count(), 1, "{out}");
    }

    #[test]
    fn recursion_counts_each_entry_and_the_outer_time_once() {
        let out = run("(profile constructs)
             (deffunction f (?n) (if (> ?n 0) then (f (- ?n 1))))
             (f 2)
             (profile-info)");
        // f entered 1, 2, 3; left 4, 5, 6: kids time 6 - 1 once; info at 7
        assert!(
            out.contains("f                                              3        5.000000"),
            "{out}"
        );
        assert!(out.contains("71.43%         5.000000     71.43%"), "{out}");
    }
}
