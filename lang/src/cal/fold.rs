//! Radiance's constant folding rules (calexpr.c `isconstvar`, `isconstfun`,
//! `epflatten`). The arithmetic folds themselves are in `resolve.rs`, applied as each
//! node is built, because that is when Radiance applies them.

use super::ir::{Callee, Expr, Node, SymId};
use super::resolve::Module;
use super::syntax::DefKind;

/// `isconstvar`: a `:` variable (not a function), or a call of a constant function
/// whose arguments are numbers or constant functions' names.
pub fn is_constant_reference(m: &Module, e: &Expr) -> bool {
    match &e.node {
        Node::Call {
            callee: Callee::Sym(s),
            args,
        } => {
            is_constant_function(m, *s)
                && args.iter().all(|a| match a.node {
                    Node::Num(_) => true,
                    Node::Var(s) => is_constant_function(m, s),
                    _ => false,
                })
        }
        Node::Var(s) => m
            .current_def(*s)
            .map(|id| m.def(id))
            .is_some_and(|d| d.kind == DefKind::Constant && !d.is_function()),
        _ => false,
    }
}

/// `isconstfun`: a function defined with `:`, or a constant library function that no
/// definition masks.
pub fn is_constant_function(m: &Module, s: SymId) -> bool {
    match m.current_def(s) {
        Some(id) => {
            let d = m.def(id);
            d.is_function() && d.kind == DefKind::Constant
        }
        None => m.symbol(s).lib.is_some_and(|l| l.is_constant()),
    }
}

/// `epoptimize`: splice nested sums into sums and products into products, then (when
/// folding) combine their numbers into the first number's place, in order. This is
/// why rcalc computes `$1+1e20-1e20` as `$1 + 0`.
pub fn optimize(e: &mut Expr, fold: bool) {
    let is_sum = matches!(e.node, Node::Sum(_));
    if let Node::Sum(kids) | Node::Product(kids) = &mut e.node {
        let mut flat = Vec::with_capacity(kids.len());
        for k in std::mem::take(kids) {
            splice(k, is_sum, &mut flat);
        }
        if fold {
            combine(&mut flat, is_sum);
        }
        if flat.len() == 1 {
            if let Some(only) = flat.pop() {
                *e = only;
            }
        } else {
            *kids = flat;
        }
    }
    match &mut e.node {
        Node::Call { args, .. } => args.iter_mut().for_each(|a| optimize(a, fold)),
        Node::Neg(a) => optimize(a, fold),
        Node::Sub(a, b) | Node::Div(a, b) | Node::Pow(a, b) => {
            optimize(a, fold);
            optimize(b, fold);
        }
        Node::Sum(v) | Node::Product(v) => v.iter_mut().for_each(|a| optimize(a, fold)),
        _ => {}
    }
}

fn splice(e: Expr, into_sum: bool, out: &mut Vec<Expr>) {
    match e.node {
        Node::Sum(kids) if into_sum => kids.into_iter().for_each(|k| splice(k, into_sum, out)),
        Node::Product(kids) if !into_sum => kids.into_iter().for_each(|k| splice(k, into_sum, out)),
        node => out.push(Expr { node, span: e.span }),
    }
}

fn combine(kids: &mut Vec<Expr>, is_sum: bool) {
    let Some(first) = kids.iter().position(|k| k.as_num().is_some()) else {
        return;
    };
    let mut combined = kids[first].as_num().unwrap_or(0.0);
    let mut i = first + 1;
    while i < kids.len() {
        if let Some(v) = kids[i].as_num() {
            if is_sum {
                combined += v;
            } else {
                combined *= v;
            }
            kids.remove(i);
        } else {
            i += 1;
        }
    }
    kids[first].node = Node::Num(combined);
}

#[cfg(test)]
mod tests {
    use crate::cal::eval::{Evaluator, NoInput};
    use crate::cal::resolve::{Env, Module};
    use crate::source::FileId;

    fn value(src: &str, out: u32) -> f64 {
        let mut m = Module::new(&Env::rcalc());
        let d = m.add_source(FileId(0), src);
        assert!(d.is_empty(), "{d:?}");
        m.optimize();
        let mut ev = Evaluator::new(&m);
        ev.next_record();
        let e = &m.outputs()[&out].body;
        ev.eval_top(e, &mut NoInput).unwrap_or(f64::NAN)
    }

    fn folded(src: &str, out: u32) -> bool {
        let mut m = Module::new(&Env::rcalc());
        m.add_source(FileId(0), src);
        m.optimize();
        m.outputs()[&out].body.as_num().is_some()
    }

    #[test]
    fn constants_fold_like_radiance() {
        assert!(folded("$1 = 2*PI", 1));
        assert!(folded("c : 3; $1 = c^2 + sin(c)", 1));
        assert!(folded("f(x) : x*2; $1 = f(3)", 1));
        assert!(!folded("f(x) = x*2; $1 = f(3)", 1));
        assert!(!folded("c = 3; $1 = c", 1));
        // A forward reference cannot fold: the definition comes later.
        assert!(!folded("$1 = c; c : 3", 1));
        assert_eq!(value("$1 = -2^2", 1), 4.0);
        assert_eq!(
            value("fact(n) : if(n, n*fact(n-1), 1); $1 = fact(5)", 1),
            120.0
        );
    }

    #[test]
    fn division_by_a_constant_multiplies_by_its_reciprocal() {
        let mut m = Module::new(&Env::rcalc());
        m.add_source(FileId(0), "$1 = x/3; x = 1");
        m.optimize();
        let mut ev = Evaluator::new(&m);
        ev.next_record();
        let v = ev
            .eval_top(&m.outputs()[&1].body, &mut NoInput)
            .unwrap_or(0.0);
        assert_eq!(v, 1.0 * (1.0 / 3.0));
    }
}
