//! The JIT against the reference interpreter, on hand-picked programs that exercise
//! each rule of calcomp's evaluation: same values to the bit, same warnings in the
//! same order, same fatal errors.

use radc_jit::interp::{Interpreter, Outputs, Record};
use radc_jit::{Error, JitProgram, RecordEngine};
use radc_lang::FileId;
use radc_lang::cal::eval::MathErrors;
use radc_lang::cal::{Env, Module};

type Run = Vec<(Result<Option<Outputs>, Error>, Vec<String>, Outputs)>;

fn module(src: &str, fold: bool) -> Module {
    let mut m = Module::new(&Env::rcalc());
    m.set_folding(fold);
    let d = m.add_source(FileId(0), src);
    assert!(d.iter().all(|d| !d.is_error()), "{src}: {d:?}");
    for name in ["recno", "outno"] {
        if m.lookup(name).is_some() {
            m.set_variable(name, 0.0);
        }
    }
    if fold {
        m.optimize();
    }
    m
}

fn drive(engine: &mut dyn RecordEngine, rows: &[&str]) -> Run {
    let mut out = Vec::new();
    if rows.is_empty() {
        let r = engine.single().map(Some);
        out.push((r, warnings(engine), engine.take_partial()));
    }
    for row in rows {
        let mut rec = Record::new(row, '\t');
        let r = engine.record(&mut rec);
        let failed = r.is_err();
        out.push((r, warnings(engine), engine.take_partial()));
        if failed {
            break;
        }
    }
    out
}

fn warnings(engine: &mut dyn RecordEngine) -> Vec<String> {
    engine
        .take_warnings()
        .iter()
        .map(|w| w.to_string())
        .collect()
}

fn bits(run: &Run) -> Vec<String> {
    run.iter()
        .map(|(r, w, p)| {
            let vals = |o: &Outputs| {
                o.iter()
                    .map(|(c, v)| {
                        // rcalc prints a NaN's sign (`-nan`), not its payload.
                        if v.is_nan() {
                            let sign = if v.is_sign_negative() { "-" } else { "+" };
                            format!("{c}:{sign}nan")
                        } else {
                            format!("{c}:{:016x}", v.to_bits())
                        }
                    })
                    .collect::<Vec<_>>()
                    .join(" ")
            };
            let r = match r {
                Ok(Some(o)) => vals(o),
                Ok(None) => "filtered".into(),
                Err(e) => format!("error {e}"),
            };
            format!("{r} | {w:?} | {}", vals(p))
        })
        .collect()
}

/// Deep recursion is legal calcomp: give both engines a large stack, as `radc calc` does.
fn agree(src: &str, rows: &[&str]) {
    agree_with(src, rows, MathErrors::default());
}

fn agree_with(src: &str, rows: &[&str], policy: MathErrors) {
    let src = src.to_string();
    let rows: Vec<String> = rows.iter().map(|r| r.to_string()).collect();
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(move || {
            let rows: Vec<&str> = rows.iter().map(String::as_str).collect();
            agree_here(&src, &rows, policy)
        })
        .expect("thread")
        .join()
        .expect("agree");
}

fn agree_here(src: &str, rows: &[&str], policy: MathErrors) {
    for fold in [true, false] {
        let m = module(src, fold);
        let mut interp = Interpreter::new(&m, policy).expect("interpreter");
        let expected = bits(&drive(&mut interp, rows));
        let mut jit = JitProgram::new(&m, policy).expect("jit");
        jit.set_stack_budget(128 << 20);
        let got = bits(&drive(&mut jit, rows));
        assert_eq!(got, expected, "program {src:?} (fold {fold})");
    }
}

#[test]
fn arithmetic() {
    agree(
        "$1=$1+$2*3-$2/7;$2=-$1^2;$3=$1/$2;$4=-$1+-$1;$5=$1*$2*$1",
        &["1\t2", "0\t0", "-0\t5", "3.5\t-2", "1e308\t1e308", "x\ty"],
    );
}

#[test]
fn division_and_power_errors() {
    agree(
        "$1=1/$1;$2=max(1/$1,5);$3=1+1/$1;$4=(-8)^(1/3)+$1;$5=$1^0.5;$6=sqrt(1/$1+2^2)",
        &["0", "2", "-4"],
    );
}

#[test]
fn library_functions() {
    agree(
        "$1=sin($1)+cos($2)+tan($1);$2=atan2($1,$2);$3=floor($1)+ceil($2);$4=sqrt($1);\
         $5=exp($1)+log($2)+log10($2);$6=asin($1)+acos($2)+atan($1);$7=rand($1)",
        &["0.5\t2", "-1\t0", "3\t-2", "0\t0"],
    );
}

#[test]
fn if_select_min_max() {
    agree(
        "$1=if($1,1/$2,2);$2=select($1,10,20,30);$3=select(0,1,2,3);$4=max($1,$2,3);\
         $5=min($2,$1);$6=max(sqrt(-1),5);$7=max(5,sqrt(-1));$8=select($1-0.6,1,2)",
        &["1\t0", "2\t3", "-1\t1", "3\t1", "0.5\t1", "4\t2"],
    );
}

#[test]
fn variables_are_cached_per_record() {
    agree(
        "z=$1; a=1/z; b : 3*4; c=a+b; $1=a; $2=sqrt(a+4); $3=c*c; $4=recno; $5=outno",
        &["0", "2", "0", "4"],
    );
}

#[test]
fn cond_filters() {
    agree(
        "cond=$1-1; $1=$1; $2=recno; $3=outno",
        &["1", "2", "0", "3"],
    );
}

#[test]
fn user_functions_and_recursion() {
    agree(
        "fact(n)=if(n,n*fact(n-1),1); fib(n)=if(n-1,fib(n-1)+fib(n-2),1); sq(x)=x*x;\
         f(x,y)=sq(x)+y; $1=fact($1); $2=fib($1); $3=f($1,$2); $4=f($1)",
        &["5\t1", "10\t2", "0\t0"],
    );
}

#[test]
fn lazy_arguments() {
    // The unused argument is never evaluated: no warning, no error.
    agree(
        "f(a,b)=if(a,a,b); g(x)=x+x; $1=f($1,1/$2); $2=f($1,nosuch); $3=g(1/$2)",
        &["1\t0", "0\t2"],
    );
    agree("f(a,b)=if(a,a,b); $1=f($1,nosuch)", &["0"]);
}

#[test]
fn errno_timing_follows_call_by_need() {
    agree(
        "f(x)=sqrt(x*0+4); g(x)=max(x,1); h(x,y)=x+sqrt(y); $1=f(1/$1); $2=g(1/$1); $3=h(1/$1,4)",
        &["0", "1"],
    );
    // An input column that overflows sets ERANGE when the callee reads it.
    agree(
        "f(x)=sqrt(x); g(x,y)=max(y,x); $1=f($1); $2=g($1,$2); $3=f($2)+in(1)",
        &["1e999\t2", "4\t-1e999"],
    );
    // Straight-line code between a library call's clearing of errno and its test:
    // only a column read (first or again), a division by zero or a nested
    // error can raise it; the C library itself never does.
    agree(
        "$1=sin(cos($1)*2+1);$2=cos(sin($2)+$1);$3=tan(sin(1/$1)+cos(2));\
         $4=atan2(sin($2),cos($1)*3)+exp(cos(0*$1));$5=sin(cos($2)+select($1,1,2))",
        &["1e999\t2", "1\t-1e999", "0\t0", "2\t1", "3\t1e999"],
    );
}

#[test]
fn functions_as_arguments() {
    agree(
        "apply(f,x)=f(x); twice(f,x)=f(f(x)); sq(x)=x*x; pass(f,x)=apply(f,x);\
         $1=apply(sq,$1); $2=twice(sq,$1); $3=apply(sin,$1); $4=pass(sqrt,$1);\
         $5=apply(max,$1); $6=twice(if,$1)",
        &["2", "3"],
    );
    agree("apply(f,x)=f(x); $1=apply(3,$1)", &["2"]);
    agree("apply(f,x)=f(x); $1=apply(nosuch,$1)", &["2"]);
    agree("apply(f,x)=f(x); $1=apply($1)", &["2"]);
    agree("call(f)=f(1); pass(g,h)=call(h); $1=pass(1)", &["2"]);
    agree("v=3; apply(f,x)=f(x); $1=apply(v,$1)", &["2"]);
}

#[test]
fn fatal_errors() {
    agree("$1=1;$2=nosuch;$3=3", &["1"]);
    agree("$1=nosuch(2)", &["1"]);
    agree("f(x)=x; $1=f", &["1"]);
    agree("f(a,b)=b; $1=f(1)", &["1"]);
    agree("$1=atan2(1)", &["1"]);
    agree("$1=if(-1,5)", &["1"]);
    agree("$1=noise3(1,2,3)", &["1"]);
    agree("$1=$1", &[]);
}

#[test]
fn input_columns() {
    agree(
        "$1=in(0);$2=in(2);$3=$3;$4=in(-1)",
        &["1 2 3", "4\t5\t6", ""],
    );
    agree("$1=$40+$2", &["1\t2"]);
}

#[test]
fn deep_recursion_warns() {
    agree(
        "down(n)=if(n,down(n-1),0); $1=down($1)",
        &["50", "150", "1500"],
    );
}

#[test]
fn deeper_than_the_recursion_limit() {
    // 20,000 levels, then "recursion too deep", in both engines.
    agree(
        "down(n)=if(n,down(n-1),0); $1=down($1)",
        &["19990", "25000"],
    );
}

/// The finalised evaluator's rules (the reference rcalc's -ffast-math build).
#[test]
fn reference_build_quirks() {
    // NaN operand order: the first NaN operand is the result.
    agree(
        "$1=$1+$2;$2=$2+$1;$3=$1-$2;$4=$2-$1;$5=$1*$2;$6=$2*$1*3;$7=-$1",
        &["nan\t-nan", "-nan\tnan", "nan\t1", "1\t-nan"],
    );
    // NaNs the hardware or the library made (-nan here) against input NaNs of
    // either sign, in every order: only operands that may be an input's NaN are
    // tested, the rest left to the instruction (its first NaN source wins).
    agree(
        "$1=sqrt(-$1)+$2;$2=$2+sqrt(-$1);$3=(sqrt(-$1)*2)-($2*1);\
         $4=sin($1)*cos($2)-tan($2)*2;$5=0*exp(1000)+(-$2)*3;\
         $6=(sqrt($1)+$2)*(sqrt($2)-$1);$7=-sqrt(-$1)*-sqrt(-$2)+log(-$2);\
         $8=(1+$1/$2)*($2/$1-1);$9=floor($1)-ceil($2)*(acos($1)+asin($2))",
        &[
            "1\tnan",
            "1\t-nan",
            "nan\t1",
            "-nan\t-nan",
            "-1\t2",
            "inf\t-inf",
            "0\t0",
            "-nan\t1",
        ],
    );
    // Zero and NaN denominators are the result, with a warning.
    agree(
        "$1=1/$1;$2=$2/$1;$3=sin(1/$1);$4=1/-$1;$5=$1/$1",
        &["0\t1", "-0\t1", "nan\t2", "-nan\t2", "2\t3"],
    );
    // `^` and atan2 evaluate right to left.
    agree(
        "$1=(1/$1)^(sqrt(-1)+0*exp(1000));$2=atan2(1/$1,exp(1e4));$3=atan2(exp(1e4),1/$1);\
         $4=(exp(1e4))^(1/$1)",
        &["0", "2"],
    );
    agree_with(
        "$1=(sqrt(-1))^(exp(1e4));$2=atan2(sqrt(-1),exp(1e4));$3=(1/$1)^(log(-1))",
        &["0", "2"],
        MathErrors::NonFinite,
    );
    // floor and ceil never give -0; min and max NaN rules.
    agree(
        "$1=floor($1);$2=ceil($1);$3=ceil(-0.5);$4=floor(-0);\
         $5=max($1,$2);$6=min($2,$1);$7=max(0,-0);$8=max(-0,0);$9=min($2,1,2)",
        &["-0\tnan", "-0.5\t1", "nan\t-0", "3.5\t-nan"],
    );
    // select: out of range is a domain error; past C's int, fatal.
    agree("$1=select($1,10,20)", &["1", "2", "3", "-1", "nan", "-0.6"]);
    agree("$1=select($1,10,20)", &["1", "1e10"]);
    agree("$1=select($1,10,20)", &["1", "2147483647.5"]);
    agree("$1=select($1,10,20)", &["1", "2147483647.4"]);
    agree("$1=select($1,10,20)", &["1", "inf"]);
    agree("$1=select($1,10,20)", &["1", "-1e10"]);
    agree("f(p)=p(1e10,1,2); $1=f(select)", &["1"]);
    agree("f(p)=p(3,1,2); $1=f(select)+f(atan2)", &["1"]);
    agree("f(p)=p(1/$1,exp($1*1e4)); $1=f(atan2)", &["0", "1"]);
}

#[test]
fn self_references_see_the_previous_value() {
    agree("a=a+1;$1=a;$2=a*2", &["1", "2", "3"]);
    agree("a=b+$1;b=a*2;$1=a;$2=b", &["1", "2", "3"]);
    agree("a=b+$1;b=a*2;$1=b;$2=a", &["1", "2", "3"]);
    agree("c:c+1;$1=c;$2=c", &["1", "2"]);
    agree("n=if(n-2,n+1,$1);$1=n", &["5", "7", "9", "11"]);
    // A fatal error inside a self-referring definition leaves its old value.
    agree("a=a+select($1,1,2);$1=a", &["1", "2", "1e10", "1"]);
    agree("f(x)=f(x)+1;a=f(a);$1=a", &["1"]);
}

#[test]
fn constants_and_nonconstant_warnings() {
    agree("a : $1; b : a*2; $1 = b + a", &["3", "4"]);
    agree("c : 2; f(x) : x*c; $1 = f(3) + f($1)", &["3"]);
}

#[test]
fn nonfinite_results_as_errors() {
    // Radiance built with `isnan` as a macro reports NaN and infinity as errors.
    agree_with(
        "$1=sqrt($1);$2=log($1)+1;$3=max(sqrt($1),5);$4=$1^0.5;$5=exp($2*1000);\
         $6=(-8)^(1/3);$7=acos($1)*0+1;$8=if($1,sqrt(-1),1)",
        &["-1\t1", "0\t2", "4\t0.5"],
        MathErrors::NonFinite,
    );
}

/// Small user functions are inlined: their arguments must still be call-by-need
/// (computed once, on first use, in the caller's frame), with the same depth count.
#[test]
fn inlined_functions_keep_call_by_need() {
    agree(
        "g(x)=x*2; f(a,b)=g(a)+g(b)+g(a); h(a,b)=if(a,b,a)+b; $1=f(1/$1,$2); $2=h($1,1/$2);\
         $3=h($2,sqrt(-$1))",
        &["0\t1", "1\t0", "-1\t-1", "2\t2"],
    );
    agree("f(a,b)=if(a,b,a); $1=f($1)", &["1", "0"]);
    agree("f(a,b)=a+b; g(x)=f(x); $1=g($1)", &["1"]);
    agree("f(a,b,c)=c+a; g(x)=f(x,x); $1=g($1)", &["1"]);
    // Depth warnings name the call that reaches the level, inlined or not.
    agree(
        "s(x)=sin(x); down(n)=if(n,s(down(n-1)),0); $1=down($1)",
        &["97", "98", "99", "150"],
    );
    agree(
        "f(n)=sin(1)+if(n,f(n-1),0); $1=f($1)",
        &["97", "98", "99", "100", "150"],
    );
}

/// A C library result reused for the same argument value, and numbers folded while
/// compiling, must leave `errno` and the warnings as the calls would.
#[test]
fn reused_and_folded_library_calls() {
    agree(
        "x=$1; $1=sqrt(x)+sqrt(x)+sqrt(x+0); $2=max($2,sin(x))+max(sin(x),$2);\
         $3=x^3+x^3+(1/x)^2+(1/x)^2; $4=sqrt(-x)+sqrt(-x)",
        &["1\t1e999", "0\t2", "-4\t-1e999", "nan\t1"],
    );
    agree(
        "c=0.66; k:2; $1=sin(c)*$1+cos(c)+tan(k*c)+atan2(c,k)+2^k+sqrt(-c)+log(-k)+exp(1e4)",
        &["1", "2"],
    );
    agree_with(
        "c=0.66; $1=sin(c)+sqrt(-c)+log(-c)+exp(1e4)+(-c)^0.5+$1^2+$1^2",
        &["1", "1e200"],
        MathErrors::NonFinite,
    );
}

/// Every output column is one call (`$*`): what one column computed, later columns
/// and other branches reuse (input columns, with the `errno` an overflowing field
/// raises each time it is read; library results on equal values; variables), and a
/// fatal error keeps the columns before it.
#[test]
fn results_shared_across_columns_and_branches() {
    let rows = &["1\t2\t3", "1e999\t-1\t0", "-1e999\t0.5\tnan", "0\t0\t0"];
    agree(
        "$1=sin($1); $2=sin($1)+cos($2); $3=if($2, sin($1), cos($2)); $4=if($3-1, $1^(1/3), 0)+$1^(1/3);\
         $5=select($3+2, atan2($1,$2), exp($2), atan2($1,$2)); $6=sin($1)*atan2($1,$2)",
        rows,
    );
    // A variable's own previous value is not its value.
    agree(
        "a=if($1, sin(a)+1, 2); b=sin(a)+a; $1=a; $2=sin(a); $3=b; $4=if($2, sin(a), a)",
        rows,
    );
    // cielab.cal's shape: one function on the same values from several columns.
    agree(
        "d:6/29; bf(x):if(x-d*d*d, x^(1/3), x/(3*d*d)+2/3*d); L(y):116*bf(y)-16;\
         A(x,y):500*(bf(x)-bf(y)); B(y,z):200*(bf(y)-bf(z)); C(x,y,z):sqrt(A(x,y)^2+B(y,z)^2);\
         $1=L($2); $2=A($1,$2); $3=B($2,$3); $4=C($1,$2,$3); $5=bf($1)",
        rows,
    );
    // A fatal error in a later column keeps the earlier ones.
    agree(
        "$1=sin($1); $2=if($2, sin($1), nosuch); $3=sin($1)",
        &["1\t1", "1\t-1", "2\t1"],
    );
    agree_with(
        "$1=sin($1)+$2^0.5; $2=$2^0.5+log($3); $3=if($1, log($3), $2^0.5)",
        rows,
        MathErrors::NonFinite,
    );
}
