//! Arbitrary bytes as an rcalc program, evaluated for one record by the Cranelift JIT
//! and by the reference interpreter: the JIT must never panic, and where both finish
//! they must give the same outputs bit for bit, or the same error. (Programs the JIT
//! declines run on the interpreter in `radc calc`, so a refusal is fine.) Recursion is
//! left out of the comparison: the two count depth against different budgets. Both run
//! on a thread with the stack `radc calc` gives them (512 MiB): their depth limits are
//! set for that stack, not for the fuzzer's main thread.
#![no_main]

use libfuzzer_sys::fuzz_target;
use radc_jit::{Interpreter, JitProgram};
use radc_lang::FileId;
use radc_lang::cal::eval::MathErrors;
use radc_lang::cal::{Env, Module};
use radc_lang::source::decode;

fuzz_target!(|data: &[u8]| {
    let data = data.to_vec();
    std::thread::Builder::new()
        .stack_size(512 << 20)
        .spawn(move || compare(&data))
        .expect("thread")
        .join()
        .expect("no panic");
});

fn compare(data: &[u8]) {
    let (text, _) = decode(FileId(0), data);
    let mut module = Module::new(&Env::rcalc());
    let diags = module.add_source(FileId(0), &text);
    if diags.iter().any(|d| d.is_error()) {
        return;
    }
    let Ok(mut jit) = JitProgram::new(&module, MathErrors::default()) else {
        return;
    };
    let got = jit.single();
    let Ok(mut interp) = Interpreter::new(&module, MathErrors::default()) else {
        panic!("the JIT started a program the interpreter refuses");
    };
    let expected = interp.single();
    let show = |r: &Result<Vec<(u32, f64)>, radc_jit::Error>| match r {
        Ok(outs) => outs
            .iter()
            .map(|(k, v)| format!("${k}={:016x}", v.to_bits()))
            .collect::<Vec<_>>()
            .join(" "),
        Err(e) => format!("error: {e}"),
    };
    let (got, expected) = (show(&got), show(&expected));
    if got.contains("recursion") || expected.contains("recursion") {
        return;
    }
    assert_eq!(got, expected, "JIT vs interpreter on {text:?}");
}
