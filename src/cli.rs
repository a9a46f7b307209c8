//! The command line: clap parses the arguments into a library [`Command`] (each command's
//! argument struct is defined once, in the library's `commands/`), which runs with the files
//! its flags name and the one writer delivers its documents. This module belongs to the binary.

use clap::{Parser, Subcommand};
use threadcheck::{
    deliver, Audience, Command, Document, Error, Files, FilterArgs, LspArgs, Outcome, Request, ServeArgs,
    Shown,
};

/// Predicts the thread a CNC program cuts (turned, tapped or thread-milled) and checks it
/// against its standard.
#[derive(Parser)]
#[command(name = "threadcheck", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Top,
}

/// The library's commands, and the server, which runs them for the page and the API.
#[derive(Subcommand)]
#[allow(clippy::large_enum_variant)]
enum Top {
    #[command(flatten)]
    Run(Command),
    /// The shop's page and the JSON API on this computer: open the address it prints in a
    /// browser (verify, compare, fit, limits); scripts POST to /api/verify and the like.
    Serve(ServeArgs),
    /// LinuxCNC's program filter: copies FILE to standard output, one line per failing thread
    /// on standard error, and with --gate exits 1 so that the control refuses the program
    /// (`[FILTER]` in the machine's INI file: docs/guide/where-programs-live.md).
    Filter(FilterArgs),
    /// A language server for editors over standard input and output (VS Code, Neovim, Emacs,
    /// Kate, …): every open program verified as it changes, a diagnostic per thread at its line,
    /// hovers with every check, the correction as a quick fix (docs/guide/where-programs-live.md).
    Lsp(LspArgs),
}

/// Every command's name and the keys its flags set (`--cutter-diameter` is `cutter_diameter`).
pub fn accepted_keys() -> Vec<(String, Vec<String>)> {
    use clap::CommandFactory;
    Cli::command()
        .get_subcommands()
        .map(|c| {
            let keys = c.get_arguments().filter_map(|a| a.get_long()).map(|l| l.replace('-', "_")).collect();
            (c.get_name().to_string(), keys)
        })
        .collect()
}

/// The one-line form of clap's rendered error: the message and its tips, without the usage
/// block and the `--help` hint.
pub fn one_line(rendered: &str) -> String {
    let mut parts = Vec::new();
    for line in rendered.lines() {
        let l = line.trim();
        if l.starts_with("Usage:") || l.starts_with("For more information") {
            break;
        }
        if !l.is_empty() {
            parts.push(l.strip_prefix("error: ").unwrap_or(l));
        }
    }
    parts.join(" ")
}

impl Cli {
    /// Runs the command: what to print on stdout and on stderr, and the outcome.
    pub fn run(self) -> Result<(Shown, Outcome), Error> {
        let command = match self.command {
            Top::Run(c) => c,
            Top::Serve(a) => {
                threadcheck::serve(a.options(), |line| {
                    use std::io::Write;
                    let mut out = std::io::stdout().lock();
                    let _ = writeln!(out, "{line}");
                    let _ = out.flush();
                })?;
                return Ok((Shown::default(), Outcome::Pass));
            }
            Top::Lsp(a) => {
                // The protocol's exit codes: 0 after the client's shutdown, 1 without it.
                let code = threadcheck::lsp(&a)?;
                return Ok((
                    Shown::default(),
                    if code == 0 { Outcome::Pass } else { Outcome::OutOfTolerance },
                ));
            }
            Top::Filter(a) => {
                // The program's bytes as read: written here, not through the text documents.
                use std::io::Write;
                let out = threadcheck::filter(&a)?;
                let written =
                    std::io::stdout().lock().write_all(&out.stdout).and_then(|()| std::io::stdout().flush());
                written.map_err(|e| Error::Io { path: "standard output".into(), source: e })?;
                return Ok((Shown { stdout: String::new(), stderr: out.stderr }, out.outcome));
            }
        };
        let dests = command.destinations();
        let mut wanted: Vec<Document> = dests.iter().map(|(d, _)| *d).collect();
        wanted.push(Document::Text);
        // A run of many shows its progress when standard error is a terminal.
        let progress = std::io::IsTerminal::is_terminal(&std::io::stderr());
        let request = Request { wanted, files: Files::Allowed, reader: Audience::Cli, progress };
        let out = command.run(&request)?;
        Ok((deliver(&out, &dests, Audience::Cli)?, out.outcome))
    }
}
