//! The scene front end never panics, whatever it is given. cargo-fuzz (`fuzz/`) explores
//! this deeply; this property test keeps a cheap version of it in every `cargo test`, so
//! CI catches a regression without a nightly toolchain.

use proptest::prelude::*;
use radc_lang::FileId;
use radc_lang::scene::{AssumeFilesExist, check_text};
use radc_lang::source::decode;

/// Fragments that mean something to the lexer, parser or checker: type keywords,
/// reserved modifier names, counts (including absurd ones), reals Radiance does and
/// does not accept, quotes, comment and command starts, continuations, NULs and
/// non-ASCII text.
const FRAGMENTS: &[&str] = &[
    "void",
    "inherit",
    "alias",
    "plastic",
    "metal",
    "glass",
    "light",
    "trans",
    "mirror",
    "illum",
    "glow",
    "spotlight",
    "dielectric",
    "interface",
    "antimatter",
    "mixfunc",
    "brightfunc",
    "colorpict",
    "texfunc",
    "mixture",
    "polygon",
    "sphere",
    "bubble",
    "cone",
    "cup",
    "cylinder",
    "tube",
    "ring",
    "source",
    "instance",
    "mesh",
    "plastc",
    "red",
    "a",
    "0",
    "1",
    "2",
    "3",
    "4",
    "5",
    "7",
    "8",
    "9",
    "12",
    "-0",
    "+4",
    "-1",
    "5.0",
    ".5",
    "5.",
    "1e-3",
    "-1E+2",
    "1e400",
    "-1e400",
    "1e",
    "nan",
    "inf",
    "0x10",
    "4294967295",
    "4294967296",
    "18446744073709551615",
    "99999999999999999999",
    "\"",
    "'",
    "\"a b\"",
    "'x y'",
    "a\"b c\"d",
    "#",
    "# comment",
    "#x",
    "!",
    "!genbox a b 1 2 3",
    "!x \\",
    "\\",
    "\0",
    "é",
    "😀",
    "\u{feff}",
    ".",
    "dirt.cal",
    "room.oct",
    "-rz",
    "-t",
];

const SEPARATORS: &[&str] = &[" ", " ", " ", "\n", "\t", "", "\r\n", "\\\n", "\u{b}"];

fn token_soup() -> impl Strategy<Value = String> {
    prop::collection::vec(
        (
            prop::sample::select(FRAGMENTS),
            prop::sample::select(SEPARATORS),
        ),
        0..120,
    )
    .prop_map(|parts| {
        parts
            .into_iter()
            .flat_map(|(word, sep)| [word, sep])
            .collect()
    })
}

/// Well-formed primitives with one thing broken: the parser's recovery paths.
fn nearly_valid_scene() -> impl Strategy<Value = String> {
    let primitive = (
        prop::sample::select(&["void", "m", "inherit", "s"][..]),
        prop::sample::select(
            &[
                "plastic", "polygon", "sphere", "alias", "mixfunc", "ring", "x",
            ][..],
        ),
        0u64..14,
        prop::collection::vec(prop::sample::select(FRAGMENTS), 0..14),
    )
        .prop_map(|(modifier, kind, n, reals)| {
            format!("{modifier} {kind} m 0 0 {n} {}\n", reals.join(" "))
        });
    prop::collection::vec(primitive, 1..12).prop_map(|lines| lines.concat())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn token_soup_never_panics(text in token_soup()) {
        let (text, _) = decode(FileId(0), text.as_bytes());
        let _ = check_text(FileId(0), &text, &AssumeFilesExist, true);
    }

    #[test]
    fn nearly_valid_scenes_never_panic(text in nearly_valid_scene()) {
        let _ = check_text(FileId(0), &text, &AssumeFilesExist, true);
    }

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        let (text, _) = decode(FileId(0), &bytes);
        let _ = check_text(FileId(0), &text, &AssumeFilesExist, true);
    }
}
