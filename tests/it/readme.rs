//! The README's commands run verbatim, in order, on a fresh copy of the data they read, and
//! none destroys what an earlier one made (issue 10). Every `cargo run --release -- …` line of
//! every ```sh block is run through bash with the built binary in place of `cargo run`, in a
//! scratch directory holding copies of `analysis/` and `figures/`; `cargo test`/`cargo bench`
//! lines are skipped (they are this test's own harness). Long (≈ 8 min in all: the full atlas,
//! two trade-off studies, the 10⁶-particle scaling run), so it is `#[ignore]`d and run by
//! `.ci/run` as a separate step: `cargo test --release --test it -- --ignored readme::`.

use std::path::Path;
use std::process::Command;

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

/// The shell lines of the README's ```sh blocks (comments kept: bash ignores them), each with
/// the error line the README shows right below it (`# error: …`, exit status 2; `# exit 3,
/// error: …` for a run that diverges), if any: such a command must fail with exactly that
/// message.
fn readme_commands() -> Vec<(String, Option<String>)> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("README.md")).unwrap();
    let mut out: Vec<(String, Option<String>)> = Vec::new();
    let mut in_sh = false;
    for line in text.lines() {
        if line.starts_with("```") {
            in_sh = line.trim() == "```sh";
            continue;
        }
        let l = line.trim();
        if !in_sh || l.is_empty() {
            continue;
        }
        if let Some(e) = l.strip_prefix("# error:") {
            if let Some(last) = out.last_mut() {
                last.1 = Some(format!("error:{e}"));
            }
        } else if let Some(e) = l.strip_prefix("# exit 3, error:") {
            // a run that diverges (exit status 3), with its message
            if let Some(last) = out.last_mut() {
                last.1 = Some(format!("3 error:{e}"));
            }
        } else if !l.starts_with('#') {
            out.push((l.to_string(), None));
        }
    }
    out
}

#[test]
fn readme_lists_commands() {
    let cmds = readme_commands();
    assert!(cmds.iter().filter(|c| c.0.contains("cargo run")).count() > 40);
}

#[test]
#[ignore = "≈ 8 min: run by .ci/run (cargo test --release --test it -- --ignored readme::)"]
fn readme_commands_run_verbatim_in_order() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::env::temp_dir().join(format!("sphstab-readme-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    copy_dir(&root.join("analysis"), &dir.join("analysis"));
    copy_dir(&root.join("figures"), &dir.join("figures"));
    let bin = env!("CARGO_BIN_EXE_sphstab");
    let mut made: Vec<(String, u64)> = Vec::new();
    for (cmd, expected_error) in readme_commands() {
        if cmd.starts_with("cargo test") || cmd.starts_with("cargo bench") {
            continue;
        }
        let line = cmd.replace("cargo run --release --", bin);
        let t = std::time::Instant::now();
        let out = Command::new("bash")
            .arg("-c")
            .arg(&line)
            .current_dir(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        match &expected_error {
            None => assert!(
                out.status.success(),
                "README command failed ({:?}): {cmd}\n{err}",
                out.status.code()
            ),
            Some(e) => {
                let (code, e) = match e.strip_prefix("3 ") {
                    Some(rest) => (3, rest),
                    None => (2, e.as_str()),
                };
                assert_eq!(out.status.code(), Some(code), "{cmd}: {err}");
                assert_eq!(err.trim_end(), e, "{cmd}: the README shows another message");
            }
        }
        eprintln!("{:7.1} s  {cmd}", t.elapsed().as_secs_f64());
        // nothing an earlier command wrote has been emptied
        for (f, len) in &made {
            let now = std::fs::metadata(dir.join(f)).map(|m| m.len()).unwrap_or(0);
            assert!(now > 0 || *len == 0, "{cmd} emptied {f}");
        }
        for w in cmd.split_whitespace().collect::<Vec<_>>().windows(2) {
            if matches!(w[0], "--out" | "--plot" | ">") && !w[1].starts_with('/') {
                let p = dir.join(w[1]);
                if p.is_file() {
                    made.push((w[1].to_string(), p.metadata().unwrap().len()));
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
