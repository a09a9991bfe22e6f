//! XML primitives of the loader: parsed files with their line index (`Source`; files nested too deep
//! for a recursive parser are refused before parsing), source locations
//! (`Loc`), required attributes, number lists, and vectors given as one or three numbers (Mitsuba's
//! `expand_value_to_xyz`). A leaf module: it uses nothing else of the loader, so that `props` and
//! `transform` can both build on it.
use anyhow::{bail, Result};
use glam::Vec3;
use std::fmt;
use std::path::{Path, PathBuf};

/// A position in a scene file.
#[derive(Clone, Debug)]
pub struct Loc {
    pub file: PathBuf,
    pub line: u32,
}

/// A parsed scene file: its path, its document, and where each of its lines starts. Every element's
/// line is wanted (for messages), and roxmltree's `text_pos_at` counts lines from the start of the
/// file, which made loading quadratic in the number of elements; with the line starts indexed once,
/// a line is a binary search.
pub struct Source<'input> {
    pub path: PathBuf,
    pub doc: roxmltree::Document<'input>,
    /// Byte offsets of the lines' starts, ascending; 0 first.
    line_starts: Vec<usize>,
}

/// Elements nested deeper than this are refused before parsing: roxmltree's parser and the loader
/// (through `twosided` BSDFs, `moment` integrators) recurse once per level, and a hostile file nested
/// tens of thousands deep would overflow the stack. Real scenes nest a handful of levels (scene,
/// shape, bsdf, bsdf, texture, transform, operation). Measured in a release build, 1,000 levels of
/// `twosided` and `moment` fit a 1 MiB stack but not 512 KiB; debug builds take more per level, so
/// 256 leaves room on a 2 MiB thread (a test's, a binding's) either way.
pub const MAX_DEPTH: usize = 256;

impl<'input> Source<'input> {
    pub fn parse(path: &Path, text: &'input str) -> Result<Self> {
        if let Some(at) = too_deep(text.as_bytes(), MAX_DEPTH) {
            let line = 1 + text.as_bytes()[..at].iter().filter(|&&b| b == b'\n').count();
            bail!("{}:{line}: elements nested more than {MAX_DEPTH} deep", path.display());
        }
        let doc = roxmltree::Document::parse(text).map_err(|e| {
            let pos = e.pos();
            anyhow::anyhow!("{}:{}:{}: malformed XML: {e}", path.display(), pos.row, pos.col)
        })?;
        // Lines end at '\n', as roxmltree counts them.
        let newlines = text.bytes().enumerate().filter(|&(_, b)| b == b'\n').map(|(i, _)| i + 1);
        let line_starts = std::iter::once(0).chain(newlines).collect();
        Ok(Source { path: path.to_path_buf(), doc, line_starts })
    }

    /// Where `node` (an element of this document) starts.
    pub fn loc(&self, node: roxmltree::Node) -> Loc {
        let line = self.line_starts.partition_point(|&start| start <= node.range().start);
        Loc { file: self.path.clone(), line: line as u32 }
    }
}

/// The byte offset of the first element nested deeper than `limit` in `text`, found by a scan over
/// its tags (comments, CDATA, processing instructions and declarations skipped, quoted attribute
/// values honoured), without parsing: the parser itself recurses per level. Malformed text that the
/// scan misreads is left to the parser to refuse.
fn too_deep(text: &[u8], limit: usize) -> Option<usize> {
    let find = |from: usize, pattern: &[u8]| -> usize {
        text[from..].windows(pattern.len()).position(|w| w == pattern).map_or(text.len(), |i| from + i)
    };
    let (mut depth, mut i) = (0usize, 0usize);
    while let Some(offset) = text[i..].iter().position(|&b| b == b'<') {
        let start = i + offset;
        let rest = &text[start..];
        i = if rest.starts_with(b"<!--") {
            find(start + 4, b"-->") + 3
        } else if rest.starts_with(b"<![CDATA[") {
            find(start + 9, b"]]>") + 3
        } else if rest.starts_with(b"<?") {
            find(start + 2, b"?>") + 2
        } else if rest.starts_with(b"<!") {
            find(start + 2, b">") + 1
        } else if rest.starts_with(b"</") {
            depth = depth.saturating_sub(1);
            find(start + 2, b">") + 1
        } else {
            // An opening tag: to its '>' outside quotes; `/>` closes it at once.
            let mut j = start + 1;
            let mut quote = None;
            while j < text.len() {
                match (quote, text[j]) {
                    (None, b'"' | b'\'') => quote = Some(text[j]),
                    (Some(q), c) if c == q => quote = None,
                    (None, b'>') => break,
                    _ => {}
                }
                j += 1;
            }
            if text.get(j.wrapping_sub(1)) != Some(&b'/') {
                depth += 1;
                if depth > limit {
                    return Some(start);
                }
            }
            j + 1
        }
        .min(text.len());
    }
    None
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.file.display(), self.line)
    }
}

pub fn attr<'a>(node: roxmltree::Node<'a, '_>, name: &str, loc: &Loc) -> Result<&'a str> {
    match node.attribute(name) {
        Some(v) => Ok(v),
        None => bail!("{loc}: <{}> needs the attribute '{name}'", node.tag_name().name()),
    }
}

/// Parses a list of numbers separated by commas and/or whitespace.
pub fn parse_numbers(text: &str, loc: &Loc) -> Result<Vec<f64>> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| s.parse::<f64>().map_err(|_| anyhow::anyhow!("{loc}: '{s}' is not a number")))
        .collect()
}

/// Why `expand_value_to_xyz` rejected a value. The callers word their own messages (a `<scale>`, an
/// `<rgb>` and a point have always said it differently), so the reason is kept apart from the text.
#[derive(Debug)]
pub enum XyzError {
    /// `value` is not a list of numbers (the message is complete).
    Numbers(anyhow::Error),
    /// `value` holds this many numbers, neither 1 nor 3.
    Count(usize),
    /// This attribute (`x`, `y` or `z`) is not a number.
    NotANumber(&'static str),
}

/// The scene's parameters (`<default>` and `-D name=value`), which `$name` in any attribute refers to.
pub type Params = std::collections::HashMap<String, String>;

/// `value` with its `$name` references replaced by the parameters' values, as Mitsuba does in every
/// attribute; an undefined one is an error naming the place.
pub fn substitute(params: &Params, value: &str, loc: &Loc) -> Result<String> {
    if !value.contains('$') {
        return Ok(value.to_string());
    }
    let mut out = String::new();
    let mut rest = value;
    while let Some(i) = rest.find('$') {
        out.push_str(&rest[..i]);
        let after = &rest[i + 1..];
        let len = after.find(|c: char| !(c.is_ascii_alphanumeric() || c == '_')).unwrap_or(after.len());
        let name = &after[..len];
        match params.get(name) {
            Some(v) => out.push_str(v),
            None => bail!("{loc}: undefined parameter ${name} (give it with -D {name}=… or a <default>)"),
        }
        rest = &after[len..];
    }
    out.push_str(rest);
    Ok(out)
}

/// Attribute `name` of `node`, its `$name` references substituted.
pub fn attribute(node: roxmltree::Node, name: &str, params: &Params, loc: &Loc) -> Result<Option<String>> {
    node.attribute(name).map(|v| substitute(params, v, loc)).transpose()
}

/// A vector given as `value="v"` (all three components), `value="x, y, z"`, or as `x=… y=… z=…`
/// attributes, each absent one `default` (0 for a translation, 1 for a scale), as Mitsuba's
/// `expand_value_to_xyz` reads it. `value` is passed separately because the callers substitute
/// `$name` references in it first (as this does in `x`, `y` and `z`); when it is given, `x`/`y`/`z`
/// are not read.
pub fn expand_value_to_xyz(
    node: roxmltree::Node,
    value: Option<&str>,
    default: f32,
    params: &Params,
    loc: &Loc,
) -> Result<Vec3, XyzError> {
    if let Some(v) = value {
        let n = parse_numbers(v, loc).map_err(XyzError::Numbers)?;
        return match n.len() {
            1 => Ok(Vec3::splat(n[0] as f32)),
            3 => Ok(Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32)),
            count => Err(XyzError::Count(count)),
        };
    }
    let get = |a: &'static str| -> Result<f32, XyzError> {
        match attribute(node, a, params, loc).map_err(XyzError::Numbers)? {
            Some(s) => s.trim().parse().map_err(|_| XyzError::NotANumber(a)),
            None => Ok(default),
        }
    };
    Ok(Vec3::new(get("x")?, get("y")?, get("z")?))
}

/// A point or vector (`expand_value_to_xyz` with absent components 0).
pub fn vector_from_node(
    node: roxmltree::Node,
    value: Option<&str>,
    params: &Params,
    loc: &Loc,
) -> Result<Vec3> {
    expand_value_to_xyz(node, value, 0.0, params, loc).map_err(|e| match e {
        XyzError::Numbers(e) => e,
        XyzError::Count(n) => anyhow::anyhow!("{loc}: expected 3 numbers, got {n}"),
        XyzError::NotANumber(a) => anyhow::anyhow!("{loc}: '{a}' must be a number"),
    })
}

#[cfg(test)]
mod tests {
    use super::too_deep;

    /// Only elements count: not tags inside comments, CDATA or quoted attribute values, nor
    /// self-closing ones.
    #[test]
    fn the_depth_scan_counts_elements_only() {
        let deep = |n: usize| format!("{}{}", "<a>".repeat(n), "</a>".repeat(n));
        assert_eq!(too_deep(deep(3).as_bytes(), 3), None);
        assert_eq!(too_deep(deep(4).as_bytes(), 3), Some(9));
        let noise = format!(
            "<?xml version=\"1.0\"?><!-- {} --><s a=\"<b>\" c='/>'><![CDATA[{}]]>{}<e/><e x=\"1\"/></s>",
            "<a>".repeat(9),
            "<a>".repeat(9),
            deep(2)
        );
        assert_eq!(too_deep(noise.as_bytes(), 3), None);
        assert!(too_deep(noise.as_bytes(), 2).is_some());
    }
}
