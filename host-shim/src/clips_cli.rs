//! `robotino-agent clips`: behaves like the `clips` command line.

use std::process::ExitCode;

#[derive(clap::Args)]
pub struct Args {
    /// Batch file, echoed as CLIPS does.
    #[arg(short = 'f')]
    pub batch: Option<std::path::PathBuf>,
}

pub fn main(_args: Args) -> ExitCode {
    eprintln!("robotino-agent clips: not implemented yet");
    ExitCode::FAILURE
}
