//! A scene's parse kept up to date across edits, re-reading only the statements an
//! edit can change.
//!
//! Where a statement ends depends on the counts before it, so an edit can move every
//! later statement boundary; in practice the statements realign right after the
//! edit. Each statement's reading depends on the text from where it starts up to some
//! byte: for the fast reader (`reader.rs`) the byte after its last word (the blank or
//! the end of the text that ends it), for the recovering parser the end of the
//! window of tokens it was handed (`parser::recover_statement`). So the statements
//! whose reading looked only at text before the edit are unchanged; reading starts
//! again after the last of them, and once a statement read anew ends in the
//! unchanged text after the edit exactly where an old statement (shifted) ended,
//! every statement after it is the old one, shifted.
//!
//! The result is exactly [`ParsedScene::new`] of the new text (tested on random edits
//! in `db`).

use std::ops::ControlFlow;

use super::parser::read_statements;
use super::syntax::{Item, SceneFile};
use crate::diagnostic::Diagnostic;
use crate::source::{self, FileId, Span};

/// What an edit cost the parse.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Reparse {
    /// Statements read again.
    pub statements: usize,
    /// Whether the whole file was parsed again.
    pub whole: bool,
    /// Which statements changed, unless the whole file was parsed again.
    pub change: Option<Change>,
}

/// The statements an edit replaced.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Change {
    /// The new statements, as indices into the new tree's items.
    pub items: std::ops::Range<usize>,
    /// The old statements they replaced: from the start of the first to the end of
    /// the last (in the old text), `u32::MAX` for "to the end".
    pub old_start: u32,
    pub old_end: u32,
    /// How far the statements after them moved.
    pub delta: i64,
}

/// A file's syntax tree and its syntax diagnostics.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ParsedScene {
    pub syntax: SceneFile,
    /// Sorted by span; a NUL byte's warning (as `radc check` reads files) included.
    pub diagnostics: Vec<Diagnostic>,
    /// For each diagnostic, where the statement that reported it starts.
    owners: Vec<u32>,
    /// The statements the recovering parser read: where each starts and the byte
    /// before which it looked at the text (`u32::MAX`: it saw the end of the text).
    recovered: Vec<(u32, u32)>,
    /// Whether the text holds a NUL byte (then every edit parses the whole file:
    /// the warning points at the first NUL of the file).
    has_nul: bool,
}

/// Statements read, as [`read_statements`] hands them over.
#[derive(Default)]
struct Reading {
    items: Vec<Item>,
    diagnostics: Vec<(Diagnostic, u32)>,
    recovered: Vec<(u32, u32)>,
}

impl Reading {
    fn add(&mut self, item: &Item, diags: &mut Vec<Diagnostic>, looked_to: Option<usize>) {
        let start = item.span().start;
        self.diagnostics.extend(diags.drain(..).map(|d| (d, start)));
        if let Some(to) = looked_to {
            self.recovered.push((start, clamp_u32(to)));
        }
        self.items.push(item.clone());
    }
}

/// Sorted by span as a whole parse sorts them: a stable sort of the order they were
/// reported in, which is statement order.
fn sort(diags: &mut [(Diagnostic, u32)]) {
    diags.sort_by_key(|(d, owner)| (d.span.start, d.span.end, *owner));
}

impl ParsedScene {
    /// Parses the whole text. A NUL byte is decoded and reported exactly as
    /// `radc check` reports it when reading from disk.
    pub fn new(file: FileId, text: &str) -> Self {
        let mut reading = Reading::default();
        let has_nul = text.as_bytes().contains(&0);
        let mut add = |item: &Item, diags: &mut Vec<Diagnostic>, to| {
            reading.add(item, diags, to);
            ControlFlow::Continue(())
        };
        let mut first = Vec::new();
        if has_nul {
            let (clean, diags) = source::decode(file, text.as_bytes());
            first = diags;
            let _ = read_statements(file, &clean, 0, &mut add);
        } else {
            let _ = read_statements(file, text, 0, &mut add);
        }
        let mut diags: Vec<(Diagnostic, u32)> = first.into_iter().map(|d| (d, 0)).collect();
        diags.append(&mut reading.diagnostics);
        sort(&mut diags);
        let (diagnostics, owners) = diags.into_iter().unzip();
        ParsedScene {
            syntax: SceneFile {
                items: reading.items,
            },
            diagnostics,
            owners,
            recovered: reading.recovered,
            has_nul,
        }
    }

    /// Brings the parse up to date after an edit: bytes `start..old_end` of the text
    /// it was parsed from are now bytes `start..new_end` of `text`, the rest is
    /// unchanged.
    pub fn edit(
        &mut self,
        file: FileId,
        text: &str,
        start: usize,
        old_end: usize,
        new_end: usize,
    ) -> Reparse {
        let valid = start <= old_end && start <= new_end && new_end <= text.len();
        let inserted_nul = valid && text.as_bytes()[start..new_end].contains(&0);
        if !valid || self.has_nul || inserted_nul || text.len() >= u32::MAX as usize - 1 {
            *self = ParsedScene::new(file, text);
            return Reparse {
                statements: self.syntax.items.len(),
                whole: true,
                change: None,
            };
        }
        let delta = new_end as i64 - old_end as i64;
        let items = &self.syntax.items;
        // Statements whose reading looked only before the edit are unchanged: those
        // ending before it, up to the first recovered one that looked further.
        let mut keep = items.partition_point(|i| (i.span().end as usize) < start);
        let kept_end = keep.checked_sub(1).map_or(0, |k| items[k].span().start);
        let looked_past = self
            .recovered
            .iter()
            .take_while(|(at, _)| *at <= kept_end)
            .find(|(_, to)| *to as usize > start);
        if let Some(&(at, _)) = looked_past {
            keep = keep.min(items.partition_point(|i| i.span().start < at));
        }
        let from = keep
            .checked_sub(1)
            .map_or(0, |k| items[k].span().end as usize);

        let mut reading = Reading::default();
        // The old statement whose end (shifted) a new statement ended at.
        let mut realigned = None;
        let mut next_old = keep;
        let mut visit = |item: &Item, diags: &mut Vec<Diagnostic>, looked_to: Option<usize>| {
            reading.add(item, diags, looked_to);
            let end = item.span().end as usize;
            if end < new_end {
                return ControlFlow::Continue(());
            }
            let old = (end as i64 - delta) as usize;
            while next_old < items.len() && (items[next_old].span().end as usize) < old {
                next_old += 1;
            }
            if next_old < items.len() && items[next_old].span().end as usize == old && old > 0 {
                realigned = Some(next_old);
                return ControlFlow::Break(());
            }
            ControlFlow::Continue(())
        };
        let _ = read_statements(file, text, from, &mut visit);
        let read_again = reading.items.len();

        // The old statements from `keep` to the realigned one are replaced; those
        // after it are kept, shifted.
        let replaced_end = realigned.map_or(items.len(), |k| k + 1);
        let old_from = items.get(keep).map_or(u32::MAX, |i| i.span().start);
        let old_after = realigned.map_or(u32::MAX, |k| items[k].span().end);
        let shift_u32 = |v: u32| (i64::from(v) + delta) as u32;

        let mut diags: Vec<(Diagnostic, u32)> = std::mem::take(&mut self.diagnostics)
            .into_iter()
            .zip(std::mem::take(&mut self.owners))
            .filter(|(_, owner)| *owner < old_from || *owner > old_after)
            .map(|(mut d, owner)| {
                if owner > old_after {
                    shift_diagnostic(&mut d, file, delta);
                    (d, shift_u32(owner))
                } else {
                    (d, owner)
                }
            })
            .collect();
        diags.append(&mut reading.diagnostics);
        sort(&mut diags);
        (self.diagnostics, self.owners) = diags.into_iter().unzip();

        let mut recovered: Vec<(u32, u32)> = Vec::with_capacity(self.recovered.len());
        recovered.extend(self.recovered.iter().filter(|(at, _)| *at < old_from));
        recovered.append(&mut reading.recovered);
        recovered.extend(self.recovered.iter().filter(|(at, _)| *at > old_after).map(
            |&(at, to)| {
                let to = if to == u32::MAX { to } else { shift_u32(to) };
                (shift_u32(at), to)
            },
        ));
        self.recovered = recovered;

        let items = &mut self.syntax.items;
        if delta != 0 {
            for item in &mut items[replaced_end..] {
                shift_item(item, delta);
            }
        }
        items.splice(keep..replaced_end, reading.items);
        Reparse {
            statements: read_again,
            whole: false,
            change: Some(Change {
                items: keep..keep + read_again,
                old_start: old_from,
                old_end: old_after,
                delta,
            }),
        }
    }
}

fn clamp_u32(v: usize) -> u32 {
    u32::try_from(v).unwrap_or(u32::MAX)
}

pub(super) fn shift(span: &mut Span, delta: i64) {
    span.start = (i64::from(span.start) + delta) as u32;
    span.end = (i64::from(span.end) + delta) as u32;
}

fn shift_diagnostic(d: &mut Diagnostic, file: FileId, delta: i64) {
    if d.span.file == file {
        shift(&mut d.span, delta);
    }
    for label in &mut d.labels {
        if label.span.file == file {
            shift(&mut label.span, delta);
        }
    }
}

fn shift_item(item: &mut Item, delta: i64) {
    let s = |span: &mut Span| shift(span, delta);
    match item {
        Item::Primitive(p) => {
            s(&mut p.span);
            s(&mut p.modifier.span);
            s(&mut p.kind.span);
            s(&mut p.name.span);
            s(&mut p.strings.count_span);
            s(&mut p.ints.count_span);
            s(&mut p.reals.count_span);
            p.strings.items.iter_mut().for_each(|w| s(&mut w.span));
            p.ints.items.iter_mut().for_each(|w| s(&mut w.span));
            p.reals.items.iter_mut().for_each(|r| s(&mut r.span));
        }
        Item::Alias(a) => {
            s(&mut a.span);
            s(&mut a.keyword);
            s(&mut a.modifier.span);
            s(&mut a.name.span);
            s(&mut a.target.span);
        }
        Item::Command(c) => s(&mut c.span),
        Item::Comment(span) | Item::Error(span) => s(span),
    }
}
