//! Writing output files without ever leaving a half-written one: write a temporary file in the
//! same folder (`tempfile`), flush it to disk, then rename it over the target (atomic on one file
//! system).
//! A target that is not a regular file (a device such as `/dev/null`, a FIFO) is written in
//! place: renaming over it would replace the device with a file. A FIFO that no program reads is
//! given up after [`FIFO_WAIT`], never waited for forever.

use crate::Error;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Where one output goes: a regular file replaced by renaming a temporary over it, or a device
/// (or FIFO) written in place.
enum Target {
    File { path: PathBuf, tmp: tempfile::NamedTempFile },
    Device { path: PathBuf },
}

/// Writes every output of one run, all or none: each regular file's bytes go to a temporary
/// beside it first (flushed to disk, with the mode of the file it replaces, or that of a plain
/// create); devices are written next; only when all of that succeeded are the temporaries
/// renamed over their targets. On an error before the renames, every old file is kept and every
/// temporary removed.
pub fn write_all_atomic(outputs: &[(PathBuf, Vec<u8>)]) -> Result<(), Error> {
    let mut targets = Vec::with_capacity(outputs.len());
    for (path, bytes) in outputs {
        targets.push(prepare(path, bytes)?);
    }
    for ((_, bytes), t) in outputs.iter().zip(&targets) {
        if let Target::Device { path } = t {
            write_device(path, bytes)?;
        }
    }
    for t in targets {
        if let Target::File { path, tmp } = t {
            tmp.persist(&path).map_err(|e| Error::io(path.display(), e.error))?;
        }
    }
    Ok(())
}

/// How long an output that is a FIFO waits for a program to read it, and for a reader that has
/// stopped taking bytes to take more: then the run gives up with an error (a named default).
pub const FIFO_WAIT: std::time::Duration = std::time::Duration::from_secs(5);

/// Writes `bytes` in place to a device or FIFO. A FIFO is opened without waiting (opening one
/// that no program reads would wait forever): tried again for [`FIFO_WAIT`], then refused; a
/// reader that stops taking bytes for as long is given up too.
fn write_device(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    let io = |e: std::io::Error| Error::io(path.display(), e);
    #[cfg(unix)]
    {
        use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
        if std::fs::metadata(path).is_ok_and(|m| m.file_type().is_fifo()) {
            let wait = FIFO_WAIT.as_secs_f64();
            let start = std::time::Instant::now();
            let mut f = loop {
                match std::fs::OpenOptions::new().write(true).custom_flags(libc::O_NONBLOCK).open(path) {
                    Ok(f) => break f,
                    // ENXIO: no program has the FIFO open for reading.
                    Err(e) if e.raw_os_error() == Some(libc::ENXIO) => {
                        if start.elapsed() >= FIFO_WAIT {
                            return Err(Error::Input(format!(
                                "{}: a FIFO that no program read within {wait} s: nothing was written to it",
                                path.display()
                            )));
                        }
                        std::thread::sleep(std::time::Duration::from_millis(20));
                    }
                    Err(e) => return Err(io(e)),
                }
            };
            let (mut rest, mut progress) = (bytes, std::time::Instant::now());
            while !rest.is_empty() {
                match f.write(rest) {
                    Ok(0) => return Err(io(std::io::ErrorKind::WriteZero.into())),
                    Ok(n) => {
                        rest = &rest[n..];
                        progress = std::time::Instant::now();
                    }
                    Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                        if progress.elapsed() >= FIFO_WAIT {
                            return Err(Error::Input(format!(
                                "{}: the FIFO's reader took nothing for {wait} s: {} of {} bytes were written",
                                path.display(),
                                bytes.len() - rest.len(),
                                bytes.len()
                            )));
                        }
                        std::thread::sleep(std::time::Duration::from_millis(5));
                    }
                    Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                    Err(e) => return Err(io(e)),
                }
            }
            return Ok(());
        }
    }
    let mut f = std::fs::OpenOptions::new().write(true).open(path).map_err(io)?;
    f.write_all(bytes).and_then(|()| f.flush()).map_err(io)
}

/// Refuses an output that is one of the run's inputs (the same file, by any path): the files
/// named in `inputs` and every regular file read on this thread since the last
/// [`forget_reads`](crate::ground::input::forget_reads) (a tool table, the insert or thread mill
/// it names, a machine profile): writing it would replace what is being checked. Refuses two
/// outputs on one file too (one would be lost).
pub fn refuse_inputs(outputs: &[(PathBuf, Vec<u8>)], inputs: &[PathBuf]) -> Result<(), Error> {
    let mut inputs: Vec<PathBuf> = inputs.iter().filter_map(|p| std::fs::canonicalize(p).ok()).collect();
    inputs.extend(crate::ground::input::reads());
    let mut seen: Vec<PathBuf> = Vec::new();
    for (path, _) in outputs {
        let real = real_target(path);
        if let Some(real) = &real {
            if inputs.contains(real) {
                return Err(Error::Input(format!(
                    "{}: is an input of this run; an output must not replace it",
                    path.display()
                )));
            }
        }
        // Devices (/dev/null, /dev/stdout) may take several outputs.
        let device = std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir());
        if let Some(real) = real.filter(|_| !device) {
            if seen.contains(&real) {
                return Err(Error::Input(format!(
                    "{}: two outputs of this run name this file; each needs its own",
                    path.display()
                )));
            }
            seen.push(real);
        }
    }
    Ok(())
}

/// Where a write to `path` lands: the real path of an existing file (links followed), or the
/// real folder joined with the name of a new one.
fn real_target(path: &Path) -> Option<PathBuf> {
    if let Ok(real) = std::fs::canonicalize(path) {
        return Some(real);
    }
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Some(std::fs::canonicalize(dir).ok()?.join(path.file_name()?))
}

/// Writes the outputs of one run as the command line does: none that is an input of the run
/// or shares a file with another, all or none, atomically, devices and FIFOs in place, links
/// followed, modes kept. The Python package writes
/// its files through this.
///
/// ```
/// let dir = std::env::temp_dir().join(format!("tc-doc-write-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let a = dir.join("a.svg");
/// threadcheck::write_files(&[(a.clone(), b"<svg/>".to_vec())])?;
/// // Two outputs on one file are refused, and nothing is written.
/// assert!(threadcheck::write_files(&[(a.clone(), b"1".to_vec()), (a.clone(), b"2".to_vec())]).is_err());
/// assert_eq!(std::fs::read(&a)?, b"<svg/>");
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_files(outputs: &[(PathBuf, Vec<u8>)]) -> Result<(), Error> {
    refuse_inputs(outputs, &[])?;
    write_all_atomic(outputs)
}

/// Resolves a target (following a symbolic link, refusing a folder) and, for a regular file,
/// writes its temporary.
fn prepare(path: &Path, bytes: &[u8]) -> Result<Target, Error> {
    let io = |e: std::io::Error| Error::io(path.display(), e);
    let mut mode = None;
    if let Ok(meta) = std::fs::metadata(path) {
        if meta.is_dir() {
            return Err(Error::Input(format!("{}: is a folder, not a file", path.display())));
        }
        if !meta.is_file() {
            return Ok(Target::Device { path: path.to_path_buf() });
        }
        if std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink()) {
            let real = std::fs::canonicalize(path).map_err(io)?;
            return prepare(&real, bytes);
        }
        mode = Some(meta.permissions());
    }
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if path.file_name().is_none() {
        return Err(Error::Input(format!("{}: not a file name", path.display())));
    }
    // Removed on drop: an error anywhere before `persist` leaves no temporary behind.
    let mut builder = tempfile::Builder::new();
    builder.prefix(".threadcheck-").suffix(".tmp");
    match mode {
        // A replaced file keeps its mode.
        Some(p) => {
            builder.permissions(p);
        }
        // tempfile creates 0600 files; a new output file gets the mode a plain create would
        // (0666 less the umask).
        None => {
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                builder.permissions(std::fs::Permissions::from_mode(0o666));
            }
        }
    }
    let mut tmp = builder.tempfile_in(&dir).map_err(io)?;
    tmp.write_all(bytes).map_err(io)?;
    tmp.as_file().sync_all().map_err(io)?;
    Ok(Target::File { path: path.to_path_buf(), tmp })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
        write_files(&[(path.to_path_buf(), bytes.to_vec())])
    }

    #[test]
    fn replaces_and_leaves_no_temporary() {
        let dir = std::env::temp_dir().join(format!("tc-out-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("a.json");
        write_atomic(&f, b"one").unwrap();
        write_atomic(&f, b"two").unwrap();
        assert_eq!(std::fs::read(&f).unwrap(), b"two");
        let n = std::fs::read_dir(&dir).unwrap().count();
        assert_eq!(n, 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_symlink_is_followed() {
        let dir = std::env::temp_dir().join(format!("tc-link-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (target, link) = (dir.join("real.json"), dir.join("link.json"));
        std::fs::write(&target, b"old").unwrap();
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link).unwrap().file_type().is_symlink());
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn the_mode_is_that_of_a_plain_create() {
        use std::os::unix::fs::PermissionsExt;
        let dir = std::env::temp_dir().join(format!("tc-mode-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::File::create(dir.join("plain")).unwrap();
        write_atomic(&dir.join("atomic"), b"x").unwrap();
        let mode = |n: &str| std::fs::metadata(dir.join(n)).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode("atomic"), mode("plain"));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_folder_is_refused() {
        let e = write_atomic(&std::env::temp_dir(), b"x").unwrap_err();
        assert!(e.to_string().contains("is a folder"), "{e}");
    }

    #[test]
    fn a_failed_write_keeps_the_old_file() {
        let missing = std::env::temp_dir().join("tc-no-such-dir-xyz").join("a.json");
        assert!(write_atomic(&missing, b"x").is_err());
    }
}
