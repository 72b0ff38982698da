//! `robotino-agent run` (and the Zenoh-linked agent of the `team-link` crate): one
//! robot's agent loop. Each cycle it reads the newest sensor
//! samples over iceoryx2, advances the running skill, passes the skill's twist through the
//! safety monitor and publishes the motor command, then reports the skill's status. Skill
//! outcomes and perceptions become facts of the agent's rule base (our engine); whenever
//! the robot is idle and something changed, the engine runs to quiescence and the skill it
//! chose starts. In a team (`--team-size` above 1) the same engine runs the team's rules
//! (`rules/team.clp`, `rules/team-agent.clp`): claims on machines, the input storage and
//! the gates, and news of machines, exchanged with the teammates over a [`TeamLink`]
//! (iceoryx2 on one host; in lockstep a message sent in one cycle is taken in the next).

use crate::shim::agent::{unreached_place, ChosenSkill, EngineAgent, MachineView, TeamSeat};
use crate::shim::behaviour::{DriveStep, DriveTo, DriveTuning, Perceived, Skill};
use crate::shim::bump::BumpMemory;
use crate::shim::config::Config;
use crate::shim::drivers::{usable, DriverError, SimDrivers};
use crate::shim::lockstep::{spawn_heartbeat, FrameWatch};
use crate::shim::payloads::{SkillRequestPayload, SkillStatus, SkillStatusPayload};
use crate::shim::rule_engine::exit_from_engine_stack;
use crate::shim::safety::{CycleInput, SafetyMonitor, Stream};
use crate::shim::team::IceoryxTeamLink;
use crate::shim::traffic::{PoseReport, TeamBoard, MAX_TEAMMATES, POSE_KIND};
use crate::shim::transport::{Pub, RobotStream, Transport, TransportError};
use crate::team::{FaultyLink, LinkFaults, TeamLink};
use hal::device::{
    Bumper, Device, Freshness, GateSignal, Gyro, IrRing, MachineLight, Odometry, OmniDrive,
    PuckGrab, PuckRelease, PuckSensor,
};
use hal::field::MachineId;
use hal::ir::IrScan;
use hal::skill::{FailReason, SkillOutcome};
use hal::{Pose2, Twist};
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
    #[arg(long, default_value = "paper", value_parser = crate::shim::agent::parse_strategy)]
    pub strategy: Strategy,
    /// Also print every cycle's and every decision's time (one `stat` line each).
    #[arg(long)]
    pub stats: bool,
    /// Robots in the team (1..=3): above 1 the agent loads the team's rules and talks to
    /// the others over the team link.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=3))]
    pub team_size: u8,
    /// Raw pucks in the input storage at the start (the team shares them).
    #[arg(long, default_value_t = 20)]
    pub raw_pucks: u32,
    /// Team link faults (our proxy at the receiver, in game time): percent of the
    /// teammates' messages lost ...
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u32).range(0..=100))]
    pub link_loss_percent: u32,
    /// ... and each delayed by up to this many seconds (so they overtake each other) ...
    #[arg(long, default_value_t = 0.0)]
    pub link_delay_s: f64,
    /// ... drawn from this seed.
    #[arg(long, default_value_t = 0)]
    pub link_seed: u64,
    /// Die at this cycle (the sim's frame in lockstep): the process ends at once, as a
    /// crash would, without answering the frame or telling the team (`game --kill-at-s`;
    /// a kill from outside lands at a cycle that depends on the machine's load).
    #[arg(long)]
    pub exit_at_cycle: Option<u64>,
}

/// A team member that waits for a place (or is done) this long drives out of the lanes
/// to a passing place of its own, so it does not stand in a teammate's way (and tries
/// again this often until it is there, around what its IR ring sees).
const PARK_AFTER_CYCLES: u64 = 30;

/// Passing places: spots more than 0.7 m from every machine's approach, the storage, the
/// gates and the recycling units (which stand in two corners); no two robots share one.
fn passing_places(robot: u8) -> &'static [(f32, f32)] {
    match robot {
        1 => &[(5.20, 0.40)],
        2 => &[(0.40, 5.20)],
        _ => &[(0.40, 3.70)],
    }
}

/// Where a waiting robot drives: its nearer passing place, unless it is there already.
fn park_goal(robot: u8, at: Pose2) -> Option<Pose2> {
    let d = |q: &(f32, f32)| (q.0 - at.x_m).hypot(q.1 - at.y_m);
    let spot = *passing_places(robot)
        .iter()
        .min_by(|a, b| d(a).total_cmp(&d(b)))?;
    (d(&spot) > 0.3).then(|| Pose2::new(spot.0, spot.1, at.phi_rad))
}

/// In a team the rules run at least this often (cycles), so claims renew and waits end
/// while nothing else happens (claims renew every 2 s of game time).
const TEAM_TICK_CYCLES: u64 = 7;

/// A team link made once the process's iceoryx2 node is open (given the node and the
/// robot's seat).
pub type LinkMaker = dyn FnOnce(&Transport, TeamSeat) -> Result<Box<dyn TeamLink>, Box<dyn std::error::Error>>
    + Send;

/// `robotino-agent run`: in a team the messages go over iceoryx2 on this host.
pub fn main(args: Args) -> ExitCode {
    main_with(
        args,
        Box::new(|t, seat| Ok(Box::new(IceoryxTeamLink::open(t, seat.id)?))),
    )
}

/// The agent loop with another team link (e.g. Zenoh between machines): the process
/// ends with the loop (the exit code: 0, or 1 after an error).
pub fn main_with(args: Args, make_link: Box<LinkMaker>) -> ExitCode {
    // The engine's arrays pass through the stack on their way to the heap.
    exit_from_engine_stack(move || match run(&args, make_link) {
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
}

impl AgentPorts {
    fn open(t: &Transport, robot: u8) -> Result<Self, TransportError> {
        let name = |s| t.names.robot(robot, s);
        Ok(Self {
            request: t.publisher(&name(RobotStream::SkillRequest))?,
            status: t.publisher(&name(RobotStream::SkillStatus))?,
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
                teammates: [None; MAX_TEAMMATES],
                bumped_towards: None,
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
    /// The cycle it started.
    started: u64,
}

fn run(args: &Args, make_link: Box<LinkMaker>) -> Result<(), Box<dyn std::error::Error>> {
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
    if args.team_size > 1 && robot > args.team_size {
        return Err(format!("robot {robot} is not in a team of {}", args.team_size).into());
    }
    let seat = (args.team_size > 1).then_some(TeamSeat {
        id: robot,
        robots: args.team_size,
        s0_supply: args.raw_pucks,
    });
    let transport = Transport::open(&config.services.prefix, &format!("robotino-agent-{robot}"))?;
    let faults = LinkFaults {
        loss_percent: args.link_loss_percent,
        delay_min: 0.0,
        delay_max: args.link_delay_s.max(0.0),
        dup_percent: 0,
    };
    let link = match seat {
        Some(seat) if faults != LinkFaults::NONE => {
            let link = make_link(&transport, seat)?;
            let cycle_s = f64::from(config.cycle_s());
            Some(Box::new(FaultyLink::new(
                link,
                seat.id,
                faults,
                args.link_seed,
                cycle_s,
            )) as Box<dyn TeamLink>)
        }
        Some(seat) => Some(make_link(&transport, seat)?),
        None => None,
    };
    agent_loop(args, config, seat, link, &transport)
}

fn agent_loop(
    args: &Args,
    config: Config,
    seat: Option<TeamSeat>,
    link: Option<Box<dyn TeamLink>>,
    transport: &Transport,
) -> Result<(), Box<dyn std::error::Error>> {
    let robot = config.robot.number;
    let mut mind = Mind {
        robot,
        agent: EngineAgent::with_team(args.strategy, seat)?,
        link,
        dirty: true,
        done_reported: false,
        known: [MachineView::default(); hal::field::MACHINE_COUNT],
        holds: Vec::new(),
        sent: 0,
        received: 0,
        board: TeamBoard::default(),
    };
    let mut ports = AgentPorts::open(transport, robot)?;
    let mut drivers = SimDrivers::open(transport, robot)?;
    let mut frames = FrameWatch::open(transport, robot)?;
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
    // A team member out of the way while it waits: the drive there, and since when it
    // waits (one parking drive per wait).
    let mut parking: Option<DriveTo> = None;
    // The parking drive makes way for a teammate (it runs whatever the rules' state).
    let mut making_way = false;
    let mut waiting_since: Option<u64> = None;
    // What the bumper last stopped (the twist sent last cycle is the motion it met).
    let mut bump = BumpMemory::default();
    let mut commanded = Twist::ZERO;
    let mut stats = LoopStats::default();
    let wall_cycle = config.wall_cycle();
    let poll = Duration::from_micros(200);
    let start = Instant::now();
    let mut cycle: u64 = 0;
    println!(
        "robotino-agent run: robot={robot} prefix={} strategy={} engine=rules team={}",
        config.services.prefix,
        args.strategy.name(),
        seat.map_or(1, |s| s.robots)
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
                stats.report(cycle, &mind);
                return Ok(());
            }
        }
        let frame_cycle = if config.timing.lockstep {
            frames.cycle().map_or(0, u64::from)
        } else {
            cycle + 1
        };
        if args.exit_at_cycle.is_some_and(|at| frame_cycle >= at) {
            println!(
                "robotino-agent run: killed robot {robot} at t={:.1}",
                frame_cycle as f64 * f64::from(config.cycle_s())
            );
            std::process::exit(137);
        }
        let work_start = Instant::now();
        cycle += 1;
        beat_cycle.store(cycle, Ordering::Relaxed);
        samples.read(&mut drivers, cycle)?;
        let mut p = samples.perceived;
        bump.observe(samples.bumper_pressed, p.pose, commanded);
        p.bumped_towards = bump.heading();
        if let Some(g) = samples.gate {
            if !mind.agent.knows_gate() {
                mind.agent.see_active_gate(g)?;
                mind.dirty = true;
            }
        }
        // The team link's cycle: in lockstep the sim's frame, so every agent counts alike.
        let link_cycle = if config.timing.lockstep {
            frames.cycle().map_or(0, u64::from)
        } else {
            u64::MAX
        };
        // The first cycle sends nothing: a teammate may not have subscribed yet (all have
        // before the sim's second frame, which waits for every agent's first answer).
        let team_heard = cycle > 1 && mind.listen(link_cycle, cycle)?;
        // The teammates' clock: the link's in lockstep, else this loop's own.
        let traffic_now = if config.timing.lockstep {
            link_cycle
        } else {
            cycle
        };
        p.teammates = mind.board.teammates(traffic_now, config.cycle_s(), &p.pose);

        // Let the rules decide once every driver is fresh (a skill planned from a pose
        // never received would start from the field's corner) and the gate's light was
        // seen (the rules deliver to it); in a team also to answer and renew claims.
        let drivers_fresh = samples.seq.iter().all(Option::is_some)
            && Stream::ALL
                .iter()
                .all(|&s| monitor.staleness(s) < config.timing.sensor_deadline_cycles);
        let ready = drivers_fresh && mind.agent.knows_gate();
        let team_tick = mind.link.is_some() && cycle > 1 && cycle.is_multiple_of(TEAM_TICK_CYCLES);
        let mut decided = None;
        if (ready && mind.dirty && (mind.link.is_none() || cycle > 1)) || team_heard || team_tick {
            let t0 = Instant::now();
            mind.think(
                cycle,
                cycle as f64 * f64::from(config.cycle_s()),
                link_cycle,
            )?;
            decided = Some(t0.elapsed());
        }
        if running.is_none() && ready {
            if let Some(chosen) = mind.agent.take_request()? {
                parking = None;
                making_way = false;
                let request = chosen.request;
                let request_seq = ports
                    .request
                    .send(|s| SkillRequestPayload::encode(s, robot, request))?;
                monitor.skill_started();
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
                            started: cycle,
                        })
                    }
                    Err(reason) => {
                        let outcome = SkillOutcome::Failed(reason);
                        mind.finish(
                            &mut ports,
                            &chosen,
                            request_seq,
                            (outcome, 0.0, false),
                            &p,
                            cycle,
                        )?;
                    }
                }
            }
        }

        // Idle where a teammate must go (it says this robot holds it back): make way,
        // to the waiting place.
        let asked = (running.is_none() && parking.is_none())
            .then(|| mind.board.asking_way(robot, traffic_now))
            .flatten();
        if let Some(mate) = asked {
            if let Some(goal) = park_goal(robot, p.pose) {
                parking = DriveTo::plan_for(&p, goal, &tuning);
                making_way = parking.is_some();
                if making_way {
                    monitor.skill_started();
                    println!(
                        "robotino-agent run: cycle={cycle} making way for robot {mate}: parking at ({:.2},{:.2})",
                        goal.x_m, goal.y_m
                    );
                }
            }
        }
        // Waiting in a team: out of the lanes after a while.
        let waits = mind.link.is_some()
            && running.is_none()
            && matches!(mind.agent.state().as_deref(), Some("TEAM-WAIT" | "DONE"));
        if !waits {
            waiting_since = None;
            if !(making_way && running.is_none()) {
                parking = None;
                making_way = false;
            }
        } else if waiting_since.is_none() {
            waiting_since = Some(cycle);
        } else if parking.is_none()
            && waiting_since.is_some_and(|since| {
                cycle > since && (cycle - since).is_multiple_of(PARK_AFTER_CYCLES)
            })
        {
            if let Some(goal) = park_goal(robot, p.pose) {
                parking = DriveTo::plan_for(&p, goal, &tuning);
                if parking.is_some() {
                    monitor.skill_started();
                    println!(
                        "robotino-agent run: cycle={cycle} parking at ({:.2},{:.2})",
                        goal.x_m, goal.y_m
                    );
                }
            }
        }
        let (desired, mut outcome) = match (running.as_mut(), parking.as_mut()) {
            // The rules abort a skill whose place is no longer this robot's (unless the
            // work is done and it only backs away).
            (Some(r), _)
                if r.skill.done_perception().is_none()
                    && mind.agent.abort_requested(r.chosen.id) =>
            {
                (Twist::ZERO, SkillOutcome::Failed(FailReason::Aborted))
            }
            (Some(r), _) => r.skill.step(&p, &tuning),
            (None, Some(drive)) => match drive.step(&p, &tuning) {
                DriveStep::Driving(t) => (t, SkillOutcome::Running),
                DriveStep::Arrived | DriveStep::Failed(_) => {
                    parking = None;
                    making_way = false;
                    (Twist::ZERO, SkillOutcome::Running)
                }
            },
            (None, None) => (Twist::ZERO, SkillOutcome::Running),
        };
        let decision = monitor.step(&CycleInput {
            latest_seq: samples.seq,
            bumper_pressed: samples.bumper_pressed,
            desired,
            skill_running: (running.is_some() && !outcome.is_terminal()) || parking.is_some(),
        });
        commanded = decision.twist;
        if running.is_none() && decision.fail_skill.is_some() {
            // Bumped (or blind) on the way to park: stop; the next try plans around
            // whatever the IR ring sees.
            parking = None;
            making_way = false;
        }
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
        // Where this robot is and how it moves, for the teammates' drives (not the
        // first cycle: a teammate may not listen yet). Before the motor command: in
        // lockstep the sim moves on once every command is in, and the teammates take
        // this cycle's messages in the next.
        if let (Some(link), true) = (mind.link.as_mut(), cycle > 1) {
            let held_by = match (running.as_ref(), parking.as_ref()) {
                (Some(r), _) => r.skill.held_by(),
                (None, Some(d)) => d.held_by(),
                (None, None) => None,
            };
            let report =
                PoseReport::new(robot, link_cycle, p.pose, decision.twist).held_by(held_by);
            link.send(link_cycle, &[report.to_msg()])?;
        }
        drivers.set_release(release)?;
        let grab = running
            .as_ref()
            .is_some_and(|r| r.skill.grabbing() && !outcome.is_terminal());
        drivers.set_grab(grab)?;
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
                let drove_s = cycle.saturating_sub(r.started) as f64 * f64::from(config.cycle_s());
                let output_waits = r.skill.output_waits();
                running = None;
                mind.finish(
                    &mut ports,
                    &chosen,
                    request_seq,
                    (outcome, drove_s, output_waits),
                    &p,
                    cycle,
                )?;
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
            stats.report(cycle, &mind);
            return Ok(());
        }
    }
}

/// What the robot knows beyond its sensors: the agent's rules (with the team's, in a
/// team) and the link to the teammates.
struct Mind {
    robot: u8,
    agent: EngineAgent,
    link: Option<Box<dyn TeamLink>>,
    /// Facts changed since the rules last ran.
    dirty: bool,
    /// The machine beliefs after the rules last ran (to log types found out).
    known: [MachineView; hal::field::MACHINE_COUNT],
    done_reported: bool,
    /// The places this robot held when the rules last ran (logged when they change).
    holds: Vec<String>,
    /// Team messages sent and taken so far.
    sent: u64,
    received: u64,
    /// Where the teammates announced themselves.
    board: TeamBoard,
}

impl Mind {
    /// Takes the teammates' messages due in `link_cycle`; `true` when there were any.
    fn listen(&mut self, link_cycle: u64, cycle: u64) -> Result<bool, Box<dyn std::error::Error>> {
        let Some(link) = self.link.as_mut() else {
            return Ok(false);
        };
        let mut msgs = link.receive(link_cycle)?;
        // Poses are the drives' business, not the rules'.
        msgs.retain(|m| {
            if m.kind != POSE_KIND {
                return true;
            }
            // A malformed announcement is dropped.
            if let Some(mut r) = PoseReport::from_msg(m) {
                if link_cycle == u64::MAX {
                    // Off lockstep the sender's cycle means nothing here: heard now.
                    r.cycle = cycle.saturating_sub(1);
                }
                self.board.hear(r);
            }
            false
        });
        for m in &msgs {
            if m.kind == "news" {
                println!(
                    "robotino-agent run: cycle={cycle} news from robot {}: {} {}",
                    m.from,
                    m.resource,
                    m.data.join(" ")
                );
            }
            self.agent.receive_team(m)?;
        }
        self.received += msgs.len() as u64;
        Ok(!msgs.is_empty())
    }

    /// Runs the rules at game time `now` (the team's clock), logs what they found out,
    /// and sends the team messages they wrote.
    fn think(
        &mut self,
        cycle: u64,
        now: f64,
        link_cycle: u64,
    ) -> Result<(), Box<dyn std::error::Error>> {
        if self.link.is_some() {
            self.agent.set_team_time(now)?;
        }
        self.agent.run_rules()?;
        self.dirty = false;
        let printed = self.agent.take_output();
        if !printed.is_empty() {
            print!("{printed}");
        }
        for (m, view) in MachineId::all().zip(self.agent.machines()) {
            let before = self.known[m.index()];
            if let (None, Some(t)) = (before.machine_type, view.machine_type) {
                println!(
                    "robotino-agent run: cycle={cycle} learned M{} T{t}",
                    m.number()
                );
            }
            self.known[m.index()] = view;
        }
        if let Some(link) = self.link.as_mut() {
            let holds = self.agent.team_holds();
            if holds != self.holds {
                println!(
                    "robotino-agent run: cycle={cycle} holds {}",
                    holds.join(" ")
                );
                self.holds = holds;
            }
            let out = self.agent.team_outbox()?;
            link.send(link_cycle, &out)?;
            self.sent += out.len() as u64;
        }
        if self.agent.is_done() && !self.done_reported {
            self.done_reported = true;
            println!("robotino-agent run: cycle={cycle} agent DONE (storage empty, hands empty)");
        }
        Ok(())
    }

    /// Publishes a skill's end and tells the rules (a `skill-outcome` fact; in a team the
    /// rules then send news of the place and release it); `drove_s`: how long it ran.
    fn finish(
        &mut self,
        ports: &mut AgentPorts,
        chosen: &ChosenSkill,
        request_seq: u32,
        (outcome, drove_s, output_waits): (SkillOutcome, f64, bool),
        p: &Perceived,
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
        // A failed skill with the puck still in the gripper keeps it (the rules hear so).
        let unreached = unreached_place(outcome, &chosen.target, drove_s);
        if output_waits {
            println!(
                "robotino-agent run: cycle={cycle} an output waits at {}",
                chosen.target
            );
        }
        self.agent
            .report_sensed(chosen.id, outcome, p.has_puck, unreached, output_waits)?;
        self.dirty = true;
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

    fn report(&self, cycle: u64, mind: &Mind) {
        let agent = &mind.agent;
        let (c_med, c_max) = median_max(&self.cycle_us);
        let (d_med, d_max) = median_max(&self.decision_cycle_us);
        let (e_med, e_max) = median_max(&self.decide_us);
        let (b_med, b_max) = median_max(&self.bumper_us);
        let b_cycles = self.bumper_cycles.iter().max().copied().unwrap_or(0);
        let s = agent.engine_stats();
        println!(
            "robotino-agent run: done cycles={cycle} cycle_work_median_us={c_med} cycle_work_max_us={c_max} decision_cycles={} decision_cycle_median_us={d_med} decision_cycle_max_us={d_max} engine_run_median_us={e_med} engine_run_max_us={e_max} bumper_hits={} bumper_latency_cycles_max={b_cycles} bumper_latency_median_us={b_med} bumper_latency_max_us={b_max} team_sent={} team_received={} state={}",
            self.decision_cycle_us.len(),
            self.bumper_us.len(),
            mind.sent,
            mind.received,
            agent.state().unwrap_or_default()
        );
        println!("robotino-agent run: engine {s:?}");
    }
}
