//! The compiler driver: decides which functions to generate (only what the entry
//! points reach), declares them in a `JITModule`, lowers each one (`lower.rs`) and
//! links the result.

use super::JitError;
use super::host;
use super::layout::Cached;
use super::lower::Lower;
use cranelift_codegen::ir;
use cranelift_codegen::ir::{AbiParam, Function, Signature, UserFuncName, types};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Linkage, Module as _, default_libcall_names};
use radc_lang::cal::eval::MathErrors;
use radc_lang::cal::ir::{Callee, DefId, Expr, Node, SymId};
use radc_lang::cal::syntax::DefKind;
use radc_lang::cal::{Module, deps};
use std::collections::{HashMap, HashSet};

/// Beyond these the program is left to the interpreter: the lowering recurses once
/// per nesting level, and huge functions take long to compile for little gain.
pub const MAX_NESTING: usize = 1000;
pub const MAX_NODES: usize = 2_000_000;

/// User functions up to this many expression nodes (callees they inline counted in)
/// are inlined at their call sites instead of called: no argument block, no thunks,
/// no indirect calls, and the optimiser sees through them.
pub const INLINE_NODES: usize = 160;

/// `=` variables up to this many nodes are inlined at their uses, up to
/// [`INLINE_VAR_NESTING`] variables within each other.
pub const INLINE_VAR_NODES: usize = 48;
pub const INLINE_VAR_NESTING: usize = 6;

/// What inlining may add to a whole program, in expression nodes: every inlined
/// call or variable body is charged its size (a function with the callees it
/// inlines), first come first served, and once the budget is spent calls and
/// variable reads are generated as calls. Inlining is cheap to compile where few
/// definitions are reached; without a bound, chains of variables used in many
/// branches (xyz_rgb.cal's `select` over nine expressions of the same derived
/// constants) were inlined again in every branch of every function, and took 2 s to
/// compile.
pub const INLINE_BUDGET: usize = 1000;

/// One function to generate.
pub enum Job<'m> {
    /// `dvalue` for a variable definition: cached per record, or once for `:`.
    Var(DefId),
    /// A user function with the uniform `(ctx, block) -> f64` signature.
    Func(DefId),
    /// One argument expression of a call, evaluated in the context of `owner`'s
    /// activation (or at top level).
    Thunk {
        id: FuncId,
        expr: &'m Expr,
        owner: Option<DefId>,
    },
    /// A requested entry point: `(ctx) -> f64`.
    Entry { id: FuncId, what: EntryBody<'m> },
}

#[derive(Clone, Copy)]
pub enum EntryBody<'m> {
    Variable(SymId),
    Output(&'m Expr),
    /// Several outputs in order, each stored at `Raw::out` as it is computed.
    Outputs(&'m [&'m Expr]),
}

/// What the lowering needs to know and may add to while it runs.
pub struct State<'m> {
    pub module: &'m Module,
    pub jit: JITModule,
    pub ptr: ir::Type,
    pub sig_var: Signature,
    pub sig_uniform: Signature,
    /// Thunks: `(ctx, caller's block, slot) -> f64`.
    pub sig_thunk: Signature,
    pub policy: MathErrors,
    pub warn_nonconstant: bool,
    pub imports: HashMap<&'static str, FuncId>,
    pub var_fns: HashMap<DefId, (FuncId, u32)>,
    pub var_slots: HashMap<DefId, u32>,
    /// Every definition whose body was generated, as a function or inlined.
    pub compiled_defs: HashSet<DefId>,
    pub user_fns: HashMap<DefId, FuncId>,
    pub host_vars: HashMap<DefId, u32>,
    /// Initial cache contents, by cache index.
    pub cache_init: Vec<Cached>,
    /// Definitions whose arguments may be called or passed on as functions.
    pub uses_fn_values: HashMap<DefId, bool>,
    /// Thunks of simple arguments, by context and (kind, number).
    pub thunks: HashMap<(Option<DefId>, (u8, u32)), FuncId>,
    /// Inlined size of user functions, `None` for those never inlined.
    pub inline_costs: HashMap<DefId, Option<usize>>,
    /// Nodes inlining may still add to the program (see [`INLINE_BUDGET`]).
    pub inline_budget: usize,
    /// Cranelift instructions generated so far (before optimisation), for
    /// [`super::Compiled::instruction_count`].
    pub instructions: usize,
    pub queue: Vec<Job<'m>>,
}

impl<'m> State<'m> {
    pub fn new(module: &'m Module, policy: MathErrors) -> Result<Self, JitError> {
        let mut flags = settings::builder();
        let set = |f: &mut settings::Builder, k: &str, v: &str| {
            f.set(k, v).map_err(|e| JitError::Backend(e.to_string()))
        };
        set(&mut flags, "opt_level", "speed")?;
        set(&mut flags, "use_colocated_libcalls", "false")?;
        set(&mut flags, "is_pic", "false")?;
        // The verifier in debug builds, or when asked for (to check the generated
        // code in release test runs).
        let verify = cfg!(debug_assertions) || super::inspect::current().verify;
        set(
            &mut flags,
            "enable_verifier",
            if verify { "true" } else { "false" },
        )?;
        let isa = cranelift_native::builder()
            .map_err(|e| JitError::Backend(e.to_string()))?
            .finish(settings::Flags::new(flags))
            .map_err(|e| JitError::Backend(e.to_string()))?;
        let mut builder = JITBuilder::with_isa(isa, default_libcall_names());
        for (name, ptr) in host::symbols() {
            builder.symbol(name, ptr);
        }
        let mut jit = JITModule::new(builder);
        let ptr = jit.target_config().pointer_type();
        let sig = |params: &[ir::Type], ret: Option<ir::Type>| {
            let mut s = jit.make_signature();
            s.params.extend(params.iter().map(|&t| AbiParam::new(t)));
            s.returns.extend(ret.map(AbiParam::new));
            s
        };
        let sig_var = sig(&[ptr], Some(types::F64));
        let sig_uniform = sig(&[ptr, ptr], Some(types::F64));
        let sig_thunk = sig(&[ptr, ptr, ptr], Some(types::F64));
        let f64_1 = sig(&[types::F64], Some(types::F64));
        let imports_sigs: Vec<(&'static str, Signature)> = vec![
            ("radc_pow", sig(&[types::F64, types::F64], Some(types::F64))),
            (
                "radc_atan2",
                sig(&[types::F64, types::F64], Some(types::F64)),
            ),
            ("radc_acos", f64_1.clone()),
            ("radc_asin", f64_1.clone()),
            ("radc_atan", f64_1.clone()),
            ("radc_cos", f64_1.clone()),
            ("radc_exp", f64_1.clone()),
            ("radc_log", f64_1.clone()),
            ("radc_log10", f64_1.clone()),
            ("radc_rand", f64_1.clone()),
            ("radc_sin", f64_1.clone()),
            ("radc_tan", f64_1),
            ("radc_warn", sig(&[ptr, types::I32, types::I32], None)),
            ("radc_fail", sig(&[ptr, types::I32, types::I32], None)),
            ("radc_depth", sig(&[ptr, types::I32, types::I64], None)),
            ("radc_chan", sig(&[ptr, types::I32], Some(types::F64))),
            ("radc_in", sig(&[ptr, types::F64], Some(types::F64))),
            (
                "radc_renderer_fn",
                sig(
                    &[ptr, types::I32, types::F64, types::F64, types::F64],
                    Some(types::F64),
                ),
            ),
            ("radc_fnval", sig(&[ptr, ptr, types::I64], Some(types::F64))),
            ("radc_chan_thunk", sig_thunk.clone()),
        ];
        let mut imports = HashMap::new();
        for (name, s) in imports_sigs {
            let id = jit
                .declare_function(name, Linkage::Import, &s)
                .map_err(|e| JitError::Backend(e.to_string()))?;
            imports.insert(name, id);
        }
        Ok(State {
            module,
            jit,
            ptr,
            sig_var,
            sig_uniform,
            sig_thunk,
            policy,
            warn_nonconstant: module.folds(),
            imports,
            var_fns: HashMap::new(),
            var_slots: HashMap::new(),
            compiled_defs: HashSet::new(),
            user_fns: HashMap::new(),
            host_vars: HashMap::new(),
            cache_init: Vec::new(),
            uses_fn_values: HashMap::new(),
            thunks: HashMap::new(),
            inline_costs: HashMap::new(),
            inline_budget: INLINE_BUDGET,
            instructions: 0,
            queue: Vec::new(),
        })
    }

    /// The cached-variable function of a definition, declared on first use.
    pub fn var_fn(&mut self, def: DefId) -> Result<(FuncId, u32), JitError> {
        if let Some(&f) = self.var_fns.get(&def) {
            return Ok(f);
        }
        let id = self
            .jit
            .declare_anonymous_function(&self.sig_var)
            .map_err(|e| JitError::Backend(e.to_string()))?;
        let slot = self.var_slot(def);
        self.var_fns.insert(def, (id, slot));
        self.queue.push(Job::Var(def));
        Ok((id, slot))
    }

    /// The cache slot of a variable definition, allocated on first use (a variable
    /// whose body is inlined at every use needs a slot but no function).
    pub fn var_slot(&mut self, def: DefId) -> u32 {
        if let Some(&s) = self.var_slots.get(&def) {
            return s;
        }
        let slot = self.cache_init.len() as u32;
        let d = self.module.def(def);
        self.cache_init.push(match d.parse_time_value {
            Some(value) => Cached {
                tick: super::layout::FOREVER,
                value,
            },
            None => Cached::default(),
        });
        self.var_slots.insert(def, slot);
        slot
    }

    /// The size of a variable's body if it is small enough to inline at its uses
    /// (the freshness test and the caching stay; see `Lower::inline_variable`).
    pub fn var_inline_size(&self, def: DefId) -> Option<usize> {
        let d = self.module.def(def);
        if d.kind != DefKind::Assign || self.host_vars.contains_key(&def) {
            return None;
        }
        let mut nodes = 0;
        let mut stack = vec![&d.body];
        while let Some(e) = stack.pop() {
            nodes += 1;
            if nodes > INLINE_VAR_NODES {
                return None;
            }
            stack.extend(e.children());
        }
        Some(nodes)
    }

    /// Take `nodes` from the program's inlining budget; false (taking nothing) if
    /// that much is not left.
    pub fn charge_inline(&mut self, nodes: usize) -> bool {
        match self.inline_budget.checked_sub(nodes) {
            Some(left) => {
                self.inline_budget = left;
                true
            }
            None => false,
        }
    }

    /// The uniform function of a user function definition, declared on first use.
    pub fn user_fn(&mut self, def: DefId) -> Result<FuncId, JitError> {
        if let Some(&f) = self.user_fns.get(&def) {
            return Ok(f);
        }
        let id = self
            .jit
            .declare_anonymous_function(&self.sig_uniform)
            .map_err(|e| JitError::Backend(e.to_string()))?;
        self.user_fns.insert(def, id);
        self.queue.push(Job::Func(def));
        Ok(id)
    }

    pub fn thunk(&mut self, expr: &'m Expr, owner: Option<DefId>) -> Result<FuncId, JitError> {
        // One thunk serves every call argument that is the same column, variable or
        // parameter in the same context: fewer functions to compile.
        let key = match expr.node {
            Node::Var(s) => Some((1u8, s.0)),
            Node::Arg(n) => Some((2, n)),
            _ => None,
        };
        if let Some(k) = key
            && let Some(&id) = self.thunks.get(&(owner, k))
        {
            return Ok(id);
        }
        let id = self
            .jit
            .declare_anonymous_function(&self.sig_thunk)
            .map_err(|e| JitError::Backend(e.to_string()))?;
        self.queue.push(Job::Thunk { id, expr, owner });
        if let Some(k) = key {
            self.thunks.insert((owner, k), id);
        }
        Ok(id)
    }

    /// Whether calls of a user function can be inlined: it is not recursive (not
    /// even through other functions), never calls through a parameter, every user
    /// function it calls is inlined too (so inlined code never builds an argument
    /// block that would need thunks for its parameters), and all that is small.
    pub fn inline_size(&mut self, def: DefId) -> Option<usize> {
        self.inline_cost(def, &mut Vec::new())
    }

    fn inline_cost(&mut self, def: DefId, visiting: &mut Vec<DefId>) -> Option<usize> {
        if let Some(&c) = self.inline_costs.get(&def) {
            return c;
        }
        if visiting.contains(&def) {
            // A cycle: every function on it is recursive, and so never inlined.
            return None;
        }
        visiting.push(def);
        let module = self.module;
        let mut cost = 0usize;
        let mut ok = true;
        let mut stack = vec![&module.def(def).body];
        while let Some(e) = stack.pop() {
            cost += 1;
            if let Node::Call { callee, .. } = &e.node {
                let inlined = match callee {
                    Callee::Arg(_) => None,
                    Callee::Sym(s) => match module
                        .current_def(*s)
                        .filter(|&d| module.def(d).is_function())
                    {
                        Some(d) => self.inline_cost(d, visiting),
                        None => Some(0),
                    },
                };
                match inlined {
                    Some(k) => cost += k,
                    None => ok = false,
                }
            }
            if !ok || cost > INLINE_NODES {
                ok = false;
                break;
            }
            stack.extend(e.children());
        }
        visiting.pop();
        let cost = ok.then_some(cost);
        self.inline_costs.insert(def, cost);
        cost
    }

    /// Whether a function's parameters can be called, or passed on to a call, as
    /// function values: only then must its callers fill in the slots' function parts.
    pub fn uses_fn_values(&mut self, def: DefId) -> bool {
        if let Some(&u) = self.uses_fn_values.get(&def) {
            return u;
        }
        let mut uses = false;
        let mut stack = vec![&self.module.def(def).body];
        while let Some(e) = stack.pop() {
            if let Node::Call { callee, args } = &e.node {
                // Library calls are inlined and never see function values; a user
                // function may be handed a parameter and call it.
                let user = match callee {
                    Callee::Arg(_) => true,
                    Callee::Sym(s) => self
                        .module
                        .current_def(*s)
                        .is_some_and(|d| self.module.def(d).is_function()),
                };
                uses |= matches!(callee, Callee::Arg(_))
                    || (user && args.iter().any(|a| matches!(a.node, Node::Arg(_))));
            }
            stack.extend(e.children());
        }
        self.uses_fn_values.insert(def, uses);
        uses
    }
}

/// The size and nesting of everything the entries reach, refused past the limits.
pub fn check_size(
    module: &Module,
    roots: &[&Expr],
    defs: &[DefId],
    (max_nodes, max_nesting): (usize, usize),
) -> Result<(), JitError> {
    let mut nodes = 0usize;
    let mut stack: Vec<(&Expr, usize)> = roots.iter().map(|e| (*e, 1)).collect();
    stack.extend(defs.iter().map(|&d| (&module.def(d).body, 1)));
    while let Some((e, depth)) = stack.pop() {
        nodes += 1;
        if depth > max_nesting {
            return Err(JitError::TooLarge(format!(
                "expression nested deeper than {max_nesting} levels"
            )));
        }
        if nodes > max_nodes {
            return Err(JitError::TooLarge(format!(
                "more than {max_nodes} expression nodes"
            )));
        }
        stack.extend(e.children().into_iter().map(|c| (c, depth + 1)));
    }
    Ok(())
}

/// The definitions the roots reach, for the size check (the functions themselves are
/// declared on demand while lowering, which reaches exactly these).
pub fn reachable(module: &Module, roots: &[&Expr], syms: &[SymId]) -> Vec<DefId> {
    let mut set = deps::needed(module, syms);
    for e in roots {
        set.extend(deps::needed_by_expr(module, e));
    }
    set.into_iter().collect()
}

/// Generate every queued function, and whatever they queue in turn.
pub fn drain(state: &mut State<'_>) -> Result<(), JitError> {
    let mut ctx = state.jit.make_context();
    let mut fctx = FunctionBuilderContext::new();
    while let Some(job) = state.queue.pop() {
        let (id, sig) = match &job {
            Job::Var(d) => (state.var_fns[d].0, state.sig_var.clone()),
            Job::Func(d) => (state.user_fns[d], state.sig_uniform.clone()),
            Job::Thunk { id, .. } => (*id, state.sig_thunk.clone()),
            Job::Entry { id, .. } => (*id, state.sig_var.clone()),
        };
        ctx.func = Function::with_name_signature(UserFuncName::user(0, id.as_u32()), sig);
        {
            let b = FunctionBuilder::new(&mut ctx.func, &mut fctx);
            Lower::build(b, state, job)?;
        }
        state.instructions += ctx.func.dfg.num_insts();
        let inspection = super::inspect::current();
        if inspection.listing.is_some() {
            ctx.set_disasm(true);
        }
        state
            .jit
            .define_function(id, &mut ctx)
            .map_err(|e| JitError::Backend(format!("{e:?}")))?;
        if let Some(dir) = &inspection.code_dir
            && let Some(c) = ctx.compiled_code()
        {
            let _ = std::fs::write(dir.join(format!("f{}.bin", id.as_u32())), c.code_buffer());
        }
        if let Some(listing) = inspection.listing {
            listing(&ctx.func.display().to_string());
            if let Some(c) = ctx.compiled_code() {
                listing(&c.vcode.clone().unwrap_or_default());
            }
        }
        state.jit.clear_context(&mut ctx);
    }
    Ok(())
}

/// A `:`-or-`=` variable's cache freshness rule, shared by the lowering.
pub fn is_constant(module: &Module, def: DefId) -> bool {
    module.def(def).kind == DefKind::Constant
}
