//! The host's folders follow the pipeline (docs/host.md): each may use only the folders its
//! `mod.rs` names in the paragraph of its module doc that begins with "Uses", and those uses form
//! no cycle. Read from the sources: every `crate::…` and `super::…` path in `host/src` (comments
//! left out), mapped to the top-level folder (or file) it names.
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// A folder (or a file) at the top of `host/src`, or the crate root (`lib.rs`'s own items).
type Node = String;
/// Uses of one node by another, each with the first place (`path:line`) it is seen.
type Graph = BTreeMap<Node, BTreeMap<Node, String>>;

const ROOT: &str = "lib.rs";

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn folders(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            out.push(path.clone());
            folders(&path, out);
        }
    }
}

/// The module a file holds, as path segments from the crate root (`prepare/buffers.rs` →
/// `[prepare, buffers]`, `prepare/mod.rs` → `[prepare]`, `lib.rs` → `[]`).
fn module_of(relative: &Path) -> Vec<String> {
    let mut segments: Vec<String> =
        relative.with_extension("").iter().map(|s| s.to_string_lossy().into_owned()).collect();
    if segments.last().is_some_and(|s| s == "mod" || s == "lib") {
        segments.pop();
    }
    segments
}

/// The text with each `//` comment (doc comments too) cut off: a path named in prose is no use.
fn code_of(text: &str) -> String {
    text.lines().map(|line| line.find("//").map_or(line, |at| &line[..at])).collect::<Vec<_>>().join("\n")
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The first segment of each path that starts at `at` in `code`: `name…` gives `name`, a group
/// `{a::x, b, c::{…}}` gives `a`, `b` and `c`.
fn first_segments(code: &str, at: usize) -> Vec<String> {
    let rest = code[at..].trim_start();
    if let Some(group) = rest.strip_prefix('{') {
        let mut names = Vec::new();
        let (mut depth, mut start) = (0usize, 0usize);
        for (i, c) in group.char_indices() {
            match c {
                '{' => depth += 1,
                '}' if depth == 0 => {
                    names.push(&group[start..i]);
                    break;
                }
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    names.push(&group[start..i]);
                    start = i + 1;
                }
                _ => {}
            }
        }
        names.iter().filter_map(|item| ident_at(item.trim_start())).collect()
    } else {
        ident_at(rest).into_iter().collect()
    }
}

fn ident_at(text: &str) -> Option<String> {
    let end = text.find(|c: char| !is_ident(c)).unwrap_or(text.len());
    (end > 0).then(|| text[..end].to_string())
}

/// The places where `keyword::` begins a path (not as the tail of another path or identifier).
fn path_starts<'a>(code: &'a str, keyword: &'a str) -> impl Iterator<Item = usize> + 'a {
    let needle = format!("{keyword}::");
    code.match_indices(keyword).map(|(i, _)| i).filter(move |&i| {
        let before = code[..i].chars().next_back();
        code[i..].starts_with(&needle) && !before.is_some_and(|c| is_ident(c) || c == ':' || c == '$')
    })
}

fn line_of(code: &str, at: usize) -> usize {
    code[..at].matches('\n').count() + 1
}

/// Every use of one top-level node by another in `host/src`.
fn uses(tops: &BTreeSet<Node>) -> Graph {
    let src = src();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut graph = Graph::new();
    for path in files {
        let relative = path.strip_prefix(&src).unwrap().to_path_buf();
        if relative == Path::new("main.rs") {
            continue; // the command line, a crate of its own that uses this one as `caustic`
        }
        let module = module_of(&relative);
        let from = module.first().cloned().unwrap_or_else(|| ROOT.to_string());
        let code = code_of(&std::fs::read_to_string(&path).unwrap());
        let mut targets = Vec::new();
        for at in path_starts(&code, "crate") {
            for name in first_segments(&code, at + "crate::".len()) {
                targets.push((name, at));
            }
        }
        for at in path_starts(&code, "super") {
            let mut end = at;
            let mut up = 0;
            while code[end..].starts_with("super::") {
                end += "super::".len();
                up += 1;
            }
            let Some(base) = module.len().checked_sub(up) else { continue };
            if base > 0 {
                targets.push((module[0].clone(), at));
            } else {
                targets.extend(first_segments(&code, end).into_iter().map(|name| (name, at)));
            }
        }
        for (name, at) in targets.into_iter().filter(|(name, _)| name != "self") {
            let to = if tops.contains(&name) { name } else { ROOT.to_string() };
            if to != from {
                let place = format!("host/src/{}:{}", relative.display(), line_of(&code, at));
                graph.entry(from.clone()).or_default().entry(to).or_insert(place);
            }
        }
    }
    graph
}

/// A cycle of `graph` as the nodes along it (the first repeated at the end), if it has one.
fn cycle(graph: &BTreeMap<Node, BTreeSet<Node>>) -> Option<Vec<&Node>> {
    fn visit<'a>(
        node: &'a Node,
        graph: &'a BTreeMap<Node, BTreeSet<Node>>,
        done: &mut BTreeSet<&'a Node>,
        path: &mut Vec<&'a Node>,
    ) -> Option<Vec<&'a Node>> {
        if let Some(at) = path.iter().position(|n| *n == node) {
            let mut found = path[at..].to_vec();
            found.push(node);
            return Some(found);
        }
        if done.contains(node) {
            return None;
        }
        path.push(node);
        for next in graph.get(node).into_iter().flatten() {
            if let Some(found) = visit(next, graph, done, path) {
                return Some(found);
            }
        }
        path.pop();
        done.insert(node);
        None
    }
    let mut done = BTreeSet::new();
    graph.keys().find_map(|node| visit(node, graph, &mut done, &mut Vec::new()))
}

/// The folders at the top of `host/src` and the modules of single files beside them.
fn top_nodes() -> (BTreeSet<Node>, BTreeSet<Node>) {
    let (mut folders, mut files) = (BTreeSet::new(), BTreeSet::new());
    for entry in std::fs::read_dir(src()).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            folders.insert(name);
        } else if path.extension().is_some_and(|e| e == "rs") && name != "lib" && name != "main" {
            files.insert(name);
        }
    }
    (folders, files)
}

/// The module doc (`//!` lines) at the head of a file, without the markers.
fn module_doc(text: &str) -> Vec<&str> {
    text.lines().map_while(|l| l.strip_prefix("//!")).map(|l| l.strip_prefix(' ').unwrap_or(l)).collect()
}

/// The folders a folder's `mod.rs` says it uses: the backquoted folder names of the doc's
/// paragraph that begins with "Uses" (`None` without one).
fn declared(doc: &[&str], folders: &BTreeSet<Node>) -> Option<BTreeSet<Node>> {
    let start = doc.iter().position(|l| l.starts_with("Uses "))?;
    let paragraph: Vec<&str> = doc[start..].iter().take_while(|l| !l.trim().is_empty()).copied().collect();
    let text = paragraph.join(" ");
    let named = text.split('`').skip(1).step_by(2).filter(|name| folders.contains(*name));
    Some(named.map(str::to_string).collect())
}

#[test]
fn every_folder_has_a_module_doc() {
    let mut all = Vec::new();
    folders(&src(), &mut all);
    assert!(!all.is_empty(), "no folders under {}", src().display());
    let mut missing = Vec::new();
    for folder in all {
        let mod_rs = folder.join("mod.rs");
        let doc = std::fs::read_to_string(&mod_rs).map(|t| !module_doc(&t).is_empty()).unwrap_or(false);
        if !doc {
            missing.push(format!("{}", mod_rs.display()));
        }
    }
    assert!(
        missing.is_empty(),
        "folders without a mod.rs that opens with a `//!` doc:\n{}",
        missing.join("\n")
    );
}

#[test]
fn folders_use_only_what_their_module_doc_declares_and_never_in_a_cycle() {
    let (folders, files) = top_nodes();
    let tops: BTreeSet<Node> = folders.union(&files).cloned().collect();
    let actual = uses(&tops);
    assert!(actual.values().map(BTreeMap::len).sum::<usize>() > 0, "no uses found: the scan is broken");

    let mut problems = String::new();
    let mut allowed: BTreeMap<Node, BTreeSet<Node>> = BTreeMap::new();
    for folder in &folders {
        let mod_rs = src().join(folder).join("mod.rs");
        let text = std::fs::read_to_string(&mod_rs).unwrap_or_default();
        match declared(&module_doc(&text), &folders) {
            Some(names) => {
                allowed.insert(folder.clone(), names);
            }
            None => writeln!(problems, "{}: its module doc has no paragraph \"Uses …\"", mod_rs.display())
                .unwrap(),
        }
    }
    for (from, targets) in &actual {
        let Some(names) = allowed.get(from) else { continue };
        for (to, place) in targets {
            if folders.contains(to) && !names.contains(to) {
                writeln!(problems, "{from} uses {to} ({place}), which {from}/mod.rs does not declare")
                    .unwrap();
            }
        }
    }
    if let Some(found) = cycle(&allowed) {
        let path: Vec<&str> = found.iter().map(|n| n.as_str()).collect();
        writeln!(problems, "the folders' declared uses form a cycle: {}", path.join(" → ")).unwrap();
    }
    let edges: BTreeMap<Node, BTreeSet<Node>> =
        actual.iter().map(|(from, to)| (from.clone(), to.keys().cloned().collect())).collect();
    if let Some(found) = cycle(&edges) {
        let steps: Vec<String> = found
            .windows(2)
            .map(|w| format!("{} → {} ({})", w[0], w[1], actual[w[0].as_str()][w[1].as_str()]))
            .collect();
        writeln!(problems, "the uses form a cycle:\n  {}", steps.join("\n  ")).unwrap();
    }
    assert!(problems.is_empty(), "{problems}");
}

#[test]
fn the_scan_sees_paths_groups_and_supers() {
    let code = code_of(
        "use crate::{alpha::x, beta, gamma::{y, z}};\nlet a = crate::delta::f(); // crate::omega\n\
         use super::super::epsilon::E;\nlet b = other_crate::zeta; $crate::eta;",
    );
    let crate_paths: Vec<String> =
        path_starts(&code, "crate").flat_map(|at| first_segments(&code, at + "crate::".len())).collect();
    assert_eq!(crate_paths, ["alpha", "beta", "gamma", "delta"]);
    let supers: Vec<usize> = path_starts(&code, "super").collect();
    assert_eq!(supers.len(), 1, "`super::super::` is one path");
    let graph: BTreeMap<Node, BTreeSet<Node>> = [("a", "b"), ("b", "c"), ("c", "a")]
        .iter()
        .map(|(f, t)| (f.to_string(), BTreeSet::from([t.to_string()])))
        .collect();
    let found = cycle(&graph).expect("a → b → c → a is a cycle");
    assert_eq!(found.first(), found.last());
    assert_eq!(found.len(), 4);
}
