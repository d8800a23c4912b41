//! Expressions node by node, in the interpreter's order: numbers, input channels,
//! arithmetic with its `errno` and NaN rules (`/` and `^` as calcomp computes them).

use super::*;

impl<'a, 'b, 'm> Lower<'a, 'b, 'm> {
    pub(super) fn expr(&mut self, e: &'m Expr) -> R<Value> {
        if !matches!(e.node, Node::Num(_))
            && let Some(v) = self.const_value(e, CONST_DEPTH)
        {
            return Ok(self.number(v));
        }
        Ok(match &e.node {
            Node::Num(v) => self.number(*v),
            Node::Chan(n) => {
                if *n < 1 {
                    self.fail(E_ILLEGAL_CHANNEL, NO_SYM)
                } else {
                    self.channel(*n)
                }
            }
            Node::Var(s) => self.variable(*s)?,
            Node::Arg(n) if self.cur == 0 => self.argument(*n),
            Node::Arg(n) => self.inline_argument(*n)?,
            Node::Neg(a) => {
                let x = self.expr(a)?;
                let k = self.op_key(OP_NEG, x, x);
                self.memo(k, |lw| lw.b.ins().fneg(x))
            }
            // Summed from 0 as calexpr.c `eadd` does: `-0 + -0` is 0.
            Node::Sum(v) => {
                let mut acc = self.number(0.0);
                for x in v {
                    let x = self.expr(x)?;
                    let k = self.op_key(OP_ADD, acc, x);
                    acc = self.memo(k, |lw| {
                        let r = lw.commuted(acc, x, |b, p, q| b.ins().fadd(p, q));
                        lw.nan_first(acc, x, r)
                    });
                }
                acc
            }
            // From 1; `1 * x` is `x` to the bit (a NaN `x` included, which
            // `nan_first` would return), so the first factor starts.
            Node::Product(v) => {
                let mut acc: Option<Value> = None;
                for x in v {
                    let x = self.expr(x)?;
                    acc = Some(match acc {
                        Some(a) => {
                            let k = self.op_key(OP_MUL, a, x);
                            self.memo(k, |lw| {
                                let r = lw.commuted(a, x, |b, p, q| b.ins().fmul(p, q));
                                lw.nan_first(a, x, r)
                            })
                        }
                        None => x,
                    });
                }
                match acc {
                    Some(a) => a,
                    None => self.number(1.0),
                }
            }
            Node::Sub(a, b) => {
                let x = self.expr(a)?;
                let y = self.expr(b)?;
                let k = self.op_key(OP_SUB, x, y);
                self.memo(k, |lw| {
                    let r = lw.b.ins().fsub(x, y);
                    lw.nan_first(x, y, r)
                })
            }
            Node::Div(a, b) => self.divide(a, b)?,
            Node::Pow(a, b) => self.power(a, b)?,
            Node::Call { callee, args } => match callee {
                Callee::Sym(s) => self.call_sym(*s, args)?,
                Callee::Arg(n) => self.call_arg(*n, args)?,
            },
        })
    }

    /// Input column `n` (`n >= 1`): read once on every path (a fatal error aborts),
    /// then reused, with the `errno` the read raised raised again, as a new read
    /// would (`Input::column` gives the same for the same record).
    pub(super) fn channel(&mut self, n: u32) -> Value {
        if let (Some(&v), Some(&e)) = (
            self.known_args.get(&Key::Chan(n)),
            self.known_args.get(&Key::ChanErrno(n)),
        ) {
            let errno = self.load_raw(types::I64, OFF_ERRNO);
            let new = self.b.ins().select(e, e, errno);
            self.store_raw(new, OFF_ERRNO);
            return v;
        }
        let c = self.i32c(n);
        let v = self.call_import_f64("radc_chan", &[self.raw, c]);
        self.check_failed();
        let e = self.load_raw(types::I64, OFF_CHAN_ERRNO);
        self.know(Key::Chan(n), v);
        self.know(Key::ChanErrno(n), e);
        self.label(v, Key::Chan(n));
        v
    }

    /// A number in an expression (one value per number in each region of code, so
    /// operations on it can be recognised as the same).
    pub(super) fn number(&mut self, v: f64) -> Value {
        self.memo(Key::Num(v.to_bits()), |lw| {
            let c = lw.f64c(v);
            lw.numbers.insert(c, v);
            c
        })
    }

    /// calexpr.c `edivi` under the reference build's -ffast-math: the denominator
    /// first; a zero or NaN denominator warns, sets `errno` and is itself the result,
    /// without evaluating the numerator.
    pub(super) fn divide(&mut self, a: &'m Expr, b: &'m Expr) -> R<Value> {
        let den = self.expr(b)?;
        if self
            .const_value(b, CONST_DEPTH)
            .is_some_and(|v| v != 0.0 && !v.is_nan())
        {
            let num = self.expr(a)?;
            let k = self.op_key(OP_DIV, num, den);
            return Ok(self.memo(k, |lw| {
                let q = lw.b.ins().fdiv(num, den);
                lw.quiet.insert(q);
                q
            }));
        }
        let zero = self.f64c(0.0);
        let is_zero = self.b.ins().fcmp(FloatCC::UnorderedOrEqual, den, zero);
        let (j, out) = self.join();
        let (z, nz) = self.cold_branch(is_zero);
        self.b.switch_to_block(z);
        let w = self.i32c(W_DIVISION);
        self.warn(w, NO_SYM);
        self.set_errno(ERRNO_RANGE);
        self.jump_with(j, den);
        self.b.switch_to_block(nz);
        let known = self.mark();
        let num = self.expr(a)?;
        self.rewind(known);
        let q = self.b.ins().fdiv(num, den);
        self.quiet.insert(q);
        self.jump_with(j, q);
        self.b.switch_to_block(j);
        Ok(self.quiet_if(out, &[den]))
    }

    /// calexpr.c `epow`: `errno` cleared, both sides (the exponent first: the
    /// reference build evaluates C arguments right to left), the C library's `pow`. No
    /// `x*x` fast path for integer exponents: the C library's `pow` is not specified
    /// to round as a product does, and results must equal the interpreter's.
    pub(super) fn power(&mut self, a: &'m Expr, b: &'m Expr) -> R<Value> {
        self.set_errno(ERRNO_NONE);
        let pure = self.pure_ready(a) && self.pure_ready(b);
        if pure
            && let (Some(x), Some(y)) = (
                self.const_value(a, CONST_DEPTH),
                self.const_value(b, CONST_DEPTH),
            )
            && x.powf(y).is_finite()
        {
            return Ok(self.f64c(x.powf(y)));
        }
        let y = self.expr(b)?;
        let x = self.expr(a)?;
        let key = Key::Pow(self.vn(x), self.vn(y));
        let d = self.pure_call(key, |lw| lw.call_lib("radc_pow", &[x, y]));
        // As for library functions: pure operands leave `errno` clear.
        if pure && self.st.policy != MathErrors::NonFinite {
            return Ok(d);
        }
        self.nonfinite(d);
        if self.errno_is_clear() {
            return Ok(d);
        }
        let errno = self.load_raw(types::I64, OFF_ERRNO);
        let (j, out) = self.join();
        let (bad, ok) = self.cold_branch(errno);
        self.b.switch_to_block(bad);
        let w = self.i32c(W_POWER);
        self.warn(w, NO_SYM);
        let zero = self.f64c(0.0);
        self.jump_with(j, zero);
        self.b.switch_to_block(ok);
        self.jump_with(j, d);
        self.b.switch_to_block(j);
        Ok(self.quiet_if(out, &[d]))
    }

    /// `MathErrors::NonFinite`: NaN is a domain error, infinity a range error.
    pub(super) fn nonfinite(&mut self, d: Value) {
        if self.st.policy != MathErrors::NonFinite {
            return;
        }
        let errno = self.load_raw(types::I64, OFF_ERRNO);
        let nan = self.b.ins().fcmp(FloatCC::Unordered, d, d);
        let abs = self.b.ins().fabs(d);
        let inf = self.f64c(f64::INFINITY);
        let is_inf = self.b.ins().fcmp(FloatCC::Equal, abs, inf);
        let range = self.i64c(ERRNO_RANGE);
        let none = self.i64c(ERRNO_NONE);
        let domain = self.i64c(ERRNO_DOMAIN);
        let code = self.b.ins().select(is_inf, range, none);
        let code = self.b.ins().select(nan, domain, code);
        let unset = self.b.ins().icmp_imm_s(IntCC::Equal, errno, 0);
        let new = self.b.ins().select(unset, code, errno);
        self.store_raw(new, OFF_ERRNO);
    }
}
