//! `threadcheck serve`'s arguments: the server's options as the command line gives them.

/// The arguments of `serve` (the command line's alone).
#[cfg_attr(feature = "cli", derive(clap::Args))]
#[derive(Clone, Debug)]
pub struct ServeArgs {
    /// The address to listen on; anything but loopback lets other machines in (said at start).
    #[cfg_attr(feature = "cli", arg(long, default_value = "127.0.0.1"))]
    pub bind: std::net::IpAddr,
    /// The port (0: any free one, printed at start).
    #[cfg_attr(feature = "cli", arg(long, default_value_t = 8080))]
    pub port: u16,
    /// Requests computed at once (default twice the cores); others wait, then get 503.
    #[cfg_attr(feature = "cli", arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024)))]
    pub max_in_flight: Option<u32>,
    /// Seconds a request waits for its turn before it is answered 503 (0: at once).
    #[cfg_attr(feature = "cli", arg(long, value_name = "SECONDS", default_value_t = 5.0, value_parser = queue_seconds))]
    pub queue_wait: f64,
    /// Seconds one request may compute before it is stopped and answered 503.
    #[cfg_attr(feature = "cli", arg(long, value_name = "SECONDS", default_value_t = 10.0, value_parser = positive_seconds))]
    pub time_budget: f64,
    /// Seconds a connection may take to send a request's head, or stay idle between requests.
    #[cfg_attr(feature = "cli", arg(long, value_name = "SECONDS", default_value_t = 5.0, value_parser = positive_seconds))]
    pub header_timeout: f64,
    /// Seconds a request's body may take to arrive once its turn has come (else 408).
    #[cfg_attr(feature = "cli", arg(long, value_name = "SECONDS", default_value_t = 10.0, value_parser = positive_seconds))]
    pub body_timeout: f64,
    /// The slowest a request's body may arrive, bytes a second, after a first second (else 408
    /// and the connection is closed).
    #[cfg_attr(feature = "cli", arg(long, value_name = "BYTES", default_value_t = super::MIN_BODY_RATE, value_parser = clap::value_parser!(u64).range(1..=1_000_000_000)))]
    pub min_body_rate: u64,
    /// Connections open at once; past it the server accepts no more until one closes.
    #[cfg_attr(feature = "cli", arg(long, value_name = "N", default_value_t = 256, value_parser = clap::value_parser!(u32).range(1..=65536)))]
    pub max_connections: u32,
    /// A host name to answer besides the bound address and localhost (repeat for more): the
    /// Host header of every other request is refused (403), so that a web page cannot reach
    /// the server through a name of its own.
    #[cfg_attr(feature = "cli", arg(long, value_name = "NAME"))]
    pub allow_host: Vec<String>,
}

/// Seconds to wait, from 0.01 to an hour.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
fn positive_seconds(s: &str) -> Result<f64, String> {
    match crate::commands::args::finite(s)? {
        v if (0.01..=3600.0).contains(&v) => Ok(v),
        _ => Err("from 0.01 to 3600 seconds".into()),
    }
}

/// Seconds to wait, from 0 to an hour.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
fn queue_seconds(s: &str) -> Result<f64, String> {
    match crate::commands::args::finite(s)? {
        v if (0.0..=3600.0).contains(&v) => Ok(v),
        _ => Err("from 0 to 3600 seconds".into()),
    }
}

impl ServeArgs {
    /// The server's options.
    pub fn options(&self) -> super::ServeOptions {
        let mut options = super::ServeOptions { bind: self.bind, port: self.port, ..Default::default() };
        if let Some(n) = self.max_in_flight {
            options.max_in_flight = n as usize;
        }
        options.time_budget = std::time::Duration::from_secs_f64(self.time_budget);
        options.queue_wait = std::time::Duration::from_secs_f64(self.queue_wait);
        options.header_timeout = std::time::Duration::from_secs_f64(self.header_timeout);
        options.body_timeout = std::time::Duration::from_secs_f64(self.body_timeout);
        options.min_body_rate = self.min_body_rate;
        options.max_connections = self.max_connections as usize;
        options.allow_hosts = self.allow_host.clone();
        options
    }
}
