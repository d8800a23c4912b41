//! Functions the generated code calls into: the math library (the very Rust
//! functions the interpreter calls, so results agree to the bit), warnings, fatal
//! errors, input columns, the depth counter's slow path, and calls through function
//! values of library functions (rare enough to run here rather than in generated code).
//!
//! Each one takes the context pointer the generated code was given; it is valid and
//! unaliased for the duration of the call (see `Compiled::run`).

use super::layout::*;
use radc_lang::cal::builtins::{Builtin, DEFAULT_NAN, LibFn, rand};
use radc_lang::cal::eval::{Errno, EvalError, Input, MAX_DEPTH, MathErrors, Warning, c_round};

/// Host symbols by the name the generated code imports them under.
pub fn symbols() -> Vec<(&'static str, *const u8)> {
    vec![
        ("radc_pow", m_pow as *const u8),
        ("radc_atan2", m_atan2 as *const u8),
        ("radc_acos", m_acos as *const u8),
        ("radc_asin", m_asin as *const u8),
        ("radc_atan", m_atan as *const u8),
        ("radc_cos", m_cos as *const u8),
        ("radc_exp", m_exp as *const u8),
        ("radc_log", m_log as *const u8),
        ("radc_log10", m_log10 as *const u8),
        ("radc_rand", m_rand as *const u8),
        ("radc_sin", m_sin as *const u8),
        ("radc_tan", m_tan as *const u8),
        ("radc_warn", h_warn as *const u8),
        ("radc_fail", h_fail as *const u8),
        ("radc_depth", h_depth as *const u8),
        ("radc_chan", h_chan as *const u8),
        ("radc_in", h_in as *const u8),
        ("radc_renderer_fn", h_renderer_fn as *const u8),
        ("radc_fnval", h_fnval as *const u8),
        ("radc_chan_thunk", h_chan_thunk as *const u8),
    ]
}

/// The import name of a one-argument library function the generated code calls.
pub fn unary_symbol(b: Builtin) -> Option<&'static str> {
    Some(match b {
        Builtin::Acos => "radc_acos",
        Builtin::Asin => "radc_asin",
        Builtin::Atan => "radc_atan",
        Builtin::Cos => "radc_cos",
        Builtin::Exp => "radc_exp",
        Builtin::Log => "radc_log",
        Builtin::Log10 => "radc_log10",
        Builtin::Rand => "radc_rand",
        Builtin::Sin => "radc_sin",
        Builtin::Tan => "radc_tan",
        _ => return None,
    })
}

extern "C" fn m_pow(x: f64, y: f64) -> f64 {
    x.powf(y)
}
extern "C" fn m_atan2(y: f64, x: f64) -> f64 {
    y.atan2(x)
}
// Direct wrappers, each the very function `Builtin::unary` calls (with its domain
// rules for acos, asin and log10): `unary` itself is a `match` in another crate that
// is not inlined, and costs as much as a fast C library call. The test below holds
// them to `Builtin::unary`, bit for bit.
extern "C" fn m_acos(x: f64) -> f64 {
    if x.abs() > 1.0 { DEFAULT_NAN } else { x.acos() }
}
extern "C" fn m_asin(x: f64) -> f64 {
    if x.abs() > 1.0 { DEFAULT_NAN } else { x.asin() }
}
extern "C" fn m_log10(x: f64) -> f64 {
    if x < 0.0 { DEFAULT_NAN } else { x.log10() }
}
extern "C" fn m_atan(x: f64) -> f64 {
    x.atan()
}
extern "C" fn m_cos(x: f64) -> f64 {
    x.cos()
}
extern "C" fn m_exp(x: f64) -> f64 {
    x.exp()
}
extern "C" fn m_log(x: f64) -> f64 {
    x.ln()
}
extern "C" fn m_sin(x: f64) -> f64 {
    x.sin()
}
extern "C" fn m_tan(x: f64) -> f64 {
    x.tan()
}
extern "C" fn m_rand(x: f64) -> f64 {
    rand(x)
}

fn raw_mut<'a>(raw: *mut Raw) -> &'a mut Raw {
    // SAFETY: the generated code only ever passes the context pointer it was called
    // with, which `Compiled::run` made from a `&mut Raw` that outlives the call; no
    // other reference to it is live while host code runs.
    unsafe { &mut *raw }
}

extern "C" fn h_warn(raw: *mut Raw, code: u32, sym: u32) {
    let raw = raw_mut(raw);
    let w = match code {
        W_DIVISION => Warning::DivisionByZero,
        W_POWER => Warning::IllegalPower,
        W_DOMAIN => Warning::Domain(raw.name(sym)),
        W_RANGE => Warning::Range(raw.name(sym)),
        _ => Warning::NonConstant(raw.name(sym)),
    };
    raw.warnings.push(w);
}

fn error(raw: &Raw, code: u32, sym: u32) -> EvalError {
    let name = raw.name(sym);
    match code {
        E_UNDEFINED_VARIABLE => EvalError::UndefinedVariable(name),
        E_UNDEFINED_FUNCTION => EvalError::UndefinedFunction(name),
        E_TOO_FEW => EvalError::TooFewArguments(name),
        E_NOT_FUNCTION => EvalError::ArgumentNotFunction(name),
        E_ILLEGAL_CHANNEL => EvalError::IllegalChannel,
        E_NOT_AVAILABLE => EvalError::NotAvailable(name),
        E_BAD_CALL => EvalError::BadArgumentCall,
        _ => EvalError::TooDeep(name),
    }
}

extern "C" fn h_fail(raw: *mut Raw, code: u32, sym: u32) {
    let raw = raw_mut(raw);
    let e = error(raw, code, sym);
    raw.fail(e);
}

/// The slow path of the depth counter: `depth` is the nesting the call of `sym` is
/// entering. Mirrors `Evaluator::call`: a warning at 100, 1000, ..., an error past
/// `MAX_DEPTH`.
extern "C" fn h_depth(raw: *mut Raw, sym: u32, depth: u64) {
    depth_event(raw_mut(raw), sym, depth);
}

fn depth_event(raw: &mut Raw, sym: u32, depth: u64) {
    if depth >= raw.next_report {
        let name = raw.name(sym);
        raw.warnings.push(Warning::Depth(name, depth));
        raw.next_report = raw.next_report.saturating_mul(10);
    }
    if depth > MAX_DEPTH {
        let name = raw.name(sym);
        raw.fail(EvalError::TooDeep(name));
    }
    raw.depth_limit = raw.next_report.min(MAX_DEPTH + 1);
}

/// Input column `n`, `n >= 1` (the generated code reports `$0` itself).
extern "C" fn h_chan(raw: *mut Raw, n: u32) -> f64 {
    let raw = raw_mut(raw);
    if raw.input.is_null() {
        return channel(raw, n);
    }
    // SAFETY: as in `channel`.
    let input = unsafe { &mut *(raw.input as *mut &mut dyn Input) };
    match input.column(n) {
        Ok((v, None)) => {
            raw.chan_errno = ERRNO_NONE;
            v
        }
        other => column_slow(raw, other),
    }
}

/// What `channel` does with a column read that raised `errno` or failed.
#[cold]
fn column_slow(raw: &mut Raw, read: Result<(f64, Option<Errno>), EvalError>) -> f64 {
    match read {
        Ok((v, errno)) => {
            raw.chan_errno = errno.map_or(ERRNO_NONE, errno_code);
            if let Some(e) = errno {
                raw.errno = errno_code(e);
            }
            v
        }
        Err(e) => {
            raw.fail(e);
            0.0
        }
    }
}

/// The thunk of every argument `$N` (N in the slot's `aux`): one host function
/// instead of a compiled thunk per call site.
extern "C" fn h_chan_thunk(raw: *mut Raw, _parent: *mut Block, slot: *mut Slot) -> f64 {
    // SAFETY: generated code passes the slot it is evaluating, in a live block.
    let n = unsafe { (*slot).aux };
    channel(raw_mut(raw), u32::try_from(n).unwrap_or(0))
}

fn channel(raw: &mut Raw, n: u32) -> f64 {
    if n < 1 {
        raw.fail(EvalError::IllegalChannel);
        return 0.0;
    }
    if raw.input.is_null() {
        raw.fail(EvalError::NoInput);
        return 0.0;
    }
    // SAFETY: while generated code runs, `input` points at a `&mut dyn Input` on
    // `Compiled::run`'s stack, borrowed for the whole call and used by nobody else.
    let input = unsafe { &mut *(raw.input as *mut &mut dyn Input) };
    let read = input.column(n);
    column_slow(raw, read)
}

fn errno_code(e: Errno) -> u64 {
    match e {
        Errno::Domain => ERRNO_DOMAIN,
        Errno::Range => ERRNO_RANGE,
    }
}

/// rcalc's `in(n)` once its argument is known (rcalc.c `l_in`).
extern "C" fn h_in(raw: *mut Raw, x: f64) -> f64 {
    let raw = raw_mut(raw);
    let n = c_round(x);
    if n != 0 {
        return channel(raw, u32::try_from(n).unwrap_or(0));
    }
    if raw.input.is_null() {
        return 0.0;
    }
    // SAFETY: as in `channel`.
    let input = unsafe { &mut *(raw.input as *mut &mut dyn Input) };
    match input.column_count() {
        Ok(v) => v,
        Err(e) => {
            raw.fail(e);
            0.0
        }
    }
}

/// A renderer library function (`arg`, `noise3`, ...) with its arguments evaluated:
/// the input (the renderer's ray) answers it.
fn renderer_fn(raw: &mut Raw, name: &'static str, args: &[f64]) -> f64 {
    if raw.input.is_null() {
        raw.fail(EvalError::NotAvailable(name.to_string()));
        return 0.0;
    }
    // SAFETY: as in `channel`.
    let input = unsafe { &mut *(raw.input as *mut &mut dyn Input) };
    match input.renderer_function(name, args) {
        Ok(v) => v,
        Err(e) => {
            raw.fail(e);
            0.0
        }
    }
}

/// A direct call of renderer function `sym` (its first `arity` arguments used).
extern "C" fn h_renderer_fn(raw: *mut Raw, sym: u32, a: f64, b: f64, c: f64) -> f64 {
    let raw = raw_mut(raw);
    match raw.tables.libs.get(sym as usize).copied().flatten() {
        Some(LibFn::Renderer(r)) => {
            let args = [a, b, c];
            renderer_fn(raw, r.name, &args[..r.arity.min(3)])
        }
        _ => {
            let name = raw.name(sym);
            raw.fail(EvalError::UndefinedFunction(name));
            0.0
        }
    }
}

/// A call through a function value the generated code does not call directly: a
/// library function passed by name, or an error deferred to the moment of the call.
extern "C" fn h_fnval(raw: *mut Raw, block: *mut Block, code: u64) -> f64 {
    let raw = raw_mut(raw);
    let sym = (code >> FN_SHIFT) as u32;
    match code & ((1 << FN_SHIFT) - 1) {
        FN_LIB => {
            let d = raw.depth + 1;
            raw.depth = d;
            depth_event(raw, sym, d);
            if raw.failed != 0 {
                return 0.0;
            }
            let v = lib_call(raw, block, sym);
            raw.depth = raw.depth.saturating_sub(1);
            v
        }
        FN_UNDEFINED => {
            depth_event(raw, sym, raw.depth + 1);
            let name = raw.name(sym);
            raw.fail(EvalError::UndefinedFunction(name));
            0.0
        }
        FN_TOO_FEW => {
            let name = raw.name(sym);
            raw.fail(EvalError::TooFewArguments(name));
            0.0
        }
        _ => {
            let name = raw.name(sym);
            raw.fail(EvalError::ArgumentNotFunction(name));
            0.0
        }
    }
}

/// Argument `n` (1-based) of a call's block, computed at most once in the caller's
/// context (calfunc.c `argument`); `None` after a fatal error.
fn block_arg(raw: &mut Raw, block: *mut Block, n: u64, sym: u32) -> Option<f64> {
    // SAFETY: `block` is an argument block built by generated code in a live stack
    // frame of the caller: a `Block` followed by `nargs` initialised `Slot`s.
    let head = unsafe { &*block };
    if n == 0 || n > head.nargs {
        let name = raw.name(sym);
        raw.fail(EvalError::TooFewArguments(name));
        return None;
    }
    // SAFETY: slot `n - 1` is within the `nargs` slots that follow the head.
    let slot = unsafe { &mut *(block.add(1) as *mut Slot).add(n as usize - 1) };
    if slot.state != 0 {
        return Some(slot.value);
    }
    let parent = head.parent;
    let thunk = slot.thunk?;
    raw.depth = raw.depth.saturating_sub(1);
    // SAFETY: `thunk` is a compiled thunk of the live module with the thunk ABI; it
    // receives the same context pointer and its own block's parent, as generated
    // code would pass them.
    let v = unsafe { thunk(raw as *mut Raw, parent, slot as *mut Slot) };
    raw.depth += 1;
    if raw.failed != 0 {
        return None;
    }
    slot.value = v;
    slot.state = 1;
    Some(v)
}

/// `Evaluator::libfunc` and `builtin` for a library function reached through a
/// function value.
fn lib_call(raw: &mut Raw, block: *mut Block, sym: u32) -> f64 {
    let lib = raw.tables.libs.get(sym as usize).copied().flatten();
    raw.errno = ERRNO_NONE;
    let d = match lib {
        Some(LibFn::Builtin(b)) => builtin(raw, block, sym, b),
        Some(LibFn::In) => block_arg(raw, block, 1, sym).map(|x| h_in(raw as *mut Raw, x)),
        Some(LibFn::Renderer(r)) => {
            let mut args = [0.0; 3];
            let n = r.arity.min(args.len());
            let mut ok = true;
            for (i, slot) in args.iter_mut().enumerate().take(n) {
                match block_arg(raw, block, i as u64 + 1, sym) {
                    Some(v) => *slot = v,
                    None => {
                        ok = false;
                        break;
                    }
                }
            }
            ok.then(|| renderer_fn(raw, r.name, &args[..n]))
        }
        None => {
            let name = raw.name(sym);
            raw.fail(EvalError::UndefinedFunction(name));
            None
        }
    };
    let Some(d) = d else { return 0.0 };
    if raw.failed != 0 {
        return 0.0;
    }
    if raw.tables.policy == MathErrors::NonFinite && raw.errno == ERRNO_NONE {
        if d.is_nan() {
            raw.errno = ERRNO_DOMAIN;
        } else if d.is_infinite() {
            raw.errno = ERRNO_RANGE;
        }
    }
    match raw.errno {
        ERRNO_NONE => d,
        e => {
            let name = raw.name(sym);
            raw.warnings.push(if e == ERRNO_DOMAIN {
                Warning::Domain(name)
            } else {
                Warning::Range(name)
            });
            0.0
        }
    }
}

fn builtin(raw: &mut Raw, block: *mut Block, sym: u32, b: Builtin) -> Option<f64> {
    // SAFETY: as in `block_arg`.
    let nargs = unsafe { (*block).nargs };
    let arg = |raw: &mut Raw, n: u64| block_arg(raw, block, n, sym);
    Some(match b {
        Builtin::If => {
            if arg(raw, 1)? > 0.0 {
                arg(raw, 2)?
            } else {
                arg(raw, 3)?
            }
        }
        Builtin::Select => {
            let a1 = arg(raw, 1)?;
            let n = c_round(a1);
            if a1.is_nan() || a1 < -0.5 || n >= nargs as i64 {
                raw.errno = ERRNO_DOMAIN;
                0.0
            } else if n == 0 {
                (nargs - 1) as f64
            } else if n < 0 {
                raw.fail(EvalError::BadArgumentCall);
                return None;
            } else {
                arg(raw, n as u64 + 1)?
            }
        }
        Builtin::Max | Builtin::Min => {
            let mut best = arg(raw, 1)?;
            let mut n = nargs;
            while n > 1 {
                let v = arg(raw, n)?;
                n -= 1;
                let keep = if b == Builtin::Max {
                    best > v
                } else {
                    best < v
                };
                if !keep {
                    best = v;
                }
            }
            best
        }
        // Arguments right to left, as the interpreter.
        Builtin::Atan2 => {
            let x = arg(raw, 2)?;
            let y = arg(raw, 1)?;
            y.atan2(x)
        }
        other => {
            let x = arg(raw, 1)?;
            other.unary(x).unwrap_or(0.0)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn math_wrappers_are_the_interpreters_functions() {
        let wrappers: [(Builtin, extern "C" fn(f64) -> f64); 10] = [
            (Builtin::Acos, m_acos),
            (Builtin::Asin, m_asin),
            (Builtin::Atan, m_atan),
            (Builtin::Cos, m_cos),
            (Builtin::Exp, m_exp),
            (Builtin::Log, m_log),
            (Builtin::Log10, m_log10),
            (Builtin::Rand, m_rand),
            (Builtin::Sin, m_sin),
            (Builtin::Tan, m_tan),
        ];
        let mut xs = vec![
            0.0,
            -0.0,
            1.0,
            -1.0,
            1.0000001,
            -1.0000001,
            0.5,
            -0.5,
            2.0,
            -2.0,
            1e-300,
            1e300,
            -1e300,
            710.0,
            -746.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            -f64::NAN,
        ];
        xs.extend((0..2000).map(|i| (i as f64 - 1000.0) * 0.0137));
        for (b, f) in wrappers {
            for &x in &xs {
                let want = b.unary(x).unwrap_or(0.0);
                let got = f(x);
                assert_eq!(got.to_bits(), want.to_bits(), "{b:?}({x})");
            }
        }
    }
}
