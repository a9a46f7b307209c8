//! The command line's option parsing (the binary's own `cli.rs`, compiled in): any argument
//! list parses or gives a usage error, and a usage error renders as one line; never a panic.
#![no_main]
use clap::Parser;
use libfuzzer_sys::fuzz_target;

#[allow(dead_code)]
#[path = "../../src/cli.rs"]
mod cli;

fuzz_target!(|args: Vec<String>| {
    let argv = std::iter::once("threadcheck".to_string()).chain(args.into_iter().take(40));
    if let Err(e) = cli::Cli::try_parse_from(argv) {
        let line = threadcheck::one_line(&cli::one_line(&e.to_string()));
        assert!(!line.contains('\n'), "{line}");
    }
});
