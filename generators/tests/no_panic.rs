//! Generators must never panic, whatever the arguments or the scene text: every
//! failure is a `GenError`. A small deterministic fuzzer over words that exercise each
//! option and its edge cases.

use radc_generators::{GenError, Host, genbox, genprism, genrev, gensky, gensurf, genworm, xform};

/// xorshift64*: reproducible without a dependency.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn pick<'a>(&mut self, words: &[&'a str]) -> &'a str {
        words[(self.next() % words.len() as u64) as usize]
    }
}

const WORDS: &[&str] = &[
    "-",
    "-i",
    "-r",
    "-b",
    "-n",
    "-s",
    "-o",
    "-l",
    "-c",
    "-e",
    "-t",
    "-rx",
    "-ry",
    "-rz",
    "-mx",
    "-my",
    "-mz",
    "-a",
    "-m",
    "-I",
    "-f",
    "-q",
    "0",
    "1",
    "-1",
    "2",
    "3",
    "4",
    "0.5",
    "1e-9",
    "1e300",
    "nan",
    "inf",
    "",
    "x",
    "m",
    "'q'",
    "\"",
    "9999999999",
    "-0",
    ".",
    "1.5.2",
    "2147483648",
];

const SCENE_WORDS: &[&str] = &[
    "void",
    "plastic",
    "polygon",
    "sphere",
    "ring",
    "cone",
    "cylinder",
    "mist",
    "glow",
    "spotlight",
    "colortext",
    "alias",
    "instance",
    "dielectric",
    "interface",
    "source",
    "0",
    "1",
    "3",
    "4",
    "5",
    "7",
    "8",
    "9",
    "12",
    "-1",
    "0.5",
    "x",
    "#",
    "\n",
    "!",
    "!genbox m b 1 1 1",
    "!xform -rz 10 s.rad",
    "!genprism m p - ",
    "'",
    "\"",
    "a>b",
    "1e999",
];

struct Files;

impl Host for Files {
    fn read_file(&mut self, path: &str) -> Result<String, GenError> {
        match path {
            "s.rad" | "sub/s.rad" => Ok("!xform s.rad\nvoid sphere s 0 0 4 1 2 3 1\n".into()),
            "v.txt" => Ok("0 0 1 0 0 1".into()),
            "args.txt" => Ok("# c\n-t 1 0 0\n!xform \"a b\" -f args.txt\n\\\n-a 2 -rz 5\n!".into()),
            _ => Err(GenError::Host(format!("no {path}"))),
        }
    }

    fn read_stdin(&mut self) -> Result<String, GenError> {
        Ok("void polygon p 0 0 9 0 0 0 1 0 0 0 1 0\n1 2".into())
    }

    fn warn(&mut self, _: &str) {}
}

#[test]
fn random_arguments_never_panic() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for _ in 0..4000 {
        let n = (rng.next() % 12) as usize;
        let mut args: Vec<String> = (0..n).map(|_| rng.pick(WORDS).to_string()).collect();
        let _ = genbox(&args);
        let _ = genprism(&args, &mut Files);
        let _ = xform(&args, &mut Files);
        let _ = gensky(&args, &mut Files);
        if rng.next().is_multiple_of(16) {
            // calcomp setup is the slow part; a sample is enough.
            let _ = genworm(&args, &mut Files);
            let _ = genrev(&args, &mut Files);
            let mut rev: Vec<String> = ["m", "v", "t", "1+t*t", "5"].map(String::from).to_vec();
            rev.extend(args.iter().cloned());
            let _ = genrev(&rev, &mut Files);
            let _ = gensurf(&args, &mut Files);
            let mut surf: Vec<String> = ["m", "s", "s", "t", "v.txt", "2", "1"]
                .map(String::from)
                .to_vec();
            surf.extend(args.iter().cloned());
            let _ = gensurf(&surf, &mut Files);
            let mut worm: Vec<String> = ["m", "w", "t", "t*t", "sin(t)", ".1", "4"]
                .map(String::from)
                .to_vec();
            worm.extend(args.iter().cloned());
            let _ = genworm(&worm, &mut Files);
        }
        let mut dated = vec!["3".to_string(), "21".into(), "12".into()];
        dated.extend(args.iter().cloned());
        let _ = gensky(&dated, &mut Files);
        // Also with a valid start, so the option parsers are reached.
        let mut boxed = vec![
            "m".to_string(),
            "b".into(),
            "1".into(),
            "2".into(),
            "3".into(),
        ];
        boxed.append(&mut args.clone());
        let _ = genbox(&boxed);
        let mut prism = vec!["m".to_string(), "p".into(), "3".into()];
        prism.extend(["0", "0", "1", "0", "0", "1"].map(String::from));
        prism.append(&mut args);
        let _ = genprism(&prism, &mut Files);
    }
}

#[test]
fn random_scenes_never_panic() {
    let mut rng = Rng(0x1234_5678_9abc_def1);
    for _ in 0..3000 {
        let n = (rng.next() % 30) as usize;
        let scene: Vec<&str> = (0..n).map(|_| rng.pick(SCENE_WORDS)).collect();
        let text = scene.join(" ");
        struct Text(String);
        impl Host for Text {
            fn read_file(&mut self, _: &str) -> Result<String, GenError> {
                Ok(self.0.clone())
            }
            fn read_stdin(&mut self) -> Result<String, GenError> {
                Ok(self.0.clone())
            }
            fn warn(&mut self, _: &str) {}
        }
        for args in [
            &["-rz", "30", "-n", "p"][..],
            &["-mx", "-I"],
            &["-c", "-s", "2"],
        ] {
            let mut args: Vec<String> = args.iter().map(|s| s.to_string()).collect();
            if args[0] == "-rz" {
                args.swap(0, 2);
                args.swap(1, 3);
            }
            let _ = xform(&args, &mut Text(text.clone()));
        }
    }
}

#[test]
fn self_including_scene_is_refused_not_overflowed() {
    let out = xform(&["s.rad".to_string()], &mut Files);
    let failure = out.expect_err("a file that includes itself fails");
    assert!(matches!(failure.error, GenError::Nesting(_)), "{failure:?}");
}
