//! The import rule of `docs/architecture.md`, checked on the source text: the engine's files
//! (`src/`) import each other by `use crate::…`/`use super::…` paths (and inline `crate::…`
//! paths) only downwards through the layers
//!
//! `math`, `linalg` → `integrator` → `scene` → `model` → `simulator` (with `error`)
//!
//! and without a circle between files (a parent's `pub use` of its own children is not counted:
//! it re-exports, it does not depend). The FMI layer (`crates/fmi2`) knows nothing of the beam
//! and the engine nothing of FMI (their manifests).
//!
//! A failure lists the offending edges or the files of a circle.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// A file's module path under `src/` (`model/space.rs` → `["model", "space"]`).
fn module_path(rel: &str) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .trim_end_matches(".rs")
        .split('/')
        .map(String::from)
        .collect();
    if matches!(parts.last().map(String::as_str), Some("mod" | "lib")) {
        parts.pop();
    }
    parts
}

fn rust_files(dir: &Path, root: &Path, out: &mut Vec<(String, String)>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, root, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            let rel = p
                .strip_prefix(root)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            out.push((rel, std::fs::read_to_string(&p).unwrap()));
        }
    }
}

/// The code of a file without its test module and comments.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or("");
    text.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The paths a file names: `use` trees (first segment after each brace) and inline paths, each
/// as segments starting with `crate`, `super` or `self`.
fn named_paths(code: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let is_ident = |c: char| c.is_alphanumeric() || c == '_';
    let bytes: Vec<char> = code.chars().collect();
    let mut i = 0;
    while i < bytes.len() {
        let rest: String = bytes[i..bytes.len().min(i + 7)].iter().collect();
        let start = rest.starts_with("crate::") as usize
            + rest.starts_with("super::") as usize
            + rest.starts_with("self::") as usize;
        let boundary = i == 0 || !(is_ident(bytes[i - 1]) || bytes[i - 1] == ':');
        if start > 0 && boundary {
            // read segments a::b::c and, after a brace, the first segment of each item
            let mut j = i;
            let mut segs = Vec::new();
            loop {
                let s = j;
                while j < bytes.len() && is_ident(bytes[j]) {
                    j += 1;
                }
                segs.push(bytes[s..j].iter().collect::<String>());
                if j + 1 < bytes.len() && bytes[j] == ':' && bytes[j + 1] == ':' {
                    j += 2;
                    if j < bytes.len() && bytes[j] == '{' {
                        // items of a group: each first segment
                        let end = bytes[j..]
                            .iter()
                            .position(|&c| c == '}')
                            .map_or(bytes.len(), |p| j + p);
                        let group: String = bytes[j + 1..end].iter().collect();
                        for item in group.split(',') {
                            let first = item.trim().split("::").next().unwrap_or("").trim();
                            let first = first.split_whitespace().next().unwrap_or("");
                            if !first.is_empty() && first.chars().all(is_ident) {
                                let mut p = segs.clone();
                                p.push(first.to_owned());
                                out.push(p);
                            }
                        }
                        j = end;
                        segs.clear();
                        break;
                    }
                    continue;
                }
                break;
            }
            if !segs.is_empty() {
                out.push(segs);
            }
            i = j.max(i + 1);
        } else {
            i += 1;
        }
    }
    out
}

/// The file a path resolves to from the module `cur`: the longest prefix that is a module.
fn resolve(
    cur: &[String],
    path: &[String],
    modules: &BTreeMap<Vec<String>, String>,
) -> Option<String> {
    let (mut base, mut segs): (Vec<String>, &[String]) = match path[0].as_str() {
        "crate" => (Vec::new(), &path[1..]),
        "self" => (cur.to_vec(), &path[1..]),
        "super" => (cur.to_vec(), path),
        _ => return None,
    };
    while segs.first().is_some_and(|s| s == "super") {
        base.pop();
        segs = &segs[1..];
    }
    let full: Vec<String> = base.into_iter().chain(segs.iter().cloned()).collect();
    (0..=full.len())
        .rev()
        .find_map(|k| modules.get(&full[..k].to_vec()).cloned())
}

/// The layer of a file (lower may not import higher).
fn layer(rel: &str) -> usize {
    let top = rel.split('/').next().unwrap().trim_end_matches(".rs");
    match top {
        "math" | "linalg" => 0,
        "integrator" => 1,
        "scene" => 2,
        "model" => 3,
        "simulator" | "error" => 4,
        "lib" => 5,
        other => panic!("src/{other}: give it a layer in tests/architecture.rs"),
    }
}

fn edges() -> BTreeMap<String, BTreeSet<String>> {
    edges_in("src")
}

/// The import edges between the files of the crate source folder `dir` (from the workspace
/// root).
fn edges_in(dir: &str) -> BTreeMap<String, BTreeSet<String>> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(dir);
    let mut files = Vec::new();
    rust_files(&root, &root, &mut files);
    let modules: BTreeMap<Vec<String>, String> = files
        .iter()
        .map(|(rel, _)| (module_path(rel), rel.clone()))
        .collect();
    let mut out = BTreeMap::new();
    for (rel, text) in &files {
        let cur = module_path(rel);
        let targets: BTreeSet<String> = named_paths(&code(text))
            .iter()
            .filter_map(|p| resolve(&cur, p, &modules))
            .filter(|t| t != rel)
            .collect();
        out.insert(rel.clone(), targets);
    }
    out
}

#[test]
fn imports_go_down_the_layers() {
    let e = edges();
    let bad: Vec<String> = e
        .iter()
        .flat_map(|(from, tos)| {
            tos.iter()
                .filter(|to| layer(to) > layer(from))
                .map(move |to| format!("{from} -> {to}"))
        })
        .collect();
    assert!(bad.is_empty(), "imports up the layers: {bad:#?}");
}

#[test]
fn no_import_circle_between_files() {
    for dir in ["src", "crates/fmu/src"] {
        let circles = circles(&edges_in(dir));
        assert!(circles.is_empty(), "import circles in {dir}: {circles:#?}");
    }
}

/// The import circles (strongly connected components of more than one file) of `e`.
fn circles(e: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    // Tarjan's strongly connected components
    struct T<'a> {
        e: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        next: usize,
        circles: Vec<Vec<&'a str>>,
    }
    impl<'a> T<'a> {
        fn visit(&mut self, v: &'a str) {
            self.index.insert(v, self.next);
            self.low.insert(v, self.next);
            self.next += 1;
            self.stack.push(v);
            self.on.insert(v);
            for w in &self.e[v] {
                let w = w.as_str();
                if !self.index.contains_key(w) {
                    self.visit(w);
                    let l = self.low[v].min(self.low[w]);
                    self.low.insert(v, l);
                } else if self.on.contains(w) {
                    let l = self.low[v].min(self.index[w]);
                    self.low.insert(v, l);
                }
            }
            if self.low[v] == self.index[v] {
                let mut comp = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on.remove(w);
                    comp.push(w);
                    if w == v {
                        break;
                    }
                }
                if comp.len() > 1 {
                    comp.sort();
                    self.circles.push(comp);
                }
            }
        }
    }
    let mut t = T {
        e,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        next: 0,
        circles: Vec::new(),
    };
    for v in e.keys() {
        if !t.index.contains_key(v.as_str()) {
            t.visit(v);
        }
    }
    t.circles
        .into_iter()
        .map(|c| c.into_iter().map(String::from).collect())
        .collect()
}

#[test]
fn the_fmi_layer_and_the_engine_do_not_know_each_other() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let manifest = |p: &str| std::fs::read_to_string(root.join(p)).unwrap();
    let deps = |text: &str| -> Vec<String> {
        let mut in_deps = false;
        let mut out = Vec::new();
        for l in text.lines() {
            if l.starts_with('[') {
                in_deps = l.trim() == "[dependencies]";
            } else if in_deps {
                if let Some((name, _)) = l.split_once('=') {
                    out.push(name.trim().to_owned());
                }
            }
        }
        out
    };
    let engine = deps(&manifest("Cargo.toml"));
    let fmi = deps(&manifest("crates/fmi2/Cargo.toml"));
    assert!(!engine.iter().any(|d| d.starts_with("fmi")), "{engine:?}");
    assert!(!fmi.iter().any(|d| d.starts_with("hybeam")), "{fmi:?}");
    // the views know the engine's shape, not FMI (the FMU adapter uses both)
    let view = deps(&manifest("crates/view/Cargo.toml"));
    assert!(!view.iter().any(|d| d.starts_with("fmi")), "{view:?}");
}

#[test]
fn the_checker_sees_a_circle_and_an_upward_import() {
    // the parser on a made-up pair: a's `use super::b::X` and b's `crate::a::f()` resolve
    let a = named_paths(&code("use super::b::{X, y::Z};\nfn f() { crate::a::g(); }"));
    assert_eq!(a[0], ["super", "b", "X"]);
    assert_eq!(a[1], ["super", "b", "y"]);
    assert_eq!(a[2], ["crate", "a", "g"]);
    let modules: BTreeMap<Vec<String>, String> = [
        (vec!["m".to_owned()], "m/mod.rs".to_owned()),
        (vec!["m".to_owned(), "b".to_owned()], "m/b.rs".to_owned()),
    ]
    .into_iter()
    .collect();
    let cur = vec!["m".to_owned(), "a".to_owned()];
    assert_eq!(resolve(&cur, &a[0], &modules).as_deref(), Some("m/b.rs"));
    assert_eq!(layer("model/space.rs"), 3);
    assert!(layer("simulator/any.rs") > layer("model/assembly.rs"));
}
