//! One robot of the team as the host sees its engine: `rules/team.clp` loaded (after
//! whatever else the robot runs, e.g. the agent), the robot's clock, messages handed in
//! as `team-recv` facts and taken out from `team-send` facts, wants asserted and
//! retracted, and the claims it holds read back.

use std::fmt;

use agent_core::{DefaultEngine, EngineError, FactId, Host, ValueRef};
use rules::RuleFile;

/// A team message as `team-send`/`team-recv` carry it (see `rules/team.clp`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TeamMsg {
    pub from: u8,
    pub seq: i64,
    /// `request`, `grant` or `release`.
    pub kind: String,
    /// The receiver of a grant; 0 for everybody.
    pub to: i64,
    pub resource: String,
    pub rseq: i64,
    pub lease: f64,
    /// `news`: the sender's belief of the resource, as symbols.
    pub data: Vec<String>,
}

impl TeamMsg {
    /// The `team-recv` fact the receiver's engine gets.
    pub fn recv_fact(&self) -> String {
        format!(
            "(team-recv (from {}) (seq {}) (kind {}) (to {}) (resource {}) (rseq {}) (lease {:?}) (data {}))",
            self.from,
            self.seq,
            self.kind,
            self.to,
            self.resource,
            self.rseq,
            self.lease,
            self.data.join(" ")
        )
    }
}

/// What went wrong in a robot's team engine.
#[derive(Debug)]
pub struct TeamError {
    pub robot: u8,
    pub during: String,
    pub message: String,
}

impl fmt::Display for TeamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "robot {}: {}: {}", self.robot, self.during, self.message)
    }
}

impl std::error::Error for TeamError {}

/// Collects what the engine prints (kept for error context).
#[derive(Default)]
pub struct MemberHost {
    pub output: String,
}

impl Host for MemberHost {
    fn write_str(&mut self, _router: &str, text: &str) {
        if self.output.len() < 1 << 16 {
            self.output.push_str(text);
        }
    }
    // (no stop button here: `run` skips its per-firing poll)
    fn never_interrupts(&self) -> bool {
        true
    }
}

/// Most rule firings one step may take: message handling fires a few rules per message;
/// this many means the rules loop.
const STEP_FIRE_LIMIT: u32 = 200_000;

/// One robot's engine with `rules/team.clp`.
pub struct TeamMember {
    pub engine: Box<DefaultEngine>,
    pub host: MemberHost,
    pub id: u8,
    now: f64,
}

impl TeamMember {
    /// An engine with `files` and then `rules/team.clp` loaded; `team_text` replaces the
    /// file's text (tests load broken variants of the protocol). Call from a thread with
    /// a large stack (the engine is built inline before it is boxed).
    pub fn new(files: &[RuleFile], team_text: Option<&str>) -> Result<TeamMember, TeamError> {
        let mut m = TeamMember {
            engine: Box::new(DefaultEngine::new()),
            host: MemberHost::default(),
            id: 0,
            now: 0.0,
        };
        // a robot's engine never lists its rules, and the agent's, collect's and the
        // team's rules with their source text would not fit the symbol table
        m.engine.set_pretty_print_forms(false);
        for f in files {
            m.load(f.name, f.text)?;
        }
        m.load(rules::TEAM.name, team_text.unwrap_or(rules::TEAM.text))?;
        Ok(m)
    }

    fn load(&mut self, name: &str, text: &str) -> Result<(), TeamError> {
        self.engine
            .load_str(&mut self.host, name, text)
            .map(|_| ())
            .map_err(|e| self.err(&format!("loading {name}"), e))
    }

    fn err(&self, during: &str, e: impl fmt::Display) -> TeamError {
        TeamError {
            robot: self.id,
            during: during.to_string(),
            message: format!("{e} (output: {})", self.host.output.trim()),
        }
    }

    /// `(reset)`, then this robot's identity and clock; `globals` overrides defglobals
    /// of the protocol (e.g. `("TEAM_LEASE", 6.0)`).
    pub fn start(
        &mut self,
        id: u8,
        robots: u8,
        now: f64,
        globals: &[(&str, f64)],
    ) -> Result<(), TeamError> {
        self.id = id;
        self.now = now;
        self.engine
            .reset(&mut self.host)
            .map_err(|e| self.err("(reset)", e))?;
        for (name, value) in globals {
            self.eval(&format!("(bind ?*{name}* {value:?})"))?;
        }
        self.assert(&format!("(team-self (id {id}) (robots {robots}))"))?;
        self.assert(&format!("(team-clock (now {now:?}))"))?;
        Ok(())
    }

    pub fn eval(&mut self, command: &str) -> Result<(), TeamError> {
        self.engine
            .eval_str(&mut self.host, command)
            .map(|_| ())
            .map_err(|e| self.err(command, e))
    }

    pub fn assert(&mut self, fact: &str) -> Result<FactId, TeamError> {
        self.engine
            .assert_str(&mut self.host, fact)
            .map_err(|e| self.err(&format!("asserting {fact}"), e))
    }

    /// This robot's clock (game time as it reads it).
    pub fn now(&self) -> f64 {
        self.now
    }

    pub fn set_time(&mut self, now: f64) -> Result<(), TeamError> {
        self.now = now;
        self.eval(&format!("(team-set-time {now:?})"))
    }

    /// Hands a message in. A copy of one still pending is one fact already (CLIPS keeps
    /// no duplicate facts): nothing to do.
    pub fn receive(&mut self, msg: &TeamMsg) -> Result<(), TeamError> {
        match self.engine.assert_str(&mut self.host, &msg.recv_fact()) {
            Ok(_) | Err(EngineError::Duplicate) => Ok(()),
            Err(e) => Err(self.err("receiving a message", e)),
        }
    }

    pub fn run(&mut self) -> Result<u32, TeamError> {
        let fired = self
            .engine
            .run(&mut self.host, Some(STEP_FIRE_LIMIT))
            .map_err(|e| self.err("(run)", e))?;
        if fired >= STEP_FIRE_LIMIT {
            return Err(self.err("(run)", "the rules fired without end"));
        }
        Ok(fired)
    }

    fn facts_of(&self, template: &str) -> Vec<FactId> {
        self.engine.facts_of(template).collect()
    }

    fn int(&self, id: FactId, slot: &str) -> i64 {
        slot_int(&self.engine, id, slot)
    }

    fn float(&self, id: FactId, slot: &str) -> f64 {
        slot_float(&self.engine, id, slot)
    }

    fn sym(&self, id: FactId, slot: &str) -> String {
        slot_sym(&self.engine, id, slot)
    }

    fn symbols(&self, id: FactId, slot: &str) -> Vec<String> {
        let n = match self.engine.fact_slot(id, slot) {
            Some(ValueRef::Multi(n)) => n as usize,
            _ => 0,
        };
        (0..n)
            .filter_map(|i| match self.engine.fact_multislot_item(id, slot, i) {
                Some(ValueRef::Symbol(s)) => Some(s.to_string()),
                Some(ValueRef::Int(i)) => Some(i.to_string()),
                _ => None,
            })
            .collect()
    }

    /// Takes the messages the rules want sent (retracting their `team-send` facts), in
    /// the order the robot numbered them.
    pub fn outbox(&mut self) -> Result<Vec<TeamMsg>, TeamError> {
        let ids = self.facts_of("team-send");
        let mut out = Vec::with_capacity(ids.len());
        for id in ids {
            out.push(TeamMsg {
                from: self.id,
                seq: self.int(id, "seq"),
                kind: self.sym(id, "kind"),
                to: self.int(id, "to"),
                resource: self.sym(id, "resource"),
                rseq: self.int(id, "rseq"),
                lease: self.float(id, "lease"),
                data: self.symbols(id, "data"),
            });
            self.engine
                .retract(&mut self.host, id)
                .map_err(|e| self.err("retracting a team-send", e))?;
        }
        out.sort_by_key(|m| m.seq);
        Ok(out)
    }

    /// The agent (or a test) wants resource `x`.
    pub fn want(&mut self, x: &str) -> Result<(), TeamError> {
        if self.wants().iter().any(|w| w == x) {
            return Ok(());
        }
        self.assert(&format!("(team-want (resource {x}))"))
            .map(|_| ())
    }

    /// No longer wants `x` (releases the claim at the next run).
    pub fn unwant(&mut self, x: &str) -> Result<(), TeamError> {
        for id in self.facts_of("team-want") {
            if self.sym(id, "resource") == x {
                self.engine
                    .retract(&mut self.host, id)
                    .map_err(|e| self.err("retracting a team-want", e))?;
            }
        }
        Ok(())
    }

    pub fn wants(&self) -> Vec<String> {
        self.facts_of("team-want")
            .into_iter()
            .map(|id| self.sym(id, "resource"))
            .collect()
    }

    /// The resources this robot holds now, on its own clock.
    pub fn held(&self) -> Vec<String> {
        self.facts_of("team-claim")
            .into_iter()
            .filter(|&id| self.float(id, "until") > self.now)
            .map(|id| self.sym(id, "resource"))
            .collect()
    }

    pub fn holds(&self, x: &str) -> bool {
        self.held().iter().any(|h| h == x)
    }

    /// Resources whose vote this robot has given to another robot, still running: what
    /// it knows to be busy.
    pub fn busy_elsewhere(&self) -> Vec<(String, u8)> {
        self.facts_of("team-vote")
            .into_iter()
            .filter(|&id| self.float(id, "until") > self.now)
            .filter_map(|id| {
                let holder = u8::try_from(self.int(id, "holder")).ok()?;
                (holder != self.id).then(|| (self.sym(id, "resource"), holder))
            })
            .collect()
    }
}

/// A fact's slot as an integer (a float truncated); 0 when absent or of another type.
pub fn slot_int(engine: &DefaultEngine, id: FactId, slot: &str) -> i64 {
    match engine.fact_slot(id, slot) {
        Some(ValueRef::Int(i)) => i,
        Some(ValueRef::Float(f)) => f as i64,
        _ => 0,
    }
}

/// A fact's slot as a number; 0.0 when absent or not a number.
pub fn slot_float(engine: &DefaultEngine, id: FactId, slot: &str) -> f64 {
    match engine.fact_slot(id, slot) {
        Some(ValueRef::Int(i)) => i as f64,
        Some(ValueRef::Float(f)) => f,
        _ => 0.0,
    }
}

/// A fact's slot as text (symbol or string); empty when absent or of another type.
pub fn slot_sym(engine: &DefaultEngine, id: FactId, slot: &str) -> String {
    match engine.fact_slot(id, slot) {
        Some(ValueRef::Symbol(s)) | Some(ValueRef::String(s)) => s.to_string(),
        _ => String::new(),
    }
}
