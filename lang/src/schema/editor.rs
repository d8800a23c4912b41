//! What editors show for a primitive type: completion snippets, hover text and
//! argument hints. Everything here reads only the schema table, so the language server,
//! the CLI's explanations and the generated reference say the same thing.

use super::{ArgList, ArgSide, Category, PrimitiveType};

/// A completion snippet (LSP/VS Code syntax) laying out the fewest arguments the type
/// accepts: `${1:mod} plastic ${2:name}\n0\n0\n5 ${3:red} ${4:green} ...`.
pub fn snippet(t: &PrimitiveType) -> String {
    let mut next = 3;
    let head = format!("${{1:mod}} {} ${{2:name}}", t.name);
    if t.category == Category::Alias {
        return format!("{head} ${{3:reference}}");
    }
    let strings = snippet_line(&t.strings, &mut next);
    let reals = snippet_line(&t.reals, &mut next);
    format!("{head}\n{strings}\n0\n{reals}")
}

fn snippet_line(list: &ArgList, next: &mut usize) -> String {
    let n = list.count.min() as usize;
    let mut line = n.to_string();
    for i in 0..n {
        let label = list.label(i).unwrap_or_else(|| format!("arg{}", i + 1));
        line.push_str(&format!(" ${{{next}:{}}}", escape_snippet(&label)));
        *next += 1;
    }
    line
}

/// Snippet syntax gives `$`, `}` and `\` meaning; labels rarely hold them, but a
/// placeholder must never be broken by one.
fn escape_snippet(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if matches!(c, '$' | '}' | '\\') {
            out.push('\\');
        }
        out.push(c);
    }
    out
}

/// The argument layout as the Radiance manual writes it, one line per section:
/// `mod plastic id` / `0` / `0` / `5 red green blue spec rough`.
pub fn layout(t: &PrimitiveType) -> String {
    if t.category == Category::Alias {
        return format!("mod {} id reference", t.name);
    }
    format!(
        "mod {} id\n{}\n0\n{}",
        t.name,
        layout_line(&t.strings),
        layout_line(&t.reals)
    )
}

fn layout_line(list: &ArgList) -> String {
    let mut words = vec![list.count.describe()];
    let required = list.count.min() as usize;
    let fixed = list.fixed.len();
    words.extend(list.fixed.iter().take(required).map(|a| a.name.to_string()));
    if fixed > required {
        let optional: Vec<_> = list.fixed[required.min(fixed)..]
            .iter()
            .map(|a| a.name)
            .collect();
        words.push(format!("[{}]", optional.join(" ")));
    }
    if !list.repeat.is_empty() {
        let groups = required
            .saturating_sub(fixed)
            .div_ceil(list.repeat.len())
            .max(1);
        let shown = fixed + groups * list.repeat.len();
        words.extend((fixed..shown).filter_map(|i| list.label(i)));
        words.push("..".into());
    }
    if list.transform {
        words.push("[transform]".into());
    }
    words.join(" ")
}

/// Hover text in markdown: what the type is, its layout and its arguments.
pub fn hover(t: &PrimitiveType) -> String {
    let mut out = format!(
        "**{}** ({})\n\n{}\n\n{}\n\n```\n{}\n```\n",
        t.name,
        t.category.as_str(),
        t.summary,
        t.doc,
        layout(t)
    );
    for (side, title) in [(ArgSide::Strings, "Strings"), (ArgSide::Reals, "Reals")] {
        let list = t.args(side);
        let named = list.fixed.len() + list.repeat.len();
        if named == 0 {
            continue;
        }
        out.push_str(&format!("\n{title} ({}):\n", list.count.describe()));
        for i in 0..named {
            if let Some(hint) = arg_hint(t, side, i) {
                out.push_str(&format!("- {hint}\n"));
            }
        }
        if list.transform {
            out.push_str(&format!("- [transform] — {}\n", ArgList::TRANSFORM.meaning));
        }
    }
    out
}

/// A one-line hint for argument `index` (0-based) of one side: `spec — specularity ...`,
/// with the hard limits when there are any. `None` past the arguments the type names.
pub fn arg_hint(t: &PrimitiveType, which: ArgSide, index: usize) -> Option<String> {
    let list = t.args(which);
    let (arg, _) = list.arg_at(index)?;
    let label = list.label(index)?;
    let mut hint = format!("{label} — {}", arg.meaning);
    if !arg.valid.is_unbounded() {
        hint.push_str(&format!(" [must be {}]", arg.valid.describe()));
    }
    Some(hint)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schema::lookup;

    fn ty(name: &str) -> &'static PrimitiveType {
        lookup(name).expect("type in table")
    }

    #[test]
    fn plastic_snippet() {
        assert_eq!(
            snippet(ty("plastic")),
            "${1:mod} plastic ${2:name}\n0\n0\n5 ${3:red} ${4:green} ${5:blue} ${6:spec} ${7:rough}"
        );
    }

    #[test]
    fn polygon_snippet_has_three_vertices() {
        assert_eq!(
            snippet(ty("polygon")),
            "${1:mod} polygon ${2:name}\n0\n0\n9 ${3:x1} ${4:y1} ${5:z1} ${6:x2} ${7:y2} \
             ${8:z2} ${9:x3} ${10:y3} ${11:z3}"
        );
    }

    #[test]
    fn functional_snippet_leaves_out_the_transform() {
        assert_eq!(
            snippet(ty("brightfunc")),
            "${1:mod} brightfunc ${2:name}\n2 ${3:refl} ${4:funcfile}\n0\n0"
        );
    }

    #[test]
    fn data_snippet_has_one_coordinate() {
        assert_eq!(
            snippet(ty("brightdata")),
            "${1:mod} brightdata ${2:name}\n4 ${3:func} ${4:datafile} ${5:funcfile} ${6:x1}\n0\n0"
        );
    }

    #[test]
    fn alias_snippet() {
        assert_eq!(
            snippet(ty("alias")),
            "${1:mod} alias ${2:name} ${3:reference}"
        );
    }

    #[test]
    fn layouts_follow_the_manual() {
        assert_eq!(
            layout(ty("plastic")),
            "mod plastic id\n0\n0\n5 red green blue spec rough"
        );
        assert_eq!(
            layout(ty("glass")),
            "mod glass id\n0\n0\n3|4 rtn gtn btn [n]"
        );
        assert_eq!(
            layout(ty("polygon")),
            "mod polygon id\n0\n0\n9+3N x1 y1 z1 x2 y2 z2 x3 y3 z3 .."
        );
        assert_eq!(
            layout(ty("plasfunc")),
            "mod plasfunc id\n2+ refl funcfile [transform]\n0\n4+ red green blue spec A5 .."
        );
        assert_eq!(
            layout(ty("colordata")).lines().nth(1),
            Some("8+ rfunc gfunc bfunc rdatafile gdatafile bdatafile funcfile x1 .. [transform]")
        );
        assert_eq!(
            layout(ty("mist")).lines().nth(3),
            Some("0|3|6|7 [rext gext bext ralb galb balb g]")
        );
    }

    #[test]
    fn hints_name_and_explain() {
        let plastic = ty("plastic");
        let spec = arg_hint(plastic, ArgSide::Reals, 3).unwrap();
        assert!(spec.starts_with("spec — specularity"), "{spec}");
        assert_eq!(arg_hint(plastic, ArgSide::Reals, 5), None);
        assert_eq!(arg_hint(plastic, ArgSide::Strings, 0), None);
        let sphere = arg_hint(ty("sphere"), ArgSide::Reals, 3).unwrap();
        assert!(sphere.ends_with("[must be not 0]"), "{sphere}");
    }

    #[test]
    fn hints_number_repeated_arguments() {
        let polygon = ty("polygon");
        assert!(
            arg_hint(polygon, ArgSide::Reals, 4)
                .unwrap()
                .starts_with("y2 — ")
        );
        let plasfunc = ty("plasfunc");
        assert!(
            arg_hint(plasfunc, ArgSide::Reals, 4)
                .unwrap()
                .starts_with("A5 — ")
        );
        assert!(
            arg_hint(plasfunc, ArgSide::Reals, 9)
                .unwrap()
                .starts_with("A10 — ")
        );
        let antimatter = ty("antimatter");
        assert!(
            arg_hint(antimatter, ArgSide::Strings, 1)
                .unwrap()
                .starts_with("mod2 — ")
        );
    }

    #[test]
    fn hover_shows_layout_and_arguments() {
        let h = hover(ty("plastic2"));
        assert!(h.starts_with("**plastic2** (material)"), "{h}");
        assert!(h.contains("4+ ux uy uz funcfile [transform]"), "{h}");
        assert!(h.contains("- urough — "), "{h}");
        assert!(h.contains("- [transform] — "), "{h}");
    }
}
