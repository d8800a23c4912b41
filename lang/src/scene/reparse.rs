//! A scene's parse kept up to date across edits, re-reading only the statements an
//! edit can change.
//!
//! Where a statement ends depends on the counts before it, so an edit can move every
//! later statement boundary; in practice the statements realign right after the
//! edit. The fast reader (`reader.rs`) reads a clean statement from its first token to
//! its last, looking at one more byte (the blank or the end of the text that ends the
//! last word), and nothing else: so a statement the fast reader read and that ends
//! before the edit is unchanged, and once a statement read anew ends in the unchanged
//! text after the edit exactly where an old statement (shifted) ended, everything
//! after it is the old parse, shifted. The statements from the first one the fast
//! reader could not read are the recovering parser's, which may look arbitrarily far
//! ahead: they are kept only whole, when the reading realigns before them; an edit
//! among them re-parses from there to the end, as a full parse does.
//!
//! The result is exactly [`ParsedScene::new`] of the new text (tested on random edits
//! below and in `db`).

use std::ops::ControlFlow;

use super::parser::{parse_each_from, parse_recovering};
use super::reader::{Outcome, read};
use super::syntax::{Item, SceneFile};
use crate::diagnostic::Diagnostic;
use crate::source::{self, FileId, Span};

/// What an edit cost the parse.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Reparse {
    /// Statements read again.
    pub statements: usize,
    /// Whether the whole file was parsed again.
    pub whole: bool,
}

/// A file's syntax tree and its syntax diagnostics.
#[derive(Clone, Debug, PartialEq, Default)]
pub struct ParsedScene {
    pub syntax: SceneFile,
    /// Sorted by span; a NUL byte's warning (as `radc check` reads files) included.
    pub diagnostics: Vec<Diagnostic>,
    /// Where the recovering parser took over from the fast reader (the end of the
    /// last statement the fast reader read), if it did: items from here on are its.
    recovered_from: Option<u32>,
    /// Whether the text holds a NUL byte (then every edit parses the whole file:
    /// the warning points at the first NUL of the file).
    has_nul: bool,
}

impl ParsedScene {
    /// Parses the whole text. A NUL byte is decoded and reported exactly as
    /// `radc check` reports it when reading from disk.
    pub fn new(file: FileId, text: &str) -> Self {
        let mut items = Vec::new();
        let mut push = |item: &Item| items.push(item.clone());
        let has_nul = text.as_bytes().contains(&0);
        let (mut diagnostics, recovered_from) = if has_nul {
            let (clean, mut diags) = source::decode(file, text.as_bytes());
            let (more, resume) = parse_each_from(file, &clean, &mut push);
            diags.extend(more);
            (diags, resume)
        } else {
            parse_each_from(file, text, &mut push)
        };
        diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
        ParsedScene {
            syntax: SceneFile { items },
            diagnostics,
            recovered_from: recovered_from.map(clamp_u32),
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
        if !valid || self.has_nul || inserted_nul || text.len() >= u32::MAX as usize {
            *self = ParsedScene::new(file, text);
            return Reparse {
                statements: self.syntax.items.len(),
                whole: true,
            };
        }
        let delta = new_end as i64 - old_end as i64;
        let items = &self.syntax.items;
        // Items before this index are the fast reader's.
        let fast = match self.recovered_from {
            Some(at) => items.partition_point(|i| i.span().start < at),
            None => items.len(),
        };
        // Fast statements whose last byte looked at (the one after them) is before
        // the edit are unchanged.
        let keep = items[..fast].partition_point(|i| (i.span().end as usize) < start);
        let from = keep
            .checked_sub(1)
            .map_or(0, |k| items[k].span().end as usize);

        let mut window = Vec::new();
        let mut window_diags = Vec::new();
        // The old fast statement whose end (shifted) a new statement ended at.
        let mut realigned = None;
        let mut next_old = keep;
        let mut visit = |item: &Item| {
            window.push(item.clone());
            let end = item.span().end as usize;
            if end < new_end {
                return ControlFlow::Continue(());
            }
            let old = (end as i64 - delta) as usize;
            while next_old < fast && (items[next_old].span().end as usize) < old {
                next_old += 1;
            }
            if next_old < fast && items[next_old].span().end as usize == old {
                realigned = Some(next_old);
                return ControlFlow::Break(());
            }
            ControlFlow::Continue(())
        };
        let outcome = read(file, text, from, &mut visit, &mut window_diags);
        let mut recovered_from = None;
        let tail = match outcome {
            Outcome::Halted => realigned,
            Outcome::End => None,
            Outcome::Stopped(resume) => {
                // A statement the fast reader cannot read: from there the recovering
                // parser reads to the end, as in a full parse. (Had the statement
                // before it ended where the old one did, the reading would have
                // realigned there.)
                let (more_items, more_diags) = parse_recovering(file, text, resume);
                window.extend(more_items);
                window_diags.extend(more_diags);
                recovered_from = Some(clamp_u32(resume));
                None
            }
        };
        let read_again = window.len();
        window_diags.sort_by_key(|d| (d.span.start, d.span.end));

        // Diagnostics of the kept statements start before `from`; those of the reused
        // ones after the end of the statement realigned at.
        let diags = &mut self.diagnostics;
        let kept = diags.partition_point(|d| (d.span.start as usize) < from);
        let reused = match tail {
            Some(k) => {
                let end = items[k].span().end;
                diags.partition_point(|d| d.span.start <= end)
            }
            None => diags.len(),
        };
        let mut suffix = diags.split_off(reused);
        diags.truncate(kept);
        for d in &mut suffix {
            shift_diagnostic(d, file, delta);
        }
        diags.extend(window_diags);
        diags.extend(suffix);

        let items = &mut self.syntax.items;
        let replaced_end = tail.map_or(items.len(), |k| k + 1);
        if tail.is_some() {
            if delta != 0 {
                for item in &mut items[replaced_end..] {
                    shift_item(item, delta);
                }
            }
            recovered_from = self
                .recovered_from
                .map(|at| clamp_u32((i64::from(at) + delta) as usize));
        }
        items.splice(keep..replaced_end, window);
        self.recovered_from = recovered_from;
        Reparse {
            statements: read_again,
            whole: false,
        }
    }
}

fn clamp_u32(v: usize) -> u32 {
    u32::try_from(v).unwrap_or(u32::MAX)
}

fn shift(span: &mut Span, delta: i64) {
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
