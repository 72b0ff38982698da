//! `robotino-agent run`: one robot's agent loop. Each cycle it reads the newest sensor
//! samples over iceoryx2, advances the running skill, passes the skill's twist through the
//! safety monitor and publishes the motor command, then reports the skill's status. When the
//! robot is idle it asks for the next skill: for now the clearly marked stand-in
//! [`ScriptedAgent`]; the engine plugs in there.

use hal::field::MachineId;
use hal::ir::IrScan;
use hal::skill::Perception;
use hal::skill::{FailReason, SkillOutcome, SkillRequest};
use hal::LightSignal;
use hal::{Pose2, Twist};
use host_shim::shim::behaviour::{DriveTuning, Perceived, Skill};
use host_shim::shim::config::Config;
use host_shim::shim::payloads::{
    BumperPayload, DriverId, GyroPayload, HeartbeatPayload, IrScanPayload, LightPayload,
    MachineClaimPayload, MotorCommandPayload, OdometryPayload, PuckPayload, SkillRequestPayload,
    SkillStatus, SkillStatusPayload, WorldModelPayload,
};
use host_shim::shim::safety::{CycleInput, SafetyMonitor, Stream};
use host_shim::shim::scripted::ScriptedAgent;
use host_shim::shim::team::{Carried, TeamView};
use host_shim::shim::transport::{Pub, RobotStream, Sub, TeamStream, Transport, TransportError};
use std::path::PathBuf;
use std::process::ExitCode;
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
    /// Cycle in lockstep with the sim: a cycle per fresh odometry sample.
    #[arg(long)]
    pub lockstep: bool,
    /// Simulated seconds per wall-clock second (overrides the file).
    #[arg(long)]
    pub time_warp: Option<f32>,
    /// STAND-IN for the engine: skills to run, e.g. `get_s0,bring:4,deliver:1`; empty
    /// loops get_s0 and bring to machines in turn.
    #[arg(long, default_value = "")]
    pub script: String,
}

pub fn main(args: Args) -> ExitCode {
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("robotino-agent run: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The agent's ports for one robot.
struct AgentPorts {
    ir: Sub<IrScanPayload>,
    bumper: Sub<BumperPayload>,
    gyro: Sub<GyroPayload>,
    odometry: Sub<OdometryPayload>,
    puck: Sub<PuckPayload>,
    light: Sub<LightPayload>,
    motor: Pub<MotorCommandPayload>,
    request: Pub<SkillRequestPayload>,
    status: Pub<SkillStatusPayload>,
    heartbeat: Pub<HeartbeatPayload>,
    world_out: Pub<WorldModelPayload>,
    world_in: Sub<WorldModelPayload>,
    claims_out: Pub<MachineClaimPayload>,
    claims_in: Sub<MachineClaimPayload>,
}

impl AgentPorts {
    fn open(t: &Transport, robot: u8) -> Result<Self, TransportError> {
        let name = |s| t.names.robot(robot, s);
        Ok(Self {
            ir: t.subscriber(&name(RobotStream::Ir))?,
            bumper: t.subscriber(&name(RobotStream::Bumper))?,
            gyro: t.subscriber(&name(RobotStream::Gyro))?,
            odometry: t.subscriber(&name(RobotStream::Odometry))?,
            puck: t.subscriber(&name(RobotStream::Puck))?,
            light: t.subscriber(&name(RobotStream::Light))?,
            motor: t.publisher(&name(RobotStream::Motor))?,
            request: t.publisher(&name(RobotStream::SkillRequest))?,
            status: t.publisher(&name(RobotStream::SkillStatus))?,
            heartbeat: t.publisher(&name(RobotStream::Heartbeat))?,
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
    perceived: Perceived,
    odometry_seq: Option<u32>,
}

impl Samples {
    fn new() -> Self {
        Self {
            seq: [None; Stream::COUNT],
            bumper_pressed: false,
            perceived: Perceived {
                pose: Pose2::default(),
                ir: IrScan::EMPTY,
                has_puck: false,
                light: None,
            },
            odometry_seq: None,
        }
    }

    fn read(&mut self, p: &mut AgentPorts) -> Result<(), TransportError> {
        if let Some(s) = p.ir.poll()? {
            if let Ok(scan) = s.decode() {
                self.perceived.ir = scan;
                self.seq[Stream::Ir as usize] = Some(s.seq);
            }
        }
        if let Some(s) = p.bumper.poll()? {
            if let Ok(pressed) = s.decode() {
                self.bumper_pressed = pressed;
                self.seq[Stream::Bumper as usize] = Some(s.seq);
            }
        }
        if let Some(s) = p.gyro.poll()? {
            if s.decode().is_ok() {
                self.seq[Stream::Gyro as usize] = Some(s.seq);
            }
        }
        if let Some(s) = p.odometry.poll()? {
            if let Ok(r) = s.decode() {
                // The driver's odometry already fuses wheels and gyro (hal::odometry).
                self.perceived.pose = r.pose;
                self.seq[Stream::Odometry as usize] = Some(s.seq);
                self.odometry_seq = Some(s.seq);
            }
        }
        if let Some(s) = p.puck.poll()? {
            if let Ok(present) = s.decode() {
                self.perceived.has_puck = present;
                self.seq[Stream::Puck as usize] = Some(s.seq);
            }
        }
        if let Some(s) = p.light.poll()? {
            if let Ok(light) = s.decode() {
                self.perceived.light = light;
            }
        }
        Ok(())
    }
}

struct Running {
    skill: Skill,
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
        robot: config.robot.number,
        script: ScriptedAgent::parse(&args.script)?,
        team: TeamView::new(config.robot.number),
        carried: None,
    };
    let transport = Transport::open(&config.services.prefix, &format!("robotino-agent-{robot}"))?;
    let mut ports = AgentPorts::open(&transport, robot)?;
    let tuning = DriveTuning {
        max_linear_m_s: config.limits.max_linear_m_s,
        max_angular_rad_s: config.limits.max_angular_rad_s,
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
    let mut stats = CycleStats::default();
    let wall_cycle = config.wall_cycle();
    let grace = Duration::from_millis(config.timing.lockstep_grace_ms);
    let poll = Duration::from_micros(200);
    let start = Instant::now();
    let mut cycle: u64 = 0;
    println!(
        "robotino-agent run: robot={robot} prefix={}",
        config.services.prefix
    );

    loop {
        // Wait for the cycle: the next fresh odometry sample in lockstep, else the clock.
        let wait_start = Instant::now();
        let last_odometry = samples.odometry_seq;
        loop {
            let due = if config.timing.lockstep {
                samples.read(&mut ports)?;
                samples.odometry_seq != last_odometry || wait_start.elapsed() >= grace
            } else {
                start.elapsed() >= wall_cycle * (cycle as u32 + 1)
            };
            if due {
                break;
            }
            if !transport.wait(poll) {
                stats.report(cycle);
                return Ok(());
            }
        }
        let work_start = Instant::now();
        cycle += 1;
        samples.read(&mut ports)?;
        let p = samples.perceived;
        mind.listen(&mut ports, cycle)?;
        // Late joiners: repeat what we know now and then (the service keeps one sample).
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

        // Idle: ask for the next skill, but only once every driver is fresh (a skill
        // planned from a pose never received would start from the field's corner).
        let drivers_fresh = samples.seq.iter().all(Option::is_some)
            && Stream::ALL
                .iter()
                .all(|&s| monitor.staleness(s) < config.timing.sensor_deadline_cycles);
        if running.is_none() && drivers_fresh {
            mind.sync_with_puck_sensor(p.has_puck);
            if let Some(choice) = mind.script.next(mind.carried, &mind.team) {
                let request = choice.request;
                if let Some((m, t, by)) = choice.shared_type {
                    println!(
                        "robotino-agent run: cycle={cycle} using shared type M{} T{t} from robot {by}",
                        m.number()
                    );
                }
                let request_seq = ports
                    .request
                    .send(|s| SkillRequestPayload::encode(s, robot, request))?;
                monitor.skill_started();
                if let SkillRequest::BringPuckTo(m) = request {
                    mind.claim(&mut ports, m, true)?;
                }
                println!("robotino-agent run: cycle={cycle} start {request:?}");
                match Skill::start(request, &p, &tuning) {
                    Ok(skill) => running = Some(Running { skill, request_seq }),
                    Err(reason) => {
                        let outcome = SkillOutcome::Failed(reason);
                        mind.finish(&mut ports, request, request_seq, outcome, cycle)?;
                    }
                }
            }
        }

        // Two robots claimed the same machine in the same moment: the lower number keeps it.
        let lost_claim = running.as_ref().is_some_and(|r| match r.skill.request() {
            SkillRequest::BringPuckTo(m) => mind
                .team
                .machine(m)
                .claimed_by
                .is_some_and(|other| other < robot),
            _ => false,
        });
        let (desired, mut outcome) = match running.as_mut() {
            Some(_) if lost_claim => (Twist::ZERO, SkillOutcome::Failed(FailReason::Aborted)),
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
            outcome = SkillOutcome::Failed(reason);
        }
        let bumper_seq = samples.seq[Stream::Bumper as usize].unwrap_or(0);
        ports
            .motor
            .send(|s| MotorCommandPayload::encode(s, bumper_seq, decision.wheels))?;
        ports
            .heartbeat
            .send(|s| HeartbeatPayload::encode(s, cycle as u32, DriverId::Agent))?;

        if let Some(r) = running.as_ref() {
            let request = r.skill.request();
            if outcome.is_terminal() {
                mind.finish(&mut ports, request, r.request_seq, outcome, cycle)?;
                running = None;
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
        stats.record(work_start.elapsed());
        if cycle.is_multiple_of(150) {
            println!(
                "robotino-agent run: cycle={cycle} pose=({:.2},{:.2},{:.2}) puck={} hold={:?}",
                p.pose.x_m, p.pose.y_m, p.pose.phi_rad, p.has_puck, decision.hold
            );
        }
        if args.cycles > 0 && cycle >= args.cycles {
            stats.report(cycle);
            return Ok(());
        }
    }
}

/// What the robot knows beyond its sensors: the (stand-in) agent, the team's shared picture
/// and the puck it believes it carries.
struct Mind {
    robot: u8,
    script: ScriptedAgent,
    team: TeamView,
    carried: Option<Carried>,
}

impl Mind {
    /// The puck sensor is the truth about holding something; the kind is remembered.
    fn sync_with_puck_sensor(&mut self, has_puck: bool) {
        if !has_puck {
            self.carried = None;
        } else if self.carried.is_none() {
            self.carried = Some(Carried::Unknown);
        }
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

    /// Takes teammates' world-model updates and claims.
    fn listen(&mut self, ports: &mut AgentPorts, cycle: u64) -> Result<(), TransportError> {
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
            println!(
                "robotino-agent run: cycle={cycle} belief from robot {}: M{} T{}",
                b.robot,
                b.machine.number(),
                b.machine_type.unwrap_or(0)
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

    /// Publishes a skill's end, updates what the robot carries and knows, releases the
    /// machine's claim and tells the (stand-in) agent.
    fn finish(
        &mut self,
        ports: &mut AgentPorts,
        request: SkillRequest,
        request_seq: u32,
        outcome: SkillOutcome,
        cycle: u64,
    ) -> Result<(), TransportError> {
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
        match (request, outcome) {
            (SkillRequest::GetS0, SkillOutcome::Final(Perception::GotS0)) => {
                self.carried = Some(Carried::S0);
            }
            (SkillRequest::BringPuckTo(m), SkillOutcome::Final(Perception::LightSeen(l))) => {
                let carried = self.carried.unwrap_or(Carried::Unknown);
                let learned_before = self.team.machine(m).machine_type;
                match l {
                    LightSignal::Green => {
                        self.carried = self.team.learn_from_placement(m, carried, true);
                    }
                    LightSignal::Yellow => {
                        self.carried = self.team.learn_from_placement(m, carried, false);
                    }
                    // Wrong input, out of order or offline: the robot keeps its puck.
                    _ => {}
                }
                if let (None, Some((t, _))) = (learned_before, self.team.machine(m).machine_type) {
                    println!(
                        "robotino-agent run: cycle={cycle} learned M{} T{t}",
                        m.number()
                    );
                }
                self.publish_belief(ports, m)?;
            }
            (SkillRequest::DeliverTo(_), SkillOutcome::Final(Perception::Delivered)) => {
                self.carried = None;
            }
            _ => {}
        }
        if let SkillRequest::BringPuckTo(m) = request {
            self.claim(ports, m, false)?;
        }
        self.script.finished(request, outcome);
        Ok(())
    }
}

/// Time spent computing each cycle (excluding the wait for the next one).
#[derive(Default)]
struct CycleStats {
    count: u64,
    total: Duration,
    max: Duration,
}

impl CycleStats {
    fn record(&mut self, d: Duration) {
        self.count += 1;
        self.total += d;
        self.max = self.max.max(d);
    }

    fn report(&self, cycle: u64) {
        let mean_us = if self.count > 0 {
            self.total.as_micros() / u128::from(self.count)
        } else {
            0
        };
        println!(
            "robotino-agent run: done cycles={cycle} cycle_work_mean_us={mean_us} cycle_work_max_us={}",
            self.max.as_micros()
        );
    }
}
