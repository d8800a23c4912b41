//! `xform [-c|-e][-I][-m mod][-n name] [transform] [-a N ...] [file ..]`
//!
//! Reproduces Radiance's `src/gen/xform.c`: reads scene text and writes every primitive
//! transformed. Points move with the whole matrix, directions without the translation,
//! radii and glow distances scale by the scale factor; a mirroring transform reverses
//! polygon vertex order (and `-I` turns surfaces inside out: sphere <-> bubble, cone <->
//! cup, cylinder <-> tube, ring normals flipped). Types whose strings hold functions,
//! and instances and meshes, get the transform appended to their string arguments
//! (prefixed by `-i 1` so their own repetition resets). Reals print as `%18.12g`,
//! except dielectric, interface and mist, which xform prints as `%12.6g`.
//!
//! `!` commands in the input are expanded: genbox, genprism and xform run here; any
//! other command goes to the [`Host`]. With `-c` they are written back as commands
//! piped through `xform -e` with the same transform.

use crate::words::{Stream, atoi, put_word};
use crate::{Failure, GenError, Host};
use radc_lang::c_number::{format_g_width as g, is_c_space, is_flt, is_int};
use radc_lang::schema::{self, Category, PrimitiveType};
use radc_lang::transform::Transform;
use radc_lang::{FileId, Span};

/// `MAXSTR` in `object.h`: longest word Radiance reads, plus one.
const MAX_WORD: usize = 512;
/// Size of xform's buffer for type names: longer names are cut to 15 characters.
const TYPE_WORD: usize = 16;
/// Size of xform's buffer for a `!` command line.
const COMMAND_LINE: usize = 2048;
/// Nested `!xform` commands deeper than this are refused (a file that includes itself
/// would otherwise recurse for ever).
const MAX_DEPTH: usize = 32;

/// More copies than this from `-a` are refused rather than filling memory.
const MAX_ARRAY: i64 = 1_000_000;

/// The scene xform prints for `args` (the words after `xform`). On failure, what it
/// printed before failing (xform writes as it reads, and Radiance keeps that output).
/// Warnings go to the host's [`Host::warn`].
pub fn xform(args: &[String], host: &mut dyn Host) -> Result<String, Failure> {
    nested(args, host, 0)
}

struct Run<'h> {
    host: &'h mut dyn Host,
    /// Standard input, kept because `-a` transforms it once per copy.
    stdin: Option<String>,
    /// Standard input was read as an argument file (`-f -`), so not as a scene.
    stdin_taken: bool,
    depth: usize,
}

/// One invocation's settings (the C program's globals).
struct Settings<'a> {
    /// The words before the file names (the header and `-c` echo them).
    xav: &'a [String],
    /// Where the transform words start in `xav`.
    xfa: usize,
    tot: Transform,
    /// Mirror (or `-I`): reverse polygon vertex order.
    reverse: bool,
    invert: bool,
    expand: bool,
    newmod: Option<&'a str>,
    idprefix: Option<String>,
}

impl Run<'_> {
    /// xform's `main()`: `-f` and `-a` rewrite the arguments and call it again.
    fn main(&mut self, args: &[String], out: &mut String) -> Result<(), GenError> {
        if let Some(fi) = args.iter().position(|a| a == "-f") {
            return self.argument_file(args, fi, out);
        }
        if let Some(ai) = args.iter().position(|a| a == "-a") {
            return self.array(args, ai, out);
        }
        let mut s = Settings {
            xav: args,
            xfa: 0,
            tot: Transform::IDENTITY,
            reverse: false,
            invert: false,
            expand: true,
            newmod: None,
            idprefix: None,
        };
        let mut a = 0;
        while a < args.len() {
            let has_value = a + 1 < args.len();
            match args[a].as_str() {
                "-m" if has_value => {
                    a += 1;
                    s.newmod.get_or_insert(args[a].as_str());
                }
                "-n" if has_value => {
                    a += 1;
                    s.idprefix = Some(match s.idprefix.take() {
                        None => args[a].clone(),
                        Some(p) => format!("{p}.{}", args[a]),
                    });
                }
                "-c" => s.expand = false,
                "-e" => s.expand = true,
                "-I" => s.invert = !s.invert,
                _ => break,
            }
            a += 1;
        }
        s.xfa = a;
        let words = spanned(&args[a..], offset_of(args, a));
        let (tot, used) =
            Transform::parse_prefix(&words).map_err(|d| late_option_hint(d, &words))?;
        let xac = a + used;
        s.xav = &args[..xac];
        s.tot = tot;
        s.reverse = tot.is_mirror() != s.invert;
        s.tot.scale = tot.scale.abs();
        out.push_str("# xform");
        for w in s.xav {
            out.push(' ');
            out.push_str(w);
        }
        out.push('\n');
        if xac == args.len() {
            if self.stdin_taken {
                return Err(GenError::Invalid("cannot use stdin more than once".into()));
            }
            let text = match &self.stdin {
                Some(t) => t.clone(),
                None => {
                    let t = self.host.read_stdin()?;
                    self.stdin = Some(t.clone());
                    t
                }
            };
            self.stream(&s, "standard input", "", &text, out)
        } else {
            for name in &args[xac..] {
                let text = self.host.read_file(name)?;
                let dir = if s.expand { parent_dir(name) } else { "" };
                self.stream(&s, name, dir, &text, out)?;
            }
            Ok(())
        }
    }

    /// `-f file`: one transform per line of the file (or `-` for standard input), the
    /// k-th named `i<k>` (or `<name>.<k>` after `-n name`); blank and `#` lines are
    /// copied to the output.
    fn argument_file(
        &mut self,
        args: &[String],
        fi: usize,
        out: &mut String,
    ) -> Result<(), GenError> {
        let missing = || GenError::Invalid("missing file for -f option".into());
        let name = args.get(fi + 1).ok_or_else(missing)?;
        if name.len() > 1 && name.starts_with('-') {
            return Err(missing());
        }
        let text = if name == "-" {
            if self.stdin_taken {
                return Err(GenError::Invalid("cannot use stdin more than once".into()));
            }
            self.stdin_taken = true;
            self.host.read_stdin()?
        } else {
            let text = self.host.read_file(name)?;
            let mut lines = Stream::new(&text);
            let mut n = 0;
            while let Some(line) = lines.line(COMMAND_LINE) {
                n += usize::from(!line.is_empty() && !line.starts_with('#'));
            }
            if n == 0 {
                return Err(GenError::Invalid(format!("empty argument file \"{name}\"")));
            }
            text
        };
        if self.depth >= MAX_DEPTH {
            return Err(GenError::Nesting("argument files nested too deep".into()));
        }
        self.depth += 1;
        let mut lines = Stream::new(&text);
        let mut k = 0;
        let mut result = Ok(());
        while let Some(line) = lines.line(COMMAND_LINE) {
            if line.is_empty() || line.starts_with('#') {
                out.push_str(&line);
                out.push('\n');
                continue;
            }
            let mut argv: Vec<String> = args[..fi].to_vec();
            argv.extend(argument_line_words(&line));
            argv.extend(args[fi + 2..].iter().cloned());
            match (1..argv.len()).find(|&i| argv[i - 1] == "-n") {
                Some(i) => argv[i] = format!("{}.{k}", argv[i]),
                None => {
                    argv.insert(0, format!("i{k}"));
                    argv.insert(0, "-n".into());
                }
            }
            result = self.main(&argv, out);
            if result.is_err() {
                break;
            }
            k += 1;
        }
        self.depth -= 1;
        result
    }

    /// `-a N`: N copies, the k-th with `-i k` in place of `-a N` and its names
    /// prefixed `a<k>` (or `<name>.<k>` after `-n name`).
    fn array(&mut self, args: &[String], ai: usize, out: &mut String) -> Result<(), GenError> {
        let n = match args.get(ai + 1) {
            Some(c) if atoi(c) > 0 => atoi(c),
            _ => return Err(GenError::Invalid("missing count for -a option".into())),
        };
        if n > MAX_ARRAY {
            return Err(GenError::Invalid(format!(
                "-a {n}: radc makes at most {MAX_ARRAY} copies"
            )));
        }
        let old_id = (1..args.len())
            .rev()
            .find(|&i| args[i - 1] == "-n")
            .map(|i| args[i].clone());
        for k in 0..n {
            let id = match &old_id {
                Some(old) => format!("{old}.{k}"),
                None => format!("a{k}"),
            };
            let mut argv: Vec<String> = Vec::with_capacity(args.len() + 2);
            if old_id.is_none() {
                argv.push("-n".into());
                argv.push(id.clone());
            }
            for (i, w) in args.iter().enumerate() {
                argv.push(match i {
                    _ if i == ai => "-i".into(),
                    _ if i == ai + 1 => k.to_string(),
                    _ if i > 0 && args[i - 1] == "-n" => id.clone(),
                    _ => w.clone(),
                });
            }
            self.main(&argv, out)?;
        }
        Ok(())
    }

    /// xform's `xform()`: copies comments, expands commands, transforms objects.
    fn stream(
        &mut self,
        s: &Settings,
        name: &str,
        dir: &str,
        text: &str,
        out: &mut String,
    ) -> Result<(), GenError> {
        let mut input = Stream::new(text);
        let mut objects = 0;
        while let Some(c) = input.peek() {
            if is_c_space(c) {
                input.next_byte();
            } else if c == b'#' {
                out.push_str(&input.comment());
            } else if c == b'!' {
                let line = input.line(COMMAND_LINE).unwrap_or_default();
                self.command(s, name, dir, &line, out)?;
                objects += 1;
            } else {
                object(s, name, &mut input, out)?;
                objects += 1;
            }
        }
        // xform.c counts what it read; a file of nothing but comments is suspect.
        if objects == 0 {
            self.host
                .warn(&format!("xform: ({name}): warning - empty file"));
        }
        Ok(())
    }

    /// A `!` line in `file`: its output transformed in place. A command that fails is
    /// not fatal, as in xform.c: the child's message, then what it wrote before
    /// failing, then "bad status". Nesting too deep is fatal (a file including itself).
    fn command(
        &mut self,
        s: &Settings,
        file: &str,
        dir: &str,
        line: &str,
        out: &mut String,
    ) -> Result<(), GenError> {
        let command = line.get(1..).unwrap_or("");
        if !s.expand {
            out.push('\n');
            out.push_str(line);
            if !s.xav.is_empty() {
                out.push_str(" | xform -e");
                for (i, w) in s.xav.iter().enumerate() {
                    if i >= s.xfa || w != "-c" {
                        out.push(' ');
                        out.push_str(w);
                    }
                }
            }
            out.push('\n');
            return Ok(());
        }
        if self.depth >= MAX_DEPTH {
            return Err(GenError::Nesting(format!(
                "commands nested more than {MAX_DEPTH} deep at \"{line}\""
            )));
        }
        self.depth += 1;
        let result = self.run_command(command, dir);
        self.depth -= 1;
        match result {
            Ok(text) => self.stream(s, line, dir, &text, out),
            Err(f) if matches!(f.error, GenError::Nesting(_)) => Err(f.error),
            Err(f) => {
                let message = f.radiance_message();
                if !message.is_empty() {
                    self.host.warn(&message);
                }
                self.stream(s, line, dir, &f.partial, out)?;
                self.host.warn(&format!(
                    "xform: ({file}): warning - bad status from \"{line}\""
                ));
                Ok(())
            }
        }
    }

    /// The output of one `!` command: a built-in generator if it is one, else the host's.
    fn run_command(&mut self, command: &str, dir: &str) -> Result<String, Failure> {
        let builtin = {
            let mut host = InDir {
                host: &mut *self.host,
                dir,
            };
            crate::command::run_builtin_at(command, &mut host, self.depth)
        };
        match builtin {
            Some(result) => result,
            None => self.host.run_command(command, dir),
        }
    }
}

/// xform run from a `!` command inside a scene, `depth` commands deep.
pub(crate) fn nested(
    args: &[String],
    host: &mut dyn Host,
    depth: usize,
) -> Result<String, Failure> {
    let mut run = Run {
        host,
        stdin: None,
        stdin_taken: false,
        depth,
    };
    Failure::keeping_partial("xform", |out| run.main(args, out))
}

/// The words of one argument-file line as xform splits them: an optional leading `!`
/// and `xform ` are skipped; a quote opens a quoted word, and (as in Radiance) every
/// later word is then read up to the next such quote rather than the next space; a
/// backslash before a newline joins lines.
fn argument_line_words(line: &str) -> Vec<String> {
    let b = line.as_bytes();
    let mut cp = usize::from(b.first() == Some(&b'!'));
    if b[cp..].starts_with(b"xform ") {
        cp += 6;
    }
    let mut words = Vec::new();
    let mut quote: Option<u8> = None;
    loop {
        while b.get(cp).is_some_and(|&c| is_c_space(c)) {
            cp += 1;
        }
        if let Some(&q @ (b'"' | b'\'')) = b.get(cp) {
            quote = Some(q);
            cp += 1;
        }
        if cp >= b.len() {
            break;
        }
        if b[cp] == b'\\' && cp + 1 < b.len() {
            cp += 1;
            if b[cp] == b'\n' {
                continue;
            }
        }
        let start = cp;
        let end = match quote {
            Some(q) => {
                let close = b[cp + 1..].iter().position(|&c| c == q).map(|i| cp + 1 + i);
                cp = close.map_or(b.len(), |i| i + 1);
                close.unwrap_or(b.len())
            }
            None => {
                cp += 1;
                while cp < b.len() && !is_c_space(b[cp]) {
                    cp += 1;
                }
                cp
            }
        };
        words.push(String::from_utf8_lossy(&b[start..end]).into_owned());
    }
    words
}

/// A host seen from a folder: relative file names are taken from that folder, as xform
/// changes into a file's folder before running the commands in it.
struct InDir<'h, 'd> {
    host: &'h mut dyn Host,
    dir: &'d str,
}

impl Host for InDir<'_, '_> {
    fn read_file(&mut self, path: &str) -> Result<String, GenError> {
        if self.dir.is_empty() || path.starts_with('/') {
            self.host.read_file(path)
        } else {
            self.host.read_file(&format!("{}/{path}", self.dir))
        }
    }

    fn read_stdin(&mut self) -> Result<String, GenError> {
        // A command inside a scene reads no terminal input.
        Ok(String::new())
    }

    fn warn(&mut self, line: &str) {
        self.host.warn(line);
    }

    fn run_command(&mut self, command: &str, dir: &str) -> Result<String, Failure> {
        let joined = match (self.dir, dir) {
            ("", d) => d.to_string(),
            (base, "") => base.to_string(),
            (base, d) if !d.starts_with('/') => format!("{base}/{d}"),
            (_, d) => d.to_string(),
        };
        self.host.run_command(command, &joined)
    }
}

/// The folder part of a file name ("" for none), where xform runs that file's commands.
fn parent_dir(name: &str) -> &str {
    match name.rfind('/') {
        Some(0) => "/",
        Some(i) => &name[..i],
        None => "",
    }
}

/// xform's own options after the transform stop it there; say where they belong.
fn late_option_hint(d: radc_lang::Diagnostic, words: &[(&str, Span)]) -> GenError {
    let word = words.iter().find(|(_, span)| *span == d.span).map(|w| w.0);
    let late = matches!(word, Some("-n" | "-m" | "-c" | "-e" | "-I"));
    let at = failing_option(&d, words);
    let diagnostic = if late && d.code == radc_lang::diagnostic::E0801 {
        d.with_hint("xform's -n, -m, -c, -e and -I go before the transform options")
    } else {
        d
    };
    GenError::Transform {
        diagnostic: Box::new(diagnostic),
        at,
    }
}

/// The word xform's "command line error at" names: `xf()` stops at the option whose
/// arguments are wrong (`-t` of `-t 1 2`, `-s` of `-s 0`), so the last option word
/// at or before the diagnostic's word.
fn failing_option(d: &radc_lang::Diagnostic, words: &[(&str, Span)]) -> String {
    let upto = words
        .iter()
        .rposition(|(_, span)| span.start <= d.span.start)
        .map_or(0, |k| k + 1);
    words[..upto]
        .iter()
        .rev()
        .find(|(w, _)| w.starts_with('-') && !is_flt(w))
        .or(words.first())
        .map(|(w, _)| w.to_string())
        .unwrap_or_default()
}

/// Byte offset of word `k` in the arguments joined by single spaces.
fn offset_of(args: &[String], k: usize) -> usize {
    args[..k].iter().map(|a| a.len() + 1).sum()
}

fn spanned(words: &[String], mut at: usize) -> Vec<(&str, Span)> {
    words
        .iter()
        .map(|w| {
            let span = Span::new(FileId(0), at..at + w.len());
            at += w.len() + 1;
            (w.as_str(), span)
        })
        .collect()
}

/// How xform rewrites a type's arguments (the C program's `ofun[].funp`).
#[derive(Clone, Copy, PartialEq)]
enum Handler {
    Default,
    AddTransform,
    Alias,
    Glow,
    Spot,
    Mist,
    Dielectric,
    Interface,
    Text,
    Source,
    Sphere,
    Face,
    Cone,
    Cylinder,
    Ring,
}

/// xform's `initotypes()` choice of handler for a type of the schema: the types whose
/// reals are geometry (or directions, radii, indices of refraction, text layouts) get
/// their own; the others take the transform in their strings when the schema says
/// their strings may end with one (Radiance's `T_F` types), or pass through unchanged.
fn handler(ty: &PrimitiveType) -> Handler {
    match ty.name {
        _ if ty.category == Category::Alias => Handler::Alias,
        "glow" => Handler::Glow,
        "spotlight" => Handler::Spot,
        "mist" => Handler::Mist,
        "dielectric" => Handler::Dielectric,
        "interface" => Handler::Interface,
        "brighttext" | "colortext" | "mixtext" => Handler::Text,
        "source" => Handler::Source,
        "sphere" | "bubble" => Handler::Sphere,
        "polygon" => Handler::Face,
        "cone" | "cup" => Handler::Cone,
        "cylinder" | "tube" => Handler::Cylinder,
        "ring" => Handler::Ring,
        _ if ty.strings.transform => Handler::AddTransform,
        _ => Handler::Default,
    }
}

/// A primitive's argument lists (`FUNARGS`).
struct Args {
    strings: Vec<String>,
    reals: Vec<f64>,
}

/// `readfargs()`: `None` where Radiance's reader fails.
fn read_args(input: &mut Stream) -> Option<Args> {
    let count = |input: &mut Stream| {
        let w = input.word(MAX_WORD)?;
        let n = if is_int(&w) { atoi(&w) } else { -1 };
        usize::try_from(n).ok()
    };
    let ns = count(input)?;
    let mut strings = Vec::new();
    for _ in 0..ns {
        strings.push(input.word(MAX_WORD)?);
    }
    if count(input)? != 0 {
        return None;
    }
    let nf = count(input)?;
    let mut reals = Vec::new();
    for _ in 0..nf {
        let w = input.word(MAX_WORD)?;
        if !is_flt(&w) {
            return None;
        }
        reals.push(radc_lang::c_number::atof(&w));
    }
    Some(Args { strings, reals })
}

/// xform's `xfobject()`: one primitive, read from `input` and written transformed.
fn object(s: &Settings, file: &str, input: &mut Stream, out: &mut String) -> Result<(), GenError> {
    let modifier_name = input.word(MAX_WORD).unwrap_or_default();
    let type_name = input.word(TYPE_WORD).unwrap_or_default();
    let Some(info) = schema::lookup(&type_name) else {
        return Err(GenError::Scene(format!(
            "({file}): unknown object type \"{type_name}\""
        )));
    };
    out.push('\n');
    // Surfaces take the new modifier, the id prefix and (inside out) their inverse
    // type; modifiers keep their modifier and name.
    let surface = info.category == Category::Surface;
    if surface {
        put_word(out, s.newmod.unwrap_or(&modifier_name));
        let shown = match info.inverse {
            Some(inverse) if s.invert => inverse,
            _ => info.name,
        };
        out.push_str(&format!(" {shown} "));
    } else {
        put_word(out, &modifier_name);
        out.push_str(&format!(" {type_name} "));
    }
    let name = input.word(MAX_WORD).unwrap_or_default();
    match &s.idprefix {
        Some(prefix) if surface => put_word(out, &format!("{prefix}.{name}")),
        _ => put_word(out, &name),
    }
    out.push('\n');
    let bad = || GenError::Scene(format!("({file}): bad {type_name} \"{name}\""));
    let handler = handler(info);
    if handler == Handler::Alias {
        let target = input.word(MAX_WORD).ok_or_else(bad)?;
        out.push_str(&format!("\t{target}\n"));
        return Ok(());
    }
    let args = read_args(input).ok_or_else(bad)?;
    write_args(s, handler, &args, out).ok_or_else(bad)
}

fn g18(x: f64) -> String {
    g(x, 18, 12)
}

fn g12(x: f64) -> String {
    g(x, 12, 6)
}

fn push_strings(out: &mut String, strings: &[String]) {
    out.push_str(&strings.len().to_string());
    for w in strings {
        out.push(' ');
        put_word(out, w);
    }
    out.push('\n');
}

fn push_reals(out: &mut String, reals: &[f64]) {
    out.push_str(&reals.len().to_string());
    for &r in reals {
        out.push(' ');
        out.push_str(&g18(r));
    }
    out.push('\n');
}

/// Three numbers each preceded by a space, as `" %18.12g %18.12g %18.12g"`.
fn push3(out: &mut String, v: [f64; 3]) {
    for x in v {
        out.push(' ');
        out.push_str(&g18(x));
    }
}

/// Writes the transformed argument lists; `None` where xform reports "bad <type>".
fn write_args(s: &Settings, handler: Handler, a: &Args, out: &mut String) -> Option<()> {
    let (tot, sca) = (&s.tot, s.tot.scale);
    let f = &a.reals;
    let p3 = |k: usize| [f[k], f[k + 1], f[k + 2]];
    let geometry = |ns: usize, nf: bool| (ns == 0 && nf).then_some(());
    match handler {
        Handler::Default => {
            push_strings(out, &a.strings);
            out.push_str("0\n");
            push_reals(out, f);
        }
        Handler::AddTransform => {
            let xf = &s.xav[s.xfa..];
            let reset = !xf.is_empty() && xf[0] != "-i";
            let count = a.strings.len() + if reset { 2 } else { 0 } + xf.len();
            out.push_str(&count.to_string());
            for w in &a.strings {
                out.push(' ');
                put_word(out, w);
            }
            if reset {
                out.push_str(" -i 1");
            }
            for w in xf {
                out.push(' ');
                out.push_str(w);
            }
            out.push_str("\n0\n");
            push_reals(out, f);
        }
        Handler::Alias => return None,
        Handler::Glow => {
            geometry(a.strings.len(), f.len() == 4)?;
            out.push_str("0\n0\n4");
            push3(out, p3(0));
            out.push_str(&format!(" {}\n", g18(f[3] * sca)));
        }
        Handler::Spot => {
            geometry(a.strings.len(), f.len() == 7)?;
            out.push_str("0\n0\n7");
            push3(out, p3(0));
            out.push_str(&format!(" {}\n", g18(f[3])));
            let v = tot.vector(p3(4));
            out.push_str(&format!("\t{} {} {}\n", g18(v[0]), g18(v[1]), g18(v[2])));
        }
        Handler::Mist => {
            if f.len() > 7 {
                return None;
            }
            out.push_str(&a.strings.len().to_string());
            for w in &a.strings {
                out.push(' ');
                match &s.idprefix {
                    None => out.push_str(w),
                    Some(p) => out.push_str(&prefix_sources(p, w)),
                }
            }
            out.push_str(&format!("\n0\n{}", f.len()));
            if f.len() > 2 {
                for &x in &f[..3] {
                    out.push(' ');
                    out.push_str(&g12(x / sca));
                }
            }
            for &x in f.iter().skip(3) {
                out.push(' ');
                out.push_str(&g12(x));
            }
            out.push('\n');
        }
        Handler::Dielectric => {
            geometry(a.strings.len(), f.len() == 5)?;
            out.push_str("0\n0\n5");
            for &x in &f[..3] {
                out.push(' ');
                out.push_str(&g12(x.powf(1.0 / sca)));
            }
            out.push_str(&format!(" {} {}\n", g12(f[3]), g12(f[4])));
        }
        Handler::Interface => {
            geometry(a.strings.len(), f.len() == 8)?;
            out.push_str("0\n0\n8\n");
            for half in [&f[..4], &f[4..]] {
                let c: Vec<String> = half[..3].iter().map(|&x| g12(x.powf(1.0 / sca))).collect();
                out.push_str(&format!("{} {} {} {}\n", c[0], c[1], c[2], g12(half[3])));
            }
        }
        Handler::Text => {
            if f.len() < 9 {
                return None;
            }
            push_strings(out, &a.strings);
            out.push_str(&format!("0\n{}\n", f.len()));
            push3(out, tot.point(p3(0)));
            out.push('\n');
            push3(out, tot.vector(p3(3)));
            out.push('\n');
            push3(out, tot.vector(p3(6)));
            for (i, &x) in f.iter().enumerate().skip(9) {
                if i % 3 == 0 {
                    out.push('\n');
                }
                out.push(' ');
                out.push_str(&g18(x));
            }
            out.push('\n');
        }
        Handler::Source => {
            geometry(a.strings.len(), f.len() == 4)?;
            out.push_str("0\n0\n4");
            push3(out, tot.vector(p3(0)));
            out.push_str(&format!(" {}\n", g18(f[3])));
        }
        Handler::Sphere => {
            geometry(a.strings.len(), f.len() == 4)?;
            out.push_str("0\n0\n4");
            push3(out, tot.point(p3(0)));
            out.push_str(&format!(" {}\n", g18(f[3] * sca)));
        }
        Handler::Face => {
            geometry(a.strings.len(), f.len().is_multiple_of(3))?;
            out.push_str(&format!("0\n0\n{}\n", f.len()));
            let n = f.len() / 3;
            for i in 0..n {
                let k = if s.reverse { n - 1 - i } else { i };
                push3(out, tot.point(p3(3 * k)));
                out.push('\n');
            }
        }
        Handler::Cone => {
            geometry(a.strings.len(), f.len() == 8)?;
            out.push_str("0\n0\n8\n");
            push3(out, tot.point(p3(0)));
            out.push('\n');
            push3(out, tot.point(p3(3)));
            out.push_str(&format!("\n {} {}\n", g18(f[6] * sca), g18(f[7] * sca)));
        }
        Handler::Cylinder => {
            geometry(a.strings.len(), f.len() == 7)?;
            out.push_str("0\n0\n7\n");
            push3(out, tot.point(p3(0)));
            out.push('\n');
            push3(out, tot.point(p3(3)));
            out.push_str(&format!("\n {}\n", g18(f[6] * sca)));
        }
        Handler::Ring => {
            geometry(a.strings.len(), f.len() == 8)?;
            out.push_str("0\n0\n8\n");
            push3(out, tot.point(p3(0)));
            out.push('\n');
            let mut d = tot.vector(p3(3));
            if s.invert {
                d = [-d[0], -d[1], -d[2]];
            }
            push3(out, d);
            out.push_str(&format!("\n {} {}\n", g18(f[6] * sca), g18(f[7] * sca)));
        }
    }
    Some(())
}

/// Mist source names get the `-n` prefix on each `>`-separated part, as xform does.
fn prefix_sources(prefix: &str, names: &str) -> String {
    let mut out = String::new();
    let mut rest = names;
    while !rest.is_empty() {
        let end = rest.find('>').map_or(rest.len(), |i| i + 1);
        out.push_str(prefix);
        out.push('.');
        out.push_str(&rest[..end]);
        rest = &rest[end..];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The names xform gives handlers of their own are types of the schema, and the
    /// types that take a transform in their strings are the schema's `T_F` types.
    #[test]
    fn handlers_follow_the_schema() {
        for name in [
            "glow",
            "spotlight",
            "mist",
            "dielectric",
            "interface",
            "brighttext",
            "colortext",
            "mixtext",
            "source",
            "sphere",
            "bubble",
            "polygon",
            "cone",
            "cup",
            "cylinder",
            "tube",
            "ring",
        ] {
            let ty = schema::lookup(name).expect(name);
            assert!(
                !matches!(handler(ty), Handler::Default | Handler::AddTransform),
                "{name}"
            );
        }
        let transformed: Vec<_> = schema::PRIMITIVE_TYPES
            .iter()
            .filter(|t| handler(t) == Handler::AddTransform)
            .map(|t| t.name)
            .collect();
        assert_eq!(transformed.len(), 31, "{transformed:?}");
        assert!(transformed.contains(&"instance") && transformed.contains(&"mesh"));
        let inverted: Vec<_> = schema::PRIMITIVE_TYPES
            .iter()
            .filter_map(|t| Some((t.name, t.inverse?)))
            .collect();
        for (a, b) in &inverted {
            assert_eq!(schema::lookup(b).and_then(|t| t.inverse), Some(*a));
        }
        assert_eq!(inverted.len(), 6);
    }
}
