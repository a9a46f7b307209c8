//! Issue 30: `threadcheck serve`, the JSON API against the command line, its bounds and its
//! errors, over real HTTP on loopback (the page itself is driven in Chromium by
//! `browser::page_in_chromium`).

use crate::*;
use std::io::{BufRead, BufReader};
use std::process::{Child, Stdio};

/// A running `threadcheck serve` on a free loopback port, stopped when dropped.
pub struct Server {
    /// The server process.
    pub child: Child,
    /// `http://127.0.0.1:PORT/`.
    pub url: String,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts the server with `extra` options and reads its start-up line for the address.
pub fn start(extra: &[&str]) -> Server {
    let mut command = Command::new(env!("CARGO_BIN_EXE_threadcheck"));
    command.args(["serve", "--port", "0"]).args(extra);
    start_command(command)
}

/// Runs `command` (a `threadcheck serve` however it is started) and reads its start-up line.
fn start_command(mut command: Command) -> Server {
    let mut child = command.stdout(Stdio::piped()).stderr(Stdio::piped()).spawn().unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
    let url = line
        .split_whitespace()
        .find(|w| w.starts_with("http://"))
        .unwrap_or_else(|| panic!("no address in the start-up line: {line:?}"))
        .to_string();
    assert!(line.contains("loopback"), "{line}");
    Server { child, url }
}

/// POSTs `body` to `path`: the status, the outcome header and the body.
pub fn post(url: &str, path: &str, body: &str) -> (u16, Option<String>, String) {
    let agent: ureq::Agent = ureq::Agent::config_builder().http_status_as_error(false).build().into();
    let mut r = agent.post(&format!("{url}{path}")).content_type("application/json").send(body).unwrap();
    let outcome = r.headers().get("x-threadcheck-outcome").map(|v| v.to_str().unwrap().to_string());
    let status = r.status().as_u16();
    let text = r.body_mut().with_config().limit(64 << 20).read_to_string().unwrap();
    (status, outcome, text)
}

/// POSTs a body of `len` bytes to `api/verify`: the server answers 413 from the declared length
/// before taking the body (and closes), so the answer is read before any of it is sent, which
/// keeps the exchange free of races; the body follows only if no answer came.
fn post_big(url: &str, len: usize) -> (u16, Option<String>, String) {
    use std::io::{Read, Write};
    let addr = url.trim_start_matches("http://").trim_end_matches('/');
    let mut tcp = std::net::TcpStream::connect(addr).unwrap();
    let head = format!(
        "POST /api/verify HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/json\r\nContent-Length: {len}\r\nConnection: close\r\n\r\n"
    );
    tcp.write_all(head.as_bytes()).unwrap();
    tcp.set_read_timeout(Some(std::time::Duration::from_secs(10))).unwrap();
    let mut answer = read_answer(&mut tcp);
    if answer.is_empty() {
        let chunk = vec![b' '; 1 << 20];
        for _ in 0..len >> 20 {
            if tcp.write_all(&chunk).is_err() {
                break;
            }
        }
        let _ = tcp.read_to_end(&mut answer);
    }
    let answer = String::from_utf8_lossy(&answer).into_owned();
    let status = answer.split_whitespace().nth(1).and_then(|c| c.parse().ok()).unwrap_or(0);
    let body = answer.split("\r\n\r\n").nth(1).unwrap_or_default().to_string();
    (status, None, body)
}

/// Reads an answer until its head and its declared body are in (the server may keep the
/// connection open), the server closes, or the read times out.
fn read_answer(tcp: &mut std::net::TcpStream) -> Vec<u8> {
    use std::io::Read;
    let mut answer = Vec::new();
    let mut buf = [0u8; 4096];
    loop {
        let text = String::from_utf8_lossy(&answer).into_owned();
        if let Some(at) = text.find("\r\n\r\n") {
            let declared = text[..at]
                .lines()
                .find_map(|l| {
                    l.to_ascii_lowercase().strip_prefix("content-length:").map(|v| v.trim().to_string())
                })
                .and_then(|v| v.parse::<usize>().ok())
                .unwrap_or(0);
            if answer.len() >= at + 4 + declared {
                break;
            }
        }
        match tcp.read(&mut buf) {
            Ok(0) | Err(_) => break,
            Ok(n) => answer.extend_from_slice(&buf[..n]),
        }
    }
    answer
}

fn get(url: &str, path: &str) -> (u16, String) {
    let agent: ureq::Agent = ureq::Agent::config_builder().http_status_as_error(false).build().into();
    let mut r = agent.get(&format!("{url}{path}")).call().unwrap();
    (r.status().as_u16(), r.body_mut().read_to_string().unwrap())
}

/// The JSON arguments of a program: its text and the name the CLI is given.
fn program_args(path: &std::path::Path, extra: &str) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    format!(
        "{{\"program\": {}, \"program_name\": {}{extra}}}",
        serde_json::to_string(&text).unwrap(),
        serde_json::to_string(&path.display().to_string()).unwrap()
    )
}

/// An error answer: its status, and a JSON object whose `error` is one line.
fn assert_error(answer: &(u16, Option<String>, String), status: u16, contains: &str) {
    assert_eq!(answer.0, status, "{}", answer.2);
    let v: serde_json::Value = serde_json::from_str(&answer.2).unwrap();
    let e = v["error"].as_str().unwrap();
    assert!(!e.contains('\n') && e.contains(contains), "{e}");
    assert_eq!(v["status"], status);
}

/// The API answers with the bytes `--json -` prints for the same input, for every command, and
/// its outcome header is the exit code's.
#[test]
fn api_json_is_byte_identical_to_the_cli() {
    let s = start(&[]);
    let g76 = data("programs/fanuc-g76-timing.nc");
    let p = g76.to_str().unwrap();
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        (
            "verify",
            program_args(&g76, r#", "thread": "M20x1.5-6g", "insert": "full", "dialect": "fanuc""#),
            vec![
                "verify",
                "--thread",
                "M20x1.5-6g",
                "--insert",
                "full",
                "--program",
                p,
                "--dialect",
                "fanuc",
            ],
        ),
        (
            "verify",
            r#"{"thread": "M10x1.5-6g", "final_x": 8.2, "insert": "full"}"#.into(),
            vec!["verify", "--thread", "M10x1.5-6g", "--final-x", "8.2", "--insert", "full"],
        ),
        ("passes", program_args(&g76, ""), vec!["passes", "--program", p]),
        ("limits", r#"{"thread": "1/4-20 UNC-2A"}"#.into(), vec!["limits", "1/4-20 UNC-2A"]),
        ("compare", r#"{"thread": "M10x1.5-6g"}"#.into(), vec!["compare", "--thread", "M10x1.5-6g"]),
        ("fit", r#"{"thread": "M10x1.5-6H/6g"}"#.into(), vec!["fit", "--thread", "M10x1.5-6H/6g"]),
        (
            "correct",
            r#"{"thread": "M10x1.5-6g", "measured_d2": 8.85}"#.into(),
            vec!["correct", "--thread", "M10x1.5-6g", "--measured-d2", "8.85"],
        ),
        (
            "capability",
            r#"{"thread": "M10x1.5-6g", "x_sigma": 0.01, "samples": 300}"#.into(),
            vec!["capability", "--thread", "M10x1.5-6g", "--x-sigma", "0.01", "--samples", "300"],
        ),
    ];
    for (command, body, mut args) in cases {
        args.extend(["--json", "-"]);
        let cli = run(&args);
        let code = cli.status.code().unwrap();
        assert!(code < 2, "{}", stderr(&cli));
        let (status, outcome, text) = post(&s.url, &format!("api/{command}"), &body);
        assert_eq!(status, 200, "{command}: {text}");
        // The same bytes, but that each names an argument as its user typed it (`--insert full`
        // on the command line, `insert full` through the API).
        let cli_json = String::from_utf8(cli.stdout.clone()).unwrap();
        assert_eq!(text, as_keys(&cli_json), "{command}: the API's JSON is not the CLI's");
        assert_eq!(
            outcome.as_deref(),
            Some(if code == 0 { "pass" } else { "out-of-tolerance" }),
            "{command}"
        );
    }
}

/// The command line's text with each flag (`--gauge-only`) written as the API's key
/// (`gauge_only`).
fn as_keys(cli: &str) -> String {
    let mut out = String::new();
    let mut rest = cli;
    while let Some(i) = rest.find("--") {
        out.push_str(&rest[..i]);
        let after = &rest[i + 2..];
        let n = after
            .find(|c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'))
            .unwrap_or(after.len());
        if n > 0 && after.starts_with(|c: char| c.is_ascii_lowercase()) {
            out.push_str(&after[..n].replace('-', "_"));
        } else {
            out.push_str("--");
            out.push_str(&after[..n]);
        }
        rest = &after[n..];
    }
    out.push_str(rest);
    out
}

/// The page, its documents and the corrected program: `/api/verify/fix` is `verify --fix -`, and
/// the SVG and HTML are what `--svg` and `--html` write.
#[test]
fn api_documents_are_the_cli_files() {
    let s = start(&[]);
    let g76 = data("programs/fanuc-g76-timing.nc");
    let p = g76.to_str().unwrap();
    let body = program_args(&g76, r#", "thread": "M20x1.5-6g", "insert": "full""#);
    let fixed = run(&["verify", "--thread", "M20x1.5-6g", "--insert", "full", "--program", p, "--fix", "-"]);
    let (status, _, text) = post(&s.url, "api/verify/fix", &body);
    assert_eq!(status, 200, "{text}");
    assert_eq!(text.as_bytes(), &fixed.stdout[..]);
    // The G76 sheet: X18.2 cuts d2 72 µm over 6g; the fix moves that X and nothing else.
    assert!(text.contains("G76 X18.058 Z-20. P900 Q450 F1.5"), "{text}");
    let dir = tempdir("serve-docs");
    let svg = dir.join("v.svg");
    let html = dir.join("v.html");
    let o = run(&[
        "verify",
        "--thread",
        "M20x1.5-6g",
        "--insert",
        "full",
        "--program",
        p,
        "--svg",
        svg.to_str().unwrap(),
        "--html",
        html.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    for (doc, file) in [("svg", &svg), ("html", &html)] {
        let (status, _, text) = post(&s.url, &format!("api/verify/{doc}"), &body);
        assert_eq!(status, 200);
        assert_eq!(text, as_keys(&std::fs::read_to_string(file).unwrap()), "{doc}");
    }
    let (status, page) = get(&s.url, "");
    assert_eq!(status, 200);
    assert!(page.contains("<title>threadcheck</title>") && page.contains("/app.js"));
    let (status, index) = get(&s.url, "api");
    assert_eq!(status, 200);
    let v: serde_json::Value = serde_json::from_str(&index).unwrap();
    let names: Vec<&str> =
        v["commands"].as_array().unwrap().iter().map(|c| c["command"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "verify",
            "passes",
            "limits",
            "compare",
            "fit",
            "correct",
            "capability",
            "mill",
            "tap",
            "thread-mill"
        ]
    );
}

/// Bad input: a 20 MB body 413, malformed JSON 400, an unknown key 400, a file of the server's
/// 400, an unknown command 404, the CLI's message for a bad designation: each one JSON line.
#[test]
fn api_errors_are_one_json_line_with_their_status() {
    let s = start(&[]);
    assert_error(&post_big(&s.url, 20 << 20), 413, "larger than 8388608 bytes");
    assert_error(&post(&s.url, "api/verify", "{\"thread\": "), 400, "not a JSON object");
    assert_error(&post(&s.url, "api/verify", "[1]"), 400, "JSON object of keyword arguments");
    assert_error(
        &post(&s.url, "api/verify", r#"{"thread": "M10x1.5-6g", "wire": 1}"#),
        400,
        "verify takes no argument 'wire'",
    );
    assert_error(
        &post(&s.url, "api/verify", r#"{"thread": 10}"#),
        400,
        "verify: thread: a designation or a list of them",
    );
    assert_error(
        &post(&s.url, "api/verify", r#"{"thread": "M10x1.5-6g", "insert": "/etc/passwd"}"#),
        400,
        "the server reads none",
    );
    assert_error(
        &post(
            &s.url,
            "api/verify",
            r#"{"thread": "M10x1.5-6g", "program": "G0 X1\n", "tools": "[tools]\n1 = \"/etc/passwd\"\n"}"#,
        ),
        400,
        "names an insert file",
    );
    assert_error(&post(&s.url, "api/shutdown", "{}"), 404, "unknown command 'shutdown'");
    assert_error(
        &post(&s.url, "api/limits/svg", r#"{"thread": "M10x1.5-6g"}"#),
        404,
        "limits gives no svg document",
    );
    let cli = run(&["verify", "--thread", "M10x1.5-6q"]);
    let line = stderr(&cli).trim().strip_prefix("threadcheck: error: ").unwrap().to_string();
    assert_error(&post(&s.url, "api/verify", r#"{"thread": "M10x1.5-6q"}"#), 400, &line);
    // A program's place, its control characters escaped.
    let answer = post(
        &s.url,
        "api/verify",
        "{\"thread\": \"M10x1.5-6g\", \"program\": \"G76.1 X\\u001b[31m\\n\", \"program_name\": \"p.nc\"}",
    );
    assert_error(&answer, 400, "p.nc:1:");
    assert!(!answer.2.contains('\u{1b}'), "{}", answer.2);
}

/// Issue 59: the API refuses a designation of another size than the program cuts, as the command
/// line does (an M30x1.5 bolt given M20x1.5-6g), naming both diameters.
#[test]
fn api_refuses_a_designation_of_another_size() {
    let s = start(&[]);
    let path = data("programs/m30x1.5-turned.nc");
    let answer = post(&s.url, "api/verify", &program_args(&path, r#", "thread": "M20x1.5-6g""#));
    assert_error(&answer, 400, "about Ø30.0 (final X28.160), the designation M20x1.5-6g is Ø20 (d3 18.160)");
}

/// The slowest request the API takes: the Monte Carlo at its work bound (42 553 samples of a
/// 7-pass plan: about 0.7 s on 2 cores).
const SLOW: &str = r#"{"thread": "M10x1.5-6g", "insert": "full", "x_sigma": 0.01, "samples": 42553}"#;

/// Overload: with one request computed at once and no queue, a second request while a slow one
/// runs gets 503 and the slow one still gets its answer; the server answers afterwards.
#[test]
fn overload_gives_503_and_loses_no_answer() {
    let s = start(&["--max-in-flight", "1", "--queue-wait", "0", "--time-budget", "60"]);
    // The slow request goes first and the probes wait for it to hold the only slot (a probe
    // that held the slot at the moment it arrived would turn it away instead: then try again).
    let mut outcome_of_first = None;
    for _attempt in 0..5 {
        let url = s.url.clone();
        let first = std::thread::spawn(move || post(&url, "api/capability", SLOW));
        std::thread::sleep(std::time::Duration::from_millis(100));
        let mut busy = None;
        for _ in 0..100 {
            let a = post(&s.url, "api/limits", r#"{"thread": "M10x1.5-6g"}"#);
            if a.0 == 503 {
                busy = Some(a);
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        let answer = first.join().unwrap();
        if let Some(busy) = busy {
            assert_error(&busy, 503, "busy: 1 requests are being computed");
            outcome_of_first = Some(answer);
            break;
        }
        assert_eq!(answer.0, 503, "the slow request neither held the slot nor was turned away: {}", answer.2);
    }
    let first = outcome_of_first.expect("no 503 while the slow request ran, in five attempts");
    let (status, outcome, body) = first;
    assert_eq!(status, 200, "{body}");
    assert!(outcome.is_some());
    let v: serde_json::Value = serde_json::from_str(&body).unwrap();
    assert_eq!(v["samples"], 42553);
    assert_eq!(post(&s.url, "api/limits", r#"{"thread": "M10x1.5-6g"}"#).0, 200);
}

/// A request past the budget of 0.2 s on a one-slot server is answered 503 at the budget and
/// stopped, so that a limits request sent while it computed is answered within a second.
fn past_the_budget_frees_the_slot(path: &'static str, body: &'static str) {
    let s = start(&["--max-in-flight", "1", "--queue-wait", "5", "--time-budget", "0.2"]);
    let url = s.url.clone();
    let slow = std::thread::spawn(move || {
        let t = std::time::Instant::now();
        (post(&url, path, body), t.elapsed())
    });
    std::thread::sleep(std::time::Duration::from_millis(50));
    let t = std::time::Instant::now();
    let quick = post(&s.url, "api/limits", r#"{"thread": "M10x1.5-6g"}"#);
    let waited = t.elapsed();
    let (answer, took) = slow.join().unwrap();
    assert_error(&answer, 503, "time budget of 0.2 s; it was stopped");
    assert!(took < std::time::Duration::from_millis(900), "{path}: the slow request took {took:?}");
    assert_eq!(quick.0, 200, "{}", quick.2);
    assert!(waited < std::time::Duration::from_secs(1), "{path}: the limits request waited {waited:?}");
}

/// Issue 42: a request past its time budget (the Monte Carlo at its largest) is stopped and frees
/// its slot.
#[test]
fn a_request_past_its_budget_is_stopped_and_frees_its_slot() {
    past_the_budget_frees_the_slot("api/capability", SLOW);
}

/// Issue 58: a Klartext program that loops (about 2 s of reading on the CLI) is stopped at the
/// budget, not left running with the only slot.
#[test]
fn a_klartext_loop_past_the_budget_frees_its_slot() {
    past_the_budget_frees_the_slot(
        "api/verify",
        r#"{"thread": "M8x1.25-6H", "dialect": "klartext", "program": "0 BEGIN PGM LOOP MM\n1 LBL 1\n2 Q1 = Q1 + 1\n3 FN 12: IF +Q1 LT +100000000 GOTO LBL 1\n4 END PGM LOOP MM\n"}"#,
    );
}

/// A raw HTTP exchange on a new connection: `request` sent whole, the answer read until the
/// server closes or `wait` passes. Returns the status (0: none) and the body.
fn raw(url: &str, request: &str, wait: std::time::Duration) -> (u16, String) {
    use std::io::Write;
    let addr = url.trim_start_matches("http://").trim_end_matches('/');
    let mut tcp = std::net::TcpStream::connect(addr).unwrap();
    tcp.write_all(request.as_bytes()).unwrap();
    tcp.set_read_timeout(Some(wait)).unwrap();
    let answer = read_answer(&mut tcp);
    let text = String::from_utf8_lossy(&answer).into_owned();
    let status = text.split_whitespace().nth(1).and_then(|c| c.parse().ok()).unwrap_or(0);
    (status, text.split("\r\n\r\n").nth(1).unwrap_or_default().to_string())
}

/// Issue 42: every layer's error is the documented JSON object: a wrong Host (403; a name
/// `--allow-host` gives is answered), a body that is not JSON (415), a method the path does not
/// take (405), a path over 2 KiB (414), headers over 16 KiB (431), a request without Host.
#[test]
fn every_layer_answers_its_error_as_json() {
    let s = start(&["--allow-host", "lathe-3.shop"]);
    let addr = s.url.trim_start_matches("http://").trim_end_matches('/').to_string();
    let second = std::time::Duration::from_secs(5);
    let limits = r#"{"thread": "M10x1.5-6g"}"#;
    let req = |host: &str, ctype: &str| {
        format!(
            "POST /api/limits HTTP/1.1\r\nHost: {host}\r\nContent-Type: {ctype}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{limits}",
            limits.len()
        )
    };
    let json = |(status, body): (u16, String), want: u16, contains: &str| {
        assert_error(&(status, None, body), want, contains);
    };
    json(
        raw(&s.url, &req("evil.example", "application/json"), second),
        403,
        "Host 'evil.example' is not a name of this server",
    );
    json(raw(&s.url, &req("evil.example:80", "application/json"), second), 403, "--allow-host evil.example");
    assert_eq!(raw(&s.url, &req("lathe-3.shop:8080", "application/json"), second).0, 200);
    assert_eq!(raw(&s.url, &req(&addr, "application/json; charset=utf-8"), second).0, 200);
    assert_eq!(raw(&s.url, &req("localhost", "application/json"), second).0, 200);
    // Issue 58: two Host headers (the first used to win) are refused.
    json(
        raw(&s.url, &req(&format!("{addr}\r\nHost: evil.example"), "application/json"), second),
        400,
        "more than one Host header",
    );
    json(
        raw(&s.url, &req(&addr, "text/plain"), second),
        415,
        "must be JSON, sent as Content-Type: application/json",
    );
    let close = "Connection: close\r\n";
    json(
        raw(&s.url, &format!("DELETE /api/limits HTTP/1.1\r\nHost: {addr}\r\n{close}\r\n"), second),
        405,
        "DELETE /api/limits: not taken here",
    );
    json(
        raw(&s.url, &format!("GET /api/verify HTTP/1.1\r\nHost: {addr}\r\n{close}\r\n"), second),
        405,
        "GET /api/verify",
    );
    let long = "a".repeat(3000);
    json(
        raw(&s.url, &format!("GET /{long} HTTP/1.1\r\nHost: {addr}\r\n{close}\r\n"), second),
        414,
        "longer than 2048 bytes",
    );
    let big = "b".repeat(17 << 10);
    json(
        raw(&s.url, &format!("GET / HTTP/1.1\r\nHost: {addr}\r\nX-Big: {big}\r\n{close}\r\n"), second),
        431,
        "larger than 16384 bytes",
    );
    json(raw(&s.url, &format!("GET / HTTP/1.1\r\n{close}\r\n"), second), 403, "names no Host");
}

/// Issue 42: an idle connection, and one that stops half-way through its head, are closed
/// within the stated timeout (`--header-timeout 1`); a body that stops half-way is answered
/// 408 after `--body-timeout`.
#[test]
fn idle_and_slow_connections_are_closed() {
    let s = start(&["--header-timeout", "1", "--body-timeout", "1"]);
    let addr = s.url.trim_start_matches("http://").trim_end_matches('/').to_string();
    let wait = std::time::Duration::from_secs(10);
    for sent in ["", "POST /api/limits HTTP/1.1\r\nHost: "] {
        let t = std::time::Instant::now();
        let (status, _) = raw(&s.url, sent, wait);
        let took = t.elapsed();
        assert_eq!(status, 0, "{sent:?}");
        assert!(
            took > std::time::Duration::from_millis(800) && took < std::time::Duration::from_secs(3),
            "{sent:?}: closed after {took:?}"
        );
    }
    let t = std::time::Instant::now();
    let half = format!(
        "POST /api/limits HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/json\r\nContent-Length: 100\r\n\r\n{{\"thr"
    );
    let answer = raw(&s.url, &half, wait);
    assert!(t.elapsed() < std::time::Duration::from_secs(3), "{:?}", t.elapsed());
    assert_error(&(answer.0, None, answer.1), 408, "did not arrive within 1 s");
}

/// Issue 58 item 8: a client trickling its body (a byte every 200 ms) held the only slot for
/// the whole body timeout (10 s); it falls behind the minimum rate (16 KiB/s after a first
/// second) at once and is answered 408 with its connection closed, about a second after its
/// slot was taken, and the request queued behind it is answered.
#[test]
fn a_trickled_body_is_answered_408_and_frees_its_slot() {
    use std::io::{Read, Write};
    let s = start(&["--max-in-flight", "1", "--queue-wait", "5"]);
    let addr = s.url.trim_start_matches("http://").trim_end_matches('/').to_string();
    let mut tcp = std::net::TcpStream::connect(&addr).unwrap();
    let t = std::time::Instant::now();
    write!(
        tcp,
        "POST /api/limits HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/json\r\nContent-Length: 100\r\n\r\n"
    )
    .unwrap();
    let trickle = std::thread::spawn(move || {
        for b in b"{\"thread\": \"M10x1.5-6g\"" {
            if tcp.write_all(&[*b]).is_err() {
                break;
            }
            std::thread::sleep(std::time::Duration::from_millis(200));
        }
        tcp.set_read_timeout(Some(std::time::Duration::from_secs(10))).unwrap();
        let mut answer = Vec::new();
        let _ = tcp.read_to_end(&mut answer);
        String::from_utf8_lossy(&answer).into_owned()
    });
    std::thread::sleep(std::time::Duration::from_millis(100));
    let queued = post(&s.url, "api/limits", r#"{"thread": "M10x1.5-6g"}"#);
    let waited = t.elapsed();
    assert_eq!(queued.0, 200, "{}", queued.2);
    assert!(waited < std::time::Duration::from_secs(3), "the queued request waited {waited:?}");
    let answer = trickle.join().unwrap();
    assert!(answer.starts_with("HTTP/1.1 408"), "{answer}");
    assert!(answer.to_ascii_lowercase().contains("connection: close"), "{answer}");
    assert!(answer.contains("arrived slower than 16384 bytes a second"), "{answer}");
}

/// Issue 58 item 8: `docs/api.md`'s `curl` examples run as written (all three got 415: they sent
/// no `Content-Type`): each against a server here, in a folder whose `request.json` holds the
/// second example's object; each answer is the command's document, not an error.
#[test]
fn the_api_guide_s_curl_examples_run() {
    let found = Command::new("curl").arg("--version").output();
    assert!(
        found.is_ok_and(|o| o.status.success()),
        "curl is needed to run docs/api.md's examples: install it"
    );
    let guide = std::fs::read_to_string(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/api.md"))
        .unwrap();
    let examples = guide
        .split("### Examples")
        .nth(1)
        .unwrap()
        .split("```sh\n")
        .nth(1)
        .unwrap()
        .split("```")
        .next()
        .unwrap();
    // A line ending inside a quote goes on with the next one, as a shell reads it.
    let mut lines: Vec<String> = Vec::new();
    for l in examples.lines() {
        match lines.last_mut() {
            Some(last) if last.matches('\'').count() % 2 == 1 => {
                last.push('\n');
                last.push_str(l);
            }
            _ => lines.push(l.to_string()),
        }
    }
    assert_eq!(lines.len(), 3, "{lines:?}");
    let s = start(&[]);
    let addr = s.url.trim_start_matches("http://").trim_end_matches('/');
    let dir = tempdir("api-examples");
    let second = lines[1].split("-d '").nth(1).unwrap().trim_end_matches('\'');
    std::fs::write(dir.join("request.json"), second).unwrap();
    for line in &lines {
        let o = Command::new("sh")
            .arg("-c")
            .arg(line.replace("localhost:8080", addr))
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(o.status.success(), "{line}: {}", String::from_utf8_lossy(&o.stderr));
        let out = String::from_utf8_lossy(&o.stdout).into_owned();
        if line.contains("> post-fixed.nc") {
            let fixed = std::fs::read_to_string(dir.join("post-fixed.nc")).unwrap();
            assert!(fixed.starts_with("G0 X24 Z5\n") && fixed.contains("G76 X"), "{line}: {fixed}");
        } else {
            let v: serde_json::Value =
                serde_json::from_str(&out).unwrap_or_else(|e| panic!("{line}: {e}: {out}"));
            assert!(v.get("error").is_none(), "{line}: {out}");
        }
    }
}

/// Issue 58 item 8: `GET /api` lists only what each command serves (verify listed SARIF, JUnit
/// and JSON Lines, and each was answered 400): every listed document of verify and limits is
/// answered 200, and a run of many's document is 404 naming the command line that makes it.
#[test]
fn the_api_serves_every_document_it_lists() {
    let s = start(&[]);
    let (status, index) = get(&s.url, "api");
    assert_eq!(status, 200);
    let index: serde_json::Value = serde_json::from_str(&index).unwrap();
    for (command, body) in [
        (
            "verify",
            r#"{"thread": "M10x1.5-6g", "insert": "full", "program": "G0 X12 Z5\nG76 P010060 Q100 R0\nG76 X8.16 Z-20 P920 Q300 F1.5\n"}"#,
        ),
        ("limits", r#"{"thread": "M10x1.5-6g"}"#),
    ] {
        let listed = index["commands"].as_array().unwrap().iter().find(|c| c["command"] == command).unwrap();
        let documents: Vec<&str> =
            listed["documents"].as_array().unwrap().iter().map(|d| d.as_str().unwrap()).collect();
        assert!(!documents.is_empty());
        for d in &documents {
            let path = if *d == "json" { format!("api/{command}") } else { format!("api/{command}/{d}") };
            let (status, _, answer) = post(&s.url, &path, body);
            assert_eq!(status, 200, "{path}: {answer}");
        }
        assert!(
            !documents.contains(&"sarif")
                && !documents.contains(&"junit")
                && !documents.contains(&"json-lines")
        );
    }
    let (status, _, answer) =
        post(&s.url, "api/verify/sarif", r#"{"thread": "M10x1.5-6g", "insert": "full"}"#);
    assert_error(
        &(status, None, answer),
        404,
        "made on the command line (threadcheck verify FOLDER --sarif)",
    );
}

/// The server's resident memory, KiB (`VmRSS`, or `VmHWM` for the peak).
fn memory_kib(pid: u32, field: &str) -> u64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap();
    status
        .lines()
        .find_map(|l| l.strip_prefix(field))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse().ok())
        .unwrap()
}

/// Issue 42: 150 connections each announcing a 7 MiB body and sending 2 MiB of it hold the
/// server under 64 MiB (bodies are read only with a slot: four at most), and it answers others
/// meanwhile; a body announced over the limit is answered 413 before any of it is sent.
#[test]
fn unfinished_large_bodies_hold_little_memory() {
    use std::io::Write;
    let s = start(&["--max-connections", "512"]);
    let addr = s.url.trim_start_matches("http://").trim_end_matches('/').to_string();
    let chunk = vec![b' '; 1 << 20];
    let mut open = Vec::new();
    for _ in 0..150 {
        let mut tcp = std::net::TcpStream::connect(&addr).unwrap();
        let head = format!(
            "POST /api/verify HTTP/1.1\r\nHost: {addr}\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
            7 << 20
        );
        tcp.write_all(head.as_bytes()).unwrap();
        tcp.set_nonblocking(true).unwrap();
        for _ in 0..2 {
            let _ = tcp.write(&chunk);
        }
        open.push(tcp);
    }
    std::thread::sleep(std::time::Duration::from_millis(500));
    let peak = memory_kib(s.child.id(), "VmHWM:");
    assert!(peak < 64 << 10, "peak memory {peak} KiB with 150 unfinished bodies");
    let quick = raw(
        &s.url,
        &format!("GET /api HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"),
        std::time::Duration::from_secs(10),
    );
    assert_eq!(quick.0, 200);
    drop(open);
    assert_error(&post_big(&s.url, 20 << 20), 413, "larger than 8388608 bytes");
}

/// Issue 42: Ctrl-C (SIGINT) stops the server within a second while it computes the slowest
/// request it takes and three more wait for the one slot (about 3 s of work in all).
#[test]
fn ctrl_c_stops_the_server_within_a_second() {
    let mut s = start(&["--time-budget", "60", "--max-in-flight", "1", "--queue-wait", "60"]);
    let slow: Vec<_> = (0..4)
        .map(|_| {
            let url = s.url.clone();
            std::thread::spawn(move || post_or_gone(&url, "api/capability", SLOW))
        })
        .collect();
    std::thread::sleep(std::time::Duration::from_millis(150));
    let kill = Command::new("kill").args(["-INT", &s.child.id().to_string()]).status().unwrap();
    assert!(kill.success());
    let t = std::time::Instant::now();
    let status = loop {
        if let Some(st) = s.child.try_wait().unwrap() {
            break st;
        }
        assert!(t.elapsed() < std::time::Duration::from_secs(1), "still running 1 s after Ctrl-C");
        std::thread::sleep(std::time::Duration::from_millis(10));
    };
    assert_eq!(status.code(), Some(0));
    for t in slow {
        let _ = t.join();
    }
}

/// POSTs, tolerating a server that goes away mid-request: the status, or 0.
fn post_or_gone(url: &str, path: &str, body: &str) -> u16 {
    let agent: ureq::Agent = ureq::Agent::config_builder().http_status_as_error(false).build().into();
    agent
        .post(&format!("{url}{path}"))
        .content_type("application/json")
        .send(body)
        .map_or(0, |r| r.status().as_u16())
}

/// Issue 42: out of file descriptors (a limit of 64), 100 idle connections do not stop the
/// server: accept errors wait and serving goes on, the idle ones are closed by the head
/// timeout, and a request is answered within a few seconds.
#[test]
fn out_of_file_descriptors_the_server_goes_on() {
    let mut command = Command::new("sh");
    command.args([
        "-c",
        &format!(
            "ulimit -n 64 && exec {} serve --port 0 --header-timeout 1",
            env!("CARGO_BIN_EXE_threadcheck")
        ),
    ]);
    let s = start_command(command);
    let addr = s.url.trim_start_matches("http://").trim_end_matches('/').to_string();
    let idle: Vec<_> = (0..100).filter_map(|_| std::net::TcpStream::connect(&addr).ok()).collect();
    assert!(idle.len() >= 64, "only {} connections", idle.len());
    let t = std::time::Instant::now();
    let answer = raw(
        &s.url,
        &format!("GET /api HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"),
        std::time::Duration::from_secs(15),
    );
    assert_eq!(answer.0, 200, "after {:?}", t.elapsed());
    assert!(t.elapsed() < std::time::Duration::from_secs(8), "answered after {:?}", t.elapsed());
    drop(idle);
}

/// `--bind` other than loopback is said at start; a bad port is a usage error.
#[test]
fn serve_options_are_checked() {
    let o = run(&["serve", "--max-in-flight", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(stderr(&o).lines().count(), 1, "{}", stderr(&o));
    let o = run(&["serve", "--port", "70000"]);
    assert_eq!(o.status.code(), Some(2));
}
