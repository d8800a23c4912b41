//! rcalc's `-o` record formats (rcalc.c `readfmt`, `readfield`, `putrec`): literal
//! text, `${expr}` numbers and `$(name)` string variables, laid out in the width the
//! field takes in the format itself.

use radc_lang::c_number::{format_e, format_g};

/// One field of an output format.
#[derive(Clone, Debug, PartialEq)]
pub enum Field {
    Literal(String),
    /// `${expr}`: the expression text without blanks, and the field's width (the
    /// number of format characters it spans, `$`, braces and blanks included).
    Number {
        expr: String,
        width: usize,
    },
    /// `$(name)`: a string variable set with `-s name=value`.
    Text {
        name: String,
        width: usize,
    },
}

/// Split a format into fields, adding rcalc's final newline when the format does not
/// end with one (unless `-l` came first). `Err` carries rcalc's message.
pub fn parse(spec: &str, ignore_eol: bool) -> Result<Vec<Field>, String> {
    let chars: Vec<char> = spec.chars().collect();
    let mut fields = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        if chars[i] == '$' && chars.get(i + 1).is_some_and(|&c| c == '{' || c == '(') {
            let close = if chars[i + 1] == '{' { '}' } else { ')' };
            let start = i;
            i += 2;
            let mut body = String::new();
            while i < chars.len() && chars[i] != close {
                if !chars[i].is_whitespace() {
                    body.push(chars[i]);
                }
                i += 1;
            }
            // A field closed by the end of the format still counts what it spans.
            let end = (i + 1).min(chars.len());
            let width = end - start;
            i = end;
            fields.push(if close == '}' {
                Field::Number { expr: body, width }
            } else {
                Field::Text { name: body, width }
            });
        } else {
            let mut lit = String::new();
            while i < chars.len() {
                if chars[i] == '$' {
                    match chars.get(i + 1) {
                        Some('$') => {
                            lit.push('$');
                            i += 2;
                            continue;
                        }
                        Some('{' | '(') => break,
                        _ => return Err("format error".to_string()),
                    }
                }
                lit.push(chars[i]);
                i += 1;
            }
            fields.push(Field::Literal(lit));
        }
    }
    if !ignore_eol && !spec.ends_with('\n') {
        fields.push(Field::Literal("\n".to_string()));
    }
    Ok(fields)
}

/// How a number is printed: rcalc picks `%g` for narrow fields, `%.{w-5}e` for wide
/// ones, and `%.0f` for values within 1e-14 of an integer below 2^31.
fn number_type(v: f64, width: usize) -> NumberType {
    let av = v.abs();
    if av < 2_147_483_648.0 {
        let iv = (av + 0.5) as i64;
        if iv != 0 && (av - iv as f64).abs() <= av * 1e-14 {
            return NumberType::Fixed0;
        }
    }
    if width <= 9 {
        NumberType::G
    } else {
        NumberType::E(width - 5)
    }
}

enum NumberType {
    G,
    E(usize),
    Fixed0,
}

fn format_number(v: f64, t: &NumberType) -> String {
    match t {
        NumberType::G => format_g(v, 6),
        NumberType::E(p) => format_e(v, *p),
        // Only finite values below 2^31 are printed so (`number_type`).
        NumberType::Fixed0 => format!("{v:.0}"),
    }
}

/// A value ready for one output field.
pub enum Value<'a> {
    Literal,
    Number(f64),
    Text(&'a str),
}

/// rcalc.c `putrec`: fields adjacent to non-blank neighbours are printed without
/// padding, others right-justified (or left-justified after adjacent text) in their
/// width. `blanks_equal` is rcalc's `-b` state (on by default).
pub fn render(fields: &[Field], values: &[Value<'_>], blanks_equal: bool) -> String {
    let mut out = String::new();
    let mut adlast = false;
    for (i, (f, v)) in fields.iter().zip(values).enumerate() {
        let adnext = blanks_equal
            && fields
                .get(i + 1)
                .is_some_and(|n| !matches!(n, Field::Literal(l) if l.starts_with(' ')));
        match (f, v) {
            (Field::Literal(l), _) => {
                out.push_str(l);
                adlast = !l.ends_with(' ');
            }
            (Field::Text { width, .. }, Value::Text(s)) => {
                let pad = width.saturating_sub(s.len());
                if adlast {
                    out.push_str(s);
                }
                if !(adlast && adnext) {
                    out.extend(std::iter::repeat_n(' ', pad));
                }
                if !adlast {
                    out.push_str(s);
                }
                adlast = true;
            }
            (Field::Number { width, .. }, Value::Number(x)) => {
                let text = format_number(*x, &number_type(*x, *width));
                if adlast && adnext {
                    out.push_str(&text);
                } else if adlast {
                    out.push_str(&format!("{text:<width$}"));
                } else {
                    out.push_str(&format!("{text:>width$}"));
                }
                adlast = true;
            }
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_and_widths() {
        let f = parse("x=${ a + 1 } $(name)$$", false).unwrap_or_default();
        assert_eq!(
            f,
            vec![
                Field::Literal("x=".into()),
                Field::Number {
                    expr: "a+1".into(),
                    width: 10
                },
                Field::Literal(" ".into()),
                Field::Text {
                    name: "name".into(),
                    width: 7
                },
                Field::Literal("$".into()),
                Field::Literal("\n".into()),
            ]
        );
        assert!(parse("$x", false).is_err());
    }

    #[test]
    fn number_styles() {
        assert_eq!(format_e(1234.5, 3), "1.234e+03");
        assert_eq!(format_number(3.0, &number_type(3.0, 4)), "3");
        assert_eq!(format_number(0.5, &number_type(0.5, 4)), "0.5");
        assert_eq!(format_number(0.5, &number_type(0.5, 12)), "5.0000000e-01");
    }
}
