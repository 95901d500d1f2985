//! Shards: a study split into independent cells for a batch system's job array (a Slurm
//! `--array`, GNU parallel, a shell loop), and the shards merged back into the report of the
//! unsharded run.
//!
//! A study that shards implements [`Sharded`]: its configuration gives a fixed list of cells
//! (the atlas's form × kernel × h/Δx × σ̄, the pairing study's rows kernel × lattice × h/Δx × σ̄,
//! the trade-off study's configurations form × kernel × h/Δx, the artificial-stress study's
//! predictions and runs), each computed from the configuration alone, and its report is
//! assembled from the cells in index order. Cell `c` belongs to shard `c mod n`: consecutive
//! cells, which often cost alike (neighbouring h/Δx), go to different shards, so the shards
//! take about equally long.
//!
//! [`run_shard`] computes one shard into a [`ShardFile`]: JSON that says what it is — the
//! study, the sphstab version, the whole configuration and the budget it ran within (a budget
//! can turn a cell into a skipped one), the shard i/n, the number of cells of the study and the
//! shard's cells with their indices. [`merge`] checks that the files are the n shards of one
//! study — same version, configuration, budget and n, every shard once, every cell once and in
//! its own shard, a plausible clock — and every cell against the configuration
//! ([`Sharded::check_cell`]: a shard file is data that users keep and pass around, so a cell
//! that cannot be the study's is refused, naming the file and the cell, instead of being
//! merged); then it assembles the report with the code of the unsharded run ([`run_whole`]),
//! so the merged report equals the unsharded one bit for bit, except what a clock measures:
//! `runtime_s` (after a merge the sum over the shards), `threads` (the first shard's) and the
//! trade-off study's costs (measured per cell on whichever machine ran its shard).

use crate::budget::Budget;
use crate::display::num;
use crate::error::{Error, Result, Text, field};
use crate::progress::Progress;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

/// The `format` of every shard file.
pub const FORMAT: &str = "sphstab-shard";
/// The sphstab version that writes (and alone merges) shard files.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
/// Most shards of one study.
pub const MAX_SHARDS: usize = 100_000;
/// Largest `runtime_s` of a shard file (≈ 30 years).
pub const MAX_RUNTIME_S: f64 = 1e9;

/// One shard of n (0 ≤ index < count): the cells c with c mod count = index.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq, Eq)]
#[serde(deny_unknown_fields)]
pub struct Shard {
    /// This shard.
    pub index: usize,
    /// Number of shards.
    pub count: usize,
}

impl Shard {
    /// The whole study as one shard.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Parses `i/n` (0 ≤ i < n ≤ [`MAX_SHARDS`]); the error names the field `shard`.
    pub fn parse(s: &str) -> Result<Self> {
        let bad = || {
            Error::Incompatible(
                field("shard")
                    + format!(
                        " '{s}': must be i/n with integers 0 ≤ i < n ≤ {MAX_SHARDS} (e.g. 0/8)"
                    ),
            )
        };
        let (a, b) = s.split_once('/').ok_or_else(bad)?;
        let index: usize = a.trim().parse().map_err(|_| bad())?;
        let count: usize = b.trim().parse().map_err(|_| bad())?;
        if count == 0 || count > MAX_SHARDS || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// Whether cell `c` belongs to this shard.
    pub fn owns(self, c: usize) -> bool {
        c % self.count == self.index
    }
}

/// What a clock says about a run (not reproducible; left out of the bit-for-bit comparison).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Timing {
    /// Wall-clock seconds (after a merge: the sum over the shards).
    pub runtime_s: f64,
    /// Worker threads (after a merge: the first shard's).
    pub threads: usize,
}

/// A study whose work splits into cells computed independently from its configuration. A value
/// of the type may carry what a run needs besides the configuration (the trade-off study's
/// memory probe).
pub trait Sharded {
    /// The study's name, the `study` of its shard files (the command, e.g. `pairing`).
    const STUDY: &'static str;
    /// Everything the cells are computed from; shards merge only when theirs are equal.
    type Config: Clone + PartialEq + Serialize + DeserializeOwned;
    /// One cell's result.
    type Cell: Serialize + DeserializeOwned;
    /// The study's report.
    type Report;

    /// Validates the configuration (errors name the field) and counts its cells.
    fn cells(&self, cfg: &Self::Config) -> Result<usize>;

    /// The budget the configuration carries (not serialised with it).
    fn budget(&self, cfg: &Self::Config) -> Budget;

    /// The configuration with `budget`.
    fn with_budget(&self, cfg: Self::Config, budget: Budget) -> Self::Config;

    /// Computes the cells `shard` owns, ascending, each with its index; tells `progress` the
    /// fraction done.
    fn compute(
        &self,
        cfg: &Self::Config,
        shard: Shard,
        progress: &dyn Progress,
    ) -> Result<Vec<(usize, Self::Cell)>>;

    /// The report from every cell of the study, in index order.
    fn report(
        &self,
        cfg: &Self::Config,
        cells: Vec<Self::Cell>,
        timing: Timing,
    ) -> Result<Self::Report>;

    /// The check of a stored cell against the configuration, prepared once per merge from the
    /// (valid) configuration: called with each cell's index and result, it says what is wrong
    /// with a cell that cannot be the study's (a field that does not fit the configuration at
    /// that index, a number out of its range). The default accepts every cell; the checks of
    /// the index and the shard ([`merge`]) apply to every study.
    fn check_cell<'a>(&'a self, cfg: &'a Self::Config) -> Result<CellCheck<'a, Self::Cell>> {
        let _ = cfg;
        Ok(Box::new(|_, _| Ok(())))
    }
}

/// A check of one stored cell (its index, its result): what is wrong with it, if anything
/// ([`Sharded::check_cell`]).
pub type CellCheck<'a, C> = Box<dyn Fn(usize, &C) -> std::result::Result<(), Text> + 'a>;

/// The budget a shard ran within.
#[derive(Clone, Copy, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ShardBudget {
    /// Bytes of memory (`max_memory`).
    pub max_memory: f64,
    /// Particle-steps (`max_steps`).
    pub max_steps: f64,
}

/// One computed cell.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ShardCell<R> {
    /// Position in the study (0 ≤ index < `total_cells`).
    pub index: usize,
    /// The cell's result.
    pub result: R,
}

/// One shard of a study, as written to its file (module docs).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ShardFile<C, R> {
    /// Always [`FORMAT`].
    pub format: String,
    /// The sphstab version that computed it ([`VERSION`]).
    pub sphstab_version: String,
    /// The study ([`Sharded::STUDY`]).
    pub study: String,
    /// This shard.
    pub shard: Shard,
    /// Cells of the whole study.
    pub total_cells: usize,
    /// The budget it ran within.
    pub budget: ShardBudget,
    /// Wall-clock seconds of this shard.
    pub runtime_s: f64,
    /// Worker threads.
    pub threads: usize,
    /// The study's whole configuration.
    pub config: C,
    /// The cells of this shard, ascending.
    pub cells: Vec<ShardCell<R>>,
}

/// The shard file of study `S`.
pub type ShardOf<S> = ShardFile<<S as Sharded>::Config, <S as Sharded>::Cell>;

fn shard_budget(b: Budget) -> ShardBudget {
    ShardBudget {
        max_memory: b.max_memory,
        max_steps: b.max_steps,
    }
}

/// Computes one shard of the study.
pub fn run_shard<S: Sharded>(
    study: &S,
    cfg: &S::Config,
    shard: Shard,
    progress: impl Progress,
) -> Result<ShardOf<S>> {
    let total_cells = study.cells(cfg)?;
    let t0 = std::time::Instant::now();
    let cells = study.compute(cfg, shard, &progress)?;
    Ok(ShardFile {
        format: FORMAT.into(),
        sphstab_version: VERSION.into(),
        study: S::STUDY.into(),
        shard,
        total_cells,
        budget: shard_budget(study.budget(cfg)),
        runtime_s: t0.elapsed().as_secs_f64(),
        threads: rayon::current_num_threads(),
        config: cfg.clone(),
        cells: cells
            .into_iter()
            .map(|(index, result)| ShardCell { index, result })
            .collect(),
    })
}

/// Runs the whole study (one shard of one) and assembles its report.
pub fn run_whole<S: Sharded>(
    study: &S,
    cfg: &S::Config,
    progress: impl Progress,
) -> Result<S::Report> {
    let total = study.cells(cfg)?;
    let t0 = std::time::Instant::now();
    let cells = study.compute(cfg, Shard::WHOLE, &progress)?;
    debug_assert!(cells.iter().enumerate().all(|(i, c)| c.0 == i) && cells.len() == total);
    let timing = Timing {
        runtime_s: t0.elapsed().as_secs_f64(),
        threads: rayon::current_num_threads(),
    };
    study.report(cfg, cells.into_iter().map(|c| c.1).collect(), timing)
}

/// The head of a shard file: what it is, read before the rest.
#[derive(Deserialize)]
struct Head {
    format: Option<String>,
    study: Option<String>,
    sphstab_version: Option<String>,
    /// Present in an atlas written before the atlas had shard files (no `format`).
    shard: Option<serde::de::IgnoredAny>,
}

fn merge_error(file: Option<&str>, cell: Option<usize>, problem: impl Into<Text>) -> Error {
    Error::Merge {
        file: file.map(str::to_string),
        cell,
        problem: problem.into(),
    }
}

/// The study of the shard file `file` (its text): refuses JSON that is not a shard file (an
/// atlas of the format before shard files among them, which is not read any more: its shards
/// are computed again) and a shard of another sphstab version, before the cells are read.
pub fn study_of(file: &str, text: &str) -> Result<String> {
    let err = |p: String| merge_error(Some(file), None, p);
    let head: Head = serde_json::from_str(text).map_err(|e| err(format!("not JSON: {e}")))?;
    if head.format.as_deref() != Some(FORMAT) {
        return Err(err(if head.shard.is_some() && head.format.is_none() {
            "an atlas of the old format (a `shard` field, no `format`), which this sphstab does not read: compute its shards again (`sphstab atlas --shard i/n --out FILE`)".into()
        } else {
            format!(
                "not a shard file (`format` is not \"{FORMAT}\"; shard files are written by `sphstab <study> --shard i/n --out FILE`)"
            )
        }));
    }
    let Some(study) = head.study else {
        return Err(err("has no `study`".into()));
    };
    match head.sphstab_version.as_deref() {
        Some(VERSION) => Ok(study),
        v => Err(err(format!(
            "written by sphstab {}, this is {VERSION}: merge shards with the version that computed them",
            v.unwrap_or("(unknown)")
        ))),
    }
}

/// Parses the shard file `file` of study `S`: refuses what [`study_of`] refuses and a shard of
/// another study before reading the cells.
pub fn parse<S: Sharded>(file: &str, text: &str) -> Result<ShardOf<S>> {
    let study = study_of(file, text)?;
    let err = |p: String| merge_error(Some(file), None, p);
    if study != S::STUDY {
        return Err(err(format!(
            "a shard of the `{study}` study, not of `{}`",
            S::STUDY
        )));
    }
    serde_json::from_str(text).map_err(|e| err(e.to_string()))
}

/// The first top-level field in which two configurations differ (their JSON).
fn differing_field<C: Serialize>(a: &C, b: &C) -> String {
    let (Ok(serde_json::Value::Object(x)), Ok(serde_json::Value::Object(y))) =
        (serde_json::to_value(a), serde_json::to_value(b))
    else {
        return "config".into();
    };
    x.iter()
        .find(|(k, v)| y.get(*k) != Some(*v))
        .map(|(k, _)| k.clone())
        .or_else(|| y.keys().find(|k| !x.contains_key(*k)).cloned())
        .unwrap_or_else(|| "config".into())
}

/// Merges the shard files `(name, shard)` of one study into its report (module docs). Refuses,
/// naming the file and the cell: shards of different configurations, budgets or shard counts,
/// a shard given twice or missing, a clock out of range (`threads`, `runtime_s`), a cell out
/// of range, in the wrong shard, given twice or missing, and a cell the study's
/// [`Sharded::check_cell`] refuses.
pub fn merge<S: Sharded>(study: &S, parts: Vec<(String, ShardOf<S>)>) -> Result<S::Report> {
    let Some((first_name, first)) = parts.first() else {
        return Err(merge_error(None, None, "no shard files given"));
    };
    let (cfg, budget, count) = (first.config.clone(), first.budget, first.shard.count);
    let cfg = study.with_budget(
        cfg,
        Budget {
            max_memory: budget.max_memory,
            max_steps: budget.max_steps,
        },
    );
    let invalid = |e: Error| {
        merge_error(
            Some(first_name),
            None,
            format!("its configuration is not valid: {e}"),
        )
    };
    let total = study.cells(&cfg).map_err(invalid)?;
    let check = study.check_cell(&cfg).map_err(invalid)?;
    let mut shard_file: Vec<Option<usize>> = vec![None; count.min(MAX_SHARDS)];
    let mut seen = vec![false; total];
    let mut runtime_s = 0.0;
    for (p, (name, s)) in parts.iter().enumerate() {
        let at = |cell: Option<usize>, problem: Text| merge_error(Some(name), cell, problem);
        if s.config != first.config {
            return Err(at(
                None,
                format!(
                    "computed with a different configuration than {first_name} (`{}` differs)",
                    differing_field(&s.config, &first.config)
                )
                .into(),
            ));
        }
        if s.budget != budget {
            return Err(at(
                None,
                Text::from(format!(
                    "computed within a different budget than {first_name} ("
                )) + field("max_memory")
                    + ", "
                    + field("max_steps")
                    + ": give every shard the same)",
            ));
        }
        let sh = s.shard;
        if sh.count != count {
            return Err(at(
                None,
                format!(
                    "is shard {}/{}, but {first_name} is one of {count}",
                    sh.index, sh.count
                )
                .into(),
            ));
        }
        if sh.index >= count || count > MAX_SHARDS {
            return Err(at(
                None,
                format!("shard {}/{count} does not exist", sh.index).into(),
            ));
        }
        if let Some(q) = shard_file[sh.index] {
            return Err(at(
                None,
                format!(
                    "shard {}/{count} given twice (also {})",
                    sh.index, parts[q].0
                )
                .into(),
            ));
        }
        shard_file[sh.index] = Some(p);
        if s.threads == 0 {
            return Err(at(None, "threads = 0: must be at least 1".into()));
        }
        if !(0.0..=MAX_RUNTIME_S).contains(&s.runtime_s) {
            return Err(at(
                None,
                format!(
                    "runtime_s = {} is out of range: must be a number in [0, {}]",
                    num(s.runtime_s),
                    num(MAX_RUNTIME_S)
                )
                .into(),
            ));
        }
        if s.total_cells != total {
            return Err(at(
                None,
                format!(
                    "total_cells = {}, but its configuration has {total} cells",
                    s.total_cells
                )
                .into(),
            ));
        }
        for c in &s.cells {
            let i = c.index;
            if i >= total {
                return Err(at(
                    Some(i),
                    format!(
                        "out of range (the study has {total} cells, 0…{})",
                        total.saturating_sub(1)
                    )
                    .into(),
                ));
            }
            if !sh.owns(i) {
                return Err(at(
                    Some(i),
                    format!(
                        "belongs to shard {}/{count}, not to this file's shard {}/{count}",
                        i % count,
                        sh.index
                    )
                    .into(),
                ));
            }
            if seen[i] {
                return Err(at(Some(i), "given twice".into()));
            }
            seen[i] = true;
            check(i, &c.result).map_err(|p| at(Some(i), p))?;
        }
        runtime_s += s.runtime_s;
    }
    if let Some(missing) = shard_file.iter().position(Option::is_none) {
        return Err(merge_error(
            None,
            None,
            format!("shard {missing}/{count} is missing (give all {count} shard files)"),
        ));
    }
    if let Some(i) = seen.iter().position(|&s| !s) {
        // every shard is there (above), so the file that should hold the cell is known
        let name = shard_file[i % count].map(|p| parts[p].0.as_str());
        return Err(merge_error(
            name,
            Some(i),
            format!("missing from shard {}/{count}", i % count),
        ));
    }
    let threads = first.threads;
    let mut cells: Vec<Option<S::Cell>> = Vec::new();
    cells.resize_with(total, || None);
    for (_, s) in parts {
        for c in s.cells {
            cells[c.index] = Some(c.result);
        }
    }
    let cells = cells.into_iter().flatten().collect();
    study.report(&cfg, cells, Timing { runtime_s, threads })
}
