//! The host's folders follow the pipeline (docs/host.md): each may use only the folders its
//! `mod.rs` names in the paragraph of its module doc that begins with "Uses", and those uses form
//! no cycle. Read from the sources: every `crate::…` and `super::…` path in `host/src` (comments
//! left out), mapped to the top-level folder (or file) it names.
//!
//! Modules, one per file, form no cycle either: the same paths (and `self::…`, and `child::…` where
//! a file declares `mod child;`) resolved to the deepest module they name (`module_uses`).
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

/// A module of `host/src` as its path from the crate root (`[]` is `lib.rs`): one per file, a
/// `mod.rs` being its folder's module.
type Module = Vec<String>;

/// The code of a file with comments, string and character literals blanked to spaces (lines
/// kept): the module scan needs braces that balance, and no path read out of a message.
fn code_without_literals(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |c: char| if c == '\n' { '\n' } else { ' ' };
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let next = chars.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < chars.len() && chars[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < chars.len() {
                if chars[i] == '/' && chars.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if chars[i] == '*' && chars.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(chars[i]));
                    i += 1;
                }
            }
        } else if (c == 'r' || (c == 'b' && next == Some('r')))
            && !chars[..i].last().is_some_and(|&p| is_ident(p))
            && {
                let start = if c == 'b' { i + 2 } else { i + 1 };
                let hashes = chars[start..].iter().take_while(|&&h| h == '#').count();
                chars.get(start + hashes) == Some(&'"')
            }
        {
            // A raw string: `r"…"`, `r#"…"#`, `br"…"`.
            let start = if c == 'b' { i + 2 } else { i + 1 };
            let hashes = chars[start..].iter().take_while(|&&h| h == '#').count();
            let closing: Vec<char> = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
            let body = start + hashes + 1;
            let close =
                (body..chars.len()).find(|&j| chars[j..].starts_with(&closing)).unwrap_or(chars.len());
            let end = (close + closing.len()).min(chars.len());
            out.extend(&chars[i..body]);
            out.extend(chars[body..close].iter().map(|&x| blank(x)));
            out.extend(&chars[close..end]);
            i = end;
        } else if c == '"' {
            out.push('"');
            i += 1;
            while i < chars.len() && chars[i] != '"' {
                let step = if chars[i] == '\\' { 2 } else { 1 };
                for &x in &chars[i..(i + step).min(chars.len())] {
                    out.push(blank(x));
                }
                i += step;
            }
            if i < chars.len() {
                out.push('"');
                i += 1;
            }
        } else if c == '\'' && (next == Some('\\') || chars.get(i + 2) == Some(&'\'')) {
            // A character literal (a lifetime `'a` has no closing quote after one character).
            let end = if next == Some('\\') {
                (i + 3..chars.len()).find(|&j| chars[j] == '\'').unwrap_or(chars.len() - 1)
            } else {
                i + 2
            };
            out.push('\'');
            out.extend(chars[i + 1..end].iter().map(|&x| blank(x)));
            out.push('\'');
            i = end + 1;
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

/// Every `mod NAME` item in `code`: where `mod` starts, the name, and the text after the name.
fn mod_items(code: &str) -> impl Iterator<Item = (usize, String, &str)> {
    code.match_indices("mod").filter_map(move |(at, _)| {
        if code[..at].chars().next_back().is_some_and(is_ident) {
            return None;
        }
        let rest = &code[at + "mod".len()..];
        if !rest.starts_with(char::is_whitespace) {
            return None;
        }
        let rest = rest.trim_start();
        let name = ident_at(rest)?;
        let after = rest[name.len()..].trim_start();
        Some((at, name, after))
    })
}

/// The byte ranges of the inline modules (`mod tests { … }`) in `code`, innermost last.
fn inline_modules(code: &str) -> Vec<std::ops::Range<usize>> {
    let mut ranges = Vec::new();
    for (at, _, after) in mod_items(code).filter(|(_, _, after)| after.starts_with('{')) {
        let open = code.len() - after.len();
        let mut depth = 0usize;
        let mut end = code.len();
        for (i, c) in code[open..].char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        end = open + i + 1;
                        break;
                    }
                }
                _ => {}
            }
        }
        ranges.push(at..end);
    }
    ranges
}

/// The child modules a file declares (`mod name;`, `pub mod name;`), which its own code may name
/// without `self::`.
fn declared_children(code: &str) -> BTreeSet<String> {
    mod_items(code).filter(|(_, _, after)| after.starts_with(';')).map(|(_, name, _)| name).collect()
}

/// Every path that starts at `at` in `code` (just after its `crate::`, `super::` or the like), as
/// its segments: `a::b::C` gives `[a, b, C]`, a group `{a::x, b, c::{y, self}}` gives `[a, x]`,
/// `[b]`, `[c, y]` and `[c]`. A path ends at the first thing that is neither a name nor `::`.
fn full_paths(code: &str, at: usize) -> Vec<Vec<String>> {
    fn skip(text: &str, at: usize) -> usize {
        text.len() - text[at..].trim_start().len()
    }
    fn tree(text: &str, at: usize, prefix: &[String], out: &mut Vec<Vec<String>>) -> usize {
        let mut at = skip(text, at);
        if text[at..].starts_with('{') {
            at += 1;
            loop {
                at = skip(text, at);
                if text[at..].starts_with('}') {
                    return at + 1;
                }
                at = skip(text, tree(text, at, prefix, out));
                if text[at..].starts_with(',') {
                    at += 1;
                } else {
                    return at + usize::from(text[at..].starts_with('}'));
                }
            }
        }
        let Some(name) = ident_at(&text[at..]) else {
            out.push(prefix.to_vec());
            return at + usize::from(text[at..].starts_with('*'));
        };
        at += name.len();
        let mut segments = prefix.to_vec();
        if name != "self" {
            segments.push(name);
        }
        let after = skip(text, at);
        if text[after..].starts_with("::") {
            return tree(text, after + 2, &segments, out);
        }
        out.push(segments);
        if let Some(alias) = text[after..].strip_prefix("as").filter(|r| r.starts_with(char::is_whitespace)) {
            let alias_at = skip(text, text.len() - alias.len());
            return alias_at + ident_at(&text[alias_at..]).map_or(0, |a| a.len());
        }
        at
    }
    let mut out = Vec::new();
    tree(code, at, &[], &mut out);
    out
}

/// The deepest module that `path` names (`[scene, instancing, Instance]` → `[scene,
/// instancing]`).
fn resolve<'a>(modules: &'a BTreeSet<Module>, path: &[String]) -> &'a Module {
    (0..=path.len()).rev().find_map(|n| modules.get(&path[..n])).expect("the crate root is a module")
}

/// One use of a module by another: the place it is seen (`host/src/path:line`).
type ModuleGraph = BTreeMap<Module, BTreeMap<Module, Vec<String>>>;

/// Every use of one module by another in `host/src` (`main.rs` aside): `crate::…`, `super::…`
/// and `self::…` paths, and in a file that declares `mod child;`, paths that begin `child::`.
/// Code in an inline module (`mod tests { … }`) counts as its file's, its `super::` reaching the
/// file first.
fn module_uses() -> ModuleGraph {
    let src = src();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.retain(|path| path.strip_prefix(&src).unwrap() != Path::new("main.rs"));
    let modules: BTreeSet<Module> =
        files.iter().map(|path| module_of(path.strip_prefix(&src).unwrap())).collect();
    let mut graph = ModuleGraph::new();
    for path in &files {
        let relative = path.strip_prefix(&src).unwrap();
        let module = module_of(relative);
        let code = code_without_literals(&std::fs::read_to_string(path).unwrap());
        let inline = inline_modules(&code);
        let depth = |at: usize| inline.iter().filter(|r| r.contains(&at)).count();
        let mut found: Vec<(Module, usize)> = Vec::new();
        let mut add = |base: &[String], at: usize, end: usize| {
            for tail in full_paths(&code, end) {
                let whole: Vec<String> = base.iter().cloned().chain(tail).collect();
                found.push((resolve(&modules, &whole).clone(), at));
            }
        };
        for at in path_starts(&code, "crate") {
            add(&[], at, at + "crate::".len());
        }
        for at in path_starts(&code, "self") {
            add(&module, at, at + "self::".len());
        }
        for at in path_starts(&code, "super") {
            let mut end = at;
            let mut up = 0usize;
            while code[end..].starts_with("super::") {
                end += "super::".len();
                up += 1;
            }
            let Some(base) = module.len().checked_sub(up.saturating_sub(depth(at))) else { continue };
            add(&module[..base], at, end);
        }
        for child in declared_children(&code) {
            for at in path_starts(&code, &child).filter(|&at| depth(at) == 0) {
                add(&module, at, at);
            }
        }
        for (to, at) in found {
            if to != module {
                let place = format!("host/src/{}:{}", relative.display(), line_of(&code, at));
                let places = graph.entry(module.clone()).or_default().entry(to).or_default();
                if !places.contains(&place) {
                    places.push(place);
                }
            }
        }
    }
    graph
}

/// The strongly connected components of `graph` with more than one node: every edge between two
/// nodes of one lies on a cycle.
fn tangles<N: Ord + Clone>(graph: &BTreeMap<N, BTreeSet<N>>) -> Vec<BTreeSet<N>> {
    let reach = |from: &N| {
        let mut seen = BTreeSet::from([from.clone()]);
        let mut stack = vec![from.clone()];
        while let Some(node) = stack.pop() {
            for next in graph.get(&node).into_iter().flatten() {
                if seen.insert(next.clone()) {
                    stack.push(next.clone());
                }
            }
        }
        seen
    };
    let reached: BTreeMap<&N, BTreeSet<N>> = graph.keys().map(|n| (n, reach(n))).collect();
    let mut out: Vec<BTreeSet<N>> = Vec::new();
    for (node, forward) in &reached {
        if out.iter().any(|c| c.contains(*node)) {
            continue;
        }
        let component: BTreeSet<N> = forward
            .iter()
            .filter(|other| reached.get(other).is_some_and(|back| back.contains(*node)))
            .cloned()
            .collect();
        if component.len() > 1 {
            out.push(component);
        }
    }
    out
}

fn module_name(module: &Module) -> String {
    if module.is_empty() {
        ROOT.to_string()
    } else {
        module.join("::")
    }
}

/// No module uses itself through others: on failure, every use (file:line) between the modules of
/// each cycle. A file's inline modules (`mod tests { … }`) count as the file, test code included.
#[test]
fn modules_never_use_each_other_in_a_cycle() {
    let actual = module_uses();
    assert!(actual.values().map(BTreeMap::len).sum::<usize>() > 100, "few uses found: the scan is broken");
    let edges: BTreeMap<Module, BTreeSet<Module>> =
        actual.iter().map(|(from, to)| (from.clone(), to.keys().cloned().collect())).collect();
    let mut problems = String::new();
    for component in tangles(&edges) {
        let names: Vec<String> = component.iter().map(module_name).collect();
        writeln!(problems, "these modules use each other in a cycle: {}", names.join(", ")).unwrap();
        for from in &component {
            for (to, places) in actual[from].iter().filter(|(to, _)| component.contains(*to)) {
                writeln!(problems, "  {} → {}: {}", module_name(from), module_name(to), places.join(", "))
                    .unwrap();
            }
        }
    }
    assert!(problems.is_empty(), "{problems}");
}

#[test]
fn the_module_scan_sees_full_paths_inline_modules_and_literals() {
    let code = code_without_literals(
        "use crate::{alpha::x, beta, gamma::{y, self, z::W}};\nlet s = \"crate::omega\"; let c = '{';\n\
         /* crate::psi */ let r = r#\"crate::chi {\"#; let l: &'a str;\nmod child;\n\
         mod tests {\n    use super::*;\n    fn f() { super::super::sibling::g(); }\n}\n",
    );
    let at = path_starts(&code, "crate").collect::<Vec<_>>();
    assert_eq!(at.len(), 1, "only the `use`: the others are in literals and comments");
    let paths: Vec<String> =
        full_paths(&code, at[0] + "crate::".len()).iter().map(|p| p.join("::")).collect();
    assert_eq!(paths, ["alpha::x", "beta", "gamma::y", "gamma", "gamma::z::W"]);
    let inline = inline_modules(&code);
    assert_eq!(inline.len(), 1);
    assert!(code[inline[0].clone()].starts_with("mod tests {") && code[inline[0].clone()].ends_with('}'));
    assert_eq!(declared_children(&code), BTreeSet::from(["child".to_string()]));
    let modules: BTreeSet<Module> =
        [vec![], vec!["a".to_string()], vec!["a".to_string(), "b".to_string()]].into();
    let path = ["a", "b", "C", "f"].map(String::from);
    assert_eq!(resolve(&modules, &path), &["a", "b"].map(String::from).to_vec());
    assert_eq!(resolve(&modules, &["z".to_string()]), &Module::new());
    let graph: BTreeMap<u8, BTreeSet<u8>> =
        [(1, [2].into()), (2, [3].into()), (3, [1, 4].into()), (4, [5].into()), (5, [4].into())].into();
    assert_eq!(tangles(&graph), [BTreeSet::from([1, 2, 3]), BTreeSet::from([4, 5])]);
    let actual = module_uses();
    let scene = vec!["scene".to_string()];
    assert!(actual.keys().any(|from| from.len() > 1), "uses are seen from files below a folder");
    assert!(actual.values().any(|to| to.contains_key(&scene)), "some module uses `scene` (its `mod.rs`)");
}
