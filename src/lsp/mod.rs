//! `threadcheck lsp`: a language server over standard input and output (the Language Server
//! Protocol 3.17, framed and typed by rust-analyzer's `lsp-server` and `lsp-types`). Each program
//! an editor opens is verified as `verify PROGRAM` verifies it (the dialect from its extension,
//! every thread named by the program) whenever it changes; the server publishes a diagnostic per
//! thread-making operation at its line, answers a hover on an operation's line with every check,
//! and offers the correction, in the program's own words, as a quick fix.
//!
//! The loop reads messages on a thread of its own; the main thread answers them and hands each
//! document's check to a thread of its own (at most [`MAX_CHECKS`] at once), so that `shutdown`,
//! `exit` and other documents' requests are answered while a long program is checked. Before it
//! starts checks the main thread takes every message already waiting, so that a newer change of
//! a document replaces an older one not yet checked; a change while a check runs stops that check
//! (its [`Cancel`](crate::Cancel) is raised) and starts one of the new text. A hover or quick fix
//! asked of a document being checked is answered when its check ends. A message that is not JSON gets JSON-RPC's parse error
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
use std::sync::mpsc::Sender;
use std::sync::Arc;

/// The most documents the server keeps open at once.
pub const MAX_OPEN_DOCUMENTS: usize = 256;

/// The most checks running at once (a stopped check counts until its thread has ended).
pub const MAX_CHECKS: usize = 4;

/// One open program.
struct Doc {
    /// Its path, for its dialect (by extension) and its messages.
    name: String,
    text: String,
    version: i32,
    /// Its view, `None` until checked after the last change.
    view: Option<EditorView>,
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
    /// A check's thread ended: the document, the version it checked, its view (`None` when it
    /// was stopped).
    Checked {
        uri: String,
        version: i32,
        view: Option<EditorView>,
    },
}

/// A check under way.
struct Running {
    version: i32,
    stop: crate::Cancel,
}

/// A request waiting for its document's check.
struct Waiting {
    id: RequestId,
    method: String,
    params: Value,
    uri: String,
}

/// What a request finds of its document.
enum Lookup<'a> {
    /// Not open: answered with nothing.
    Absent,
    /// Being checked (or about to be): the request waits.
    Pending,
    Ready(&'a Doc),
}

/// How the loop goes on.
enum Flow {
    Continue,
    /// The process ends with this code (0 after shutdown, 1 otherwise: the protocol's rule).
    Exit(i32),
    /// The input ended: the process ends with this code once the checks under way have ended.
    Ending(i32),
}

struct Server<W: Write> {
    out: W,
    initialized: bool,
    shut_down: bool,
    docs: BTreeMap<String, Doc>,
    settings: Arc<VerifyArgs>,
    tools: Arc<Option<crate::analysis::tools::ToolTable>>,
    /// The check of each document under way.
    running: HashMap<String, Running>,
    /// Check threads not yet ended (stopped ones included).
    alive: usize,
    /// The check threads, joined once they have ended (none outlives the server).
    threads: Vec<std::thread::JoinHandle<()>>,
    /// Requests waiting for a check, in the order they came.
    waiting: Vec<Waiting>,
    /// Where a check's thread hands its view.
    events: Sender<Event>,
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
    let events = tx.clone();
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
        settings: Arc::new(VerifyArgs::default()),
        tools: Arc::new(None),
        running: HashMap::new(),
        alive: 0,
        threads: Vec::new(),
        waiting: Vec::new(),
        events,
    };
    // The input's end once seen: the checks under way are finished and published, then the
    // server ends with this code.
    let mut ending: Option<i32> = None;
    let code = 'serve: loop {
        if let Some(code) = ending {
            if server.alive == 0 {
                break code;
            }
        }
        // The main thread holds a sender, so this waits for a message or a check's end.
        let Ok(first) = rx.recv() else { break 1 };
        // Every message already waiting is handled before any check starts: a newer change
        // replaces an older one.
        let mut events = vec![first];
        events.extend(rx.try_iter());
        for event in events {
            match server.handle(event)? {
                Flow::Continue => {}
                Flow::Exit(code) => break 'serve code,
                Flow::Ending(code) => ending = Some(code),
            }
        }
        server.start_checks();
    };
    // The checks stopped end within milliseconds (at their next check of the flag): waited
    // for, up to two seconds, so that no thread of this server outlives it.
    server.stop_all();
    let until = std::time::Instant::now() + std::time::Duration::from_secs(2);
    while server.alive > 0 {
        match rx.recv_timeout(until.saturating_duration_since(std::time::Instant::now())) {
            Ok(Event::Checked { .. }) => server.alive -= 1,
            Ok(_) => {}
            Err(_) => break,
        }
    }
    // Each thread that has handed over its view returns at once: joined (one still checking
    // past the two seconds is left, the process's end stops it).
    for h in std::mem::take(&mut server.threads) {
        if server.alive == 0 || h.is_finished() {
            let _ = h.join();
        }
    }
    drop(rx);
    // The reader ends at `exit` or at the end of the input (it has sent either when the loop
    // ends): joined once it has returned, within a tenth of a second; otherwise it is left
    // blocked on its input, which the process's end closes.
    let until = std::time::Instant::now() + std::time::Duration::from_millis(100);
    while !reader.is_finished() && std::time::Instant::now() < until {
        std::thread::sleep(std::time::Duration::from_millis(1));
    }
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
                // A hover or quick fix of a document being checked waits for its check.
                if let Some(uri) = self.waits_for_check(&r.method, &r.params) {
                    self.waiting.push(Waiting { id: r.id, method: r.method, params: r.params, uri });
                    return Ok(Flow::Continue);
                }
                let id = r.id.clone();
                let result = self.request(&r.method, r.params);
                self.respond(id, result)?;
                Ok(Flow::Continue)
            }
            Event::Checked { uri, version, view } => {
                self.alive = self.alive.saturating_sub(1);
                if self.running.get(&uri).is_some_and(|r| r.version == version) {
                    self.running.remove(&uri);
                }
                let current = self.docs.get_mut(&uri).filter(|d| d.version == version && d.view.is_none());
                if let (Some(doc), Some(view)) = (current, view) {
                    doc.view = Some(view);
                    self.publish(&uri)?;
                    self.answer_waiting(&uri)?;
                }
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
            Event::End => Ok(Flow::Ending(if self.shut_down { 0 } else { 1 })),
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
                // Answered at once: the checks under way are stopped, and what waited for them
                // is answered with nothing.
                self.shut_down = true;
                self.stop_all();
                Ok(Value::Null)
            }
            "textDocument/hover" => {
                let p: lt::HoverParams = serde_json::from_value(params).map_err(bad)?;
                let pos = p.text_document_position_params;
                let line = pos.position.line as usize + 1;
                let Lookup::Ready(doc) = self.lookup(pos.text_document.uri.as_str()) else {
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
                let Lookup::Ready(doc) = self.lookup(uri.as_str()) else {
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
            // Through the bounded reader, as every file: a FIFO or /dev/zero named here is given up.
            let text = crate::ground::input::read_text_bounded(
                std::path::Path::new(path),
                crate::ground::bounds::MAX_DATA_FILE_BYTES,
                "a tool table",
            )
            .map_err(|e| format!("tools_file: {}", e.one_line()))?;
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
        self.tools = Arc::new(
            args.tools
                .as_ref()
                .map(|t| crate::commands::args::tool_table(t, Files::Refused))
                .transpose()
                .map_err(|e| e.one_line_for(crate::Audience::Api))?,
        );
        let mut settings = args;
        settings.plan.reading.subroutine_path = subroutine_path;
        self.settings = Arc::new(settings);
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
                    if let Some(r) = self.running.remove(&uri) {
                        r.stop.raise();
                    }
                    Ok(())
                }),
            "textDocument/didClose" => serde_json::from_value::<lt::DidCloseTextDocumentParams>(params)
                .map_err(|e| e.to_string())
                .and_then(|p| {
                    let uri = p.text_document.uri.as_str();
                    self.docs.remove(uri);
                    if let Some(r) = self.running.remove(uri) {
                        r.stop.raise();
                    }
                    self.answer_waiting(uri).map_err(|e| e.to_string())?;
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

    /// The document a request asks about, if it is one that waits for its check.
    fn waits_for_check(&self, method: &str, params: &Value) -> Option<String> {
        if !self.initialized || self.shut_down {
            return None;
        }
        if !matches!(method, "textDocument/hover" | "textDocument/codeAction") {
            return None;
        }
        let uri = params.get("textDocument")?.get("uri")?.as_str()?;
        matches!(self.lookup(uri), Lookup::Pending).then(|| uri.to_string())
    }

    /// What a request finds of the document `uri`.
    fn lookup(&self, uri: &str) -> Lookup<'_> {
        match self.docs.get(uri) {
            None => Lookup::Absent,
            Some(d) if d.view.is_none() => Lookup::Pending,
            Some(d) => Lookup::Ready(d),
        }
    }

    /// Answers the requests that waited for `uri`'s check, in the order they came (the
    /// document closed or the server shut down: with nothing).
    fn answer_waiting(&mut self, uri: &str) -> Result<(), Error> {
        let (now, later): (Vec<Waiting>, Vec<Waiting>) =
            std::mem::take(&mut self.waiting).into_iter().partition(|w| w.uri == uri);
        self.waiting = later;
        for w in now {
            let result = self.request(&w.method, w.params);
            self.respond(w.id, result)?;
        }
        Ok(())
    }

    /// Stops every check under way and answers what waited for one.
    fn stop_all(&mut self) {
        for (_, r) in self.running.drain() {
            r.stop.raise();
        }
        for w in std::mem::take(&mut self.waiting) {
            let empty =
                if w.method == "textDocument/codeAction" { Value::Array(Vec::new()) } else { Value::Null };
            let _ = self.respond(w.id, Ok(empty));
        }
    }

    /// Starts the checks of the documents changed and not being checked, while fewer than
    /// [`MAX_CHECKS`] threads run.
    fn start_checks(&mut self) {
        // The threads that have ended are joined.
        for h in std::mem::take(&mut self.threads) {
            if h.is_finished() {
                let _ = h.join();
            } else {
                self.threads.push(h);
            }
        }
        if self.shut_down {
            return;
        }
        let due: Vec<String> = self
            .docs
            .iter()
            .filter(|(u, d)| d.view.is_none() && !self.running.contains_key(*u))
            .map(|(u, _)| u.clone())
            .collect();
        for uri in due {
            if self.alive >= MAX_CHECKS {
                return;
            }
            let Some(doc) = self.docs.get(&uri) else { continue };
            let (name, text, version) = (doc.name.clone(), doc.text.clone(), doc.version);
            let (settings, tools, events) =
                (Arc::clone(&self.settings), Arc::clone(&self.tools), self.events.clone());
            let stop = crate::Cancel::new();
            let mine = stop.clone();
            let key = uri.clone();
            let spawned = std::thread::Builder::new().name("threadcheck-lsp-check".into()).spawn(move || {
                let request = Request {
                    wanted: Vec::new(),
                    files: Files::Refused,
                    reader: crate::Audience::Api,
                    progress: false,
                };
                let checked = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    mine.run(|| settings.for_editor(&name, text, (*tools).as_ref(), &request))
                }));
                // A check that panicked (a bug) is said on the document, not waited for forever.
                let view = checked.unwrap_or_else(|_| {
                    EditorView::unreadable(
                        "threadcheck stopped unexpectedly checking this program: a bug, please report it"
                            .into(),
                        None,
                    )
                });
                let view = (!mine.is_raised()).then_some(view);
                let _ = events.send(Event::Checked { uri: key, version, view });
            });
            if let Ok(handle) = spawned {
                self.alive += 1;
                self.threads.push(handle);
                self.running.insert(uri, Running { version, stop });
            }
        }
    }

    /// Publishes the diagnostics of `uri`'s checked view.
    fn publish(&mut self, uri: &str) -> Result<(), Error> {
        let Some(doc) = self.docs.get(uri) else { return Ok(()) };
        let diagnostics = doc
            .view
            .iter()
            .flat_map(|v| &v.diagnostics)
            .map(|d| lt::Diagnostic {
                range: word_range(&doc.text, d.line, d.column, 0),
                severity: Some(match d.severity {
                    Severity::Error => lt::DiagnosticSeverity::ERROR,
                    Severity::Information => lt::DiagnosticSeverity::INFORMATION,
                    Severity::Warning => lt::DiagnosticSeverity::WARNING,
                }),
                code: Some(lt::NumberOrString::String(d.code.clone())),
                source: Some("threadcheck".into()),
                message: d.message.clone(),
                ..lt::Diagnostic::default()
            })
            .collect();
        let version = Some(doc.version);
        let Ok(parsed) = uri.parse::<lt::Uri>() else { return Ok(()) };
        self.notify(
            "textDocument/publishDiagnostics",
            lt::PublishDiagnosticsParams { uri: parsed, diagnostics, version },
        )
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
