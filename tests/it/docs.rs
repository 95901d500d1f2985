//! Every command of README.md and docs/*.md runs as written, and prints what the page shows
//! (issue 25: "every command in README.md and docs/ runs as written, checked by a test that
//! extracts and runs them, so they can never go stale again").
//!
//! What counts as a documented command: every line of a ```` ```sh ```` block (comments are
//! skipped). A `cargo run --release -- …` line runs with the built binary in its place;
//! `cargo test`/`cargo bench` lines are skipped (they are this test's own harness). Below a
//! command, a `# error: …` line is the message it must fail with (exit status 2), `# exit 3,
//! error: …` that of a run that diverges. A ```` ```text ```` block right after an `sh` block
//! (only blank lines between) is what the block's last command prints on stdout: its lines
//! must appear in the output in order and, between lines `…` (which stand for lines left
//! out), one after another.
//!
//! Each page runs in its own scratch directory holding copies of `analysis/` and `figures/`,
//! its commands in order; no command may empty a file that an earlier one wrote. Running them
//! all takes minutes (the full atlas, two trade-off studies, a 10⁶-particle scaling run), so
//! the runs are `#[ignore]`d and `.ci/run` runs them: `cargo test --release --test it --
//! --ignored docs::`. The default suite checks the pages' shape: README under 300 lines with
//! at most ten recipes, a page per command, every page reachable from docs/README.md.

use std::path::{Path, PathBuf};
use std::process::Command;

/// One documented command with what the page says it does.
#[derive(Debug)]
struct Documented {
    /// The shell line as written.
    line: String,
    /// `(exit status, message)` when the page shows an error below it.
    error: Option<(i32, String)>,
    /// The lines the page shows as its output (`…` = lines left out).
    output: Option<Vec<String>>,
}

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// README.md, then the pages of docs/ in name order.
fn pages() -> Vec<PathBuf> {
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    let mut all = vec![root().join("README.md")];
    all.extend(docs);
    all
}

/// The documented commands of one page, in order.
fn commands(text: &str) -> Vec<Documented> {
    let mut out: Vec<Documented> = Vec::new();
    let mut block: Option<String> = None; // the info string of the open block
    let mut last_was_sh = false; // the previous block was `sh`, with only blank lines since
    let mut text_lines: Vec<String> = Vec::new();
    for line in text.lines() {
        if let Some(info) = line.trim_start().strip_prefix("```") {
            match block.take() {
                None => {
                    if info.trim() == "text" && last_was_sh {
                        text_lines.clear();
                        block = Some("output".into());
                    } else {
                        block = Some(info.trim().to_string());
                    }
                }
                Some(kind) => {
                    last_was_sh = kind == "sh";
                    if kind == "output" {
                        let last = out.last_mut().expect("an output block after an sh block");
                        last.output = Some(std::mem::take(&mut text_lines));
                    }
                }
            }
            continue;
        }
        match block.as_deref() {
            None => {
                if !line.trim().is_empty() {
                    last_was_sh = false;
                }
            }
            Some("sh") => {
                let l = line.trim();
                if l.is_empty() {
                    continue;
                }
                if let Some(e) = l.strip_prefix("# error:") {
                    out.last_mut().expect("an error line below a command").error =
                        Some((2, format!("error:{e}")));
                } else if let Some(e) = l.strip_prefix("# exit 3, error:") {
                    out.last_mut().expect("an error line below a command").error =
                        Some((3, format!("error:{e}")));
                } else if !l.starts_with('#') {
                    out.push(Documented {
                        line: l.to_string(),
                        error: None,
                        output: None,
                    });
                }
            }
            Some("output") => text_lines.push(line.trim_end().to_string()),
            Some(_) => {}
        }
    }
    out
}

/// Whether one shown line matches a printed one: equal, or, where the shown line has `…`
/// inside it (a run time, say), equal around it.
fn line_matches(shown: &str, printed: &str) -> bool {
    if !shown.contains('…') {
        return shown == printed;
    }
    let parts: Vec<&str> = shown.split('…').collect();
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !printed.starts_with(first) || printed.len() < first.len() + last.len() {
        return false;
    }
    let mut rest = &printed[first.len()..];
    for p in &parts[1..parts.len() - 1] {
        match rest.find(p) {
            Some(i) => rest = &rest[i + p.len()..],
            None => return false,
        }
    }
    rest.ends_with(last)
}

/// Whether `shown` (with `…` for lines left out) appears in `printed`: its runs of lines
/// between `…` markers, in order, each run as consecutive lines of the output. Trailing
/// spaces do not count; `…` inside a line stands for text left out. Returns the first run
/// that is not found.
fn shown_in(shown: &[String], printed: &str) -> Result<(), String> {
    let printed: Vec<&str> = printed.lines().map(str::trim_end).collect();
    let mut at = 0;
    for run in shown.split(|l| l.trim() == "…") {
        let run: Vec<&str> = run.iter().map(|l| l.trim_end()).collect();
        if run.is_empty() {
            continue;
        }
        if printed.len() < at + run.len() {
            return Err(run.join("\n"));
        }
        match (at..=printed.len().saturating_sub(run.len()))
            .find(|&i| (0..run.len()).all(|k| line_matches(run[k], printed[i + k])))
        {
            Some(i) => at = i + run.len(),
            None => return Err(run.join("\n")),
        }
    }
    Ok(())
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let p = e.path();
        if p.is_dir() {
            copy_dir(&p, &to.join(e.file_name()));
        } else {
            std::fs::copy(&p, to.join(e.file_name())).unwrap();
        }
    }
}

/// Runs the commands of one page in a scratch directory; returns the failures.
fn run_page(page: &Path) -> Vec<String> {
    // README.md or docs/X.md: the scratch directory's name must tell README.md from docs/README.md
    let name = page.strip_prefix(root()).unwrap().display().to_string();
    let text = std::fs::read_to_string(page).unwrap();
    let dir = std::env::temp_dir().join(format!(
        "sphstab-docs-{}-{}",
        std::process::id(),
        name.replace('/', "-")
    ));
    let _ = std::fs::remove_dir_all(&dir);
    copy_dir(&root().join("analysis"), &dir.join("analysis"));
    copy_dir(&root().join("figures"), &dir.join("figures"));
    let bin = env!("CARGO_BIN_EXE_sphstab");
    let mut failures = Vec::new();
    let mut made: Vec<(String, u64)> = Vec::new();
    for c in commands(&text) {
        if c.line.starts_with("cargo test") || c.line.starts_with("cargo bench") {
            continue;
        }
        let line = c.line.replace("cargo run --release --", bin);
        let t = std::time::Instant::now();
        let out = Command::new("bash")
            .arg("-c")
            .arg(&line)
            .current_dir(&dir)
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        let stderr = String::from_utf8_lossy(&out.stderr);
        eprintln!("{:7.1} s  {name}: {}", t.elapsed().as_secs_f64(), c.line);
        match &c.error {
            None if !out.status.success() => failures.push(format!(
                "{name}: `{}` failed ({:?}):\n{stderr}",
                c.line,
                out.status.code()
            )),
            Some((code, e)) if out.status.code() != Some(*code) || stderr.trim_end() != e => {
                failures.push(format!(
                    "{name}: `{}` should fail with exit {code} and\n  {e}\nbut exited {:?} with\n  {}",
                    c.line,
                    out.status.code(),
                    stderr.trim_end()
                ))
            }
            _ => {}
        }
        if let Some(shown) = &c.output
            && let Err(run) = shown_in(shown, &stdout)
        {
            failures.push(format!(
                "{name}: `{}` does not print what the page shows:\n{run}\n--- it prints:\n{stdout}",
                c.line
            ));
        }
        // nothing an earlier command wrote has been emptied
        for (f, len) in &made {
            let now = std::fs::metadata(dir.join(f)).map(|m| m.len()).unwrap_or(0);
            if now == 0 && *len > 0 {
                failures.push(format!("{name}: `{}` emptied {f}", c.line));
            }
        }
        for w in c.line.split_whitespace().collect::<Vec<_>>().windows(2) {
            if matches!(w[0], "--out" | "--plot" | ">") && !w[1].starts_with('/') {
                let p = dir.join(w[1]);
                if p.is_file() {
                    made.push((w[1].to_string(), p.metadata().unwrap().len()));
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    failures
}

#[test]
fn extraction_reads_commands_errors_and_outputs() {
    let page = "text\n\n```sh\ncargo run --release -- a # c\n# a comment\ncargo run --release -- b\n\
                # error: --x = 0 is out of range\n```\n\n```text\nline 1\n…\nline 3\n```\n\n\
                ```text\nnot an output\n```\n\n```sh\nc\n# exit 3, error: DIVERGED\n```\nprose\n\
                ```text\nnot an output either\n```\n";
    let c = commands(page);
    assert_eq!(c.len(), 3);
    assert_eq!(c[0].line, "cargo run --release -- a # c");
    assert!(c[0].error.is_none() && c[0].output.is_none());
    assert_eq!(
        c[1].error,
        Some((2, "error: --x = 0 is out of range".into()))
    );
    assert_eq!(
        c[1].output.as_deref(),
        Some(&["line 1".to_string(), "…".into(), "line 3".into()][..])
    );
    assert_eq!(c[2].error, Some((3, "error: DIVERGED".into())));
    assert!(c[2].output.is_none());
    let shown = |s: &str| s.lines().map(String::from).collect::<Vec<_>>();
    assert!(shown_in(&shown("a\nb"), "x\na\nb\ny").is_ok());
    assert!(
        shown_in(&shown("a\nb"), "a\nx\nb").is_err(),
        "a run is consecutive"
    );
    assert!(shown_in(&shown("a\n…\nb"), "a\nx\nb").is_ok());
    assert!(
        shown_in(&shown("b\n…\na"), "a\nx\nb").is_err(),
        "runs keep their order"
    );
    assert!(shown_in(&shown("a  "), "a").is_ok());
    assert!(shown_in(&shown("t = 1 (… s), x"), "t = 1 (0.07 s), x").is_ok());
    assert!(shown_in(&shown("t = 1 (… s), x"), "t = 2 (0.07 s), x").is_err());
    assert!(shown_in(&shown("t = 1 (… s), x"), "t = 1 (0.07 s), y").is_err());
}

/// The README is short and made of recipes; every command has its page and every page is
/// reachable from docs/README.md; every README recipe with a text block shows real lines.
#[test]
fn readme_is_short_and_docs_cover_every_command() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let lines = readme.lines().count();
    assert!(
        lines < 300,
        "README.md has {lines} lines (issue 25: under 300)"
    );
    let recipes = readme.lines().filter(|l| l.starts_with("### ")).count();
    assert!(
        (9..=10).contains(&recipes),
        "README.md has {recipes} recipes (issue 25: at most ten)"
    );
    let cmds = commands(&readme);
    assert!(
        cmds.iter()
            .any(|c| c.line.starts_with("cargo test --release"))
    );
    assert!(cmds.iter().filter(|c| c.output.is_some()).count() >= 5);
    let index = std::fs::read_to_string(root().join("docs/README.md")).unwrap();
    for page in pages().iter().skip(1) {
        let name = page.file_name().unwrap().to_string_lossy();
        if name != "README.md" {
            assert!(
                index.contains(&format!("({name})")),
                "docs/README.md does not link {name}"
            );
        }
    }
    // every subcommand has a page whose first heading names it
    let bin = env!("CARGO_BIN_EXE_sphstab");
    let help = Command::new(bin).arg("--help").output().unwrap();
    let help = String::from_utf8_lossy(&help.stdout).to_string();
    let subcommands: Vec<&str> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .collect();
    assert!(subcommands.len() >= 15, "{help}");
    let headings: Vec<String> = pages()
        .iter()
        .skip(1)
        .filter_map(|p| {
            let t = std::fs::read_to_string(p).unwrap();
            t.lines().find(|l| l.starts_with("# ")).map(String::from)
        })
        .collect();
    for c in subcommands {
        assert!(
            headings
                .iter()
                .any(|h| h.contains(&format!("`{c}`")) || h.contains(&format!("`{c} "))),
            "no page of docs/ is headed by the command `{c}`"
        );
    }
}

/// Every relative link of README.md and docs/ points at a file that exists (anchors are not
/// checked), so moving a page cannot leave a dead link behind.
#[test]
fn relative_links_resolve() {
    let mut checked = 0;
    for page in pages() {
        let text = std::fs::read_to_string(&page).unwrap();
        let base = page.parent().unwrap();
        for (i, _) in text.match_indices("](") {
            let rest = &text[i + 2..];
            let Some(end) = rest.find(')') else { continue };
            let target = rest[..end].split('#').next().unwrap();
            if target.is_empty() || target.contains("://") || target.contains(' ') {
                continue;
            }
            assert!(
                base.join(target).exists(),
                "{}: the link to {target} is dead",
                page.display()
            );
            checked += 1;
        }
    }
    assert!(
        checked > 50,
        "only {checked} relative links found: is the parser right?"
    );
}

#[test]
#[ignore = "minutes: run by .ci/run (cargo test --release --test it -- --ignored docs::)"]
fn readme_commands_run_and_print_what_it_shows() {
    let failures = run_page(&root().join("README.md"));
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
#[ignore = "minutes: run by .ci/run (cargo test --release --test it -- --ignored docs::)"]
fn docs_commands_run_and_print_what_they_show() {
    let mut failures = Vec::new();
    for page in pages().iter().skip(1) {
        failures.extend(run_page(page));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
