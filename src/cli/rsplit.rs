//! `radc rsplit`: Radiance's rsplit (see `radc_jit::records::split`): standard input
//! split among outputs named in turn: files (refused when they exist, unless `-f`; `-a`
//! appends), `-` for standard output, `.` to discard, `!command` (through `sh`, only with
//! `--allow-commands` or when radc is called as rsplit).

use std::io::{BufReader, Write};
use std::process::{Child, ExitCode, Stdio};

use radc_jit::records::split::{Split, SplitEnd, SplitOutput, split};
use radc_lang::c_number::{atoi, atol};
use radc_picture::tools::{command_line, format_line};

use super::picture_tools::stdout_position;

const NAME: &str = "rsplit";

/// Standard output, buffered once and shared by every `-` output, so their fields stay
/// in order (a `Stdout` handle each would flush at every newline).
#[derive(Clone)]
struct SharedStdout(std::rc::Rc<std::cell::RefCell<std::io::BufWriter<std::io::Stdout>>>);

impl Write for SharedStdout {
    fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().write(b)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.0.borrow_mut().flush()
    }
}

pub fn run(args: &[String]) -> ExitCode {
    let (allow, args) = match args.first().map(String::as_str) {
        Some("--allow-commands") => (true, &args[1..]),
        _ => (false, args),
    };
    let fail = |message: &str| {
        eprintln!("{NAME}: {message}");
        ExitCode::from(1)
    };
    let (mut read_header, mut read_resolution) = (false, false);
    let (mut force, mut append) = (false, false);
    let (mut xr, mut yr, mut records) = (0i64, 0i64, 0i64);
    let mut term = b'\n';
    let (mut components, mut bytes, mut format) = (1usize, 0usize, "ascii");
    let (mut header, mut resolution) = (false, false);
    let mut stdout_used = false;
    let stdout = SharedStdout(std::rc::Rc::new(std::cell::RefCell::new(
        std::io::BufWriter::new(std::io::stdout()),
    )));
    let mut outputs: Vec<SplitOutput> = Vec::new();
    let mut names: Vec<&str> = Vec::new();
    let mut children: Vec<Child> = Vec::new();
    let mut i = 0;
    while i < args.len() {
        let a = args[i].as_str();
        let b = a.as_bytes();
        let value = |i: usize| args.get(i + 1).map(String::as_str).unwrap_or("");
        let new = |output: Option<Box<dyn Write>>, flags: (bool, bool), stdout: bool, start| {
            SplitOutput {
                output,
                components,
                bytes,
                terminator: term,
                format,
                header: flags.0,
                resolution: flags.1,
                stdout,
                start,
            }
        };
        if b.first() == Some(&b'-') {
            match b.get(1) {
                Some(b't') => term = b.get(2).copied().unwrap_or(b'\n'),
                Some(b'i') => match b.get(2) {
                    Some(b'h') => read_header = !read_header,
                    Some(b'H') => read_resolution = !read_resolution,
                    _ => return fail("bad option"),
                },
                Some(b'f') => force = !force,
                Some(b'a') => append = !append,
                Some(b'x') => {
                    xr = i64::from(atoi(value(i)));
                    i += 1;
                }
                Some(b'y') => {
                    yr = i64::from(atoi(value(i)));
                    i += 1;
                }
                Some(b'o') => {
                    let (f, size) = match b.get(2) {
                        Some(b'n') => {
                            records = atol(value(i));
                            i += 2;
                            continue;
                        }
                        Some(b'h') => {
                            header = !header;
                            i += 1;
                            continue;
                        }
                        Some(b'H') => {
                            resolution = !resolution;
                            i += 1;
                            continue;
                        }
                        Some(b'f') => ("float", 4),
                        Some(b'd') => ("double", 8),
                        Some(b'i') => ("int", 4),
                        Some(b'w') => ("16-bit", 2),
                        Some(b'b') => ("byte", 1),
                        Some(b'a') => ("ascii", 0),
                        _ => return fail("bad option"),
                    };
                    (format, bytes) = (f, size);
                    components = if b.get(3).is_some_and(u8::is_ascii_digit) {
                        atoi(&a[3..]).max(0) as usize
                    } else {
                        1
                    };
                    if bytes * components > 16384 {
                        return fail("output size too big");
                    }
                }
                None => {
                    // Standard output: only its first use writes a header.
                    let flags = if stdout_used {
                        (false, false)
                    } else {
                        (header, resolution)
                    };
                    let start = if stdout_used { None } else { stdout_position() };
                    stdout_used = true;
                    outputs.push(new(Some(Box::new(stdout.clone())), flags, true, start));
                    names.push(a);
                }
                _ => return fail("bad option"),
            }
            i += 1;
            continue;
        }
        if a == "." {
            outputs.push(new(None, (false, false), false, None));
            names.push(a);
        } else if let Some(command) = a.strip_prefix('!') {
            if !allow {
                return fail(&format!(
                    "{a}: radc runs no commands without --allow-commands (or when called as rsplit)"
                ));
            }
            let child = std::process::Command::new("sh")
                .arg("-c")
                .arg(command)
                .stdin(Stdio::piped())
                .spawn();
            let Some((child, stdin)) = child.ok().and_then(|mut c| c.stdin.take().map(|s| (c, s)))
            else {
                eprintln!("{a}: cannot start command");
                return ExitCode::from(1);
            };
            outputs.push(new(
                Some(Box::new(stdin)),
                (header, resolution),
                false,
                None,
            ));
            names.push(a);
            children.push(child);
        } else {
            if names.contains(&a) {
                eprintln!("{NAME}: duplicate output: {a}");
                return ExitCode::from(1);
            }
            if append && (header || resolution) {
                return fail("-a option incompatible with -oh and -oH");
            }
            if !append && !force && std::path::Path::new(a).exists() {
                eprintln!("{a}: file exists -- use -f to overwrite");
                return ExitCode::from(1);
            }
            let file = std::fs::OpenOptions::new()
                .create(true)
                .append(append)
                .write(true)
                .truncate(!append)
                .open(a);
            let Ok(file) = file else {
                eprintln!("{a}: cannot open for output");
                return ExitCode::from(1);
            };
            let start = file
                .metadata()
                .ok()
                .map(|m| if append { m.len() } else { 0 });
            let out: Box<dyn Write> = Box::new(std::io::BufWriter::new(file));
            outputs.push(new(Some(out), (header, resolution), false, start));
            names.push(a);
        }
        i += 1;
    }
    if outputs.is_empty() {
        return fail("no output streams");
    }
    let line = |f: &str, start: Option<u64>, written: usize| format_line(f, start, written);
    let mut s = Split {
        outputs,
        read_header,
        read_resolution,
        resolution: (xr, yr),
        records,
        command_line: command_line(&crate::cli::programs::printed_name(NAME), args),
        format_line: &line,
    };
    let stdin = std::io::stdin();
    let mut input = BufReader::new(stdin.lock());
    let result = split(&mut s, &mut input, &mut |w| eprintln!("{NAME}: {w}"));
    drop(s);
    for mut c in children {
        let _ = c.wait();
    }
    match result {
        Ok(SplitEnd::Done) => ExitCode::SUCCESS,
        Ok(SplitEnd::Premature) => {
            eprintln!("{NAME}: warning: premature EOD");
            ExitCode::SUCCESS
        }
        Err(e) => fail(&e.to_string()),
    }
}
