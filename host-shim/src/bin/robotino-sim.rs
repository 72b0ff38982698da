//! `robotino-sim`: stands for the Robotino's driver processes and the field. It offers the
//! same services one driver per device would on a real robot (IR, bumper, gyro, odometry,
//! puck sensor, camera light, heartbeat) and reads the motor command, for up to three robots.
//!
//! The game (hidden machine types, lights, pucks, clock, score) is the rules issue's CLIPS
//! referee (`rules/referee.clp`) run by our engine ([`ClipsReferee`]); the setup is drawn
//! from `--seed` like `robotino-agent sim --seed`.
//!
//! Cycles: in real time (`time_warp` 1) a cycle every 1/15 s; with `time_warp` W, W times as
//! fast; in lockstep, a cycle as soon as every live robot's agent answered the cycle's
//! frame with its motor command (`host_shim::shim::lockstep`: an agent whose heartbeat
//! stopped is dead and no longer waited for, so its wheels stop by the dead-man rule).

use clap::Parser;
use hal::field::GateId;
use hal::WheelSpeeds;
use host_shim::shim::config::Config;
use host_shim::shim::field_sim::{Command, FieldSim, SensorFrame};
use host_shim::shim::lockstep::{AgentLife, AgentWatch};
use host_shim::shim::payloads::{
    BumperPayload, DriverId, GyroPayload, HeartbeatPayload, IrScanPayload, LightPayload,
    MotorCommandPayload, OdometryPayload, OdometryReading, PuckPayload,
};
use host_shim::shim::referee::{ClipsReferee, Referee};
use host_shim::shim::rule_engine::exit_from_engine_stack;
use host_shim::shim::transport::{Pub, RobotStream, Sub, Transport, TransportError};
use std::path::PathBuf;
use std::time::{Duration, Instant};

#[derive(Parser)]
#[command(
    name = "robotino-sim",
    about = "Simulated Robotino drivers and LLSF field"
)]
struct Args {
    /// Configuration file (TOML); defaults to a Robotino 2.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Service-name prefix (overrides the file).
    #[arg(long)]
    prefix: Option<String>,
    /// Number of robots on the field (1..=3; LLSF teams field at most three).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u8).range(1..=3))]
    robots: u8,
    /// Stop after this many cycles (0: when the game ends).
    #[arg(long, default_value_t = 0)]
    cycles: u64,
    /// Simulated seconds per wall-clock second (overrides the file).
    #[arg(long)]
    time_warp: Option<f32>,
    /// Advance one cycle per agent motor command (overrides the file).
    #[arg(long)]
    lockstep: bool,
    /// Game length in simulated seconds.
    #[arg(long, default_value_t = 900.0)]
    game_seconds: f32,
    /// Raw pucks in the input storage.
    #[arg(long, default_value_t = 20)]
    raw_pucks: u32,
    /// Seed of the game setup: hidden machine types and the active gate.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Test hook: press robot 1's bumper in this cycle and report the latency, in cycles,
    /// until a zero motor command answering that sample arrives.
    #[arg(long)]
    bump_at_cycle: Option<u64>,
}

/// One robot's driver ports.
struct DriverPorts {
    ir: Pub<IrScanPayload>,
    bumper: Pub<BumperPayload>,
    gyro: Pub<GyroPayload>,
    odometry: Pub<OdometryPayload>,
    puck: Pub<PuckPayload>,
    light: Pub<LightPayload>,
    heartbeat: Pub<HeartbeatPayload>,
    motor: Sub<MotorCommandPayload>,
}

impl DriverPorts {
    fn open(t: &Transport, robot: u8) -> Result<Self, TransportError> {
        let name = |s| t.names.robot(robot, s);
        Ok(Self {
            ir: t.publisher(&name(RobotStream::Ir))?,
            bumper: t.publisher(&name(RobotStream::Bumper))?,
            gyro: t.publisher(&name(RobotStream::Gyro))?,
            odometry: t.publisher(&name(RobotStream::Odometry))?,
            puck: t.publisher(&name(RobotStream::Puck))?,
            light: t.publisher(&name(RobotStream::Light))?,
            heartbeat: t.publisher(&name(RobotStream::Heartbeat))?,
            motor: t.subscriber(&name(RobotStream::Motor))?,
        })
    }

    /// Hands the current frame to subscribers that joined since it was published.
    fn update_connections(&self) -> Result<(), TransportError> {
        self.ir.update_connections()?;
        self.bumper.update_connections()?;
        self.gyro.update_connections()?;
        self.odometry.update_connections()?;
        self.puck.update_connections()?;
        self.light.update_connections()?;
        self.heartbeat.update_connections()
    }

    /// Publishes a frame; returns the bumper sample's sequence number.
    fn publish(
        &mut self,
        f: &SensorFrame,
        gate: Option<GateId>,
        cycle: u32,
    ) -> Result<u32, TransportError> {
        self.ir.send(|s| IrScanPayload::encode(s, &f.ir))?;
        let bumper_seq = self.bumper.send(|s| BumperPayload::encode(s, f.bumper))?;
        self.gyro.send(|s| GyroPayload::encode(s, f.gyro))?;
        let reading = OdometryReading {
            pose: f.odometry,
            measured: f.measured,
        };
        self.odometry
            .send(|s| OdometryPayload::encode(s, &reading))?;
        self.puck.send(|s| PuckPayload::encode(s, f.has_puck))?;
        self.light
            .send(|s| LightPayload::encode(s, f.light).with_gate(gate))?;
        self.heartbeat
            .send(|s| HeartbeatPayload::encode(s, cycle, DriverId::Sim))?;
        Ok(bumper_seq)
    }

    /// The newest valid motor command and the bumper sample it answers (in lockstep, the
    /// frame it answers). An invalid one is dropped (and so is not fresh: the dead-man
    /// rule counts it as missing).
    fn command(&mut self) -> Result<Option<(Command, u32)>, TransportError> {
        Ok(self.motor.poll()?.and_then(|p| {
            let wheels: WheelSpeeds = p.decode().ok()?;
            let release = p.release().ok()?;
            let grab = p.grab().ok()?;
            Some((
                Command {
                    seq: p.seq,
                    wheels,
                    release,
                    grab,
                },
                p.bumper_seq,
            ))
        }))
    }
}

/// Measures the cycles from a pressed bumper sample to the first zero command answering it.
struct BumperLatency {
    pressed_seq: u32,
    /// The wheels turned when the bumper was pressed.
    was_moving: bool,
    published_cycle: u64,
    result: Option<(u64, bool)>,
}

fn main() {
    let args = Args::parse();
    // The referee's engine passes its arrays through the stack on the way to the heap.
    exit_from_engine_stack(move || match run(&args) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("robotino-sim: {e}");
            1
        }
    })
}

fn run(args: &Args) -> Result<(), Box<dyn std::error::Error>> {
    let mut config = Config::load(args.config.as_deref())?;
    if let Some(p) = &args.prefix {
        config.services.prefix = p.clone();
    }
    if let Some(w) = args.time_warp {
        config.timing.time_warp = w;
    }
    config.timing.lockstep |= args.lockstep;
    let robots = args.robots;
    let transport = Transport::open(&config.services.prefix, "robotino-sim")?;
    let mut ports = (1..=robots)
        .map(|r| DriverPorts::open(&transport, r))
        .collect::<Result<Vec<_>, _>>()?;
    let mut setup = rules::setup::GameSetup::for_seed(args.seed);
    setup.s0_supply = args.raw_pucks;
    // The referee's clock counts whole seconds; the field's clock ends the game on time.
    setup.clock_limit_s = Some(args.game_seconds.ceil() as u32);
    let referee = ClipsReferee::new(&setup)?;
    let gate = referee.active_gate();
    let mut field = FieldSim::new(&config, robots, referee);

    let wall_cycle = config.wall_cycle();
    let poll = Duration::from_micros(200);
    let mut watches = (1..=robots)
        .map(|r| {
            AgentWatch::open(
                &transport,
                r,
                Duration::from_millis(config.timing.heartbeat_timeout_ms),
                Duration::from_millis(config.timing.startup_timeout_ms),
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    let mut last_seq: Vec<Option<u32>> = vec![None; ports.len()];
    let mut latency: Option<BumperLatency> = None;
    let mut bumps_seen = vec![0u32; ports.len()];
    let start = Instant::now();

    // The bumper sample of each robot's current frame: a lockstep answer names it.
    let mut frame_seq: Vec<u32> = Vec::with_capacity(ports.len());
    for (i, p) in ports.iter_mut().enumerate() {
        frame_seq.push(p.publish(&field.sense(i), gate, 0)?);
    }
    println!(
        "robotino-sim: ready prefix={} robots={robots} seed={} gate=D{} referee=rules/referee.clp",
        config.services.prefix,
        args.seed,
        gate.map_or(0, GateId::number)
    );
    loop {
        // Wait for the next cycle.
        let mut commands: Vec<Option<(Command, u32)>> = vec![None; ports.len()];
        loop {
            for (c, p) in commands.iter_mut().zip(ports.iter_mut()) {
                *c = p.command()?;
            }
            let due = if config.timing.lockstep {
                let mut all_answered = true;
                for (i, w) in watches.iter_mut().enumerate() {
                    let (life, changed) = w.poll()?;
                    if let Some(new) = changed {
                        println!(
                            "robotino-sim: agent robot={} cycle={} {}",
                            i + 1,
                            field.cycle(),
                            match new {
                                AgentLife::Starting => "starting",
                                AgentLife::Alive => "alive",
                                AgentLife::Dead => "dead (heartbeat stopped): not waited for",
                            }
                        );
                    }
                    let answered = commands[i].is_some_and(|(_, b)| b == frame_seq[i]);
                    all_answered &= answered || life == AgentLife::Dead;
                }
                all_answered
            } else {
                start.elapsed() >= wall_cycle * (field.cycle() as u32 + 1)
            };
            if due {
                break;
            }
            for p in &ports {
                p.update_connections()?;
            }
            if !transport.wait(poll) {
                println!("robotino-sim: terminated");
                return Ok(());
            }
        }
        // A command is fresh once: in lockstep only the one answering this frame counts.
        for (i, (last, c)) in last_seq.iter_mut().zip(commands.iter_mut()).enumerate() {
            let stale = c.is_some_and(|(c, b)| {
                Some(c.seq) == *last || (config.timing.lockstep && b != frame_seq[i])
            });
            if stale {
                *c = None;
            } else if let Some((c, _)) = c {
                *last = Some(c.seq);
            }
        }

        if let (Some(l), Some(Some((Command { wheels, .. }, bumper_seq)))) =
            (&mut latency, commands.first())
        {
            if l.result.is_none() && *bumper_seq >= l.pressed_seq {
                let cycles = field.cycle() + 1 - l.published_cycle;
                l.result = Some((cycles, wheels.is_zero()));
                println!(
                    "robotino-sim: bumper-latency cycles={cycles} zero={} was_moving={}",
                    wheels.is_zero(),
                    l.was_moving
                );
            }
        }

        let step: Vec<Option<Command>> = commands.iter().map(|c| c.map(|(c, _)| c)).collect();
        field.step(&step);
        for line in field.referee.take_log() {
            println!("robotino-sim: cycle={} {line}", field.cycle());
        }
        let cycle = field.cycle();
        let bump_now = args.bump_at_cycle == Some(cycle);
        if bump_now {
            field.force_bumper(0);
        }
        for (i, p) in ports.iter_mut().enumerate() {
            let frame = field.sense(i);
            let bumper_seq = p.publish(&frame, gate, cycle as u32)?;
            frame_seq[i] = bumper_seq;
            if bump_now && i == 0 {
                latency = Some(BumperLatency {
                    pressed_seq: bumper_seq,
                    was_moving: !field.robots[0].wheels().is_zero(),
                    published_cycle: cycle,
                    result: None,
                });
            }
        }
        for r in &field.robots {
            if r.bumper() && r.contact.is_some() && r.bumps > bumps_seen[usize::from(r.number) - 1]
            {
                bumps_seen[usize::from(r.number) - 1] = r.bumps;
                println!(
                    "robotino-sim: cycle={cycle} bump robot={} with={} at=({:.2},{:.2},{:.2}) odometry=({:.2},{:.2})",
                    r.number,
                    r.contact.map(|c| c.to_string()).unwrap_or_default(),
                    r.true_pose.x_m,
                    r.true_pose.y_m,
                    r.true_pose.phi_rad,
                    r.odometry_pose().x_m,
                    r.odometry_pose().y_m
                );
            }
            // Log the dead-man rule's transitions (the cycle it trips and the one it clears).
            let silent = r.cycles_without_command();
            if silent == config.timing.motor_deadline_cycles {
                println!(
                    "robotino-sim: dead-man robot={} cycle={cycle} wheels stopped",
                    r.number
                );
            }
        }
        if cycle.is_multiple_of(150) {
            let r = &field.robots[0];
            println!(
                "robotino-sim: cycle={cycle} score={} robot1=({:.2},{:.2},{:.2}) wheels_zero={} held={:?}",
                field.referee.score(),
                r.true_pose.x_m,
                r.true_pose.y_m,
                r.true_pose.phi_rad,
                r.wheels().is_zero(),
                r.held
            );
        }
        let finished = (args.cycles > 0 && cycle >= args.cycles) || field.referee.game_over();
        if finished {
            if let Some(e) = &field.referee.fault {
                return Err(format!("the referee stopped: {e}").into());
            }
            let bumps: u32 = field.robots.iter().map(|r| r.bumps).sum();
            // Both robots of a contact count it: a collision is one contact of two.
            let robot_contacts: u32 = field.robots.iter().map(|r| r.robot_contacts).sum();
            println!(
                "robotino-sim: done cycles={cycle} game_time_s={:.1} score={} bumps={bumps} robot_contacts={robot_contacts} wall_ms={}",
                field.referee.clock_s(),
                field.referee.score(),
                start.elapsed().as_millis()
            );
            for r in &field.robots {
                println!(
                    "robotino-sim: travel robot={} m={:.1}",
                    r.number, r.travel_m
                );
            }
            println!(
                "robotino-sim: referee engine {:?}",
                field.referee.engine_stats()
            );
            return Ok(());
        }
    }
}
