//! The Base Protocol's framing, read within bounds: `Content-Length: N` headers, a blank line,
//! N bytes of JSON. `lsp-server`'s own reader allocates whatever a header announces (10¹² bytes
//! aborted the process); here a header line is at most [`MAX_HEADER_LINE`] bytes and a body at
//! most [`MAX_BODY`], and a message announced larger is refused without reading it: the reader
//! then looks for the next `Content-Length:` header (a client writes it right after a body) and
//! reads on from there.

use std::io::{BufRead, Read};

/// The longest header line read.
pub const MAX_HEADER_LINE: usize = 4096;

/// The largest body read: a document at the program limit written as JSON (each byte at most
/// two when escaped) with the rest of its message.
pub const MAX_BODY: usize = 2 * crate::ground::bounds::MAX_PROGRAM_BYTES + 64 * 1024;

/// What one read gives.
pub enum Frame {
    /// A message's body (JSON, parsed by the server: `lsp-server` stays behind its one door).
    Body(Vec<u8>),
    /// A message announced larger than [`MAX_BODY`]: not read.
    TooLarge(u64),
    /// The input ended between messages.
    End,
}

/// The framing reader; `resync` is set after a message too large to read, so that the next read
/// first skips to a `Content-Length:` header line.
pub struct Framed<R> {
    input: R,
    resync: bool,
}

impl<R: BufRead> Framed<R> {
    pub fn new(input: R) -> Self {
        Framed { input, resync: false }
    }

    /// One header line without its line end, `None` at the end of the input.
    fn line(&mut self) -> std::io::Result<Option<String>> {
        let mut buf = Vec::new();
        let n = (&mut self.input).take(MAX_HEADER_LINE as u64 + 1).read_until(b'\n', &mut buf)?;
        if n == 0 {
            return Ok(None);
        }
        if buf.len() > MAX_HEADER_LINE {
            return Err(broken(format!("a header line longer than {MAX_HEADER_LINE} bytes")));
        }
        Ok(Some(String::from_utf8_lossy(&buf).trim_end_matches(['\r', '\n']).to_string()))
    }

    /// The next frame; an error when the framing itself breaks.
    pub fn read(&mut self) -> std::io::Result<Frame> {
        let mut length: Option<u64> = None;
        let mut first = true;
        loop {
            let Some(mut line) = self.line()? else {
                return if first {
                    Ok(Frame::End)
                } else {
                    Err(broken("the input ended inside a header".into()))
                };
            };
            if self.resync {
                // A client writes the next header right after a body: look for it anywhere.
                match line.to_ascii_lowercase().find("content-length:") {
                    Some(at) => line = line[at..].to_string(),
                    None => continue,
                }
                self.resync = false;
            }
            // By `get`: a header of other bytes may hold a character across byte 15 (a fuzzed
            // header of 0xFF bytes, read as U+FFFD, panicked here).
            let value = line
                .get(..15)
                .filter(|h| h.eq_ignore_ascii_case("content-length:"))
                .and_then(|_| line.get(15..));
            if line.is_empty() {
                if first {
                    continue;
                }
                break;
            }
            first = false;
            if let Some(n) = value {
                let n = n.trim();
                length = Some(n.parse().map_err(|_| {
                    broken(format!("Content-Length '{}' is not a length", crate::ground::error::one_line(n)))
                })?);
            }
        }
        let Some(n) = length else { return Err(broken("a message without Content-Length".into())) };
        if n > MAX_BODY as u64 {
            self.resync = true;
            return Ok(Frame::TooLarge(n));
        }
        let mut body = vec![0u8; n as usize];
        self.input.read_exact(&mut body)?;
        Ok(Frame::Body(body))
    }
}

fn broken(why: String) -> std::io::Error {
    std::io::Error::new(std::io::ErrorKind::InvalidData, why)
}
