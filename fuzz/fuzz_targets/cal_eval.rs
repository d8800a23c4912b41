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

// On a thread with the stack `radc calc` gives the interpreter (512 MiB): its depth
// limit is set for that stack, not for the fuzzer's main thread.
fuzz_target!(|data: &[u8]| {
    let data = data.to_vec();
    std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(move || evaluate(&data))
        .expect("thread")
        .join()
        .expect("no panic");
});

fn evaluate(data: &[u8]) {
    let (text, _) = decode(FileId(0), data);
    let mut module = Module::new(&Env::rcalc());
    let diags = module.add_source(FileId(0), &text);
    if diags.iter().any(|d| d.is_error()) {
        return;
    }
    if let Ok(mut interp) = Interpreter::new(&module, MathErrors::default()) {
        let _ = interp.single();
    }
}
