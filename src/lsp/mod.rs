//! `threadcheck lsp`: a language server over standard input and output (the Language Server
//! Protocol 3.17, framed and typed by rust-analyzer's `lsp-server` and `lsp-types`). Each program
//! an editor opens is verified as `verify PROGRAM` verifies it (the dialect from its extension,
//! every thread named by the program) whenever it changes; the server publishes a diagnostic per
//! thread-making operation at its line, answers a hover on an operation's line with every check,
//! and offers the correction, in the program's own words, as a quick fix.
//!
//! The loop reads messages on a thread of its own; the main thread answers them in order and,
//! before verifying, takes every message already waiting, so that a newer change of a document
//! replaces an older one not yet verified. A message that is not JSON gets JSON-RPC's parse error
//! (−32700) and the server reads on; a request before `initialize` gets −32002, an unknown one
//! −32601, one with bad parameters −32602.

mod args;
mod frame;

pub use args::LspArgs;

use crate::commands::VerifyArgs;
use crate::report::lsp::{EditorView, Severity};
use crate::{Error, Files, Request};
use lsp_server::{ErrorCode, Message, Notification, RequestId, Response};
use lsp_types as lt;
use serde_json::Value;
use std::collections::{BTreeMap, HashMap};
use std::io::{BufRead, Write};

/// The most documents the server keeps open at once.
pub const MAX_OPEN_DOCUMENTS: usize = 256;

/// One open program.
struct Doc {
    /// Its path, for its dialect (by extension) and its messages.
    name: String,
    text: String,
    version: i32,
    /// Its view, `None` until verified after the last change.
    view: Option<EditorView>,
    /// Its diagnostics are to be published.
    unpublished: bool,
}

/// What the reader thread hands over.
enum Event {
    Message(Message),
    /// A message whose body is not a JSON-RPC message (the framing held).
    Malformed(String),
    /// A message announced larger than the framing reader takes: skipped, not read.
    TooLarge(u64),
    /// The input ended.
    End,
    /// The framing broke (a header without Content-Length, a read error): nothing after it can
    /// be read.
    Broken(String),
}

/// How the loop goes on.
enum Flow {
    Continue,
    /// The process ends with this code (0 after shutdown, 1 otherwise: the protocol's rule).
    Exit(i32),
}

struct Server<W: Write> {
    out: W,
    initialized: bool,
    shut_down: bool,
    docs: BTreeMap<String, Doc>,
    settings: VerifyArgs,
    tools: Option<crate::analysis::tools::ToolTable>,
}

/// Runs the server on standard input and output until the client's `exit` (or the end of the
/// input); the exit code is the protocol's: 0 after `shutdown`, else 1.
pub fn lsp(_args: &LspArgs) -> Result<i32, Error> {
    let stdin = std::io::stdin();
    run(std::io::BufReader::new(stdin), std::io::stdout().lock())
}

/// The server over any input and output (the tests' pipes).
///
/// ```
/// use std::io::Cursor;
/// let framed = |s: &str| format!("Content-Length: {}\r\n\r\n{s}", s.len());
/// let input = [
///     framed(r#"{"jsonrpc":"2.0","id":1,"method":"initialize","params":{"capabilities":{}}}"#),
///     framed(r#"{"jsonrpc":"2.0","id":2,"method":"shutdown"}"#),
///     framed(r#"{"jsonrpc":"2.0","method":"exit"}"#),
/// ]
/// .concat();
/// let mut out = Vec::new();
/// let code = threadcheck::lsp_run(Cursor::new(input.into_bytes()), &mut out)?;
/// assert_eq!(code, 0);
/// assert!(String::from_utf8(out)?.contains(r#""hoverProvider":true"#));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run<R: BufRead + Send + 'static, W: Write>(input: R, out: W) -> Result<i32, Error> {
    let (tx, rx) = std::sync::mpsc::channel::<Event>();
    let reader = std::thread::spawn(move || {
        let mut input = frame::Framed::new(input);
        loop {
            let event = match input.read() {
                Ok(frame::Frame::Body(body)) => match serde_json::from_slice::<Message>(&body) {
                    Ok(m) => {
                        let exit = matches!(&m, Message::Notification(n) if n.method == "exit");
                        if tx.send(Event::Message(m)).is_err() || exit {
                            return;
                        }
                        continue;
                    }
                    // The framing held: answered, and the reader reads on.
                    Err(e) => {
                        if tx.send(Event::Malformed(format!("malformed LSP payload: {e}"))).is_err() {
                            return;
                        }
                        continue;
                    }
                },
                Ok(frame::Frame::End) => Event::End,
                Ok(frame::Frame::TooLarge(n)) => {
                    if tx.send(Event::TooLarge(n)).is_err() {
                        return;
                    }
                    continue;
                }
                Err(e) => Event::Broken(e.to_string()),
            };
            let _ = tx.send(event);
            return;
        }
    });
    let mut server = Server {
        out,
        initialized: false,
        shut_down: false,
        docs: BTreeMap::new(),
        settings: VerifyArgs::default(),
        tools: None,
    };
    let code = 'serve: loop {
        let Ok(first) = rx.recv() else { break 1 };
        // Every message already waiting is handled before any verification: a newer change
        // replaces an older one.
        let mut events = vec![first];
        events.extend(rx.try_iter());
        for event in events {
            // A request (or the end) is answered after the changes before it are published.
            let answers = match &event {
                Event::Message(Message::Request(_)) | Event::End => true,
                Event::Message(Message::Notification(n)) => n.method == "exit",
                _ => false,
            };
            if answers {
                server.publish()?;
            }
            match server.handle(event)? {
                Flow::Continue => {}
                Flow::Exit(code) => break 'serve code,
            }
        }
        server.publish()?;
    };
    drop(rx);
    // The reader ends at `exit` or at the end of the input; at neither it is left blocked on
    // its input, which the process's end closes.
    if reader.is_finished() {
        let _ = reader.join();
    }
    Ok(code)
}

/// The first line of a text, cut to a message's length.
fn short(s: &str) -> String {
    crate::one_line(s).chars().take(300).collect()
}

impl<W: Write> Server<W> {
    fn send(&mut self, m: Message) -> Result<(), Error> {
        m.write(&mut self.out).map_err(|e| Error::Io { path: "standard output".into(), source: e })
    }

    fn respond(&mut self, id: RequestId, result: Result<Value, (ErrorCode, String)>) -> Result<(), Error> {
        let r = match result {
            Ok(v) => Response::new_ok(id, v),
            Err((code, message)) => Response::new_err(id, code as i32, message),
        };
        self.send(Message::Response(r))
    }

    /// An error answer to a message whose id is not known.
    fn null_id_error(&mut self, code: ErrorCode, message: &str) -> Result<(), Error> {
        let body = serde_json::json!({
            "jsonrpc": "2.0",
            "id": null,
            "error": {"code": code as i32, "message": message},
        })
        .to_string();
        write!(self.out, "Content-Length: {}\r\n\r\n{body}", body.len())
            .and_then(|()| self.out.flush())
            .map_err(|e| Error::Io { path: "standard output".into(), source: e })
    }

    fn notify<P: serde::Serialize>(&mut self, method: &str, params: P) -> Result<(), Error> {
        self.send(Message::Notification(Notification::new(method.to_string(), params)))
    }

    /// A message for the editor's log (a notification that could not be answered otherwise).
    fn log(&mut self, kind: lt::MessageType, message: String) -> Result<(), Error> {
        self.notify("window/logMessage", lt::LogMessageParams { typ: kind, message })
    }

    fn handle(&mut self, event: Event) -> Result<Flow, Error> {
        match event {
            Event::Message(Message::Request(r)) => {
                let id = r.id.clone();
                let result = self.request(&r.method, r.params);
                self.respond(id, result)?;
                Ok(Flow::Continue)
            }
            Event::Message(Message::Notification(n)) => self.notification(&n.method, n.params),
            Event::Message(Message::Response(_)) => Ok(Flow::Continue),
            // JSON-RPC 2.0: an error whose request cannot be read is answered with a null id.
            Event::Malformed(why) => {
                self.null_id_error(ErrorCode::ParseError, &short(&why))?;
                Ok(Flow::Continue)
            }
            Event::TooLarge(n) => {
                self.null_id_error(
                    ErrorCode::InvalidRequest,
                    &format!(
                        "a message of {n} bytes is larger than the {} bytes a document and its framing take: skipped, not read",
                        frame::MAX_BODY
                    ),
                )?;
                Ok(Flow::Continue)
            }
            Event::End => Ok(Flow::Exit(if self.shut_down { 0 } else { 1 })),
            // Nothing after a broken framing can be read: said on standard error, and the
            // process ends as the protocol's rule has it for an end without `shutdown` (1).
            Event::Broken(why) => {
                eprintln!(
                    "threadcheck: error: the language client's messages cannot be read on: {}",
                    short(&why)
                );
                Ok(Flow::Exit(if self.shut_down { 0 } else { 1 }))
            }
        }
    }

    fn request(&mut self, method: &str, params: Value) -> Result<Value, (ErrorCode, String)> {
        let bad = |e: serde_json::Error| (ErrorCode::InvalidParams, format!("{method}: {e}"));
        if self.shut_down {
            return Err((ErrorCode::InvalidRequest, format!("{method} after shutdown")));
        }
        if method == "initialize" {
            if self.initialized {
                return Err((ErrorCode::InvalidRequest, "initialize was sent twice".into()));
            }
            let p: lt::InitializeParams = serde_json::from_value(params).map_err(bad)?;
            self.configure(p.initialization_options).map_err(|e| (ErrorCode::InvalidParams, e))?;
            self.initialized = true;
            return Ok(initialize_result());
        }
        if !self.initialized {
            return Err((ErrorCode::ServerNotInitialized, format!("{method} before initialize")));
        }
        match method {
            "shutdown" => {
                self.shut_down = true;
                Ok(Value::Null)
            }
            "textDocument/hover" => {
                let p: lt::HoverParams = serde_json::from_value(params).map_err(bad)?;
                let pos = p.text_document_position_params;
                let line = pos.position.line as usize + 1;
                let Some(doc) = self.fresh(pos.text_document.uri.as_str()) else {
                    return Ok(Value::Null);
                };
                let hover =
                    doc.view.iter().flat_map(|v| &v.hovers).find(|h| h.line == line).map(|h| lt::Hover {
                        contents: lt::HoverContents::Markup(lt::MarkupContent {
                            kind: lt::MarkupKind::Markdown,
                            value: h.markdown.clone(),
                        }),
                        range: None,
                    });
                Ok(serde_json::to_value(hover).unwrap_or(Value::Null))
            }
            "textDocument/codeAction" => {
                let p: lt::CodeActionParams = serde_json::from_value(params).map_err(bad)?;
                let (first, last) = (p.range.start.line as usize + 1, p.range.end.line as usize + 1);
                let uri = p.text_document.uri;
                let Some(doc) = self.fresh(uri.as_str()) else {
                    return Ok(Value::Array(Vec::new()));
                };
                let actions: Vec<lt::CodeActionOrCommand> = doc
                    .view
                    .iter()
                    .flat_map(|v| &v.fixes)
                    .filter(|f| {
                        (first..=last).contains(&f.line)
                            || f.edits.iter().any(|e| (first..=last).contains(&e.line))
                    })
                    .map(|f| {
                        let edits = f
                            .edits
                            .iter()
                            .map(|e| lt::TextEdit {
                                range: word_range(&doc.text, e.line, e.column, e.old.chars().count()),
                                new_text: e.new.clone(),
                            })
                            .collect();
                        lt::CodeActionOrCommand::CodeAction(lt::CodeAction {
                            title: f.title.clone(),
                            kind: Some(lt::CodeActionKind::QUICKFIX),
                            edit: Some(lt::WorkspaceEdit {
                                changes: Some(HashMap::from([(uri.clone(), edits)])),
                                ..lt::WorkspaceEdit::default()
                            }),
                            is_preferred: Some(true),
                            ..lt::CodeAction::default()
                        })
                    })
                    .collect();
                Ok(serde_json::to_value(actions).unwrap_or(Value::Null))
            }
            _ => Err((ErrorCode::MethodNotFound, format!("threadcheck does not answer {method}"))),
        }
    }

    /// The editor's options: the API's `verify` keys (`insert`, `dialect`, `machine_type`,
    /// `gauge_only`, `tools` as TOML text, …), `tools_file`, a tool table's path, and
    /// `subroutine_path`, LinuxCNC's folders of subroutine files (`:` between them).
    fn configure(&mut self, options: Option<Value>) -> Result<(), String> {
        let mut options = match options {
            None | Some(Value::Null) => serde_json::Map::new(),
            Some(Value::Object(m)) => m,
            Some(_) => return Err("initializationOptions must be an object of verify's options".into()),
        };
        if let Some(path) = options.remove("tools_file") {
            let path = path.as_str().ok_or("tools_file must be a path")?;
            let text = std::fs::read_to_string(path).map_err(|e| format!("tools_file {path}: {e}"))?;
            options.insert("tools".into(), Value::String(text));
        }
        let subroutine_path = match options.remove("subroutine_path") {
            None | Some(Value::Null) => Vec::new(),
            Some(Value::String(p)) => {
                p.split(':').filter(|d| !d.is_empty()).map(std::path::PathBuf::from).collect()
            }
            Some(_) => return Err("subroutine_path is a list of folders separated by ':'".into()),
        };
        for key in ["program", "program_name", "thread"] {
            if options.contains_key(key) {
                return Err(format!(
                    "initializationOptions takes no '{key}': the editor's documents are the programs"
                ));
            }
        }
        let command = crate::Command::from_api("verify", &Value::Object(options).to_string())
            .map_err(|e| e.one_line_for(crate::Audience::Api))?;
        let crate::Command::Verify(args) = command else {
            return Err("initializationOptions: not verify's options".into());
        };
        self.tools = args
            .tools
            .as_ref()
            .map(|t| crate::commands::args::tool_table(t, Files::Refused))
            .transpose()
            .map_err(|e| e.one_line_for(crate::Audience::Api))?;
        self.settings = args;
        self.settings.plan.subroutine_path = subroutine_path;
        Ok(())
    }

    fn notification(&mut self, method: &str, params: Value) -> Result<Flow, Error> {
        if method == "exit" {
            return Ok(Flow::Exit(if self.shut_down { 0 } else { 1 }));
        }
        if !self.initialized {
            // The protocol drops notifications before initialize (but exit).
            return Ok(Flow::Continue);
        }
        let outcome: Result<(), String> = match method {
            "textDocument/didOpen" => serde_json::from_value::<lt::DidOpenTextDocumentParams>(params)
                .map_err(|e| e.to_string())
                .and_then(|p| {
                    let uri = p.text_document.uri.as_str().to_string();
                    if !self.docs.contains_key(&uri) && self.docs.len() >= MAX_OPEN_DOCUMENTS {
                        return Err(format!(
                            "more than {MAX_OPEN_DOCUMENTS} programs open: {uri} is not checked"
                        ));
                    }
                    let name = document_name(&uri);
                    self.docs.insert(
                        uri,
                        Doc {
                            name,
                            text: p.text_document.text,
                            version: p.text_document.version,
                            view: None,
                            unpublished: true,
                        },
                    );
                    Ok(())
                }),
            "textDocument/didChange" => serde_json::from_value::<lt::DidChangeTextDocumentParams>(params)
                .map_err(|e| e.to_string())
                .and_then(|p| {
                    let uri = p.text_document.uri.as_str().to_string();
                    let doc = self
                        .docs
                        .get_mut(&uri)
                        .ok_or_else(|| format!("{uri} changed but was never opened"))?;
                    // The server asked for whole documents (TextDocumentSyncKind::FULL).
                    let whole = p.content_changes.into_iter().rev().find(|c| c.range.is_none());
                    let change =
                        whole.ok_or("a change of part of a document: threadcheck takes whole documents")?;
                    doc.text = change.text;
                    doc.version = p.text_document.version;
                    doc.view = None;
                    doc.unpublished = true;
                    Ok(())
                }),
            "textDocument/didClose" => serde_json::from_value::<lt::DidCloseTextDocumentParams>(params)
                .map_err(|e| e.to_string())
                .and_then(|p| {
                    self.docs.remove(p.text_document.uri.as_str());
                    self.notify(
                        "textDocument/publishDiagnostics",
                        lt::PublishDiagnosticsParams {
                            uri: p.text_document.uri,
                            diagnostics: Vec::new(),
                            version: None,
                        },
                    )
                    .map_err(|e| e.to_string())
                }),
            _ => Ok(()),
        };
        if let Err(why) = outcome {
            self.log(lt::MessageType::ERROR, format!("threadcheck: {method}: {}", short(&why)))?;
        }
        Ok(Flow::Continue)
    }

    /// The document with its view verified for its text as it is now.
    fn fresh(&mut self, uri: &str) -> Option<&Doc> {
        let request = Request { wanted: Vec::new(), files: Files::Refused, reader: crate::Audience::Api };
        let (settings, tools) = (&self.settings, self.tools.as_ref());
        let doc = self.docs.get_mut(uri)?;
        if doc.view.is_none() {
            doc.view = Some(settings.for_editor(&doc.name, doc.text.clone(), tools, &request));
        }
        Some(doc)
    }

    /// Verifies every changed document and publishes its diagnostics.
    fn publish(&mut self) -> Result<(), Error> {
        let waiting: Vec<String> =
            self.docs.iter().filter(|(_, d)| d.unpublished).map(|(u, _)| u.clone()).collect();
        for uri in waiting {
            let Some(doc) = self.fresh(&uri) else { continue };
            let diagnostics = doc
                .view
                .iter()
                .flat_map(|v| &v.diagnostics)
                .map(|d| lt::Diagnostic {
                    range: word_range(&doc.text, d.line, d.column, 0),
                    severity: Some(match d.severity {
                        Severity::Error => lt::DiagnosticSeverity::ERROR,
                        Severity::Information => lt::DiagnosticSeverity::INFORMATION,
                    }),
                    code: Some(lt::NumberOrString::String(d.code.clone())),
                    source: Some("threadcheck".into()),
                    message: d.message.clone(),
                    ..lt::Diagnostic::default()
                })
                .collect();
            let version = Some(doc.version);
            let Ok(parsed) = uri.parse::<lt::Uri>() else { continue };
            if let Some(d) = self.docs.get_mut(&uri) {
                d.unpublished = false;
            }
            self.notify(
                "textDocument/publishDiagnostics",
                lt::PublishDiagnosticsParams { uri: parsed, diagnostics, version },
            )?;
        }
        Ok(())
    }
}

/// What the server says it does.
fn initialize_result() -> Value {
    let result = lt::InitializeResult {
        capabilities: lt::ServerCapabilities {
            text_document_sync: Some(lt::TextDocumentSyncCapability::Kind(lt::TextDocumentSyncKind::FULL)),
            hover_provider: Some(lt::HoverProviderCapability::Simple(true)),
            code_action_provider: Some(lt::CodeActionProviderCapability::Simple(true)),
            ..lt::ServerCapabilities::default()
        },
        server_info: Some(lt::ServerInfo {
            name: "threadcheck".into(),
            version: Some(env!("CARGO_PKG_VERSION").into()),
        }),
    };
    serde_json::to_value(result).unwrap_or(Value::Null)
}

/// A document's name for its dialect and messages: a `file:` URI's path, decoded; else the URI.
fn document_name(uri: &str) -> String {
    match uri.strip_prefix("file://") {
        Some(path) => percent_encoding::percent_decode_str(path).decode_utf8_lossy().to_string(),
        None => uri.to_string(),
    }
}

/// The range of `chars` characters from `column` (1-based, in characters) on `line` (1-based), in
/// the protocol's UTF-16 positions; `chars` 0 takes the word there (to the next blank).
fn word_range(text: &str, line: usize, column: usize, chars: usize) -> lt::Range {
    let l = text.lines().nth(line.saturating_sub(1)).unwrap_or("");
    let start: usize = l.chars().take(column.saturating_sub(1)).map(char::len_utf16).sum();
    let rest = l.chars().skip(column.saturating_sub(1));
    let len: usize = if chars == 0 {
        rest.take_while(|c| !c.is_whitespace()).map(char::len_utf16).sum()
    } else {
        rest.take(chars).map(char::len_utf16).sum()
    };
    let at =
        |character: usize| lt::Position { line: line.saturating_sub(1) as u32, character: character as u32 };
    lt::Range { start: at(start), end: at(start + len.max(1)) }
}
