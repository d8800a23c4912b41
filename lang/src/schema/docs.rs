//! The user reference for primitive types, generated from the schema table.
//! `docs/primitives.md` at the repository root is this output; a test keeps them equal
//! (`RADC_BLESS=1 cargo test -p radc-lang` rewrites the file).

use super::editor::layout;
use super::{ArgList, ArgSide, Category, PRIMITIVE_TYPES, PrimitiveType};

const CATEGORIES: [(Category, &str); 7] = [
    (Category::Surface, "Surfaces"),
    (Category::Light, "Light sources"),
    (Category::Material, "Materials"),
    (Category::Texture, "Textures"),
    (Category::Pattern, "Patterns"),
    (Category::Mixture, "Mixtures"),
    (Category::Alias, "Aliases"),
];

/// The whole reference as markdown.
pub fn markdown() -> String {
    let mut out = String::from(
        "# Radiance primitive types\n\n\
         <!-- Generated from lang/src/schema/table.rs by `schema::markdown()`; do not edit. \
         Regenerate with `RADC_BLESS=1 cargo test -p radc-lang`. -->\n\n\
         Every primitive is written `modifier type identifier`, then the string arguments \
         (a count and the strings), the integer arguments (always `0`) and the real \
         arguments (a count and the numbers). Counts are written `5` (exactly), `4+` (at \
         least), `0..32` (between), `0|3|6|9` (one of) or `9+3N` (9, 12, 15, ...). \
         Arguments in `[brackets]` are optional; `..` means the group repeats. \
         **Valid** limits are errors (Radiance fails or the value means nothing); \
         **plausible** ranges only warn.\n\n\
         A trailing `[transform]` is an xform-style transform (`-t -rx -ry -rz -s -mx -my \
         -mz -i`) that places an instance or mesh, or the coordinate frame of the \
         function file; it starts at the first string that is a transform option. A function file `.` means no file.\n",
    );
    for (category, title) in CATEGORIES {
        let names: Vec<_> = of(category)
            .map(|t| format!("[{}](#{})", t.name, t.name.to_lowercase()))
            .collect();
        out.push_str(&format!("\n- **{title}:** {}", names.join(", ")));
    }
    out.push('\n');
    for (category, title) in CATEGORIES {
        out.push_str(&format!("\n## {title}\n"));
        for t in of(category) {
            section(&mut out, t);
        }
    }
    out
}

fn of(category: Category) -> impl Iterator<Item = &'static PrimitiveType> {
    PRIMITIVE_TYPES
        .iter()
        .filter(move |t| t.category == category)
}

fn section(out: &mut String, t: &PrimitiveType) {
    out.push_str(&format!(
        "\n### {}\n\n*{}* — {}.\n\n{}\n\n```\n{}\n```\n",
        t.name,
        t.category.as_str(),
        t.summary,
        t.doc,
        layout(t)
    ));
    if t.category == Category::Alias {
        return;
    }
    args_table(out, t, ArgSide::Strings);
    args_table(out, t, ArgSide::Reals);
}

fn args_table(out: &mut String, t: &PrimitiveType, side: ArgSide) {
    let list = t.args(side);
    let title = match side {
        ArgSide::Strings => "String arguments",
        ArgSide::Reals => "Real arguments",
    };
    if list.fixed.is_empty() && list.repeat.is_empty() {
        if list.count.max() == Some(0) {
            out.push_str(&format!("\n{title}: none.\n"));
        }
        return;
    }
    out.push_str(&format!("\n{title} ({}):\n\n", list.count.describe()));
    match side {
        ArgSide::Strings => out.push_str("| # | name | kind | meaning |\n|---|---|---|---|\n"),
        ArgSide::Reals => {
            out.push_str("| # | name | meaning | valid | plausible |\n|---|---|---|---|---|\n")
        }
    }
    for (i, row) in rows(list).into_iter().enumerate() {
        let (name, arg) = row;
        let pos = if i < list.fixed.len() {
            (i + 1).to_string()
        } else {
            "..".into()
        };
        let meaning = cell(arg.meaning);
        match side {
            ArgSide::Strings => out.push_str(&format!(
                "| {pos} | `{name}` | {} | {meaning} |\n",
                arg.kind.describe()
            )),
            ArgSide::Reals => out.push_str(&format!(
                "| {pos} | `{name}` | {meaning} | {} | {} |\n",
                bounds(&arg.valid),
                bounds(&arg.plausible)
            )),
        }
    }
    if list.transform {
        out.push_str(&format!(
            "| .. | `[transform]` | transform | {} |\n",
            cell(ArgList::TRANSFORM.meaning)
        ));
    }
}

/// The fixed arguments, then one row per argument of the repeated group, named as its
/// first occurrence (`x1`, `A5`) with `..` to show it repeats.
fn rows(list: &ArgList) -> Vec<(String, super::Arg)> {
    let mut rows: Vec<_> = list
        .fixed
        .iter()
        .map(|a| (a.name.to_string(), *a))
        .collect();
    for (k, arg) in list.repeat.iter().enumerate() {
        let i = list.fixed.len() + k;
        let label = list.label(i).unwrap_or_else(|| arg.name.to_string());
        rows.push((format!("{label} .."), *arg));
    }
    rows
}

fn bounds(b: &super::Bounds) -> String {
    if b.is_unbounded() {
        "—".into()
    } else {
        b.describe()
    }
}

/// Table cells cannot hold a bare `|`.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}

#[cfg(test)]
mod tests {
    use super::*;

    const COMMITTED: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/primitives.md");

    /// The committed reference must be what the table generates; set RADC_BLESS=1 to
    /// rewrite it after changing the table.
    #[test]
    fn committed_reference_is_current() {
        let generated = markdown();
        if std::env::var_os("RADC_BLESS").is_some() {
            std::fs::write(COMMITTED, &generated).expect("write docs/primitives.md");
            return;
        }
        let committed = std::fs::read_to_string(COMMITTED).unwrap_or_default();
        assert!(
            committed == generated,
            "docs/primitives.md is stale: run `RADC_BLESS=1 cargo test -p radc-lang`"
        );
    }

    #[test]
    fn every_type_has_a_section() {
        let md = markdown();
        for t in PRIMITIVE_TYPES {
            assert!(md.contains(&format!("\n### {}\n", t.name)), "{}", t.name);
        }
    }
}
