//! The scene's functions: the patterns that modify materials and lights, evaluated per
//! ray as Radiance's func.c and p_func.c evaluate them. Each function file a pattern
//! names becomes one [`Program`] (its module, as `lang` loaded it after rayinit.cal,
//! plus the patterns' expressions parsed in its context), compiled once per render by
//! the JIT and shared by all threads; each thread keeps its own evaluation state
//! (cached `=` values), so results never depend on the thread count.
//!
//! Only what a reachable material or light uses is compiled (`Functions` is built by
//! the scene compiler from the modifier chains it meets).

pub mod brdf;
mod channels;
mod data;
mod pattern;
mod picture;

pub use brdf::{BrdfLookup, BrtdLookup, Directional, SHADING_VARIABLES, ShadeState};
pub use channels::{Channels, RayView};
pub use data::{DataLookup, DataSource};
pub use pattern::{MixSource, Pattern, PatternKind, bounded};
pub use picture::PictureLookup;

use std::cell::RefCell;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

use radc_jit::compile::Entry;
use radc_jit::{Compiled, Context, Jit};
use radc_lang::cal::Module;
use radc_lang::cal::eval::{EvalError, Evaluator, Input, MathErrors, Warning};
use radc_lang::cal::ir::Expr;

/// Which evaluator runs the functions: the JIT, or the reference interpreter (which
/// gives the same values bit for bit; a test renders with both).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Engine {
    #[default]
    Jit,
    Interpreter,
}

/// One function file and the expressions evaluated in its context.
pub struct Program {
    pub file: String,
    module: Module,
    exprs: Vec<Expr>,
    compiled: Option<Compiled>,
    /// The compiled entry of each expression (`#k`), looked up once.
    entries: Vec<Entry>,
}

/// Index of a [`Program`] in [`Functions`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProgramId(pub u32);

/// Every program and pattern a render uses.
pub struct Functions {
    id: u64,
    engine: Engine,
    pub programs: Vec<Program>,
    pub patterns: Vec<Pattern>,
    /// Warnings (once each) and errors met while rendering, for the front end to print.
    messages: Mutex<Messages>,
    /// How long [`Functions::compile`] took.
    pub compile_time: std::time::Duration,
}

#[derive(Default)]
struct Messages {
    warned: std::collections::HashSet<(u32, String)>,
    lines: Vec<String>,
    failed: bool,
}

static NEXT_ID: AtomicU64 = AtomicU64::new(1);

thread_local! {
    /// Per thread, per program (by index): the JIT's evaluation state, and the
    /// [`Functions`] it belongs to.
    static CONTEXTS: RefCell<Vec<Option<(u64, Context)>>> = const { RefCell::new(Vec::new()) };
}

impl std::fmt::Debug for Functions {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Functions")
            .field("programs", &self.programs.len())
            .field("patterns", &self.patterns.len())
            .finish()
    }
}

impl Functions {
    pub fn new() -> Functions {
        Functions {
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
            engine: Engine::Jit,
            programs: Vec::new(),
            patterns: Vec::new(),
            messages: Mutex::new(Messages::default()),
            compile_time: std::time::Duration::ZERO,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.patterns.is_empty()
    }

    /// The program for function file `file`, made from `module` the first time.
    pub fn program(&mut self, file: &str, module: &Module) -> ProgramId {
        if let Some(i) = self.programs.iter().position(|p| p.file == file) {
            return ProgramId(i as u32);
        }
        self.programs.push(Program {
            file: file.to_string(),
            module: module.clone(),
            exprs: Vec::new(),
            compiled: None,
            entries: Vec::new(),
        });
        ProgramId(self.programs.len() as u32 - 1)
    }

    /// Parses `text` as an expression in program `p`'s context; its index there.
    pub fn add_expression(&mut self, p: ProgramId, text: &str) -> Result<usize, String> {
        let program = self
            .programs
            .get_mut(p.0 as usize)
            .ok_or_else(|| "no such program".to_string())?;
        let e = program
            .module
            .add_expression(radc_lang::FileId(u32::MAX - 1), text)
            .map_err(|d| {
                d.first()
                    .map_or_else(|| format!("bad expression '{text}'"), |d| d.message.clone())
            })?;
        if let Some(problem) = unavailable(&program.module, &e) {
            return Err(problem);
        }
        program.exprs.push(e);
        Ok(program.exprs.len() - 1)
    }

    /// Compiles every program (call once all expressions are in). A program the JIT
    /// declines runs on the interpreter.
    pub fn compile(&mut self, engine: Engine) -> std::time::Duration {
        let start = std::time::Instant::now();
        self.engine = engine;
        if engine == Engine::Jit {
            for p in &mut self.programs {
                let exprs: Vec<&Expr> = p.exprs.iter().collect();
                p.compiled = Jit::new()
                    .with_policy(MathErrors::ErrnoOnly)
                    .compile_with_expressions(&p.module, &[], &exprs)
                    .ok();
                let entries: Option<Vec<Entry>> = p.compiled.as_ref().and_then(|c| {
                    (0..p.exprs.len())
                        .map(|k| c.entry(&format!("#{k}")))
                        .collect()
                });
                match entries {
                    Some(e) => p.entries = e,
                    None => p.compiled = None,
                }
            }
        }
        self.compile_time = start.elapsed();
        self.compile_time
    }

    /// Definitions the JIT compiled, over all programs: only what the patterns'
    /// expressions reach (of rayinit.cal's and each file's definitions).
    pub fn compiled_definitions(&self) -> usize {
        self.programs
            .iter()
            .filter_map(|p| p.compiled.as_ref())
            .map(Compiled::function_count)
            .sum()
    }

    /// Definitions the programs' modules hold in all.
    pub fn loaded_definitions(&self) -> usize {
        self.programs.iter().map(|p| p.module.defs().len()).sum()
    }

    /// Evaluates expressions `exprs` of program `p` for one (primitive, ray): the
    /// `=` cache starts afresh (func.c `setfunc` ticks the clock whenever the object or
    /// the ray changes). `None` when an evaluation raised `errno` (p_func.c: "compute
    /// error", the pattern is not applied) or failed.
    pub fn eval(
        &self,
        pattern: u32,
        p: ProgramId,
        exprs: &[usize],
        input: &mut RayInput<'_>,
        out: &mut [f64],
    ) -> Option<()> {
        let program = self.programs.get(p.0 as usize)?;
        let (result, warnings) = match (&program.compiled, self.engine) {
            (Some(compiled), Engine::Jit) => CONTEXTS.with(|c| {
                let mut slots = c.borrow_mut();
                let i = p.0 as usize;
                if slots.len() <= i {
                    slots.resize_with(i + 1, || None);
                }
                let slot = &mut slots[i];
                if slot.as_ref().is_none_or(|(id, _)| *id != self.id) {
                    *slot = Some((self.id, compiled.context()));
                }
                let Some((_, ctx)) = slot.as_mut() else {
                    return (Err(EvalError::NotAvailable("context".into())), Vec::new());
                };
                ctx.next_record();
                let mut result = Ok(());
                for (slot, &k) in out.iter_mut().zip(exprs) {
                    let entry = program.entries.get(k).copied();
                    match entry.map(|e| compiled.eval(e, ctx, input)) {
                        Some(Ok(v)) => *slot = v,
                        Some(Err(e)) => {
                            result = Err(e);
                            break;
                        }
                        None => {
                            result = Err(EvalError::NotAvailable(format!("#{k}")));
                            break;
                        }
                    }
                }
                let warnings = if ctx.has_warnings() {
                    ctx.take_warnings()
                } else {
                    Vec::new()
                };
                (result, warnings)
            }),
            _ => {
                let mut ev = Evaluator::new(&program.module).with_policy(MathErrors::ErrnoOnly);
                ev.next_record();
                let mut result = Ok(());
                for (slot, &k) in out.iter_mut().zip(exprs) {
                    match program.exprs.get(k).map(|e| ev.eval_top(e, input)) {
                        Some(Ok(v)) => *slot = v,
                        Some(Err(e)) => {
                            result = Err(e);
                            break;
                        }
                        None => break,
                    }
                }
                (result, std::mem::take(&mut ev.warnings))
            }
        };
        let raised = warnings
            .iter()
            .any(|w| !matches!(w, Warning::Depth(..) | Warning::NonConstant(_)));
        for w in &warnings {
            self.warn(pattern, &w.to_string());
        }
        match result {
            Err(e) => {
                self.fail(pattern, &e.to_string());
                None
            }
            Ok(()) if raised => {
                self.warn(pattern, "compute error");
                None
            }
            Ok(()) => Some(()),
        }
    }

    fn warn(&self, pattern: u32, what: &str) {
        let mut m = self.messages.lock().unwrap_or_else(|e| e.into_inner());
        if m.warned.insert((pattern, what.to_string())) {
            let who = self.patterns.get(pattern as usize).map_or("", |p| &p.who);
            m.lines.push(format!("warning - {who}: {what}"));
        }
    }

    fn fail(&self, pattern: u32, what: &str) {
        self.warn(pattern, what);
        self.messages
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .failed = true;
    }

    /// Messages met so far (each once), and whether an evaluation failed outright
    /// (Radiance stops there; radc finishes the picture and reports it).
    pub fn take_messages(&self) -> (Vec<String>, bool) {
        let mut m = self.messages.lock().unwrap_or_else(|e| e.into_inner());
        (std::mem::take(&mut m.lines), m.failed)
    }
}

impl Default for Functions {
    fn default() -> Self {
        Functions::new()
    }
}

/// The renderer functions radc evaluates (the rest are refused at compile time):
/// `arg` here, the pure ones in `lang::cal::renderer_math`. (noise3.c also caches the
/// last point, which only shows for NaN coordinates; that cache is not kept here.)
const AVAILABLE: &[&str] = &[
    "arg", "noise3", "noise3x", "noise3y", "noise3z", "fnoise3", "erf", "erfc",
];

/// Why evaluating `e` cannot work: a name it reaches that nothing defines, or a
/// renderer function radc does not evaluate yet.
fn unavailable(module: &Module, e: &Expr) -> Option<String> {
    use radc_lang::cal::builtins::LibFn;
    let mut refs = Vec::new();
    e.symbols(&mut refs);
    for d in radc_lang::cal::deps::needed_by_expr(module, e) {
        module.def(d).body.symbols(&mut refs);
    }
    for (s, _) in refs {
        let sym = module.symbol(s);
        if !sym.stack.is_empty() {
            continue;
        }
        match sym.lib {
            Some(LibFn::Renderer(r)) if !AVAILABLE.contains(&r.name) => {
                return Some(format!("the function {}() is not evaluated yet", r.name));
            }
            Some(_) => {}
            // Ray channels are definitions (`Dx = $1`) and never get here; the
            // per-shade variables of *func materials (`NxP`, `CrP`, ...) do.
            None if module.host_name(s).is_some() => {
                return Some(format!("the variable {} is not set yet", sym.name));
            }
            None => return Some(format!("'{}' is not defined", sym.name)),
        }
    }
    None
}

/// What a function evaluated for one primitive and ray reads: the ray channels, the
/// primitive's real arguments, and (for the function a data pattern applies) the
/// values found in its data, as channels after the ray's.
pub struct RayInput<'a> {
    pub channels: &'a Channels,
    pub args: &'a [f64],
    pub data: &'a [f64],
}

impl Input for RayInput<'_> {
    fn column(&mut self, n: u32) -> Result<(f64, Option<radc_lang::cal::eval::Errno>), EvalError> {
        self.channels
            .get(n)
            .or_else(|| {
                n.checked_sub(data::DATA_CHANNEL)
                    .and_then(|i| self.data.get(i as usize).copied())
            })
            .map(|v| (v, None))
            .ok_or(EvalError::IllegalChannel)
    }

    fn column_count(&mut self) -> Result<f64, EvalError> {
        Ok(channels::COUNT as f64)
    }

    fn renderer_function(&mut self, name: &'static str, args: &[f64]) -> Result<f64, EvalError> {
        match name {
            // func.c `l_arg`: argument n, rounded; 0 gives the count.
            "arg" => {
                let x = args.first().copied().unwrap_or(0.0);
                let n = (x + 0.5) as i64;
                if n == 0 {
                    return Ok(self.args.len() as f64);
                }
                usize::try_from(n - 1)
                    .ok()
                    .and_then(|i| self.args.get(i))
                    .copied()
                    .ok_or_else(|| EvalError::NotAvailable("missing real argument".into()))
            }
            _ => radc_lang::cal::renderer_math::call(name, args)
                .ok_or_else(|| EvalError::NotAvailable(name.to_string())),
        }
    }
}
