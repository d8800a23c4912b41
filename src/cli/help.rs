//! `radc COMMAND --help` and `radc help COMMAND`: the command's summary, its usage and
//! its options one line each (the texts beside this file), on standard output, exit 0.
//! The generators' options are Radiance's own, listed with their usage.

use std::io::Write;
use std::process::ExitCode;

/// The option texts, by command.
const TEXTS: &[(&str, &str)] = &[
    ("trace", include_str!("help/trace.txt")),
    ("render", include_str!("help/render.txt")),
    ("calc", include_str!("help/calc.txt")),
    ("check", include_str!("help/check.txt")),
    ("fmt", include_str!("help/fmt.txt")),
    ("build", include_str!("help/build.txt")),
    ("lsp", include_str!("help/lsp.txt")),
    ("pfilt", include_str!("help/pfilt.txt")),
    ("vwrays", include_str!("help/vwrays.txt")),
    ("cnt", include_str!("help/cnt.txt")),
    ("total", include_str!("help/total.txt")),
    ("rlam", include_str!("help/rlam.txt")),
    ("rsplit", include_str!("help/rsplit.txt")),
    ("getinfo", include_str!("help/getinfo.txt")),
    ("pvalue", include_str!("help/pvalue.txt")),
    ("radcompare", include_str!("help/radcompare.txt")),
    ("pflip", include_str!("help/pflip.txt")),
    ("protate", include_str!("help/protate.txt")),
    ("ra_ppm", include_str!("help/ra_ppm.txt")),
    ("ra_rgbe", include_str!("help/ra_rgbe.txt")),
    ("ra_xyze", include_str!("help/ra_xyze.txt")),
    ("links", include_str!("help/links.txt")),
    ("genbox", include_str!("help/generators.txt")),
    ("gendaylit", include_str!("help/generators.txt")),
    ("genprism", include_str!("help/generators.txt")),
    ("genrev", include_str!("help/generators.txt")),
    ("gensky", include_str!("help/generators.txt")),
    ("gensurf", include_str!("help/generators.txt")),
    ("genworm", include_str!("help/generators.txt")),
    ("xform", include_str!("help/generators.txt")),
    ("doc", include_str!("help/doc.txt")),
    ("explain", include_str!("help/doc.txt")),
];

/// Prints the help of command `name`.
pub fn command(name: &str, summary: &str) -> ExitCode {
    let text = TEXTS
        .iter()
        .find(|(n, _)| *n == name)
        .map_or("", |(_, t)| t);
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "radc {name}: {summary}\n");
    let _ = out.write_all(text.replace("{name}", name).as_bytes());
    ExitCode::SUCCESS
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every command has its text, so `--help` never prints only a summary.
    #[test]
    fn every_command_has_a_help_text() {
        for c in super::super::COMMANDS.iter().filter(|c| c.name != "help") {
            assert!(
                TEXTS.iter().any(|(n, _)| *n == c.name),
                "no help text for {}",
                c.name
            );
        }
    }
}
