//! The `threadcheck` command line: parses typed arguments ([`cli`]) into a command of the
//! library, runs it, and decides the exit code in one place: 0 pass, 1 out of tolerance, 2 error (one
//! line on stderr, clap's own usage errors included).

mod cli;

use clap::Parser;
use std::io::Write;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = match cli::Cli::try_parse() {
        Ok(c) => c,
        Err(e) => return usage_error(&e),
    };
    // An error names the flags of the command in use (another command's with its name).
    let flags =
        threadcheck::CliFlags::of(&std::env::args().nth(1).unwrap_or_default(), &cli::accepted_keys());
    match cli.run() {
        Ok((shown, outcome)) => {
            let written = std::io::stdout()
                .lock()
                .write_all(shown.stdout.as_bytes())
                .and_then(|()| std::io::stdout().flush());
            let _ = std::io::stderr().lock().write_all(shown.stderr.as_bytes());
            match written {
                // A closed pipe (`| head`) is the reader's choice, not an error worth a message.
                Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
                    eprintln!(
                        "threadcheck: error: standard output: {}",
                        threadcheck::one_line(&e.to_string())
                    );
                    ExitCode::from(2)
                }
                _ => ExitCode::from(outcome.exit_code() as u8),
            }
        }
        Err(e) => {
            // One line, whatever the message carried.
            eprintln!("threadcheck: error: {}", e.one_line_for_command(&flags));
            ExitCode::from(2)
        }
    }
}

/// Help and version print as clap writes them (exit 0); every other clap error is one line on
/// stderr with exit 2, like every other error.
fn usage_error(e: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            ExitCode::SUCCESS
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            eprintln!(
                "threadcheck: error: no command given: {}, serve, filter, lsp (threadcheck --help)",
                threadcheck::Command::NAMES.join(", ")
            );
            ExitCode::from(2)
        }
        _ => {
            eprintln!("threadcheck: error: {}", threadcheck::one_line(&cli::one_line(&e.to_string())));
            ExitCode::from(2)
        }
    }
}
