//! What `radc check` reports for calcomp text, as data: one line per diagnostic
//! (code, line:column, message, hint), snapshot-tested so a change in wording or in a
//! span is reviewed.

use radc_lang::cal::{Env, check, check_with_entries};
use radc_lang::{Diagnostic, FileId, LineIndex};

fn render(text: &str, diags: &[Diagnostic]) -> String {
    let index = LineIndex::new(text);
    diags
        .iter()
        .map(|d| {
            let (l, c) = index.line_col(text, d.span.start as usize);
            let snippet = text.get(d.span.range()).unwrap_or("");
            let mut line = format!("{} {l}:{c} `{snippet}` {}", d.code.id, d.message);
            for label in &d.labels {
                let (ll, lc) = index.line_col(text, label.span.start as usize);
                line.push_str(&format!(" [{ll}:{lc}: {}]", label.message));
            }
            if let Some(h) = &d.hint {
                line.push_str(&format!(" (hint: {h})"));
            }
            line
        })
        .collect::<Vec<_>>()
        .join("\n")
}

const PROGRAM: &str = "\
{ a program with one of everything wrong }
scale : 2.5;
scale : 3;
gain = $1 * scael;
k : gain * 2;
f(x, y) = x * y;
sin(x) = x;
$1 = f(1) + sqrt(2, 3) + atan2(1);
$2 = f + 1;
$3 = gain(2);
$4 = 1 / 0;
$5 = (1 + ;
$6 = 2 --3;
unused = 4;
";

#[test]
fn program_diagnostics() {
    insta::assert_snapshot!(render(
        PROGRAM,
        &check(FileId(0), PROGRAM, &Env::rcalc().complete())
    ));
}

const LIBRARY: &str = "\
{ a function file for a scene: free names are its user's }
bump(s) = s * noise3(Px, Py, Pz) + offset;
tilt : Dx * 2;
scaled = bump(scale) + nosuch_fn(1);
helper = 1;
";

#[test]
fn library_diagnostics_in_the_renderer() {
    insta::assert_snapshot!(render(
        LIBRARY,
        &check_with_entries(FileId(0), LIBRARY, &Env::renderer(), Some(&["scaled"]))
    ));
}
