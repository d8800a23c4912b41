//! What is known while compiling: numbers and pure expressions of numbers folded as the
//! interpreter would compute them (results only when finite; the depth check and
//! `errno` clearing stay).

use super::*;

impl<'a, 'b, 'm> Lower<'a, 'b, 'm> {
    /// The value of `e` if it is known while compiling and computing it has no
    /// effect: numbers, variables defined as a number (read without a warning, see
    /// [`Lower::variable`]), and the exact arithmetic of those, computed as the
    /// interpreter computes it (a division only by a non-zero number).
    pub(super) fn const_value(&self, e: &Expr, depth: u32) -> Option<f64> {
        let depth = depth.checked_sub(1)?;
        let c = |x: &Expr| self.const_value(x, depth);
        Some(match &e.node {
            Node::Num(v) => *v,
            Node::Var(s) => {
                let module = self.st.module;
                let d = module
                    .current_def(*s)
                    .filter(|&d| !module.def(d).is_function())?;
                if self.st.host_vars.contains_key(&d) {
                    return None;
                }
                module.def(d).body.as_num()?
            }
            Node::Neg(a) => -c(a)?,
            Node::Sub(a, b) => {
                let (x, y) = (c(a)?, c(b)?);
                nan_first(x, y, x - y)
            }
            Node::Sum(v) => {
                let mut sum = 0.0;
                for x in v {
                    let x = c(x)?;
                    sum = nan_first(sum, x, sum + x);
                }
                sum
            }
            Node::Product(v) => {
                let mut prod = 1.0;
                for x in v {
                    let x = c(x)?;
                    prod = nan_first(prod, x, prod * x);
                }
                prod
            }
            Node::Div(a, b) => {
                let den = c(b)?;
                if den == 0.0 || den.is_nan() {
                    return None;
                }
                c(a)? / den
            }
            _ => return None,
        })
    }

    /// Whether `e` can be computed here with no effect at all: numbers, parameters
    /// and variables already computed on every path to this point, and the
    /// arithmetic of those that cannot warn (`-`, `+`, `*`, `/` by a non-zero number).
    pub(super) fn pure_ready(&self, e: &Expr) -> bool {
        self.pure_within(e, 16)
    }

    pub(super) fn pure_within(&self, e: &Expr, depth: u32) -> bool {
        let Some(depth) = depth.checked_sub(1) else {
            return false;
        };
        if self.const_value(e, CONST_DEPTH).is_some() {
            return true;
        }
        match &e.node {
            Node::Num(_) => true,
            Node::Div(a, b) => {
                self.const_value(b, CONST_DEPTH)
                    .is_some_and(|v| v != 0.0 && !v.is_nan())
                    && self.pure_within(a, depth)
            }
            Node::Arg(n) => self.known_args.contains_key(&Key::Arg(self.cur, *n)),
            Node::Var(s) => self
                .st
                .module
                .current_def(*s)
                .is_some_and(|d| self.known_args.contains_key(&Key::Var(d.0))),
            Node::Neg(a) => self.pure_within(a, depth),
            Node::Sub(a, b) => self.pure_within(a, depth) && self.pure_within(b, depth),
            Node::Sum(v) | Node::Product(v) => v.iter().all(|x| self.pure_within(x, depth)),
            _ => false,
        }
    }
}
