//! Studies in shards (issue 25): each study that runs longer than a minute (atlas, pairing,
//! tradeoff, art-stress) computed once whole and once as 3 shards, the shards written as files (JSON
//! text) and read back, merged: the merged report serialises to the same bytes as the whole
//! one, once what a clock measures is set aside (`runtime_s`, `threads`, the trade-off costs).
//! Then the merges that must fail — a shard missing or given twice, shards of another
//! configuration, budget, version or study, a cell index out of range, in the wrong shard or
//! missing — each naming the file and the cell; and the same through the command line and
//! the job-array script `analysis/cluster/study_array.sh`.

use crate::common;
use sphstab::error::Error;
use sphstab::studies::art_stress::{ArtStressConfig, ArtStressSetup, ArtStressStudy};
use sphstab::studies::atlas::{AtlasConfig, AtlasStudy};
use sphstab::studies::pairing::{PairingConfig, PairingStudy};
use sphstab::studies::shard::{self, Shard, ShardOf, Sharded};
use sphstab::studies::tradeoff::{TradeoffConfig, TradeoffReport, TradeoffStudy};
use std::path::{Path, PathBuf};

/// The `n` shards of a study, each through its file format (JSON text) and back.
fn shards<S: Sharded>(study: &S, cfg: &S::Config, n: usize) -> Vec<(String, ShardOf<S>)> {
    (0..n)
        .map(|index| {
            let s = shard::run_shard(study, cfg, Shard { index, count: n }, ()).unwrap();
            let name = format!("shard-{index}-of-{n}.json");
            let text = serde_json::to_string(&s).unwrap();
            (name.clone(), shard::parse::<S>(&name, &text).unwrap())
        })
        .collect()
}

/// A report (JSON) with the clock (runtime_s, threads) set aside, as text.
fn clockless(mut v: serde_json::Value) -> String {
    v["runtime_s"] = 0.into();
    v["threads"] = 0.into();
    v.to_string()
}

/// A report with the clock set aside, as JSON text.
fn report_bytes<T: serde::Serialize>(r: &T) -> String {
    clockless(serde_json::to_value(r).unwrap())
}

/// A report file with the clock set aside, as JSON text.
fn without_clock(p: &Path) -> String {
    clockless(serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap())
}

/// The atlas of [`common::SMALL_ATLAS`]: 42 cells, σ̄ interpolated.
fn atlas_config() -> AtlasConfig {
    AtlasConfig {
        forms: vec!["classical".into(), "nonlocal".into()],
        kernels: vec!["m4".into()],
        h_points: 3,
        stress_points: 7,
        kappas: 64,
        ..Default::default()
    }
}

#[test]
fn atlas_shards_merge_bit_for_bit() {
    let cfg = atlas_config();
    let whole = sphstab::studies::atlas::run(&cfg, ()).unwrap();
    assert_eq!(whole.cells.len(), 42);
    assert!(whole.cells.iter().any(|c| !c.stable) && whole.cells.iter().any(|c| c.stable));
    let merged = shard::merge(&AtlasStudy, shards(&AtlasStudy, &cfg, 3)).unwrap();
    assert_eq!(report_bytes(&merged), report_bytes(&whole));
}

/// Stored atlas cells that do not fit the sweep are refused, naming the file and the cell (the
/// study's own check, [`Sharded::check_cell`]; the command-line table of corruptions is
/// `fuzz_cli::hostile_shard_files`).
#[test]
fn atlas_cells_are_checked_against_the_sweep() {
    let parts = shards(&AtlasStudy, &atlas_config(), 2);
    let name = Some(parts[1].0.clone());
    let growing = parts[1]
        .1
        .cells
        .iter()
        .position(|c| !c.result.stable)
        .unwrap();
    let stable = parts[1]
        .1
        .cells
        .iter()
        .position(|c| c.result.stable)
        .unwrap();
    type Edit = fn(&mut sphstab::studies::atlas::Cell);
    let edits: [(usize, Edit); 8] = [
        (growing, |c| c.max_growth_rate = 1e308),
        (growing, |c| c.max_growth_rate = -0.5),
        (growing, |c| c.form = "nope".into()),
        (growing, |c| c.kernel = "m5".into()),
        (growing, |c| c.h_over_dx = 1.7),
        (growing, |c| c.kappa_at_max = Some(1.0)),
        (stable, |c| c.max_growth_rate = 0.25),
        (stable, |c| c.index += 2),
    ];
    for (j, edit) in edits {
        let mut bad = parts.clone();
        let cell = &mut bad[1].1.cells[j];
        edit(&mut cell.result);
        let i = cell.index;
        match shard::merge(&AtlasStudy, bad) {
            Err(Error::Merge { file, cell, .. }) => {
                assert_eq!((file, cell), (name.clone(), Some(i)))
            }
            other => panic!("cell {i}: {:?}", other.map(|_| "merged")),
        }
    }
}

/// 2 kernels × sc, bcc × h/Δx = 0.8, 1.2 × 2 stresses at 4³ wave vectors: 16 rows.
fn pairing_config() -> PairingConfig {
    PairingConfig {
        kernels: vec!["m4".into(), "wendland-c2".into()],
        lattices: vec!["sc".into(), "bcc".into()],
        h_min: 0.8,
        h_max: 1.2,
        h_step: 0.4,
        stresses: vec![-0.01, -0.1],
        grid: 4,
        ..Default::default()
    }
}

#[test]
fn pairing_shards_merge_bit_for_bit() {
    let cfg = pairing_config();
    let whole = sphstab::studies::pairing::run(&cfg, ()).unwrap();
    assert_eq!(whole.rows.len(), 16);
    let parts = shards(&PairingStudy, &cfg, 3);
    assert_eq!(parts.iter().map(|p| p.1.cells.len()).sum::<usize>(), 16);
    // in any order of the files
    let mut reversed = parts.clone();
    reversed.reverse();
    let merged = shard::merge(&PairingStudy, reversed).unwrap();
    assert_eq!(report_bytes(&merged), report_bytes(&whole));
}

/// Everything but the clock: wall time, threads and the timed costs.
fn tradeoff_bytes(mut r: TradeoffReport) -> String {
    r.runtime_s = 0.0;
    r.threads = 0;
    for row in &mut r.rows {
        row.ns_per_particle_step = None;
        row.ns_per_particle_time = None;
        row.bytes_per_particle = None;
    }
    for row in &mut r.integrator_rows {
        row.ns_per_particle_step = None;
        row.ns_per_evaluation = None;
        row.ns_per_particle_time = None;
    }
    serde_json::to_string(&r).unwrap()
}

#[test]
fn tradeoff_shards_merge_bit_for_bit() {
    let cfg = TradeoffConfig {
        forms: vec!["classical".into(), "total-lagrangian".into()],
        kernels: vec!["m4".into()],
        h_points: 2,
        repeats: 1,
        integrators: vec!["kdk".into(), "rk4".into()],
        ..Default::default()
    };
    let study = TradeoffStudy::default();
    let whole = shard::run_whole(&study, &cfg, ()).unwrap();
    assert_eq!((whole.rows.len(), whole.integrator_rows.len()), (4, 8));
    let merged = shard::merge(&study, shards(&study, &cfg, 3)).unwrap();
    assert!(merged.rows.iter().all(|r| r.ns_per_particle_step.is_some()));
    assert_eq!(tradeoff_bytes(merged), tradeoff_bytes(whole));
}

#[test]
fn art_stress_shards_merge_bit_for_bit() {
    // per (h, f): 3 predictions and 1 Swegle run, in a 9×9 box; with a stored comparison
    let setup = ArtStressSetup {
        config: ArtStressConfig {
            h: vec![1.2],
            density_ratio: vec![0.99, 0.95],
            eps: vec![0.0, 0.2, 0.4],
            runs: vec![0.3],
            size: 9,
            ..ArtStressConfig::quick()
        },
        compare: Some(sphstab::studies::art_stress::Comparison {
            label: "other 1.0".into(),
            points: vec![(1.2, 0.99, 0.3, Some(0.01)), (1.2, 0.95, 0.2, None)],
        }),
    };
    let whole =
        sphstab::studies::art_stress::run(&setup.config, setup.compare.as_ref(), ()).unwrap();
    assert_eq!(whole.cases.len(), 2);
    let merged = shard::merge(&ArtStressStudy, shards(&ArtStressStudy, &setup, 3)).unwrap();
    assert_eq!(
        serde_json::to_string(&merged).unwrap(),
        serde_json::to_string(&whole).unwrap()
    );
}

/// The merge's error: file, cell.
fn merge_error(parts: Vec<(String, ShardOf<PairingStudy>)>) -> (Option<String>, Option<usize>) {
    match shard::merge(&PairingStudy, parts) {
        Err(Error::Merge { file, cell, .. }) => (file, cell),
        Err(e) => panic!("not a merge error: {e}"),
        Ok(_) => panic!("merged"),
    }
}

#[test]
fn bad_shards_are_refused_naming_the_file_and_the_cell() {
    let cfg = PairingConfig {
        kernels: vec!["m4".into()],
        lattices: vec!["sc".into()],
        h_min: 1.0,
        h_max: 1.4,
        h_step: 0.2,
        stresses: vec![-0.1],
        grid: 2,
        ..Default::default()
    };
    let parts = shards(&PairingStudy, &cfg, 3);
    let name = |i: usize| Some(parts[i].0.clone());
    // shard 2/3 missing; shard 1/3 twice
    assert_eq!(merge_error(parts[..2].to_vec()), (None, None));
    let mut twice = parts.clone();
    twice.push(parts[1].clone());
    assert_eq!(merge_error(twice), (name(1), None));
    // another configuration (h/Δx range), budget or shard count
    let mut other = parts.clone();
    other[2].1.config.h_max = 1.2;
    assert_eq!(merge_error(other), (name(2), None));
    let mut other = parts.clone();
    other[1].1.budget.max_memory /= 2.0;
    assert_eq!(merge_error(other), (name(1), None));
    let mut other = parts.clone();
    other[1].1.shard.count = 4;
    assert_eq!(merge_error(other), (name(1), None));
    // a corrupted cell index: out of range, in another shard's place, a cell left out
    let mut bad = parts.clone();
    bad[0].1.cells[0].index = 99;
    assert_eq!(merge_error(bad), (name(0), Some(99)));
    let mut bad = parts.clone();
    bad[0].1.cells[0].index = 1;
    assert_eq!(merge_error(bad), (name(0), Some(1)));
    let mut bad = parts.clone();
    bad[1].1.cells.remove(0);
    assert_eq!(merge_error(bad), (name(1), Some(1)));
    let mut bad = parts.clone();
    let c = bad[2].1.cells[0].clone();
    bad[2].1.cells.push(c);
    assert_eq!(merge_error(bad), (name(2), Some(2)));
    // a total that does not fit the configuration
    let mut bad = parts.clone();
    bad[0].1.total_cells = 4;
    assert_eq!(merge_error(bad), (name(0), None));
    // another version, another study, not a shard: refused when the file is read
    let text = serde_json::to_string(&parts[0].1).unwrap();
    for t in [
        text.replace(shard::VERSION, "0.0.0-other"),
        text.replace("\"pairing\"", "\"tradeoff\""),
        "{\"cells\": []}".into(),
        "not json".into(),
    ] {
        match shard::parse::<PairingStudy>("f.json", &t) {
            Err(Error::Merge { file, .. }) => assert_eq!(file.as_deref(), Some("f.json")),
            other => panic!("{t}: {other:?}"),
        }
    }
    // a pairing shard is not a trade-off shard
    assert!(shard::parse::<TradeoffStudy>("f.json", &text).is_err());
    assert_eq!(shard::study_of("f.json", &text).unwrap(), "pairing");
    assert!(matches!(
        shard::study_of("f.json", "{\"config\": {}}"),
        Err(Error::Merge {
            file: Some(_),
            cell: None,
            ..
        })
    ));
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("sphstab-shard-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const PAIRING_FLAGS: [&str; 11] = [
    "pairing",
    "--kernels",
    "m4",
    "--h-min",
    "1",
    "--h-max",
    "1.4",
    "--stresses",
    "-0.1",
    "--grid",
    "4",
];

/// Runs `flags` once whole (`--out`) and as 3 shards, merges them (`--out`) and checks that the
/// merged report equals the whole one apart from the clock: (the whole run's stdout, the
/// merge's, the shard files).
fn cli_whole_and_merged(dir: &Path, flags: &[&str]) -> (String, String, Vec<String>) {
    let p = |f: &str| dir.join(f).display().to_string();
    let mut whole = flags.to_vec();
    let whole_out = p("whole.json");
    whole.extend(["--out", &whole_out]);
    let (code, whole_stdout, err) = common::sphstab(&whole);
    assert_eq!(code, 0, "{err}");
    let files: Vec<String> = (0..3).map(|i| p(&format!("s{i}.json"))).collect();
    for (i, f) in files.iter().enumerate() {
        let spec = format!("{i}/3");
        let mut a = flags.to_vec();
        a.extend(["--shard", &spec, "--out", f]);
        let (code, _, err) = common::sphstab(&a);
        assert_eq!(code, 0, "{err}");
    }
    let merged_out = p("merged.json");
    let mut m = vec!["merge"];
    m.extend(files.iter().map(String::as_str));
    m.extend(["--out", &merged_out]);
    let (code, merged_stdout, err) = common::sphstab(&m);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        without_clock(Path::new(&merged_out)),
        without_clock(Path::new(&whole_out))
    );
    (whole_stdout, merged_stdout, files)
}

#[test]
fn cli_shards_merge_into_the_single_run() {
    let dir = scratch("cli");
    let p = |f: &str| dir.join(f).display().to_string();
    let (_, table, files) = cli_whole_and_merged(&dir, &PAIRING_FLAGS);
    assert!(table.contains("onsets"), "{table}");
    // a corrupted cell index: exit 2, one line naming the file and the cell
    let text = std::fs::read_to_string(&files[1]).unwrap();
    let bad = p("bad.json");
    let corrupted = text.replacen("{\"index\":1,\"result\"", "{\"index\":7,\"result\"", 1);
    assert_ne!(corrupted, text);
    std::fs::write(&bad, corrupted).unwrap();
    let (code, out, err) = common::sphstab(&["merge", &files[0], &bad, &files[2]]);
    assert_eq!((code, out.as_str()), (2, ""), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(err.contains(&bad) && err.contains("cell 7"), "{err}");
    // a missing shard, a shard twice: exit 2, one line
    for args in [
        vec!["merge", &files[0], &files[1]],
        vec!["merge", &files[0], &files[1], &files[1], &files[2]],
    ] {
        let (code, _, err) = common::sphstab(&args);
        assert_eq!(code, 2, "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
    common::assert_bad_inputs(&[
        (
            &["pairing", "--shard", "3/3", "--out", &p("x.json")],
            "--shard",
        ),
        (&["pairing", "--shard", "0/3"], "--out"),
        (
            &["pairing", "--shard", "0/3", "--out", &p("x.json"), "--json"],
            "--json",
        ),
        (
            &["tradeoff", "--shard", "1/0", "--out", &p("x.json")],
            "--shard",
        ),
        (&["art-stress", "--shard", "0/2"], "--out"),
    ]);
    std::fs::remove_dir_all(&dir).ok();
}

/// The atlas through the command line: 3 shards merged equal the single run (`--out`) and
/// print its summary, with its units; a shard missing or given twice is refused.
#[test]
fn cli_atlas_shards_merge_into_the_single_run() {
    let dir = scratch("atlas");
    let p = |f: &str| dir.join(f).display().to_string();
    let (summary, merged_summary, files) = cli_whole_and_merged(&dir, &common::SMALL_ATLAS);
    for s in [&summary, &merged_summary] {
        assert!(s.contains("c/Δx") && s.contains("h in Δx"), "{s}");
    }
    let merged_out = p("merged.json");
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&merged_out).unwrap()).unwrap();
    // the units of every report, from the one table (tests/it/units.rs checks the table)
    assert_eq!(report["units"]["max_growth_rate"], "c/dx");
    assert_eq!(report["units"]["h_over_dx"], "dx");
    assert_eq!(report["units"]["stress"], "sigma/C");
    assert_eq!(report["cells"].as_array().unwrap().len(), 2 * 3 * 7);
    // a missing or repeated shard is an error, not a silent hole
    for args in [
        vec!["merge", &files[0], &files[1]],
        vec!["merge", &files[0], &files[0], &files[1]],
    ] {
        let (code, out, err) = common::sphstab(&args);
        assert_eq!((code, out.as_str()), (2, ""), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
    common::assert_bad_inputs(&[
        (&["atlas", "--shard", "3/3"], "--shard"),
        (&["atlas", "--shard", "x"], "--shard"),
        (&["atlas", "--shard", "0/3"], "--out"),
        (
            &["atlas", "--shard", "0/3", "--out", &p("x.json"), "--json"],
            "--json",
        ),
        (&["atlas", "--kappas", "1"], "--kappas"),
        (&["atlas", "--stress-min", "-2"], "--stress-min"),
    ]);
    std::fs::remove_dir_all(&dir).ok();
}

/// The job-array script on one machine, as a Slurm array task would call it and in `local`
/// mode, merged equal to the single run.
#[test]
fn job_array_script_runs_a_study_in_shards() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let script = root.join("analysis/cluster/study_array.sh");
    let dir = scratch("script");
    let run = |args: &[&str], env: &[(&str, &str)]| {
        let out = std::process::Command::new("bash")
            .arg(&script)
            .args(args)
            .envs(env.iter().copied())
            .env("SPHSTAB", env!("CARGO_BIN_EXE_sphstab"))
            .current_dir(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr).into_owned();
        (out.status.code(), err)
    };
    // Slurm array tasks 0..2 of 3, each with its $SLURM_ARRAY_TASK_ID
    for i in ["0", "1", "2"] {
        let mut a = vec!["shard", "3", "slurm"];
        a.extend(PAIRING_FLAGS);
        let (code, err) = run(&a, &[("SLURM_ARRAY_TASK_ID", i)]);
        assert_eq!(code, Some(0), "{err}");
    }
    let (code, err) = run(&["merge", "3", "slurm", "--out", "slurm.json"], &[]);
    assert_eq!(code, Some(0), "{err}");
    // one machine, two shards at a time, then the merge again into a file
    let mut a = vec!["local", "3", "local"];
    a.extend(PAIRING_FLAGS);
    let (code, err) = run(&a, &[("JOBS", "2")]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = run(&["merge", "3", "local", "--out", "local.json"], &[]);
    assert_eq!(code, Some(0), "{err}");
    let mut whole = PAIRING_FLAGS.to_vec();
    let whole_out = dir.join("whole.json").display().to_string();
    whole.extend(["--out", &whole_out]);
    let (code, _, err) = common::sphstab(&whole);
    assert_eq!(code, 0, "{err}");
    for merged in ["slurm.json", "local.json"] {
        assert_eq!(
            without_clock(&dir.join(merged)),
            without_clock(&dir.join("whole.json"))
        );
    }
    // a missing shard is named with the array task that reruns it
    std::fs::remove_file(dir.join("slurm/shard-1-of-3.json")).unwrap();
    let (code, err) = run(&["merge", "3", "slurm"], &[]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("--array=1"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
