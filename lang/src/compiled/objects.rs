//! The binary scene section of octrees and mesh files (sceneio.c's `readscene`): a
//! table of type names, then objects that name their type by index in it and their
//! modifier by index among the file's objects.
//!
//! radc turns the objects back into scene text, which the scene front end lowers like
//! any other: one reader of primitives, one set of checks. A modifier is written by
//! name, which binds to the most recent definition of that name, as the index did
//! when oconv or obj2mesh read the original text; a file whose index points past a
//! later redefinition (which no text could say) is refused.

use std::collections::HashMap;
use std::fmt::Write as _;

use super::portio::{BinaryError, Reader, Result};

/// One object as stored.
#[derive(Clone, Debug, PartialEq)]
pub struct BinaryObject {
    pub type_name: String,
    /// Index of its modifier among the section's objects; `None` for `void`.
    pub modifier: Option<usize>,
    pub name: String,
    pub strings: Vec<String>,
    pub reals: Vec<f64>,
}

/// Reads a scene section (`readscene`): `objsize`-byte modifier indices.
pub fn read_objects(r: &mut Reader<'_>, objsize: usize) -> Result<Vec<BinaryObject>> {
    let mut types = Vec::new();
    loop {
        let at = r.offset();
        let t = r.string()?;
        if t.is_empty() {
            break;
        }
        if types.len() >= 1024 {
            return r.error(at, "too many object types in the scene section");
        }
        types.push(t);
    }
    let mut objects = Vec::new();
    loop {
        let at = r.offset();
        let index = r.int(1)?;
        if index == -1 {
            return Ok(objects);
        }
        let Some(type_name) = usize::try_from(index).ok().and_then(|i| types.get(i)) else {
            return r.error(at, "reference to unknown type");
        };
        let type_name = type_name.clone();
        let m_at = r.offset();
        let m = r.int(objsize)?;
        let modifier = match m {
            -1 => None,
            m => match usize::try_from(m) {
                Ok(m) if m < objects.len() => Some(m),
                _ => return r.error(m_at, format!("bad modifier index {m}")),
            },
        };
        let name = r.string()?;
        let n = r.int(2)?;
        let mut strings = Vec::new();
        for _ in 0..n.max(0) {
            strings.push(r.string()?);
        }
        let n = r.int(2)?;
        let mut reals = Vec::new();
        for _ in 0..n.max(0) {
            reals.push(r.real()?);
        }
        objects.push(BinaryObject {
            type_name,
            modifier,
            name,
            strings,
            reals,
        });
    }
}

/// The objects as scene text, one primitive each in order; reals written so that they
/// read back to the same doubles.
pub fn objects_text(objects: &[BinaryObject]) -> std::result::Result<String, BinaryError> {
    let mut text = String::new();
    let mut latest: HashMap<&str, usize> = HashMap::new();
    for (i, o) in objects.iter().enumerate() {
        let name_of = |m: usize| -> std::result::Result<&str, BinaryError> {
            let name = objects[m].name.as_str();
            if latest.get(name) == Some(&m) {
                Ok(name)
            } else {
                Err(BinaryError {
                    offset: 0,
                    message: format!(
                        "object '{}' refers to an earlier '{name}' that a later one redefines",
                        o.name
                    ),
                })
            }
        };
        if o.type_name == "alias" {
            // An alias stores its target as its modifier and no strings (the alias
            // passes the target's modifier through), or its own modifier and the
            // target's name.
            let (modifier, target) = match (o.modifier, o.strings.first()) {
                (Some(m), None) => ("inherit", name_of(m)?),
                (m, Some(target)) => (m.map_or(Ok("void"), name_of)?, target.as_str()),
                (None, None) => {
                    return Err(BinaryError {
                        offset: 0,
                        message: format!("alias '{}' has no target", o.name),
                    });
                }
            };
            let _ = writeln!(
                text,
                "{} alias {} {}",
                word(modifier),
                word(&o.name),
                word(target)
            );
        } else {
            let modifier = o.modifier.map_or(Ok("void"), name_of)?;
            let _ = write!(
                text,
                "{} {} {}\n{}",
                word(modifier),
                o.type_name,
                word(&o.name),
                o.strings.len()
            );
            for s in &o.strings {
                let _ = write!(text, " {}", word(s));
            }
            let _ = write!(text, "\n0\n{}", o.reals.len());
            for x in &o.reals {
                let _ = write!(text, " {x:e}");
            }
            text.push('\n');
        }
        latest.insert(o.name.as_str(), i);
    }
    Ok(text)
}

/// A word as the scene reader reads it back: quoted when it holds white space.
fn word(s: &str) -> String {
    if s.is_empty() || s.chars().any(char::is_whitespace) {
        format!("\"{s}\"")
    } else {
        s.to_string()
    }
}

/// Writes objects as `writescene` does, with `types` as the type table (the writer's
/// `ofun` list, in its order) and `objsize`-byte indices.
pub fn write_objects(
    w: &mut super::portio::Writer,
    types: &[&str],
    objects: &[BinaryObject],
    objsize: usize,
) {
    for t in types {
        w.string(t);
    }
    w.string("");
    for o in objects {
        let index = types.iter().position(|t| *t == o.type_name).unwrap_or(0);
        w.int(index as i64, 1);
        w.int(o.modifier.map_or(-1, |m| m as i64), objsize);
        w.string(&o.name);
        w.int(o.strings.len() as i64, 2);
        for s in &o.strings {
            w.string(s);
        }
        w.int(o.reals.len() as i64, 2);
        for &x in &o.reals {
            w.real(x);
        }
    }
    w.int(-1, 1);
}

#[cfg(test)]
mod tests {
    use super::super::portio::Writer;
    use super::*;

    fn object(t: &str, m: Option<usize>, name: &str, s: &[&str], r: &[f64]) -> BinaryObject {
        BinaryObject {
            type_name: t.into(),
            modifier: m,
            name: name.into(),
            strings: s.iter().map(|s| s.to_string()).collect(),
            reals: r.to_vec(),
        }
    }

    #[test]
    fn objects_read_back_and_turn_into_text() {
        let objects = vec![
            object("brightfunc", None, "stripes", &["stripe", "s.cal"], &[]),
            object("plastic", Some(0), "red", &[], &[0.5, 0.1, 0.1, 0.0, 0.0]),
        ];
        let mut w = Writer::default();
        write_objects(&mut w, &["plastic", "brightfunc"], &objects, 4);
        let mut r = Reader::new(&w.bytes, "truncated");
        let back = read_objects(&mut r, 4).unwrap();
        assert_eq!(back.len(), 2);
        assert_eq!(back[1].modifier, Some(0));
        assert!((back[1].reals[0] - 0.5).abs() < 1e-9);
        let text = objects_text(&back).unwrap();
        assert!(text.starts_with("void brightfunc stripes\n2 stripe s.cal\n0\n0\n"));
        assert!(text.contains("stripes plastic red\n0\n0\n5 "));
    }

    #[test]
    fn a_shadowed_modifier_is_refused() {
        let objects = vec![
            object("plastic", None, "m", &[], &[0.5, 0.5, 0.5, 0.0, 0.0]),
            object("plastic", None, "m", &[], &[0.2, 0.2, 0.2, 0.0, 0.0]),
            object("brightfunc", Some(0), "p", &["x", "."], &[]),
        ];
        assert!(objects_text(&objects).is_err());
    }

    #[test]
    fn damage_is_an_error_with_its_offset() {
        let mut w = Writer::default();
        write_objects(
            &mut w,
            &["plastic"],
            &[object("plastic", None, "a", &[], &[])],
            4,
        );
        let cut = &w.bytes[..w.bytes.len() - 3];
        assert!(read_objects(&mut Reader::new(cut, "truncated"), 4).is_err());
        let mut bad = w.bytes.clone();
        bad[9] = 7; // type index past the table
        let e = read_objects(&mut Reader::new(&bad, "truncated"), 4).unwrap_err();
        assert_eq!(e.offset, 9);
    }
}
