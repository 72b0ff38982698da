//! `robotino-sim`: stands for the Robotino's driver processes and the field. It offers the
//! same services one driver per device would on a real robot (IR, bumper, gyro, odometry,
//! puck sensor, camera light, heartbeat) and reads the motor command, for up to three robots.
//!
//! The game (hidden machine types, lights, pucks, clock, score) is the rules issue's CLIPS
//! referee (`rules/referee.clp`) run by our engine ([`ClipsReferee`]); the setup is drawn
//! from `--seed` like `robotino-agent sim --seed`.
//!
//! Cycles: in real time (`time_warp` 1) a cycle every 1/15 s; with `time_warp` W, W times as
//! fast; in lockstep, a cycle as soon as every robot's agent sent a fresh motor command (or
//! after `lockstep_grace_ms`, so a dead agent still trips the dead-man rule).

use clap::Parser;
use hal::field::GateId;
use hal::WheelSpeeds;
use host_shim::shim::config::Config;
use host_shim::shim::field_sim::{Command, FieldSim, SensorFrame};
use host_shim::shim::payloads::{
    BumperPayload, DriverId, GyroPayload, HeartbeatPayload, IrScanPayload, LightPayload,
    MotorCommandPayload, OdometryPayload, OdometryReading, PuckPayload,
};
use host_shim::shim::referee::{ClipsReferee, Referee};
use host_shim::shim::rule_engine::with_engine_stack;
use host_shim::shim::transport::{Pub, RobotStream, Sub, Transport, TransportError};
use std::path::PathBuf;
use std::process::ExitCode;
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
    /// Number of robots on the field (1..=3).
    #[arg(long, default_value_t = 1)]
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

    /// The newest valid motor command and the bumper sample it answers. An invalid one is
    /// dropped (and so is not fresh: the dead-man rule counts it as missing).
    fn command(&mut self) -> Result<Option<(Command, u32)>, TransportError> {
        Ok(self.motor.poll()?.and_then(|p| {
            let wheels: WheelSpeeds = p.decode().ok()?;
            let release = p.release().ok()?;
            Some((
                Command {
                    seq: p.seq,
                    wheels,
                    release,
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

fn main() -> ExitCode {
    let args = Args::parse();
    // The referee's engine passes its arrays through the stack on the way to the heap.
    match with_engine_stack(move || run(&args).map_err(|e| e.to_string())) {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(e)) | Err(e) => {
            eprintln!("robotino-sim: {e}");
            ExitCode::FAILURE
        }
    }
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
    let robots = args.robots.clamp(1, 3);
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
    let grace = Duration::from_millis(config.timing.lockstep_grace_ms);
    let poll = Duration::from_micros(200);
    let mut last_seq: Vec<Option<u32>> = vec![None; ports.len()];
    let mut latency: Option<BumperLatency> = None;
    let start = Instant::now();

    for (i, p) in ports.iter_mut().enumerate() {
        p.publish(&field.sense(i), gate, 0)?;
    }
    println!(
        "robotino-sim: ready prefix={} robots={robots} seed={} gate=D{} referee=rules/referee.clp",
        config.services.prefix,
        args.seed,
        gate.map_or(0, GateId::number)
    );
    loop {
        // Wait for the next cycle.
        let cycle_start = Instant::now();
        let mut commands: Vec<Option<(Command, u32)>> = vec![None; ports.len()];
        loop {
            for (c, p) in commands.iter_mut().zip(ports.iter_mut()) {
                *c = p.command()?;
            }
            let all_fresh = commands
                .iter()
                .zip(last_seq.iter())
                .all(|(c, last)| c.is_some_and(|(c, _)| Some(c.seq) != *last));
            let due = if config.timing.lockstep {
                all_fresh || cycle_start.elapsed() >= grace
            } else {
                start.elapsed() >= wall_cycle * (field.cycle() as u32 + 1)
            };
            if due {
                break;
            }
            if !transport.wait(poll) {
                println!("robotino-sim: terminated");
                return Ok(());
            }
        }
        for (last, c) in last_seq.iter_mut().zip(commands.iter()) {
            *last = c.map(|(c, _)| c.seq);
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
            println!(
                "robotino-sim: done cycles={cycle} game_time_s={:.1} score={} wall_ms={}",
                field.referee.clock_s(),
                field.referee.score(),
                start.elapsed().as_millis()
            );
            println!(
                "robotino-sim: referee engine {:?}",
                field.referee.engine_stats()
            );
            return Ok(());
        }
    }
}
