//! The one bounded reader every input file goes through (programs, inserts, tool tables, machine
//! profiles, targets): the byte limit is enforced while reading, never taken from metadata (a
//! device or a pipe reports 0), and a FIFO that never delivers is given up after a stated time
//! instead of blocking for ever.

use crate::Error;
use std::io::Read;
use std::path::Path;
use std::time::Duration;

/// How long a read of a FIFO, a pipe or a device may wait for its data.
pub const PIPE_TIMEOUT: Duration = Duration::from_secs(10);

/// The bytes of the file at `path`, at most `limit` of them: a longer file is refused (its
/// first `limit + 1` bytes are read, no more). A regular file is read directly; anything else
/// (a FIFO, a pipe, a device) on a helper thread, given up after [`PIPE_TIMEOUT`].
pub fn read_bounded(path: &Path, limit: usize, what: &str) -> Result<Vec<u8>, Error> {
    let shown = path.display().to_string();
    let io = |e: std::io::Error| Error::io(shown.clone(), e);
    let regular = std::fs::metadata(path).map_err(io)?.is_file();
    let too_large =
        || Error::File { file: shown.clone(), message: format!("{what} is larger than {limit} bytes") };
    let read = move |p: std::path::PathBuf| -> std::io::Result<Vec<u8>> {
        let mut bytes = Vec::new();
        std::fs::File::open(p)?.take(limit as u64 + 1).read_to_end(&mut bytes)?;
        Ok(bytes)
    };
    let bytes = if regular {
        read(path.to_path_buf()).map_err(io)?
    } else {
        let (tx, rx) = std::sync::mpsc::channel();
        let p = path.to_path_buf();
        std::thread::spawn(move || {
            let _ = tx.send(read(p));
        });
        match rx.recv_timeout(PIPE_TIMEOUT) {
            Ok(r) => r.map_err(io)?,
            Err(_) => {
                return Err(Error::File {
                    file: shown.clone(),
                    message: format!(
                        "no data within {} s: a FIFO or device with no writer is not read",
                        PIPE_TIMEOUT.as_secs()
                    ),
                })
            }
        }
    };
    if bytes.len() > limit {
        return Err(too_large());
    }
    if regular {
        if let Ok(real) = std::fs::canonicalize(path) {
            READ.with(|r| r.borrow_mut().push(real));
        }
    }
    Ok(bytes)
}

thread_local! {
    /// The regular files read on this thread since [`forget_reads`] last emptied it.
    static READ: std::cell::RefCell<Vec<std::path::PathBuf>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The regular files read on this thread (their real paths) since [`forget_reads`]: the output
/// writer refuses to replace any of them, whether the run named it directly or a tool table or
/// a thread mill's file did.
pub fn reads() -> Vec<std::path::PathBuf> {
    READ.with(|r| r.borrow().clone())
}

/// Empties the list of files read on this thread: a long-lived caller (the Python package)
/// calls it as a new run begins.
pub fn forget_reads() {
    READ.with(|r| r.borrow_mut().clear());
}

/// The text of the file at `path`, bounded as [`read_bounded`] reads it; not UTF-8 is refused.
pub fn read_text_bounded(path: &Path, limit: usize, what: &str) -> Result<String, Error> {
    let bytes = read_bounded(path, limit, what)?;
    String::from_utf8(bytes).map_err(|e| Error::File {
        file: path.display().to_string(),
        message: format!("{what} is not UTF-8 text (byte {})", e.utf8_error().valid_up_to() + 1),
    })
}
