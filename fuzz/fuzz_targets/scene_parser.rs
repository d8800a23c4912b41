//! Arbitrary bytes through the whole scene front end, as `radc check` runs it: decode,
//! parse, lower and check. Any panic, abort or hang is a bug (DEVELOPERS.md: bad input
//! never crashes).
#![no_main]

use libfuzzer_sys::fuzz_target;
use radc_lang::FileId;
use radc_lang::scene::{AssumeFilesExist, check_text};
use radc_lang::source::decode;

fuzz_target!(|data: &[u8]| {
    let (text, _) = decode(FileId(0), data);
    let _ = check_text(FileId(0), &text, &AssumeFilesExist, true);
});
