//! Which PLY properties become mesh attributes, and their names, as Mitsuba 3.9.1's `ply` plugin
//! decides: `r g b [a]` (or `red green blue [alpha]`) make `<element>_color`; other properties named
//! `<prefix>_<c>` are grouped while consecutive ones share the prefix and their one-letter suffixes
//! run through one of the sequences `x y z w`, `r g b a`, `0 1 2 3` or `1 2 3 4`, making
//! `<element>_<prefix>` (`<element>_<prefix>_color` for `r g b`); a group must have one or three
//! members. Everything else is skipped with a warning, as Mitsuba does. Values are read as numbers:
//! Mitsuba 3.9.1 neither divides integer colours by 255 nor decodes sRGB (a `uchar` 255 is read as
//! 255.0; measured with `attribute_buffer` on ASCII and binary files), and warns, as caustic does.
use anyhow::{bail, Result};
use std::collections::HashSet;

/// One property of an element, as the header declares it.
pub struct Field {
    pub name: String,
    /// An integer type (Mitsuba warns when a colour is one).
    pub integer: bool,
    /// A list property: never an attribute.
    pub list: bool,
}

/// An attribute: its Mitsuba name and the indices of its fields in the element's field list.
#[derive(Debug, PartialEq)]
pub struct Group {
    pub name: String,
    pub fields: Vec<usize>,
}

/// Suffix sequences by position (row) and kind (column): `x y z w`, `r g b a`, `0 1 2 3`, `1 2 3 4`.
const SUFFIXES: [&[u8; 4]; 4] = [b"xr01", b"yg12", b"zb23", b"wa34"];
const COLOR_KIND: usize = 1;

/// The attributes among `fields` (an element's properties that are not positions, normals, texture
/// coordinates or face indices), named with `element` (`"vertex_"` or `"face_"`).
pub fn groups(element: &str, fields: &[Field], warnings: &mut Vec<String>) -> Result<Vec<Group>> {
    let find = |name: &str| fields.iter().position(|f| f.name == name);
    let mut out = Vec::new();
    // The colour: `r g b [a]`, else `red green blue [alpha]`; the short names are reserved either way.
    let mut reserved: Vec<&str> = vec!["r", "g", "b", "a"];
    let short = ["r", "g", "b"].map(find);
    let long = ["red", "green", "blue"].map(find);
    let color = if short.iter().all(Option::is_some) {
        Some((short, find("a")))
    } else if long.iter().all(Option::is_some) {
        reserved.extend(["red", "green", "blue", "alpha"]);
        Some((long, find("alpha")))
    } else {
        None
    };
    if let Some((rgb, alpha)) = color {
        let indices: Vec<usize> = rgb.into_iter().flatten().chain(alpha).collect();
        if fields[indices[0]].integer {
            warnings.push(format!(
                "mesh attribute '{element}color' has integer fields, read as they are (Mitsuba expects colours in [0, 1] and does not rescale them either)"
            ));
        }
        out.push(Group { name: format!("{element}color"), fields: indices });
    }

    let mut seen: HashSet<String> = HashSet::new();
    // The group being read: prefix, suffix kind, fields so far.
    let mut current: Option<(String, usize, Vec<usize>)> = None;
    let flush = |current: &mut Option<(String, usize, Vec<usize>)>,
                 warnings: &mut Vec<String>,
                 seen: &mut HashSet<String>,
                 out: &mut Vec<Group>| {
        let Some((prefix, kind, members)) = current.take() else { return };
        let name = format!("{element}{prefix}{}", if kind == COLOR_KIND { "_color" } else { "" });
        if members.len() != 1 && members.len() != 3 {
            warnings.push(format!(
                "attribute '{name}' has {} fields; Mitsuba takes 1 or 3: ignored",
                members.len()
            ));
            return;
        }
        if members.len() == 3 && fields[members[0]].integer {
            warnings.push(format!(
                "mesh attribute '{name}' has integer fields, read as they are (Mitsuba expects colours in [0, 1] and does not rescale them either)"
            ));
        }
        seen.insert(prefix);
        out.push(Group { name, fields: members });
    };
    let mut i = 0;
    while i < fields.len() {
        let field = &fields[i];
        if reserved.contains(&field.name.as_str()) {
            i += 1;
            continue;
        }
        let parts = field.name.rsplit_once('_').filter(|(_, suffix)| suffix.len() == 1 && !field.list);
        let Some((prefix, suffix)) = parts else {
            warnings.push(format!(
                "property '{}' is not named <prefix>_<one letter> (or is a list): not an attribute, ignored",
                field.name
            ));
            flush(&mut current, warnings, &mut seen, &mut out);
            i += 1;
            continue;
        };
        if current.as_ref().is_some_and(|(p, _, _)| p != prefix) {
            flush(&mut current, warnings, &mut seen, &mut out);
        }
        let skip_prefix = |i: &mut usize| {
            let start = format!("{prefix}_");
            while *i < fields.len() && fields[*i].name.starts_with(&start) {
                *i += 1;
            }
        };
        let c = suffix.as_bytes()[0];
        match &mut current {
            None if seen.contains(prefix) => {
                warnings.push(format!("attribute prefix '{prefix}' appears twice: '{}' ignored", field.name));
                skip_prefix(&mut i);
                continue;
            }
            None => {
                let Some(kind) = SUFFIXES[0].iter().position(|&s| s == c) else {
                    warnings.push(format!(
                        "property '{}': an attribute cannot start with this suffix; ignored",
                        field.name
                    ));
                    i += 1;
                    continue;
                };
                current = Some((prefix.to_string(), kind, vec![i]));
            }
            Some((_, kind, members)) => {
                if members.len() >= SUFFIXES.len() || SUFFIXES[members.len()][*kind] != c {
                    warnings.push(format!("attribute '{prefix}': its suffixes are out of sequence; ignored"));
                    current = None;
                    skip_prefix(&mut i);
                    continue;
                }
                members.push(i);
            }
        }
        i += 1;
    }
    flush(&mut current, warnings, &mut seen, &mut out);
    let mut names = HashSet::new();
    if let Some(g) = out.iter().find(|g| !names.insert(g.name.as_str())) {
        bail!("attribute '{}' is defined twice (Mitsuba refuses it too)", g.name);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fields(names: &str) -> Vec<Field> {
        names.split_whitespace().map(|n| Field { name: n.into(), integer: false, list: false }).collect()
    }

    fn names(element: &str, list: &str) -> Vec<(String, Vec<usize>)> {
        let mut w = Vec::new();
        groups(element, &fields(list), &mut w).unwrap().into_iter().map(|g| (g.name, g.fields)).collect()
    }

    #[test]
    fn colours_and_prefixed_groups_get_mitsubas_names() {
        // The names Mitsuba 3.9.1 gave these properties (attribute_buffer on the same header).
        assert_eq!(
            names("vertex_", "red green blue alpha temp_x w_0"),
            [
                ("vertex_color".into(), vec![0, 1, 2, 3]),
                ("vertex_temp".into(), vec![4]),
                ("vertex_w".into(), vec![5])
            ]
        );
        assert_eq!(
            names("face_", "q_r q_g q_b solo one_x"),
            [("face_q_color".into(), vec![0, 1, 2]), ("face_one".into(), vec![4])]
        );
        assert_eq!(
            names("vertex_", "r g b n_1 n_2 n_3"),
            [("vertex_color".into(), vec![0, 1, 2]), ("vertex_n".into(), vec![3, 4, 5])]
        );
    }

    #[test]
    fn groups_of_two_or_four_and_broken_sequences_are_skipped() {
        assert!(names("vertex_", "d_x d_y").is_empty());
        assert!(names("vertex_", "d_x d_y d_z d_w").is_empty());
        assert_eq!(names("vertex_", "d_x d_z e_0"), [("vertex_e".into(), vec![2])]);
        // Red and green alone are no colour.
        assert!(names("vertex_", "red green").is_empty());
    }
}
