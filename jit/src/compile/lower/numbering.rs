//! Value numbering: the same value (a variable's, an input column, a number, an
//! operation or a pure library call on numbered values) computed once per generated
//! function and reused, directly where every path to the point computed it and through
//! a flag in an SSA variable where only some did; what is known is scoped to the
//! current point and undone after a branch.

use super::*;

impl<'a, 'b, 'm> Lower<'a, 'b, 'm> {
    /// Whether a value is a number that is not NaN (its NaN test is then known).
    pub(super) fn not_nan(&self, v: Value) -> bool {
        self.numbers.get(&v).is_some_and(|x| !x.is_nan())
    }

    /// Record that `key` is computed, as `v`, on every path from here.
    pub(super) fn know(&mut self, key: Key, v: Value) {
        let old = self.known_args.insert(key, v);
        self.undo.push((key, old));
    }

    /// The state of `known_args` before a branch, for [`Lower::rewind`].
    pub(super) fn mark(&self) -> usize {
        self.undo.len()
    }

    /// Forget what was learned since `mark` (at the end of a branch).
    pub(super) fn rewind(&mut self, mark: usize) {
        while self.undo.len() > mark {
            let Some((key, old)) = self.undo.pop() else {
                break;
            };
            match old {
                Some(v) => self.known_args.insert(key, v),
                None => self.known_args.remove(&key),
            };
        }
    }

    /// The value already computed for `key` on every path here, or `make`'s.
    pub(super) fn memo(&mut self, key: Key, make: impl FnOnce(&mut Self) -> Value) -> Value {
        if let Some(&v) = self.known_args.get(&key) {
            return v;
        }
        let v = make(self);
        self.know(key, v);
        self.label(v, key);
        v
    }

    pub(super) fn intern(&mut self, key: Key) -> Vn {
        if let Some(&n) = self.interned.get(&key) {
            return n;
        }
        let n = self.next_vn;
        self.next_vn += 1;
        self.interned.insert(key, n);
        n
    }

    /// The value number of `v`: its key's if it was given one, else its own.
    pub(super) fn vn(&mut self, v: Value) -> Vn {
        if let Some(&n) = self.vns.get(&v) {
            return n;
        }
        let n = self.intern(Key::Val(v));
        self.vns.insert(v, n);
        n
    }

    /// `v` is the value of `key` (a value keeps the first number it was given; a
    /// key not yet numbered takes the value's).
    pub(super) fn label(&mut self, v: Value, key: Key) {
        match self.vns.get(&v) {
            Some(&n) => {
                self.interned.entry(key).or_insert(n);
            }
            None => {
                let n = self.intern(key);
                self.vns.insert(v, n);
            }
        }
    }

    pub(super) fn op_key(&mut self, kind: u8, x: Value, y: Value) -> Key {
        Key::Op(kind, self.vn(x), self.vn(y))
    }

    /// A pure library function's result for `key`: the value already computed on
    /// every path here; else, if some path may have computed it, a test of that
    /// (the value, or a call); else a call, remembered for later calls.
    pub(super) fn pure_call(&mut self, key: Key, call: impl FnOnce(&mut Self) -> Value) -> Value {
        if let Some(&v) = self.known_args.get(&key) {
            return v;
        }
        let v = match self.lazy.get(&key).copied() {
            Some((flag, val)) => {
                let done = self.b.use_var(flag);
                let (j, out) = self.join();
                let have = self.b.create_block();
                let compute = self.b.create_block();
                self.b.ins().brif(done, have, &[], compute, &[]);
                self.b.switch_to_block(have);
                let v = self.b.use_var(val);
                self.jump_with(j, v);
                self.b.switch_to_block(compute);
                let d = call(self);
                let one = self.b.ins().iconst(types::I8, 1);
                self.b.def_var(flag, one);
                self.b.def_var(val, d);
                self.jump_with(j, d);
                self.b.switch_to_block(j);
                // Every value of `val` is a result of the same call.
                self.quiet_if(out, &[d])
            }
            None => {
                let d = call(self);
                if self.lazy.len() < MAX_LAZY {
                    // Never defined on the paths that do not compute it, the flag
                    // reads as 0 there (Cranelift's SSA construction zero-fills).
                    let flag = self.b.declare_var(types::I8);
                    let val = self.b.declare_var(types::F64);
                    let one = self.b.ins().iconst(types::I8, 1);
                    self.b.def_var(flag, one);
                    self.b.def_var(val, d);
                    self.lazy.insert(key, (flag, val));
                }
                d
            }
        };
        self.know(key, v);
        self.label(v, key);
        v
    }

    /// `x op y` for a commutative IEEE operation (`+`, `*`: the same value either
    /// way for operands that are not NaN, zeros' signs included), with a number that
    /// is not NaN second, where the machine code can read it from memory; the NaN
    /// cases are `nan_first`'s, which looks at the operands, not at the order.
    pub(super) fn commuted(
        &mut self,
        x: Value,
        y: Value,
        op: impl FnOnce(&mut FunctionBuilder<'b>, Value, Value) -> Value,
    ) -> Value {
        if self.not_nan(x) && !self.numbers.contains_key(&y) {
            op(&mut self.b, y, x)
        } else {
            op(&mut self.b, x, y)
        }
    }

    /// Whether a value is either not a NaN or a quiet NaN made by the hardware or
    /// the C library ([`Lower::quiet`]), never a signalling NaN.
    pub(super) fn is_quiet(&self, v: Value) -> bool {
        self.not_nan(v) || self.quiet.contains(&v)
    }

    /// Mark `v` as [`Lower::is_quiet`] when every value it can be is.
    pub(super) fn quiet_if(&mut self, v: Value, parts: &[Value]) -> Value {
        if parts.iter().all(|&p| self.is_quiet(p)) {
            self.quiet.insert(v);
        }
        v
    }

    /// `Evaluator`'s `nan_first`: with a NaN operand, the first NaN operand itself
    /// (x86 keeps the destination's NaN, and the order is the reference rcalc's);
    /// otherwise the computed result.
    ///
    /// The SSE/AVX instruction `result` was computed by (`first op second`) already
    /// gives that for quiet NaNs: the first source operand if it is a NaN, else the
    /// second, each unchanged when quiet (only a signalling NaN is changed, to its
    /// quiet form). So a test is needed only for an operand that may be a
    /// signalling NaN (an input column, a variable's cached value, a parameter): the
    /// second's when it may be one, and then the first's too (unless a number), so
    /// that a NaN first still wins over the second's select.
    pub(super) fn nan_first(&mut self, first: Value, second: Value, result: Value) -> Value {
        self.quiet.insert(result);
        let second_quiet = self.is_quiet(second);
        let r = if second_quiet {
            result
        } else {
            let second_nan = self.b.ins().fcmp(FloatCC::Unordered, second, second);
            self.b.ins().select(second_nan, second, result)
        };
        if self.not_nan(first) || (second_quiet && self.is_quiet(first)) {
            return self.quiet_if(r, &[first, second]);
        }
        let first_nan = self.b.ins().fcmp(FloatCC::Unordered, first, first);
        self.b.ins().select(first_nan, first, r)
    }
}
