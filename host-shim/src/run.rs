//! `robotino-agent run`: one robot's agent loop. Each cycle it reads the newest sensor
//! samples over iceoryx2, advances the running skill, passes the skill's twist through the
//! safety monitor and publishes the motor command, then reports the skill's status. Skill
//! outcomes and perceptions become facts of the agent's rule base (our engine); whenever
//! the robot is idle and something changed, the engine runs to quiescence and the skill it
//! chose starts.

use hal::device::{
    Bumper, Device, Freshness, GateSignal, Gyro, IrRing, MachineLight, Odometry, OmniDrive,
    PuckRelease, PuckSensor,
};
use hal::field::MachineId;
use hal::ir::IrScan;
use hal::skill::{SkillOutcome, SkillRequest};
use hal::{Pose2, Twist};
use host_shim::shim::agent::{ChosenSkill, EngineAgent, MachineView};
use host_shim::shim::behaviour::{DriveTuning, Perceived, Skill};
use host_shim::shim::config::Config;
use host_shim::shim::drivers::{usable, DriverError, SimDrivers};
use host_shim::shim::lockstep::{spawn_heartbeat, FrameWatch};
use host_shim::shim::payloads::{
    MachineClaimPayload, SkillRequestPayload, SkillStatus, SkillStatusPayload, WorldModelPayload,
};
use host_shim::shim::rule_engine::exit_from_engine_stack;
use host_shim::shim::safety::{CycleInput, SafetyMonitor, Stream};
use host_shim::shim::team::TeamView;
use host_shim::shim::transport::{Pub, RobotStream, Sub, TeamStream, Transport, TransportError};
use rules::Strategy;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

#[derive(clap::Args)]
pub struct Args {
    /// Configuration file (TOML); defaults to a Robotino 2.
    #[arg(long)]
    pub config: Option<PathBuf>,
    /// Service-name prefix (overrides the file).
    #[arg(long)]
    pub prefix: Option<String>,
    /// Robot number 1..=3 (overrides the file).
    #[arg(long)]
    pub robot: Option<u8>,
    /// Stop after this many cycles (0: run until terminated).
    #[arg(long, default_value_t = 0)]
    pub cycles: u64,
    /// Cycle in lockstep with the sim: a cycle per complete sensor frame, however long it
    /// takes to come (the sim waits for this agent's answer as long as its heartbeat beats).
    #[arg(long)]
    pub lockstep: bool,
    /// Simulated seconds per wall-clock second (overrides the file).
    #[arg(long)]
    pub time_warp: Option<f32>,
    /// Production strategy of the agent's rules: naive, paper or travel.
    #[arg(long, default_value = "paper", value_parser = crate::sim::parse_strategy)]
    pub strategy: Strategy,
    /// Also print every cycle's and every decision's time (one `stat` line each).
    #[arg(long)]
    pub stats: bool,
}

pub fn main(args: Args) -> ExitCode {
    // The engine's arrays pass through the stack on their way to the heap.
    exit_from_engine_stack(move || match run(&args) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("robotino-agent run: {e}");
            1
        }
    })
}

/// The agent's ports for one robot.
struct AgentPorts {
    request: Pub<SkillRequestPayload>,
    status: Pub<SkillStatusPayload>,
    world_out: Pub<WorldModelPayload>,
    world_in: Sub<WorldModelPayload>,
    claims_out: Pub<MachineClaimPayload>,
    claims_in: Sub<MachineClaimPayload>,
}

impl AgentPorts {
    fn open(t: &Transport, robot: u8) -> Result<Self, TransportError> {
        let name = |s| t.names.robot(robot, s);
        Ok(Self {
            request: t.publisher(&name(RobotStream::SkillRequest))?,
            status: t.publisher(&name(RobotStream::SkillStatus))?,
            world_out: t.publisher(&t.names.team(TeamStream::WorldModel))?,
            world_in: t.subscriber(&t.names.team(TeamStream::WorldModel))?,
            claims_out: t.publisher(&t.names.team(TeamStream::Claims))?,
            claims_in: t.subscriber(&t.names.team(TeamStream::Claims))?,
        })
    }
}

/// The newest valid samples: a sample that fails validation is ignored, so it is not fresh.
struct Samples {
    seq: [Option<u32>; Stream::COUNT],
    bumper_pressed: bool,
    /// When a pressed bumper sample following a released one was received, and in which
    /// cycle (the loop's count at receipt): the start of the bumper-latency measurement.
    bumper_hit: Option<(Instant, u64)>,
    perceived: Perceived,
    gate: Option<hal::field::GateId>,
}

impl Samples {
    fn new() -> Self {
        Self {
            seq: [None; Stream::COUNT],
            bumper_pressed: false,
            bumper_hit: None,
            perceived: Perceived {
                pose: Pose2::default(),
                ir: IrScan::EMPTY,
                has_puck: false,
                light: None,
            },
            gate: None,
        }
    }

    /// Reads every device through the `hal` traits; a missing or invalid reading keeps
    /// the last one (and its stream goes stale for the safety monitor).
    fn read<D>(&mut self, d: &mut D, cycle: u64) -> Result<(), DriverError>
    where
        D: IrRing<Error = DriverError>
            + Bumper<Error = DriverError>
            + Gyro<Error = DriverError>
            + Odometry<Error = DriverError>
            + PuckSensor<Error = DriverError>
            + MachineLight<Error = DriverError>
            + GateSignal<Error = DriverError>
            + Freshness,
    {
        if let Some(scan) = usable(d.read_scan())? {
            self.perceived.ir = scan;
        }
        if let Some(pressed) = usable(d.is_pressed())? {
            if pressed && !self.bumper_pressed {
                self.bumper_hit = Some((Instant::now(), cycle));
            }
            self.bumper_pressed = pressed;
        }
        usable(Gyro::read(d))?;
        if let Some(o) = usable(d.read_pose())? {
            self.perceived.pose = o.pose;
        }
        if let Some(present) = usable(d.has_puck())? {
            self.perceived.has_puck = present;
        }
        if let Some(light) = usable(d.read_light())? {
            self.perceived.light = light;
        }
        if let Some(gate) = usable(d.active_gate())? {
            self.gate = gate.or(self.gate);
        }
        for s in Stream::ALL {
            self.seq[s as usize] = d.sequence(match s {
                Stream::Ir => Device::Ir,
                Stream::Bumper => Device::Bumper,
                Stream::Gyro => Device::Gyro,
                Stream::Odometry => Device::Odometry,
                Stream::Puck => Device::Puck,
            });
        }
        Ok(())
    }
}

struct Running {
    skill: Skill,
    chosen: ChosenSkill,
    request_seq: u32,
}

fn run(args: &Args) -> Result<(), Box<dyn std::error::Error>> {
    let mut config = Config::load(args.config.as_deref())?;
    if let Some(p) = &args.prefix {
        config.services.prefix = p.clone();
    }
    if let Some(r) = args.robot {
        config.robot.number = r;
    }
    if let Some(w) = args.time_warp {
        config.timing.time_warp = w;
    }
    config.timing.lockstep |= args.lockstep;
    let robot = config.robot.number;
    let mut mind = Mind {
        robot,
        agent: EngineAgent::new(args.strategy)?,
        team: TeamView::new(robot),
        dirty: true,
        done_reported: false,
        published: [MachineView::default(); hal::field::MACHINE_COUNT],
    };
    let transport = Transport::open(&config.services.prefix, &format!("robotino-agent-{robot}"))?;
    let mut ports = AgentPorts::open(&transport, robot)?;
    let mut drivers = SimDrivers::open(&transport, robot)?;
    let mut frames = FrameWatch::open(&transport, robot)?;
    // The sim tells a dead agent from a slow one by this thread's beats.
    let beat_cycle = Arc::new(AtomicU64::new(0));
    spawn_heartbeat(
        &transport.names,
        robot,
        Duration::from_millis(config.timing.heartbeat_period_ms),
        Arc::clone(&beat_cycle),
    )?;
    let tuning = DriveTuning {
        max_linear_m_s: config.limits.max_linear_m_s,
        max_angular_rad_s: config.limits.max_angular_rad_s,
        max_linear_acc_m_s2: config.limits.max_linear_acc_m_s2,
        robot_radius_m: config.robot.radius_m,
        robot_number: config.robot.number,
        ..DriveTuning::default()
    };
    let mut monitor = SafetyMonitor::new(
        config.geometry(),
        config.limits(),
        config.cycle_s(),
        config.timing.sensor_deadline_cycles,
        config.timing.skill_timeout_cycles,
    );
    let mut samples = Samples::new();
    let mut running: Option<Running> = None;
    let mut stats = LoopStats::default();
    let wall_cycle = config.wall_cycle();
    let poll = Duration::from_micros(200);
    let start = Instant::now();
    let mut cycle: u64 = 0;
    println!(
        "robotino-agent run: robot={robot} prefix={} strategy={} engine=rules",
        config.services.prefix,
        args.strategy.name()
    );

    loop {
        // Wait for the cycle: the sim's next complete frame in lockstep, else the clock.
        loop {
            let due = if config.timing.lockstep {
                frames.fresh_frame()?
            } else {
                start.elapsed() >= wall_cycle * (cycle as u32 + 1)
            };
            if due {
                break;
            }
            if !transport.wait(poll) {
                stats.report(cycle, &mind.agent);
                return Ok(());
            }
        }
        let work_start = Instant::now();
        cycle += 1;
        beat_cycle.store(cycle, Ordering::Relaxed);
        samples.read(&mut drivers, cycle)?;
        let p = samples.perceived;
        mind.listen(&mut ports, cycle)?;
        if let Some(g) = samples.gate {
            if !mind.agent.knows_gate() {
                mind.agent.see_active_gate(g)?;
                mind.dirty = true;
            }
        }
        // Late joiners: repeat what we found out now and then (the service keeps one sample).
        if cycle.is_multiple_of(150) {
            for m in MachineId::all() {
                if mind
                    .team
                    .machine(m)
                    .machine_type
                    .is_some_and(|(_, by)| by == robot)
                {
                    mind.publish_belief(&mut ports, m)?;
                }
            }
        }

        // Idle: let the rules decide, but only once every driver is fresh (a skill planned
        // from a pose never received would start from the field's corner) and the gate's
        // light was seen (the rules deliver to it).
        let drivers_fresh = samples.seq.iter().all(Option::is_some)
            && Stream::ALL
                .iter()
                .all(|&s| monitor.staleness(s) < config.timing.sensor_deadline_cycles);
        let mut decided = None;
        if running.is_none() && drivers_fresh && mind.agent.knows_gate() && mind.dirty {
            let t0 = Instant::now();
            let chosen = mind.decide(&mut ports, cycle)?;
            decided = Some(t0.elapsed());
            if let Some(chosen) = chosen {
                let request = chosen.request;
                let request_seq = ports
                    .request
                    .send(|s| SkillRequestPayload::encode(s, robot, request))?;
                monitor.skill_started();
                if let SkillRequest::BringPuckTo(m) = request {
                    mind.claim(&mut ports, m, true)?;
                }
                println!(
                    "robotino-agent run: cycle={cycle} start {request:?} (skill-request {} {} {} holding {})",
                    chosen.id, chosen.name, chosen.target, chosen.puck
                );
                match Skill::start(request, &p, &tuning) {
                    Ok(skill) => {
                        running = Some(Running {
                            skill,
                            chosen,
                            request_seq,
                        })
                    }
                    Err(reason) => {
                        let outcome = SkillOutcome::Failed(reason);
                        mind.finish(&mut ports, &chosen, request_seq, outcome, cycle)?;
                    }
                }
            }
        }

        // Two robots claimed the same machine in the same moment: the lower number goes
        // first, the other waits where it is until the machine is free.
        let lost_claim = running.as_ref().is_some_and(|r| match r.skill.request() {
            SkillRequest::BringPuckTo(m) => mind
                .team
                .machine(m)
                .claimed_by
                .is_some_and(|other| other < robot),
            _ => false,
        });
        let (desired, mut outcome) = match running.as_mut() {
            Some(_) if lost_claim => (Twist::ZERO, SkillOutcome::Running),
            Some(r) => r.skill.step(&p, &tuning),
            None => (Twist::ZERO, SkillOutcome::Running),
        };
        let decision = monitor.step(&CycleInput {
            latest_seq: samples.seq,
            bumper_pressed: samples.bumper_pressed,
            desired,
            skill_running: running.is_some() && !outcome.is_terminal(),
        });
        if let Some(reason) = decision.fail_skill {
            // A stop while only backing away from the station does not undo the work.
            outcome = match running.as_ref().and_then(|r| r.skill.done_perception()) {
                Some(p) => SkillOutcome::Final(p),
                None => SkillOutcome::Failed(reason),
            };
        }
        let release = running
            .as_ref()
            .is_some_and(|r| r.skill.releasing() && !outcome.is_terminal());
        drivers.set_release(release)?;
        drivers.set_motor_speeds(decision.wheels)?;
        if let Some((received, at_cycle)) = samples.bumper_hit {
            if decision.wheels.is_zero() {
                stats.bumper(received.elapsed(), cycle - at_cycle.min(cycle));
                samples.bumper_hit = None;
            }
        }

        if let Some(r) = running.as_ref() {
            let request = r.skill.request();
            if outcome.is_terminal() {
                let chosen = r.chosen.clone();
                let request_seq = r.request_seq;
                running = None;
                mind.finish(&mut ports, &chosen, request_seq, outcome, cycle)?;
            } else {
                let status = SkillStatus {
                    request_seq: r.request_seq,
                    robot,
                    request,
                    outcome,
                };
                ports
                    .status
                    .send(|s| SkillStatusPayload::encode(s, &status))?;
            }
        }
        let work = work_start.elapsed();
        stats.record(work, decided);
        if args.stats {
            println!(
                "robotino-agent run: stat cycle={cycle} work_us={} decision_us={}",
                work.as_micros(),
                decided.map_or(0, |d| d.as_micros())
            );
        }
        if cycle.is_multiple_of(150) {
            println!(
                "robotino-agent run: cycle={cycle} pose=({:.2},{:.2},{:.2}) puck={} hold={:?} state={}",
                p.pose.x_m,
                p.pose.y_m,
                p.pose.phi_rad,
                p.has_puck,
                decision.hold,
                mind.agent.state().unwrap_or_default()
            );
        }
        if args.cycles > 0 && cycle >= args.cycles {
            stats.report(cycle, &mind.agent);
            return Ok(());
        }
    }
}

/// What the robot knows beyond its sensors: the agent's rules and the team's shared
/// picture.
struct Mind {
    robot: u8,
    agent: EngineAgent,
    team: TeamView,
    /// Facts changed since the rules last ran.
    dirty: bool,
    /// The machine views last published (or taken from a teammate).
    published: [MachineView; hal::field::MACHINE_COUNT],
    done_reported: bool,
}

impl Mind {
    /// Runs the rules, publishes what they found out, and returns the skill they chose.
    fn decide(
        &mut self,
        ports: &mut AgentPorts,
        cycle: u64,
    ) -> Result<Option<ChosenSkill>, Box<dyn std::error::Error>> {
        let chosen = self.agent.decide()?;
        self.dirty = false;
        let printed = self.agent.take_output();
        if !printed.is_empty() {
            print!("{printed}");
        }
        self.share_findings(ports, cycle)?;
        if let Some(c) = &chosen {
            if let SkillRequest::BringPuckTo(m) = c.request {
                if let Some((t, by)) = self.team.machine(m).machine_type {
                    if by != self.robot {
                        println!(
                            "robotino-agent run: cycle={cycle} using shared type M{} T{t} from robot {by}",
                            m.number()
                        );
                    }
                }
            }
        } else if self.agent.is_done() && !self.done_reported {
            self.done_reported = true;
            println!("robotino-agent run: cycle={cycle} agent DONE (storage empty, hands empty)");
        }
        Ok(chosen)
    }

    /// Publishes what the rules believe of a machine whenever it changed by their own
    /// doing (a type found out, inputs loaded); logs types the team did not know yet.
    fn share_findings(&mut self, ports: &mut AgentPorts, cycle: u64) -> Result<(), TransportError> {
        for (m, view) in MachineId::all().zip(self.agent.machines()) {
            if self.published[m.index()] == view {
                continue;
            }
            self.published[m.index()] = view;
            if self.team.record_own(m, view.machine_type, view.loaded) {
                println!(
                    "robotino-agent run: cycle={cycle} learned M{} T{}",
                    m.number(),
                    view.machine_type.unwrap_or(0)
                );
            }
            self.publish_belief(ports, m)?;
        }
        Ok(())
    }

    fn claim(
        &mut self,
        ports: &mut AgentPorts,
        m: MachineId,
        claimed: bool,
    ) -> Result<(), TransportError> {
        self.team.apply_claim(self.robot, m, claimed);
        let robot = self.robot;
        ports
            .claims_out
            .send(|s| MachineClaimPayload::encode(s, robot, m, claimed))?;
        Ok(())
    }

    fn publish_belief(&self, ports: &mut AgentPorts, m: MachineId) -> Result<(), TransportError> {
        let belief = self.team.belief(m);
        ports
            .world_out
            .send(|s| WorldModelPayload::encode(s, &belief))?;
        Ok(())
    }

    /// Takes teammates' world-model updates (a type they found out narrows our rules'
    /// belief) and claims.
    fn listen(
        &mut self,
        ports: &mut AgentPorts,
        cycle: u64,
    ) -> Result<(), Box<dyn std::error::Error>> {
        let mut learned = Vec::new();
        let team = &mut self.team;
        ports.world_in.drain(|p| {
            if let Ok(b) = p.decode() {
                if team.apply_belief(&b) {
                    learned.push(b);
                }
            }
        })?;
        for b in learned {
            let t = b.machine_type.unwrap_or(0);
            let adopted = self.agent.adopt(b.machine, b.machine_type, b.loaded)?;
            self.dirty |= adopted;
            // What we took from a teammate is not news to repeat.
            self.published[b.machine.index()] = self.agent.machines()[b.machine.index()];
            println!(
                "robotino-agent run: cycle={cycle} belief from robot {}: M{} T{t} loaded={} adopted={adopted}",
                b.robot,
                b.machine.number(),
                b.loaded
            );
        }
        ports.claims_in.drain(|p| {
            if let Ok((robot, m, claimed)) = p.decode() {
                if robot != team.me {
                    team.apply_claim(robot, m, claimed);
                }
            }
        })?;
        Ok(())
    }

    /// Publishes a skill's end, tells the rules (a `skill-outcome` fact) and releases the
    /// machine's claim.
    fn finish(
        &mut self,
        ports: &mut AgentPorts,
        chosen: &ChosenSkill,
        request_seq: u32,
        outcome: SkillOutcome,
        cycle: u64,
    ) -> Result<(), Box<dyn std::error::Error>> {
        let request = chosen.request;
        let status = SkillStatus {
            request_seq,
            robot: self.robot,
            request,
            outcome,
        };
        ports
            .status
            .send(|s| SkillStatusPayload::encode(s, &status))?;
        let reason = match outcome {
            SkillOutcome::Failed(r) => r.symbol(),
            _ => "",
        };
        println!("robotino-agent run: cycle={cycle} end {request:?} {outcome:?} {reason}");
        self.agent.report(chosen.id, outcome)?;
        self.dirty = true;
        if let SkillRequest::BringPuckTo(m) = request {
            self.claim(ports, m, false)?;
        }
        Ok(())
    }
}

/// The loop's own counters: time spent computing each cycle (excluding the wait for the
/// next one), the cycles in which the rules ran and how long they took, and the bumper
/// latency from a pressed sample's receipt to the zero motor command's publish.
#[derive(Default)]
struct LoopStats {
    cycle_us: Vec<u32>,
    decision_cycle_us: Vec<u32>,
    decide_us: Vec<u32>,
    bumper_us: Vec<u32>,
    bumper_cycles: Vec<u64>,
}

fn micros(d: Duration) -> u32 {
    u32::try_from(d.as_micros()).unwrap_or(u32::MAX)
}

/// Median and maximum (0 for no samples).
fn median_max(v: &[u32]) -> (u32, u32) {
    let mut s = v.to_vec();
    s.sort_unstable();
    (
        s.get(s.len() / 2).copied().unwrap_or(0),
        s.last().copied().unwrap_or(0),
    )
}

impl LoopStats {
    fn record(&mut self, work: Duration, decided: Option<Duration>) {
        self.cycle_us.push(micros(work));
        if let Some(d) = decided {
            self.decision_cycle_us.push(micros(work));
            self.decide_us.push(micros(d));
        }
    }

    fn bumper(&mut self, latency: Duration, cycles: u64) {
        self.bumper_us.push(micros(latency));
        self.bumper_cycles.push(cycles);
    }

    fn report(&self, cycle: u64, agent: &EngineAgent) {
        let (c_med, c_max) = median_max(&self.cycle_us);
        let (d_med, d_max) = median_max(&self.decision_cycle_us);
        let (e_med, e_max) = median_max(&self.decide_us);
        let (b_med, b_max) = median_max(&self.bumper_us);
        let b_cycles = self.bumper_cycles.iter().max().copied().unwrap_or(0);
        let s = agent.engine_stats();
        println!(
            "robotino-agent run: done cycles={cycle} cycle_work_median_us={c_med} cycle_work_max_us={c_max} decision_cycles={} decision_cycle_median_us={d_med} decision_cycle_max_us={d_max} engine_run_median_us={e_med} engine_run_max_us={e_max} bumper_hits={} bumper_latency_cycles_max={b_cycles} bumper_latency_median_us={b_med} bumper_latency_max_us={b_max} state={}",
            self.decision_cycle_us.len(),
            self.bumper_us.len(),
            agent.state().unwrap_or_default()
        );
        println!("robotino-agent run: engine {s:?}");
    }
}
