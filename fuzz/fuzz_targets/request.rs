//! The API's request reader and the commands added since the last fuzzing (`tap`,
//! `thread-mill`, `correct`, `capability`, and `verify`/`passes` in every dialect): any
//! request gives an answer or an error, never a panic, a hang or unbounded memory.
//!
//! The input's first byte picks the command and its document; the rest is split at the first
//! NUL: a JSON object of the command's keys, then a program's text, put under `program` (so
//! the fuzzer mutates programs freely without breaking the JSON around them). Without a NUL the
//! rest is the whole request body. Its messages are named for the API or the page, by the
//! body's length.
#![no_main]
use libfuzzer_sys::fuzz_target;
use threadcheck::{run_request, Audience, Command, Files};

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else { return };
    let Ok(text) = std::str::from_utf8(rest) else { return };
    let command = Command::API[usize::from(pick) % Command::API.len()];
    let documents = Command::documents_of(command);
    let document = documents[usize::from(pick / 16) % documents.len()];
    let body = match text.split_once('\0') {
        Some((args, program)) => {
            let Ok(serde_json::Value::Object(mut map)) = serde_json::from_str::<serde_json::Value>(args)
            else {
                return;
            };
            map.insert("program".into(), serde_json::Value::String(program.to_string()));
            serde_json::Value::Object(map).to_string()
        }
        None => text.to_string(),
    };
    // The API's reader, or the page's (its messages name the page's fields): the body's length
    // picks.
    let reader = if body.len() % 2 == 0 { Audience::Api } else { Audience::Page };
    let _ = run_request(command, document, &body, Files::Refused, reader);
});
