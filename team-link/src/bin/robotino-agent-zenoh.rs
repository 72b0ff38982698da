//! `robotino-agent-zenoh`: `robotino-agent run` with the team's messages over Zenoh
//! instead of iceoryx2, for robots on machines of their own. The robot's drivers stay on
//! iceoryx2 on its own computer; only the team link changes. Peers meet on explicit
//! endpoints (scouting off):
//!
//! ```sh
//! robotino-agent-zenoh --robot 1 --team-size 3 --listen tcp/0.0.0.0:7447
//! robotino-agent-zenoh --robot 2 --team-size 3 --listen tcp/0.0.0.0:7447 --connect tcp/ROBOT1:7447
//! ```

use std::process::ExitCode;

use clap::Parser;
use host_shim::agent_loop::{self, Args};
use team_link::ZenohLink;

#[derive(Parser)]
#[command(
    name = "robotino-agent-zenoh",
    about = "One robot's agent loop; team messages over Zenoh"
)]
struct Cli {
    #[command(flatten)]
    run: Args,
    /// Zenoh endpoints this robot listens on (e.g. tcp/0.0.0.0:7447).
    #[arg(long)]
    listen: Vec<String>,
    /// Zenoh endpoints of teammates to connect to (e.g. tcp/10.0.0.2:7447).
    #[arg(long)]
    connect: Vec<String>,
    /// Key prefix of the team's messages (one per team).
    #[arg(long, default_value = "robotino")]
    zenoh_prefix: String,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let (listen, connect, prefix) = (cli.listen, cli.connect, cli.zenoh_prefix);
    agent_loop::main_with(
        cli.run,
        Box::new(move |_, seat| {
            let link = ZenohLink::open(seat.id, &prefix, &listen, &connect)?;
            Ok(Box::new(link))
        }),
    )
}
