//! `threadcheck lsp`'s arguments (the command line's alone; the editor sends the verification's
//! options as `initializationOptions`).

/// The arguments of `lsp`: none yet; the editor's options come with `initialize`.
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug, Default)]
pub struct LspArgs {}
