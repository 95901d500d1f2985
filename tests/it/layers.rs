//! The layer rule of docs/ARCHITECTURE.md (SPEC §8), read from the sources: every `crate::…`
//! path (grouped imports `use crate::{a, b::c}` included) and every `super::` chain that leaves
//! a folder is resolved to the top-level module it names, and an import that points up fails
//! the test, naming the file, the line and the edge. A second check refuses import cycles among
//! the files of `src/forms/`. The checker tests itself on small made-up sources first, so it
//! cannot pass by reading nothing.
//!
//! ```text
//! core        scalar kernel shape lattice neighbours budget error display params progress
//! integrator  integrator
//! forms       forms                      (core only: not the integrator, engine or solver)
//! engine      vonneumann                 (core, integrator, forms)
//! analysis    analysis                   (engine and below; not the solver)
//! solver      solver                     (core, integrator, forms: never the engine or analysis)
//! studies     studies                    (everything below, and plot to draw their figures)
//! plot        plot                       (core only: it takes plain series)
//! figures     figures                    (everything)
//! ```
//! The binary (src/bin) is above all of them and no library module may name it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The layer of a top-level module of the crate (None: not a module of the library).
fn layer(top: &str) -> Option<&'static str> {
    Some(match top {
        "scalar" | "kernel" | "shape" | "lattice" | "neighbours" | "budget" | "error"
        | "display" | "params" | "progress" | "units" => "core",
        "integrator" => "integrator",
        "forms" => "forms",
        "vonneumann" => "engine",
        "analysis" => "analysis",
        "solver" => "solver",
        "studies" => "studies",
        "plot" => "plot",
        "figures" => "figures",
        _ => return None,
    })
}

/// Height of a layer in the picture: an import points to a lower one.
fn rank(layer: &str) -> u8 {
    match layer {
        "core" => 0,
        "integrator" => 1,
        "forms" => 2,
        "engine" => 3,
        "analysis" | "solver" => 4,
        "studies" => 5,
        _ => 6, // plot, figures
    }
}

/// Whether layer `from` may import layer `to`; the reason when it may not.
fn allowed(from: &str, to: &str) -> Result<(), &'static str> {
    match (from, to) {
        _ if from == to => Ok(()),
        ("forms", t) if t != "core" => {
            Err("forms are rate functions on core: never the integrator, engine or solver")
        }
        ("solver", "engine" | "analysis") => {
            Err("the solver is the independent check of the analysis: never the engine or analysis")
        }
        ("plot", t) if t != "core" => Err("plot takes plain series: it imports core only"),
        ("studies" | "figures", "plot") => Ok(()),
        (_, "plot") => Err("plot is for studies and figures"),
        _ if rank(to) < rank(from) => Ok(()),
        _ => Err("an import only points down"),
    }
}

/// Imports that break the rule, allow-listed: (file, imported top-level module). None: the
/// Model1D consolidation (issue 23) removed the last (forms/model.rs → integrator).
const ALLOWED_EDGES: &[(&str, &str)] = &[];

/// Import cycles among the files of src/forms/ that are allow-listed (each a set of files, as
/// the strongly connected component the check finds). None since the Model1D consolidation.
const ALLOWED_FORMS_CYCLES: &[&[&str]] = &[];

/// Replaces comments, string and char literals by spaces (newlines kept, so lines still count).
fn strip(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    let blank = |ch: char| if ch == '\n' { '\n' } else { ' ' };
    while i < c.len() {
        if c[i] == '/' && c.get(i + 1) == Some(&'/') {
            while i < c.len() && c[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c[i] == '/' && c.get(i + 1) == Some(&'*') {
            let mut depth = 0;
            while i < c.len() {
                if c[i] == '/' && c.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(c[i]));
                    i += 1;
                }
            }
        } else if c[i] == 'r'
            && (c.get(i + 1) == Some(&'"') || c.get(i + 1) == Some(&'#'))
            && (i == 0 || !(c[i - 1].is_alphanumeric() || c[i - 1] == '_'))
        {
            // raw string r"…" / r#"…"#
            let mut j = i + 1;
            let mut hashes = 0;
            while c.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if c.get(j) != Some(&'"') {
                out.push(c[i]);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= c.len() {
                    break;
                }
                if c[j] == '"' && (0..hashes).all(|h| c.get(j + 1 + h) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            for ch in &c[i..j.min(c.len())] {
                out.push(blank(*ch));
            }
            i = j;
        } else if c[i] == '"' {
            out.push(' ');
            i += 1;
            while i < c.len() && c[i] != '"' {
                if c[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                if i < c.len() {
                    out.push(blank(c[i]));
                    i += 1;
                }
            }
            out.push(' ');
            i += 1;
        } else if c[i] == '\'' && (c.get(i + 1) == Some(&'\\') || c.get(i + 2) == Some(&'\'')) {
            // a char literal ('a', '\n', '\u{..}'); a lifetime has no closing quote
            let mut j = i + 1;
            if c.get(j) == Some(&'\\') {
                j += 2;
            } else {
                j += 1;
            }
            while j < c.len() && c[j] != '\'' {
                j += 1;
            }
            for _ in i..=j.min(c.len() - 1) {
                out.push(' ');
            }
            i = j + 1;
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

fn is_ident(ch: char) -> bool {
    ch.is_alphanumeric() || ch == '_'
}

/// The first segment of every path of a use tree starting at `rest` (`a::b`, `{a, b::c}`,
/// `*`): for a group, the first segment of each item.
fn first_segments(rest: &str) -> Vec<String> {
    let rest = rest.trim_start();
    if let Some(body) = rest.strip_prefix('{') {
        let mut out = Vec::new();
        let mut depth = 0;
        let mut item = String::new();
        for ch in body.chars() {
            match ch {
                '{' => {
                    depth += 1;
                    item.push(ch);
                }
                '}' if depth == 0 => {
                    out.extend(first_segments(&item));
                    return out;
                }
                '}' => {
                    depth -= 1;
                    item.push(ch);
                }
                ',' if depth == 0 => {
                    out.extend(first_segments(&item));
                    item.clear();
                }
                _ => item.push(ch),
            }
        }
        out
    } else {
        let id: String = rest.chars().take_while(|&ch| is_ident(ch)).collect();
        if id.is_empty() || id == "self" {
            Vec::new()
        } else {
            vec![id]
        }
    }
}

/// The first segments under `top` of a use tree (`top::a`, `{x, top::{a, b::c}}` → a, b).
fn segments_under(rest: &str, top: &str) -> Vec<String> {
    let rest = rest.trim_start();
    let items: Vec<String> = match rest.strip_prefix('{') {
        Some(body) => {
            let mut items = Vec::new();
            let (mut depth, mut item) = (0, String::new());
            for ch in body.chars() {
                match ch {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        items.push(std::mem::take(&mut item));
                        continue;
                    }
                    _ => {}
                }
                item.push(ch);
            }
            items.push(item);
            items
        }
        None => vec![rest.to_string()],
    };
    items
        .iter()
        .filter_map(|i| i.trim_start().strip_prefix(top)?.strip_prefix("::"))
        .flat_map(first_segments)
        .collect()
}

/// The module path of a source file (`src/a/b.rs` and `src/a/b/mod.rs` → [a, b]).
fn module_path(rel: &Path) -> Vec<String> {
    let mut parts: Vec<String> = rel
        .iter()
        .skip(1)
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if let Some(last) = parts.pop() {
        let stem = last.trim_end_matches(".rs").to_string();
        if stem != "mod" && stem != "lib" {
            parts.push(stem);
        }
    }
    parts
}

/// One path found in a file: the line, the absolute module path it starts from, the first
/// segments after it, the code that follows and the text of the line.
struct Reference {
    line: usize,
    base: Vec<String>,
    firsts: Vec<String>,
    rest: String,
    text: String,
}

/// Every `crate::…`, `super::…` and `self::…` path of a file (comments and strings ignored),
/// resolved against the file's module path and its inline `mod x { … }` blocks.
fn references(file_module: &[String], src: &str) -> Vec<Reference> {
    let code = strip(src);
    let lines: Vec<&str> = src.lines().collect();
    let c: Vec<char> = code.chars().collect();
    let mut out = Vec::new();
    let mut depth = 0usize;
    let mut inline: Vec<(String, usize)> = Vec::new();
    let mut line = 1;
    let mut i = 0;
    let starts_word =
        |i: usize| i == 0 || !(is_ident(c[i - 1]) || c[i - 1] == ':' || c[i - 1] == '$');
    let word_at = |i: usize, w: &str| {
        let w: Vec<char> = w.chars().collect();
        c.len() >= i + w.len() && c[i..i + w.len()] == w[..]
    };
    while i < c.len() {
        match c[i] {
            '\n' => line += 1,
            '{' => depth += 1,
            '}' => {
                depth = depth.saturating_sub(1);
                if inline.last().is_some_and(|(_, d)| *d == depth) {
                    inline.pop();
                }
            }
            _ => {}
        }
        if starts_word(i) && word_at(i, "mod ") {
            // an inline module: `mod name {`
            let rest: String = c[i + 4..].iter().take(80).collect();
            let name: String = rest
                .trim_start()
                .chars()
                .take_while(|&ch| is_ident(ch))
                .collect();
            let after = rest.trim_start()[name.len()..].trim_start().to_string();
            if !name.is_empty() && after.starts_with('{') {
                inline.push((name, depth));
            }
        }
        let (prefix, skip) = if starts_word(i) && word_at(i, "crate::") {
            ("crate", 7)
        } else if starts_word(i) && word_at(i, "super::") {
            ("super", 7)
        } else if starts_word(i) && word_at(i, "self::") {
            ("self", 6)
        } else {
            i += 1;
            continue;
        };
        let mut base: Vec<String> = file_module.to_vec();
        base.extend(inline.iter().map(|(n, _)| n.clone()));
        let mut j = i + skip;
        match prefix {
            "crate" => base.clear(),
            "super" => {
                base.pop();
                while word_at(j, "super::") {
                    base.pop();
                    j += 7;
                }
            }
            _ => {}
        }
        let rest: String = c[j..].iter().take(4000).collect();
        out.push(Reference {
            line,
            base,
            firsts: first_segments(&rest),
            rest,
            text: lines.get(line - 1).unwrap_or(&"").trim().to_string(),
        });
        i = j;
    }
    out
}

/// The top-level modules a reference names.
fn tops(r: &Reference) -> Vec<String> {
    match r.base.first() {
        Some(t) => vec![t.clone()],
        None => r.firsts.clone(),
    }
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The forbidden imports of the library sources `files` ((path relative to the crate, text)).
fn violations(files: &[(PathBuf, String)]) -> Vec<String> {
    let mut out = Vec::new();
    for (rel, src) in files {
        let name = rel.to_string_lossy().replace('\\', "/");
        if name.starts_with("src/bin/") {
            continue;
        }
        let module = module_path(rel);
        let Some(from) = module.first().and_then(|t| layer(t)) else {
            continue;
        };
        for r in references(&module, src) {
            for top in tops(&r) {
                let Some(to) = layer(&top) else { continue };
                let Err(why) = allowed(from, to) else {
                    continue;
                };
                if ALLOWED_EDGES.contains(&(name.as_str(), top.as_str())) {
                    continue;
                }
                out.push(format!(
                    "{name}:{}: {from} → {to} (crate::{top}): {why}\n    {}",
                    r.line, r.text
                ));
            }
        }
    }
    out
}

/// The file graph of src/forms/: file → the sibling files it imports (re-exports of mod.rs
/// resolved to the file that defines the item).
fn forms_graph(files: &[(PathBuf, String)]) -> BTreeMap<String, BTreeSet<String>> {
    let forms: Vec<(String, &String)> = files
        .iter()
        .filter_map(|(p, s)| {
            let n = p.to_string_lossy().replace('\\', "/");
            n.strip_prefix("src/forms/")
                .filter(|f| !f.contains('/'))
                .map(|f| (f.trim_end_matches(".rs").to_string(), s))
        })
        .collect();
    let children: BTreeSet<String> = forms
        .iter()
        .map(|(n, _)| n.clone())
        .filter(|n| n != "mod")
        .collect();
    // names re-exported by mod.rs → the child that defines them
    let mut exported: BTreeMap<String, String> = BTreeMap::new();
    if let Some((_, m)) = forms.iter().find(|(n, _)| n == "mod") {
        let code = strip(m);
        for stmt in code.split(';') {
            let s = stmt.trim();
            let Some(rest) = s
                .strip_prefix("pub use ")
                .or_else(|| s.strip_prefix("pub(crate) use "))
            else {
                continue;
            };
            let child: String = rest.chars().take_while(|&ch| is_ident(ch)).collect();
            if !children.contains(&child) {
                continue;
            }
            for leaf in rest[child.len()..].split([',', '{', '}']) {
                let leaf = leaf.trim().trim_start_matches("::");
                let name = leaf.rsplit([':', ' ']).next().unwrap_or("").trim();
                if !name.is_empty() && name != "self" {
                    exported.insert(name.to_string(), child.clone());
                }
            }
        }
    }
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (name, src) in &forms {
        let module = if name == "mod" {
            vec!["forms".to_string()]
        } else {
            vec!["forms".to_string(), name.clone()]
        };
        let edges = graph.entry(name.clone()).or_default();
        for r in references(&module, src) {
            let (base_rest, firsts): (Vec<String>, Vec<String>) = match r.base.as_slice() {
                [f, rest @ ..] if f == "forms" => (rest.to_vec(), r.firsts.clone()),
                // crate::forms::… or crate::{forms::…}: the segments after forms
                [] => (Vec::new(), segments_under(&r.rest, "forms")),
                _ => continue,
            };
            let targets = match base_rest.first() {
                Some(child) => vec![child.clone()],
                None => firsts,
            };
            for t in targets {
                let node = if children.contains(&t) {
                    t
                } else {
                    exported.get(&t).cloned().unwrap_or_else(|| "mod".into())
                };
                if &node != name {
                    edges.insert(node);
                }
            }
        }
        if name == "mod" {
            // code of mod.rs naming a child (`child::item`), re-exports excepted
            let code = strip(src);
            for l in code.lines().map(str::trim) {
                if l.starts_with("pub use ")
                    || l.starts_with("pub(crate) use ")
                    || l.contains("mod ")
                {
                    continue;
                }
                for child in &children {
                    let pat = format!("{child}::");
                    if let Some(p) = l.find(&pat)
                        && (p == 0
                            || !(is_ident(l.as_bytes()[p - 1] as char)
                                || l.as_bytes()[p - 1] == b':'))
                    {
                        edges.insert(child.clone());
                    }
                }
            }
        }
    }
    graph
}

/// Strongly connected components with more than one file (Tarjan), each sorted.
fn cycles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct T<'a> {
        g: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<String, usize>,
        low: BTreeMap<String, usize>,
        stack: Vec<String>,
        on: BTreeSet<String>,
        next: usize,
        out: Vec<Vec<String>>,
    }
    fn visit(t: &mut T, v: &str) {
        t.index.insert(v.into(), t.next);
        t.low.insert(v.into(), t.next);
        t.next += 1;
        t.stack.push(v.into());
        t.on.insert(v.into());
        let succ: Vec<String> =
            t.g.get(v)
                .map(|s| s.iter().cloned().collect())
                .unwrap_or_default();
        for w in succ {
            if !t.index.contains_key(&w) {
                visit(t, &w);
                let lw = t.low[&w];
                let lv = t.low[v];
                t.low.insert(v.into(), lv.min(lw));
            } else if t.on.contains(&w) {
                let iw = t.index[&w];
                let lv = t.low[v];
                t.low.insert(v.into(), lv.min(iw));
            }
        }
        if t.low[v] == t.index[v] {
            let mut comp = Vec::new();
            while let Some(w) = t.stack.pop() {
                t.on.remove(&w);
                let done = w == v;
                comp.push(w);
                if done {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                t.out.push(comp);
            }
        }
    }
    let mut t = T {
        g: graph,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in graph.keys() {
        if !t.index.contains_key(v) {
            visit(&mut t, v);
        }
    }
    t.out
}

/// The cycles among src/forms/ files that are not allow-listed, one line each.
fn forms_cycles(files: &[(PathBuf, String)]) -> Vec<String> {
    let g = forms_graph(files);
    cycles(&g)
        .into_iter()
        .filter(|c| {
            !ALLOWED_FORMS_CYCLES
                .iter()
                .any(|a| a.iter().map(|s| s.to_string()).collect::<Vec<_>>() == *c)
        })
        .map(|c| {
            let edges: Vec<String> = c
                .iter()
                .flat_map(|a| {
                    g[a].iter()
                        .filter(|b| c.contains(b))
                        .map(move |b| format!("{a} → {b}"))
                })
                .collect();
            format!(
                "import cycle among src/forms/ files {{{}}}: {}",
                c.join(", "),
                edges.join(", ")
            )
        })
        .collect()
}

fn sources() -> Vec<(PathBuf, String)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    rust_files(&root.join("src"))
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p.strip_prefix(root).unwrap().to_path_buf(), text)
        })
        .collect()
}

#[test]
fn no_import_points_up() {
    let files = sources();
    assert!(files.len() > 50, "read {} files", files.len());
    let v = violations(&files);
    assert!(
        v.is_empty(),
        "{} forbidden import(s) (docs/ARCHITECTURE.md):\n{}",
        v.len(),
        v.join("\n")
    );
}

#[test]
fn no_import_cycle_among_the_forms_files() {
    let files = sources();
    let c = forms_cycles(&files);
    assert!(c.is_empty(), "{}", c.join("\n"));
}

#[test]
fn every_allow_listed_edge_still_exists() {
    // an entry whose import is gone must be deleted, so the list only shrinks
    let files = sources();
    for (file, top) in ALLOWED_EDGES {
        let (rel, src) = files
            .iter()
            .find(|(p, _)| p.to_string_lossy().replace('\\', "/") == *file)
            .unwrap_or_else(|| panic!("{file} is gone: delete its ALLOWED_EDGES entry"));
        let module = module_path(rel);
        assert!(
            references(&module, src)
                .iter()
                .any(|r| tops(r).iter().any(|t| t == top)),
            "{file} no longer imports {top}: delete its ALLOWED_EDGES entry"
        );
    }
}

/// The checker on made-up sources: each forbidden form of import is found, allowed ones are not.
#[test]
fn the_checker_finds_what_it_must() {
    let f = |path: &str, src: &str| (PathBuf::from(path), src.to_string());
    let bad = [
        f("src/plot/axes.rs", "use crate::analysis::common;\n"),
        f(
            "src/solver/scene.rs",
            "use crate::{error::Result, vonneumann::classify};\n",
        ),
        f(
            "src/solver/a/b.rs",
            "use super::super::super::analysis::Query;\n",
        ),
        f(
            "src/forms/x.rs",
            "fn f() { let b = crate::solver::Run::new(); }\n",
        ),
        f(
            "src/kernel/mod.rs",
            "pub use crate::{scalar::Dual, forms::{FormKind}};\n",
        ),
        f(
            "src/integrator.rs",
            "mod t { use super::super::figures::render; }\n",
        ),
    ];
    for (p, s) in &bad {
        let v = violations(&[(p.clone(), s.clone())]);
        assert_eq!(v.len(), 1, "{} {s:?}: {v:?}", p.display());
    }
    let good = [
        f(
            "src/plot/axes.rs",
            "// use crate::analysis::x;\nuse crate::error::Result;\n",
        ),
        f(
            "src/plot/a.rs",
            "const S: &str = \"crate::analysis::x\";\nuse super::style;\n",
        ),
        f(
            "src/studies/x/run.rs",
            "use super::super::swegle::Run; use crate::plot::Curve;\n",
        ),
        f(
            "src/solver/scene.rs",
            "use crate::{error::Result, forms::FormKind, params::x};\n",
        ),
        f(
            "src/figures/mod.rs",
            "use crate::{analysis::x, solver::y, studies::z};\n",
        ),
        f(
            "src/scalar.rs",
            "mod tests { use super::*; fn f<'a>(c: char) -> bool { c == '\"' } }\n",
        ),
        f("src/bin/sphstab/main.rs", "use sphstab::figures;\n"),
    ];
    for (p, s) in &good {
        let v = violations(&[(p.clone(), s.clone())]);
        assert!(v.is_empty(), "{} {s:?}: {v:?}", p.display());
    }
    let cyclic = [
        f(
            "src/forms/mod.rs",
            "mod a;\nmod b;\npub use a::A;\npub use b::B;\n",
        ),
        f("src/forms/a.rs", "use super::B;\n"),
        f("src/forms/b.rs", "use crate::forms::A;\n"),
    ];
    assert_eq!(forms_cycles(&cyclic).len(), 1, "{:?}", forms_graph(&cyclic));
    let acyclic = [
        f(
            "src/forms/mod.rs",
            "mod a;\nmod b;\npub use a::A;\npub use b::B;\n",
        ),
        f("src/forms/a.rs", "use super::B;\n"),
        f("src/forms/b.rs", "use crate::error::Result;\n"),
    ];
    assert!(forms_cycles(&acyclic).is_empty());
}
