//! Arbitrary bytes as an rcalc program (`radc calc -n -e TEXT`): parse, then evaluate
//! one record with the reference interpreter. Errors are fine; a panic, an abort (stack
//! overflow) or a hang is a bug.
#![no_main]

use libfuzzer_sys::fuzz_target;
use radc_jit::Interpreter;
use radc_lang::FileId;
use radc_lang::cal::eval::MathErrors;
use radc_lang::cal::{Env, Module};
use radc_lang::source::decode;

fuzz_target!(|data: &[u8]| {
    let (text, _) = decode(FileId(0), data);
    let mut module = Module::new(&Env::rcalc());
    let diags = module.add_source(FileId(0), &text);
    if diags.iter().any(|d| d.is_error()) {
        return;
    }
    if let Ok(mut interp) = Interpreter::new(&module, MathErrors::default()) {
        let _ = interp.single();
    }
});
