//! Any bytes as what a language client sends `threadcheck lsp` (its framing: header lines,
//! `Content-Length`, bodies; then JSON-RPC): the server answers or ends with its code, never a
//! panic, a hang or an allocation the input did not pay for (a `Content-Length` of 10¹² is
//! skipped unread).
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut out = Vec::new();
    let code = threadcheck::lsp_run(std::io::Cursor::new(data.to_vec()), &mut out);
    if let Ok(code) = code {
        assert!(code == 0 || code == 1, "exit code {code}");
    }
});
