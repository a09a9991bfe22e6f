//! Where the loaded scene departs from what the file asks for: an unknown plugin replaced by a
//! stand-in or dropped (`Substituted`), a property or element nobody reads (`Ignored`). Each is
//! recorded per instance while loading; at the end they are either refused (`--strict`: an error
//! listing every one, each with its file:line) or reported once per kind of deviation (a scene with
//! 500 `mask` BSDFs gets one line about `mask`, saying how many and where the last is) followed by
//! one summary line counting them. Warnings that leave the image as Mitsuba renders it (a clamped
//! value, a sampling option caustic does not need) are not deviations: the loader prints those
//! directly.
use super::xml::Loc;
use std::path::Path;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// An element caustic does not know, rendered as something else or left out.
    Substituted,
    /// A property or nested element the plugin does not read.
    Ignored,
}

/// One deviation: where, what kind, which group it is reported under, and its message (which
/// names its file:line).
#[derive(Clone, Debug)]
pub struct Deviation {
    pub kind: Kind,
    /// Deviations with the same group are one kind of problem (e.g. "bsdf 'mask'").
    pub group: String,
    pub loc: Loc,
    pub message: String,
}

/// Every deviation of one scene, in the order met.
#[derive(Default)]
pub struct Deviations {
    list: Vec<Deviation>,
}

/// How many messages a `--strict` error lists before it only counts the rest.
const STRICT_LISTED: usize = 20;

impl Deviations {
    pub fn push(&mut self, kind: Kind, group: String, loc: &Loc, message: String) {
        self.list.push(Deviation { kind, group, loc: loc.clone(), message });
    }

    /// The `--strict` error: every deviation (up to `STRICT_LISTED`), or `None` when there is none.
    pub fn strict_error(&self, scene: &Path) -> Option<anyhow::Error> {
        let first = self.list.first()?;
        let mut text = first.message.clone();
        if self.list.len() > 1 {
            let more = self.list.len() - 1;
            text.push_str(&format!("\n{more} more {}:", plural(more, "deviation", "deviations")));
            for d in self.list.iter().skip(1).take(STRICT_LISTED - 1) {
                text.push_str(&format!("\n  {}", d.message));
            }
            if self.list.len() > STRICT_LISTED {
                text.push_str(&format!("\n  … and {} more", self.list.len() - STRICT_LISTED));
            }
        }
        Some(anyhow::anyhow!(
            "{text}\n(--strict refuses {}: it would not render as written; without --strict it renders as these messages say)",
            scene.display()
        ))
    }

    /// The warnings to print without `--strict`: one per group, in the order the groups were first
    /// met, then a summary line; empty when the scene loaded as written.
    pub fn report(&self, scene: &Path) -> Vec<String> {
        let mut groups: Vec<(&Deviation, &Deviation, usize)> = Vec::new();
        for d in &self.list {
            match groups.iter_mut().find(|(first, _, _)| first.group == d.group) {
                Some((_, last, count)) => {
                    *last = d;
                    *count += 1;
                }
                None => groups.push((d, d, 1)),
            }
        }
        let mut out: Vec<String> = groups
            .iter()
            .map(|(first, last, count)| match count {
                1 => first.message.clone(),
                n => format!("{} ({} more like it, the last at {})", first.message, n - 1, last.loc),
            })
            .collect();
        if !self.list.is_empty() {
            let count = |kind| self.list.iter().filter(|d| d.kind == kind).count();
            let (substituted, ignored) = (count(Kind::Substituted), count(Kind::Ignored));
            out.push(format!(
                "{}: {substituted} {} substituted or left out, {ignored} {} ignored ({} {} of deviation): \
                 the image may differ from Mitsuba's (--strict refuses such a scene)",
                scene.display(),
                plural(substituted, "element", "elements"),
                plural(ignored, "property", "properties"),
                groups.len(),
                plural(groups.len(), "kind", "kinds"),
            ));
        }
        out
    }
}

fn plural(n: usize, one: &'static str, many: &'static str) -> &'static str {
    if n == 1 {
        one
    } else {
        many
    }
}
