//! The `threadcheck` command line: parses arguments into a validated job from the library, runs
//! it, and maps the outcome to the exit code (0 pass, 1 out of tolerance, 2 error).

use clap::{Parser, Subcommand};
use std::io::Write;
use std::process::ExitCode;
use threadcheck::app::{LimitsJob, Outcome};

/// Predicts the thread a CNC lathe program cuts and checks it against its standard.
#[derive(Parser)]
#[command(name = "threadcheck", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Limits of size of a designation (ISO 965-1, BS 84, ISO 228-1).
    Limits {
        /// Designation, e.g. M10x1.25-6g, M10-6H/6g, "BSF 3/8 medium", "G1/2 A".
        designation: String,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
        /// Accept a diameter/pitch pair outside the standard series.
        #[arg(long)]
        allow_nonstandard: bool,
    },
}

fn run(cli: Cli) -> Result<Outcome, threadcheck::Error> {
    let (text, outcome) = match cli.command {
        Command::Limits { designation, json, allow_nonstandard } => {
            LimitsJob { designation, allow_nonstandard, json }.run()?
        }
    };
    let mut out = std::io::stdout().lock();
    // A closed pipe (`| head`) is not an error worth a message.
    let _ = out.write_all(text.as_bytes());
    Ok(outcome)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(o) => ExitCode::from(o.exit_code() as u8),
        Err(e) => {
            eprintln!("threadcheck: error: {e}");
            ExitCode::from(2)
        }
    }
}
