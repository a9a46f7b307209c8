//! A folder built from the input (sub-folders, programs good and bad, symbolic links to files,
//! folders and the folder itself, dangling links, FIFOs and names that are not UTF-8 or hold
//! control characters), run as `verify FOLDER`: an answer naming each regular program once,
//! never a panic and never a hang (a FIFO is not opened, a link loop is one line).
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::os::unix::ffi::OsStrExt;
use std::path::PathBuf;
use threadcheck::{Command, Document, Files, Request, VerifyArgs};

/// Programs a file may hold: a passing lathe thread, a failing one, one that cannot be read, a
/// tap, and nothing.
const TEXTS: [&str; 5] = [
    "(M10X1.5)\nG18 G21 G90\nG0 X12 Z5\nG76 P010060 Q100 R0\nG76 X8.16 Z-20 P920 Q300 F1.5\nM30\n",
    "(M10X1.5)\nG18 G21 G90\nG0 X12 Z5\nG76 P010060 Q100 R0\nG76 X9.5 Z-20 P250 Q100 F1.5\nM30\n",
    "G0 X10 Z5\nG76 X8 Z-10 P1000 Q300 F1.5 G\n",
    "(M8X1.25 TAP)\nG17 G21 G90\nT1 M6\nS500 M3\nG0 X0 Y0 Z5\nG84 Z-12 R2 F625\nG80\nM30\n",
    "",
];

fuzz_target!(|data: &[u8]| {
    static RUN: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = RUN.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let root = std::env::temp_dir().join(format!("threadcheck-fuzz-library-{}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&root).unwrap();
    let mut dirs: Vec<PathBuf> = vec![root.clone()];
    let mut files: Vec<PathBuf> = Vec::new();
    for op in data.chunks(3).take(40) {
        let [kind, a, b] = [op[0], *op.get(1).unwrap_or(&0), *op.get(2).unwrap_or(&0)];
        let dir = dirs[b as usize % dirs.len()].clone();
        let name: Vec<u8> = match a % 4 {
            0 => format!("p{a}.nc").into_bytes(),
            1 => format!("s{a}.ngc").into_bytes(),
            2 => vec![b'x', 0xff, b'0' + a % 10, b'.', b'n', b'c'],
            _ => format!("n\n{a}\u{1b}.nc").into_bytes(),
        };
        let path = dir.join(std::ffi::OsStr::from_bytes(&name));
        let _ = match kind % 7 {
            0 => std::fs::create_dir(dir.join(format!("d{a}"))).map(|()| dirs.push(dir.join(format!("d{a}")))),
            // A new file only: writing to a FIFO made before would wait for a reader.
            1 | 2 => std::fs::OpenOptions::new()
                .write(true)
                .create_new(true)
                .open(&path)
                .and_then(|mut f| std::io::Write::write_all(&mut f, TEXTS[b as usize % TEXTS.len()].as_bytes()))
                .map(|()| files.push(path.clone())),
            3 if !files.is_empty() => std::os::unix::fs::symlink(&files[a as usize % files.len()], &path),
            4 => std::os::unix::fs::symlink(&dirs[a as usize % dirs.len()], dir.join(format!("l{a}"))),
            5 => std::os::unix::fs::symlink(root.join("missing"), &path),
            _ => std::process::Command::new("mkfifo").arg(&path).status().map(|_| ()),
        };
    }
    let args = VerifyArgs { programs: vec![root.clone()], ..VerifyArgs::default() };
    let out = Command::Verify(args).run(&Request::api(Document::Text, Files::Allowed));
    if let Ok(out) = out {
        let text = out.document(Document::Text).unwrap_or_default();
        assert!(!text.contains('\u{1b}'), "an escape reached the text: {text}");
    }
    let _ = std::fs::remove_dir_all(&root);
});
