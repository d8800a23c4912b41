//! Name resolution and lowering to the IR, statement by statement as Radiance reads
//! them (caldefn.c `egetstatement`): each name is a symbol with a stack of
//! definitions; references link to the symbol, so the definition in force when the
//! program runs is the one used (forward references work). Constant folding happens
//! here, while lowering, because Radiance folds while parsing: what a `:` name or a
//! constant function call folds to depends on the definitions made *before* it.

use super::builtins::{Builtin, LibFn, RENDERER_FUNCTIONS, RENDERER_VARIABLES};
use super::eval::{Errno, EvalError, Evaluator, Input, Warning};
use super::fold;
use super::ir::{Callee, Def, DefId, Expr, Node, OutputDef, SymId, Symbol};
use super::syntax::{self, BinOp, DefKind, ExprKind, Ident, Statement};
use crate::diagnostic::{self, Diagnostic};
use crate::source::{FileId, Span};
use std::collections::{BTreeMap, HashMap};

/// Call nesting allowed while folding at parse time.
const PARSE_TIME_MAX_DEPTH: u64 = 100;

/// calcomp's context mark.
const CNTXMARK: char = '`';
/// Radiance truncates names to this many characters (calcomp.h `RMAXWORD`).
const MAX_NAME: usize = 127;

/// The program hosting the calcomp code: it decides the library and predefined names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Host {
    /// calcomp's own library only.
    Bare,
    /// rcalc: adds `in(n)` and the constant `PI`.
    #[default]
    Rcalc,
    /// rtrace/rpict: ray channels (`Dx`, `Nx`, ...), `arg`, `erf`, noise functions and
    /// the names rayinit.cal defines.
    Renderer,
}

/// Where calcomp code runs, and how it is compiled there.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct Env {
    pub host: Host,
    /// Fold constants (and flatten `+`/`*`) as rcalc does without `-n`, and as the
    /// renderer always does. Folding changes results in the last bits
    /// (`x/3` becomes `x*(1/3)`), so it must match the program being reproduced.
    pub fold: bool,
    /// All the program's sources are loaded (an `rcalc -e` program, a primitive with
    /// its function files): a name defined nowhere is an error. Otherwise the text is
    /// a library whose free names its user supplies, and they are only noted.
    pub complete: bool,
}

impl Env {
    pub fn rcalc() -> Self {
        Env {
            host: Host::Rcalc,
            fold: true,
            complete: false,
        }
    }
    pub fn renderer() -> Self {
        Env {
            host: Host::Renderer,
            fold: true,
            complete: false,
        }
    }
    /// The same environment, for a program whose sources are all loaded.
    pub fn complete(self) -> Self {
        Env {
            complete: true,
            ..self
        }
    }

    pub fn bare() -> Self {
        Env {
            host: Host::Bare,
            fold: true,
            complete: false,
        }
    }
}

/// A name the host defines without a calcomp definition this module can see.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HostName {
    /// Parameters, for a function.
    pub arity: Option<usize>,
    /// Defined with `:` (so usable in other constants).
    pub constant: bool,
}

/// A whole calcomp program: every definition made so far, in order.
#[derive(Clone, Debug, Default)]
pub struct Module {
    symbols: Vec<Symbol>,
    by_name: HashMap<String, SymId>,
    defs: Vec<Def>,
    outputs: BTreeMap<u32, OutputDef>,
    library: HashMap<&'static str, LibFn>,
    host_names: HashMap<SymId, HostName>,
    context: String,
    fold: bool,
    /// Errors while folding are the program's own (see [`Env::complete`]).
    complete: bool,
    /// Warnings Radiance prints while folding at parse time.
    pub parse_warnings: Vec<Warning>,
}

/// The renderer's starting module (ray channels, host names, rayinit.cal), built once
/// per folding mode: a scene can load thousands of function files, and the language
/// server lowers primitives one by one, so each gets a copy rather than a fresh parse.
fn renderer_base(fold: bool) -> &'static Module {
    static FOLDED: std::sync::OnceLock<Module> = std::sync::OnceLock::new();
    static UNFOLDED: std::sync::OnceLock<Module> = std::sync::OnceLock::new();
    let cell = if fold { &FOLDED } else { &UNFOLDED };
    cell.get_or_init(|| {
        let mut m = Module {
            fold,
            ..Module::default()
        };
        for b in Builtin::ALL {
            m.library.insert(b.name(), LibFn::Builtin(b));
        }
        for f in RENDERER_FUNCTIONS {
            m.library.insert(f.name, LibFn::Renderer(f));
        }
        m.define_ray_channels();
        for v in RENDERER_VARIABLES.iter().skip(RAY_CHANNELS.len()) {
            m.declare_host_name(v, None, false);
        }
        m.load_rayinit();
        m
    })
}

impl Module {
    pub fn new(env: &Env) -> Self {
        if env.host == Host::Renderer {
            let mut m = renderer_base(env.fold).clone();
            m.complete = env.complete;
            return m;
        }
        let mut m = Module {
            fold: env.fold,
            complete: env.complete,
            ..Module::default()
        };
        for b in Builtin::ALL {
            m.library.insert(b.name(), LibFn::Builtin(b));
        }
        match env.host {
            Host::Rcalc => {
                m.library.insert("in", LibFn::In);
                m.set_constant("PI", std::f64::consts::PI);
            }
            // The renderer's module is a copy of `renderer_base`, returned above.
            Host::Bare | Host::Renderer => {}
        }
        m
    }

    /// Constant folding on? rcalc turns it off with `-n` (calcomp's `E_RCONST`).
    pub fn folds(&self) -> bool {
        self.fold
    }

    pub fn set_folding(&mut self, fold: bool) {
        self.fold = fold;
    }

    /// The context names in the following statements are qualified with (the renderer
    /// uses a function file's name); empty is the global context.
    pub fn set_context(&mut self, context: &str) {
        let ctx = context.trim_start_matches(CNTXMARK);
        let mut c = String::new();
        if !ctx.is_empty() {
            c.push(CNTXMARK);
            c.extend(ctx.chars().map(|ch| if is_id(ch) { ch } else { '_' }));
            while c.ends_with(CNTXMARK) {
                c.pop();
            }
        }
        self.context = c;
    }

    /// rcalc's `varset(name, ':', value)`: PI and friends.
    pub fn set_constant(&mut self, name: &str, value: f64) {
        let ident = Ident {
            name: name.to_string(),
            span: Span::default(),
        };
        let body = Expr::num(value, Span::default());
        self.push_def(ident, None, DefKind::Constant, body, Span::default());
    }

    /// rcalc's `varset(name, '=', value)` (`recno`, `outno`), replacing `=` definitions.
    pub fn set_variable(&mut self, name: &str, value: f64) {
        let ident = Ident {
            name: name.to_string(),
            span: Span::default(),
        };
        let body = Expr::num(value, Span::default());
        self.push_def(ident, None, DefKind::Assign, body, Span::default());
    }

    /// Binds a host variable to an input channel in the global context (`name = $chan`),
    /// as the renderer's per-shading `varset`s (`NxP`, `CrP`, ...) are made visible to a
    /// function file: its definitions then read it like any ray channel.
    pub fn bind_channel(&mut self, name: &str, chan: u32) {
        let context = std::mem::take(&mut self.context);
        let ident = Ident {
            name: name.to_string(),
            span: Span::default(),
        };
        let body = Expr {
            node: Node::Chan(chan),
            span: Span::default(),
        };
        self.push_def(ident, None, DefKind::Assign, body, Span::default());
        self.context = context;
    }

    /// A name the host provides without a visible definition (the renderer's
    /// per-shading variables, rayinit.cal when its text is not at hand).
    pub fn declare_host_name(&mut self, name: &str, arity: Option<usize>, constant: bool) {
        let sym = self.insert_qualified(name.to_string());
        self.host_names.insert(sym, HostName { arity, constant });
    }

    pub fn host_name(&self, sym: SymId) -> Option<HostName> {
        self.host_names.get(&sym).copied()
    }

    /// The renderer loads rayinit.cal before any scene function file (func.c
    /// `initfunc`), in the global context: `A1`, `noise3a`, `and`, `frac`, ... are
    /// ordinary definitions over the ray channels and renderer functions, so they fold
    /// and evaluate as in Radiance. radc's built-in text is used (see
    /// [`crate::library`]); a different rayinit.cal on RAYPATH is not consulted here,
    /// since `lang` does no IO.
    fn load_rayinit(&mut self) {
        let text = crate::library::builtin(crate::library::RAYINIT).unwrap_or_default();
        let context = std::mem::take(&mut self.context);
        let diags = self.add_source(crate::library::RAYINIT_FILE, text);
        debug_assert!(diags.is_empty(), "built-in rayinit.cal: {diags:?}");
        self.context = context;
    }

    /// func.c binds the ray's values to input channels: `Dx=$1; ...`.
    fn define_ray_channels(&mut self) {
        for (name, chan) in RAY_CHANNELS {
            let ident = Ident {
                name: name.to_string(),
                span: Span::default(),
            };
            let body = Expr {
                node: Node::Chan(*chan),
                span: Span::default(),
            };
            self.push_def(ident, None, DefKind::Assign, body, Span::default());
        }
    }

    /// Parse and add a source text.
    pub fn add_source(&mut self, file: FileId, text: &str) -> Vec<Diagnostic> {
        let (program, mut diags) = super::parser::parse(file, text);
        diags.extend(self.add_program(&program));
        diags
    }

    /// Load a function file named by a primitive as the renderer does (func.c
    /// `getfunc`): its definitions live in a context named after the file (without a
    /// `.cal` suffix); `.` means no file and the global context. The primitive's
    /// expression arguments are then added with [`Module::add_expression`] in that
    /// context. Call [`Module::set_context`] with `""` to return to the global one.
    pub fn load_function_file(&mut self, file: FileId, name: &str, text: &str) -> Vec<Diagnostic> {
        if name == "." {
            self.set_context("");
            return Vec::new();
        }
        let lower = name.to_ascii_lowercase();
        let ctx = if lower.len() > 4 && lower.ends_with(".cal") {
            &name[..name.len() - 4]
        } else {
            name
        };
        self.set_context(ctx);
        self.add_source(file, text)
    }

    /// Parse and lower one expression in the current definitions (an rcalc `-o`
    /// format field: calexpr.c `eparse`, folded but never flattened).
    pub fn add_expression(&mut self, file: FileId, text: &str) -> Result<Expr, Vec<Diagnostic>> {
        let e = super::parser::parse_expr(file, text)?;
        let mut diags = Vec::new();
        let lowered = self.lower(&e, None, &mut diags);
        if diags.iter().any(Diagnostic::is_error) {
            Err(diags)
        } else {
            Ok(lowered)
        }
    }

    /// Add parsed statements in order, folding as Radiance would at each point.
    pub fn add_program(&mut self, program: &syntax::Program) -> Vec<Diagnostic> {
        let mut diags = Vec::new();
        for stmt in &program.statements {
            self.add_statement(stmt, &mut diags);
        }
        diags
    }

    fn add_statement(&mut self, stmt: &Statement, diags: &mut Vec<Diagnostic>) {
        match stmt {
            Statement::Output(o) => {
                let body = self.lower(&o.body, None, diags);
                self.outputs.insert(
                    o.channel,
                    OutputDef {
                        channel: o.channel,
                        body,
                        span: o.span,
                    },
                );
            }
            Statement::Definition(d) => {
                let body = self.lower(&d.body, d.params.as_deref(), diags);
                self.push_def(d.name.clone(), d.params.clone(), d.kind, body, d.span);
            }
        }
    }

    fn push_def(
        &mut self,
        name: Ident,
        params: Option<Vec<Ident>>,
        kind: DefKind,
        body: Expr,
        span: Span,
    ) {
        let qname = self.qualname(&truncate(&name.name), 0).unwrap_or_default();
        let sym = self.insert_qualified(qname);
        let id = DefId(self.defs.len() as u32);
        self.defs.push(Def {
            sym,
            name,
            params,
            kind,
            body,
            span,
            parse_time_value: None,
        });
        let defs = &self.defs;
        let stack = &mut self.symbols[sym.0 as usize].stack;
        match kind {
            DefKind::Constant => stack.clear(),
            DefKind::Assign => {
                while stack
                    .last()
                    .is_some_and(|d| defs[d.0 as usize].kind == DefKind::Assign)
                {
                    stack.pop();
                }
            }
        }
        stack.push(id);
    }

    // ---- lowering with calexpr.c's parse-time folding ----------------------------

    fn lower(
        &mut self,
        e: &syntax::Expr,
        params: Option<&[Ident]>,
        diags: &mut Vec<Diagnostic>,
    ) -> Expr {
        let span = e.span;
        let mk = |node| Expr { node, span };
        match &e.kind {
            ExprKind::Number(v) => Expr::num(*v, span),
            ExprKind::Channel(c) => mk(Node::Chan(*c)),
            ExprKind::Paren(inner) => {
                let mut x = self.lower(inner, params, diags);
                x.span = span;
                x
            }
            ExprKind::Error => Expr::num(0.0, span),
            ExprKind::Name(id) => {
                let node = match param_index(params, &id.name) {
                    Some(i) => Node::Arg(i),
                    None => Node::Var(self.reference(id)),
                };
                self.fold_reference(mk(node), diags)
            }
            ExprKind::Call { callee, args } => {
                let callee = match param_index(params, &callee.name) {
                    Some(i) => Callee::Arg(i),
                    None => Callee::Sym(self.reference(callee)),
                };
                let args = args.iter().map(|a| self.lower(a, params, diags)).collect();
                self.fold_reference(mk(Node::Call { callee, args }), diags)
            }
            // calexpr.c getE4: a sign on a number is part of the number; -(-E) is E.
            ExprKind::Neg(inner) => {
                let x = self.lower(inner, params, diags);
                match x.node {
                    Node::Num(v) if self.fold_always_neg() => Expr::num(-v, span),
                    Node::Neg(y) => *y,
                    _ => mk(Node::Neg(Box::new(x))),
                }
            }
            ExprKind::Binary { op, lhs, rhs } => {
                let l = self.lower(lhs, params, diags);
                let r = self.lower(rhs, params, diags);
                self.fold_binary(*op, l, r, span, diags)
            }
        }
    }

    /// getE4 negates a number literal whether or not folding is on.
    fn fold_always_neg(&self) -> bool {
        true
    }

    fn fold_binary(
        &mut self,
        op: BinOp,
        l: Expr,
        r: Expr,
        span: Span,
        diags: &mut Vec<Diagnostic>,
    ) -> Expr {
        let both_num = l.as_num().is_some() && r.as_num().is_some();
        let build = |l: Expr, r: Expr| {
            let node = match op {
                BinOp::Add => Node::Sum(vec![l, r]),
                BinOp::Sub => Node::Sub(Box::new(l), Box::new(r)),
                BinOp::Mul => Node::Product(vec![l, r]),
                BinOp::Div => Node::Div(Box::new(l), Box::new(r)),
                BinOp::Pow => Node::Pow(Box::new(l), Box::new(r)),
            };
            Expr { node, span }
        };
        if !self.fold {
            return build(l, r);
        }
        if both_num {
            return self.rconst(build(l, r), diags);
        }
        let rn = r.as_num();
        let ln = l.as_num();
        match op {
            BinOp::Add => build(l, r),
            // E - NUM becomes E + (-NUM), so the constant can combine in a sum.
            BinOp::Sub => match rn {
                Some(v) => build_sum(l, Expr::num(-v, r.span), span),
                None => build(l, r),
            },
            BinOp::Mul | BinOp::Div => match (rn, ln) {
                (Some(v), _) if op == BinOp::Div => {
                    if fast_eq(v, 0.0) {
                        diags.push(
                            Diagnostic::new(
                                diagnostic::E0604,
                                r.span,
                                "division by a zero constant",
                            )
                            .with_hint("Radiance stops with 'divide by zero constant'"),
                        );
                        build(l, r)
                    } else {
                        // For speed Radiance multiplies by the reciprocal: the result
                        // can differ from a true division in the last bit.
                        Expr {
                            node: Node::Product(vec![l, Expr::num(1.0 / v, r.span)]),
                            span,
                        }
                    }
                }
                (Some(v), _) if fast_eq(v, 0.0) => r, // E * 0
                (_, Some(v)) if fast_eq(v, 0.0) => l, // 0 * E, 0 / E
                _ => build(l, r),
            },
            BinOp::Pow => {
                let is = |x: Option<f64>, c: f64| x.is_some_and(|v| fast_eq(v, c));
                if is(ln, 0.0) {
                    l // 0 ^ E
                } else if is(rn, 0.0) || is(ln, 1.0) {
                    Expr::num(1.0, span) // E ^ 0, 1 ^ E
                } else if is(rn, 1.0) {
                    l // E ^ 1
                } else {
                    build(l, r)
                }
            }
        }
    }

    /// getE5's `isconstvar` test and `rconst`: a reference to a `:` variable, or a
    /// call of a constant function with constant arguments, becomes its value.
    fn fold_reference(&mut self, e: Expr, diags: &mut Vec<Diagnostic>) -> Expr {
        if self.fold && fold::is_constant_reference(self, &e) {
            self.rconst(e, diags)
        } else {
            e
        }
    }

    /// calexpr.c `rconst`: evaluate now. An error raised while doing so is fatal in
    /// Radiance ("bad constant expression"). Expressions that need input are left.
    fn rconst(&mut self, e: Expr, diags: &mut Vec<Diagnostic>) -> Expr {
        let mut input = ParseTimeInput::default();
        let (result, errno, computed, warnings) = {
            // Folding runs on the caller's stack (an editor, a test thread): keep it
            // shallow; a deeper constant recursion is left for run time.
            let mut ev = Evaluator::new(self).with_max_depth(PARSE_TIME_MAX_DEPTH);
            let r = ev.eval_top(&e, &mut input);
            let computed: Vec<(DefId, f64)> = ev.constants_computed().collect();
            (r, ev.errno(), computed, std::mem::take(&mut ev.warnings))
        };
        for (id, v) in computed {
            if let Some(d) = self.defs.get_mut(id.0 as usize) {
                d.parse_time_value.get_or_insert(v);
            }
        }
        match result {
            Ok(v) => {
                self.parse_warnings.extend(warnings);
                if let Some(errno) = errno {
                    let what = match errno {
                        Errno::Domain => "leaves a function's domain",
                        Errno::Range => "divides by zero or overflows",
                    };
                    // In a library checked alone, a constant that read input columns
                    // got rcalc's empty first record: only a complete program knows.
                    if self.complete || !input.read {
                        diags.push(
                            Diagnostic::new(
                                diagnostic::E0604,
                                e.span,
                                format!("this constant expression {what}"),
                            )
                            .with_hint("Radiance stops with 'bad constant expression'"),
                        );
                    }
                }
                Expr::num(v, e.span)
            }
            // Past our own depth limit, or needing the renderer: left for run time.
            Err(EvalError::TooDeep(_) | EvalError::NotAvailable(_) | EvalError::NoInput) => e,
            // A name not defined yet: fatal for rcalc, which folds as it parses; in a
            // library it is a free name its user defines.
            Err(err) => {
                if self.complete {
                    diags.push(
                        Diagnostic::new(
                            diagnostic::E0701,
                            e.span,
                            format!("folding this constant fails: {err}"),
                        )
                        .with_hint(
                            "Radiance evaluates ':' constants as it reads them: define what they use first",
                        ),
                    );
                }
                e
            }
        }
    }

    // ---- names -------------------------------------------------------------------

    /// caldefn.c `varinsert` for a name as written: link to the most qualified existing
    /// symbol, else create one (library names stay unqualified).
    fn reference(&mut self, id: &Ident) -> SymId {
        let name = truncate(&id.name);
        let sym = match self.lookup(&name) {
            Some(s) => s,
            None => {
                let qualified = if self.library.contains_key(name.as_str()) {
                    name
                } else {
                    self.qualname(&name, 0).unwrap_or(name)
                };
                self.insert_qualified(qualified)
            }
        };
        let s = &mut self.symbols[sym.0 as usize];
        s.first_use.get_or_insert(id.span);
        sym
    }

    fn insert_qualified(&mut self, qname: String) -> SymId {
        if let Some(&s) = self.by_name.get(&qname) {
            return s;
        }
        let id = SymId(self.symbols.len() as u32);
        let lib = self.library.get(qname.as_str()).copied();
        self.symbols.push(Symbol {
            name: qname.clone(),
            stack: Vec::new(),
            lib,
            first_use: None,
        });
        self.by_name.insert(qname, id);
        id
    }

    /// caldefn.c `qualname`: the name at context level `lvl` (0 = fully qualified),
    /// `None` past the global level or for explicitly local/global names at lvl > 0.
    fn qualname(&self, name: &str, lvl: usize) -> Option<String> {
        if let Some(local) = name.strip_prefix(CNTXMARK) {
            if lvl > 0 {
                return None;
            }
            return Some(self.append_context(local, 0));
        }
        if let Some(global) = name.strip_suffix(CNTXMARK) {
            if lvl > 0 {
                return None;
            }
            return Some(global.to_string());
        }
        let levels = self.context.matches(CNTXMARK).count();
        if lvl > levels {
            return None;
        }
        Some(self.append_context(name, lvl))
    }

    fn append_context(&self, name: &str, skip: usize) -> String {
        let mut ctx = self.context.as_str();
        for _ in 0..skip {
            ctx = match ctx[1..].find(CNTXMARK) {
                Some(i) => &ctx[i + 1..],
                None => "",
            };
        }
        format!("{name}{ctx}")
    }

    /// caldefn.c `varlookup`: the most qualified existing symbol for a name as written.
    pub fn lookup(&self, name: &str) -> Option<SymId> {
        let name = truncate(name);
        (0..)
            .map_while(|lvl| self.qualname(&name, lvl))
            .find_map(|q| self.by_name.get(&q).copied())
    }

    // ---- queries -----------------------------------------------------------------

    pub fn symbols(&self) -> &[Symbol] {
        &self.symbols
    }

    pub fn symbol(&self, id: SymId) -> &Symbol {
        &self.symbols[id.0 as usize]
    }

    pub fn defs(&self) -> &[Def] {
        &self.defs
    }

    pub fn def(&self, id: DefId) -> &Def {
        &self.defs[id.0 as usize]
    }

    /// The definition in force for a symbol.
    pub fn current_def(&self, sym: SymId) -> Option<DefId> {
        self.symbols.get(sym.0 as usize)?.stack.last().copied()
    }

    pub fn outputs(&self) -> &BTreeMap<u32, OutputDef> {
        &self.outputs
    }

    pub fn library(&self) -> impl Iterator<Item = &LibFn> {
        self.library.values()
    }

    /// Every name a reference could resolve to: for "did you mean" hints.
    pub fn known_names(&self) -> Vec<&str> {
        let mut v: Vec<&str> = self
            .symbols
            .iter()
            .enumerate()
            .filter(|(i, s)| {
                !s.stack.is_empty()
                    || s.lib.is_some()
                    || self.host_names.contains_key(&SymId(*i as u32))
            })
            .filter(|(_, s)| !self.is_library_private(s))
            .map(|(_, s)| s.name.as_str())
            .collect();
        v.extend(self.library.keys().copied());
        v.sort_unstable();
        v.dedup();
        v
    }

    /// A helper of the built-in rayinit.cal (a qualified name defined only there):
    /// never a name to suggest to the user.
    fn is_library_private(&self, s: &Symbol) -> bool {
        s.name.contains(CNTXMARK)
            && !s.stack.is_empty()
            && s.stack
                .iter()
                .all(|d| self.defs[d.0 as usize].span.file == crate::library::RAYINIT_FILE)
    }

    /// rcalc's `doptimize(1)`: flatten `+`/`*` chains in every definition in force and
    /// every output, combining their constants when folding is on.
    pub fn optimize(&mut self) {
        let fold = self.fold;
        let tops: Vec<DefId> = self
            .symbols
            .iter()
            .filter_map(|s| s.stack.last().copied())
            .collect();
        for id in tops {
            fold::optimize(&mut self.defs[id.0 as usize].body, fold);
        }
        for o in self.outputs.values_mut() {
            fold::optimize(&mut o.body, fold);
        }
    }
}

/// The ray channels func.c binds (`Dx=$1; ...`), in RENDERER_VARIABLES's order.
const RAY_CHANNELS: &[(&str, u32)] = &[
    ("Dx", 1),
    ("Dy", 2),
    ("Dz", 3),
    ("Nx", 4),
    ("Ny", 5),
    ("Nz", 6),
    ("Px", 7),
    ("Py", 8),
    ("Pz", 9),
    ("T", 10),
    ("Ts", 25),
    ("Rdot", 11),
    ("S", 12),
    ("Tx", 13),
    ("Ty", 14),
    ("Tz", 15),
    ("Ix", 16),
    ("Iy", 17),
    ("Iz", 18),
    ("Jx", 19),
    ("Jy", 20),
    ("Jz", 21),
    ("Kx", 22),
    ("Ky", 23),
    ("Kz", 24),
    ("Lu", 26),
    ("Lv", 27),
];

/// Input columns read while parsing: rcalc has read no record yet, so its empty
/// input buffer gives 0 for every column (rcalc.c `chanvalue` on an empty line). A
/// `:` constant that reads a column is thus 0 for good, as rcalc computes it.
#[derive(Default)]
struct ParseTimeInput {
    /// A column was read: the value depends on input, so an error found while
    /// folding is a property of rcalc's empty first buffer, not of the program.
    read: bool,
}

impl Input for ParseTimeInput {
    fn column(&mut self, _: u32) -> Result<(f64, Option<Errno>), EvalError> {
        self.read = true;
        Ok((0.0, None))
    }
    fn column_count(&mut self) -> Result<f64, EvalError> {
        self.read = true;
        Ok(0.0)
    }
}

/// `==` on doubles as the reference rcalc (built with -ffast-math) compiles it in
/// calexpr.c's folding: a NaN constant compares equal to anything, so `E^sqrt(-1)`
/// folds to 1 and `E/sqrt(-1)` is "divide by zero constant" (checked against rcalc).
fn fast_eq(v: f64, c: f64) -> bool {
    v == c || v.is_nan()
}

fn build_sum(l: Expr, r: Expr, span: Span) -> Expr {
    Expr {
        node: Node::Sum(vec![l, r]),
        span,
    }
}

fn param_index(params: Option<&[Ident]>, name: &str) -> Option<u32> {
    params?
        .iter()
        .position(|p| p.name == name)
        .map(|i| i as u32 + 1)
}

fn is_id(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_' || c == '.' || c == CNTXMARK
}

fn truncate(name: &str) -> String {
    name.chars().take(MAX_NAME).collect()
}
