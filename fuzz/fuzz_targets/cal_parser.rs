//! Arbitrary bytes as a calcomp file, through everything `radc check` does with one:
//! parse, resolve, fold, check, in both the renderer's and rcalc's environments.
#![no_main]

use libfuzzer_sys::fuzz_target;
use radc_lang::FileId;
use radc_lang::cal::{Env, check};
use radc_lang::source::decode;

fuzz_target!(|data: &[u8]| {
    let (text, _) = decode(FileId(0), data);
    let _ = check(FileId(0), &text, &Env::renderer());
    let _ = check(FileId(0), &text, &Env::rcalc().complete());
});
