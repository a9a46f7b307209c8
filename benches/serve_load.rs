//! Load on `threadcheck serve` over loopback, bounded in count and time: a typical program
//! verify (the M20x1.5 G76 of tests/data) from concurrent clients, then an overload against a
//! server that computes two requests at once and queues none. Writes `reports/serve-load.md`:
//! requests per second, p50/p99 latency, the server's peak memory, and the overload's 200s and
//! 503s with no transport error (no lost answer) and the server alive afterwards.
//!
//! `cargo bench --bench serve_load` (the release binary is the one measured).

#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

struct Server {
    child: Child,
    url: String,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn start(extra: &[&str]) -> Server {
    let mut child = Command::new(env!("CARGO_BIN_EXE_threadcheck"))
        .args(["serve", "--port", "0"])
        .args(extra)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap()).read_line(&mut line).unwrap();
    let url = line.split_whitespace().find(|w| w.starts_with("http://")).unwrap().to_string();
    Server { child, url }
}

/// The server's peak resident memory, MiB (`VmHWM`).
fn peak_mib(pid: u32) -> f64 {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

#[derive(Default)]
struct Tally {
    latencies: Vec<Duration>,
    ok: usize,
    busy: usize,
    other: usize,
    transport_errors: usize,
}

/// `clients` threads POST `body` to `path` until `count` requests are sent or `limit` passes.
fn hammer(
    url: &str,
    path: &str,
    body: &str,
    clients: usize,
    count: usize,
    limit: Duration,
) -> (Tally, Duration) {
    let sent = Arc::new(AtomicUsize::new(0));
    let tally = Arc::new(Mutex::new(Tally::default()));
    let start = Instant::now();
    let threads: Vec<_> = (0..clients)
        .map(|_| {
            let (url, path, body) = (url.to_string(), path.to_string(), body.to_string());
            let (sent, tally) = (Arc::clone(&sent), Arc::clone(&tally));
            std::thread::spawn(move || {
                let agent: ureq::Agent = ureq::Agent::config_builder()
                    .http_status_as_error(false)
                    .timeout_global(Some(Duration::from_secs(60)))
                    .build()
                    .into();
                while sent.fetch_add(1, Ordering::SeqCst) < count && start.elapsed() < limit {
                    let t = Instant::now();
                    let r = agent
                        .post(&format!("{url}{path}"))
                        .content_type("application/json")
                        .send(body.as_str());
                    let mut tally_now = Tally::default();
                    match r {
                        Ok(mut resp) => {
                            let status = resp.status().as_u16();
                            let complete =
                                resp.body_mut().with_config().limit(64 << 20).read_to_string().is_ok();
                            match (status, complete) {
                                (200, true) => tally_now.ok += 1,
                                (503, true) => tally_now.busy += 1,
                                (_, true) => tally_now.other += 1,
                                (_, false) => tally_now.transport_errors += 1,
                            }
                        }
                        Err(_) => tally_now.transport_errors += 1,
                    }
                    let mut all = tally.lock().unwrap();
                    all.latencies.push(t.elapsed());
                    all.ok += tally_now.ok;
                    all.busy += tally_now.busy;
                    all.other += tally_now.other;
                    all.transport_errors += tally_now.transport_errors;
                }
            })
        })
        .collect();
    for t in threads {
        t.join().unwrap();
    }
    let elapsed = start.elapsed();
    let mut tally = Arc::try_unwrap(tally).ok().unwrap().into_inner().unwrap();
    tally.latencies.sort();
    (tally, elapsed)
}

fn percentile(sorted: &[Duration], p: f64) -> f64 {
    if sorted.is_empty() {
        return f64::NAN;
    }
    let i = ((p / 100.0) * (sorted.len() - 1) as f64).round() as usize;
    sorted[i].as_secs_f64() * 1e3
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines().find_map(|l| {
                l.strip_prefix("model name").map(|v| v.trim_start_matches([' ', '\t', ':']).to_string())
            })
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let mem = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| s.lines().find_map(|l| l.strip_prefix("MemTotal:").map(|v| v.trim().to_string())))
        .unwrap_or_default();
    let cores = std::thread::available_parallelism().map_or(0, usize::from);
    format!("{cores} cores ({cpu}), {mem} memory")
}

fn main() {
    // `cargo bench` passes `--bench`; any other run (`cargo test --benches`) only builds.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let program = std::fs::read_to_string(root.join("tests/data/programs/fanuc-g76-timing.nc")).unwrap();
    let verify = serde_json::json!({
        "thread": "M20x1.5-6g", "program": program, "program_name": "fanuc-g76-timing.nc", "insert": "full"
    })
    .to_string();

    // 1. A typical verify, 8 clients, the server's default bounds.
    let s = start(&[]);
    let (warm, _) = hammer(&s.url, "api/verify", &verify, 2, 50, Duration::from_secs(10));
    assert_eq!(warm.ok, 50);
    let size_kb = {
        let agent: ureq::Agent = ureq::Agent::config_builder().http_status_as_error(false).build().into();
        let mut r = agent
            .post(&format!("{}api/verify", s.url))
            .content_type("application/json")
            .send(verify.as_str())
            .unwrap();
        r.body_mut().with_config().limit(64 << 20).read_to_string().unwrap().len() as f64 / 1024.0
    };
    let (t, elapsed) = hammer(&s.url, "api/verify", &verify, 8, 4000, Duration::from_secs(20));
    let rps = t.ok as f64 / elapsed.as_secs_f64();
    let mem = peak_mib(s.child.id());
    assert_eq!(t.transport_errors + t.other + t.busy, 0, "the typical load lost or refused requests");
    println!(
        "verify: {} ok in {:.2} s: {rps:.0} req/s, p50 {:.2} ms, p99 {:.2} ms, peak {mem:.1} MiB",
        t.ok,
        elapsed.as_secs_f64(),
        percentile(&t.latencies, 50.0),
        percentile(&t.latencies, 99.0)
    );
    drop(s);

    // 2. Overload: two at once, no queue, 32 clients.
    let s = start(&["--max-in-flight", "2", "--queue-wait", "0"]);
    let (o, o_elapsed) = hammer(&s.url, "api/verify", &verify, 32, 6000, Duration::from_secs(20));
    let alive = s.child.id();
    let after = hammer(&s.url, "api/verify", &verify, 1, 5, Duration::from_secs(10)).0;
    let o_mem = peak_mib(alive);
    println!("overload: {} ok, {} 503, {} other, {} transport errors in {:.2} s; afterwards {} of 5 ok; peak {o_mem:.1} MiB",
        o.ok, o.busy, o.other, o.transport_errors, o_elapsed.as_secs_f64(), after.ok);
    assert_eq!(o.transport_errors + o.other, 0, "overload lost answers");
    assert!(o.busy > 0, "the overload never reached the bound");
    assert_eq!(after.ok, 5, "the server did not answer after the overload");
    drop(s);

    let report = format!(
        "# threadcheck serve under load\n\n\
Measured by `cargo bench --bench serve_load` (benches/serve_load.rs) on {machine}, release build, \
loopback. The request is a typical program verify: the M20x1.5 two-block G76 of \
`tests/data/programs/fanuc-g76-timing.nc` with a full-profile insert, JSON answer ({size:.0} kB).\n\n\
| run | clients | requests | 200 | 503 | lost | req/s | p50 ms | p99 ms | server peak MiB |\n\
|---|---|---|---|---|---|---|---|---|---|\n\
| verify, default bounds ({inflight} at once, 5 s queue) | 8 | {n1} | {ok1} | {b1} | {l1} | {rps:.0} | {p50:.2} | {p99:.2} | {mem:.1} |\n\
| overload: 2 at once, no queue | 32 | {n2} | {ok2} | {b2} | {l2} | {rps2:.0} | {q50:.2} | {q99:.2} | {omem:.1} |\n\n\
Overload answers 503 with a one-line JSON error (`busy: …`) at once instead of queueing; no \
request went unanswered (`lost` counts transport errors and incomplete bodies), and the server \
answered the {after} requests sent after it. req/s counts answers of 200; the clients (threads of \
this benchmark) share the machine's cores with the server, so the figures are what one machine \
serves itself, a lower bound for a server with cores of its own.\n",
        machine = machine(),
        size = size_kb,
        inflight = 2 * std::thread::available_parallelism().map_or(2, usize::from),
        n1 = t.latencies.len(),
        ok1 = t.ok,
        b1 = t.busy,
        l1 = t.transport_errors + t.other,
        p50 = percentile(&t.latencies, 50.0),
        p99 = percentile(&t.latencies, 99.0),
        n2 = o.latencies.len(),
        ok2 = o.ok,
        b2 = o.busy,
        l2 = o.transport_errors + o.other,
        rps2 = o.ok as f64 / o_elapsed.as_secs_f64(),
        q50 = percentile(&o.latencies, 50.0),
        q99 = percentile(&o.latencies, 99.0),
        omem = o_mem,
        after = after.ok,
    );
    std::fs::write(root.join("reports/serve-load.md"), report).unwrap();
    println!("wrote reports/serve-load.md");
}
