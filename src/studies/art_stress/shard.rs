//! The artificial-stress study in shards ([`crate::studies::shard`]): per (h, f) case, h-major,
//! one cell per ε of the prediction grid, then one per Swegle run.

use super::config::ArtStressConfig;
use super::report::{ArtStressReport, Comparison, Point, RunPoint};
use super::run::{assemble, cells_per_case, compute_cells};
use crate::budget::Budget;
use crate::error::Result;
use crate::progress::Progress;
use crate::studies::shard::{Shard, Sharded, Timing};
use serde::{Deserialize, Serialize};

/// What the study is computed from: the config and the other code's stored runs it is drawn
/// next to (read by the caller; in every shard, so that the merge needs no file but the shards).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ArtStressSetup {
    /// The config.
    pub config: ArtStressConfig,
    /// Another code's runs (None: no comparison).
    pub compare: Option<Comparison>,
}

/// One cell: a prediction at one ε of the grid, or one Swegle run.
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum ArtStressCell {
    /// The engine's predictions at one ε.
    Prediction(Point),
    /// One Swegle run.
    Run(RunPoint),
}

/// The artificial-stress study as a [`Sharded`] study (`sphstab art-stress --shard i/n`).
pub struct ArtStressStudy;

impl Sharded for ArtStressStudy {
    const STUDY: &'static str = "art-stress";
    type Config = ArtStressSetup;
    type Cell = ArtStressCell;
    type Report = ArtStressReport;

    fn cells(&self, setup: &ArtStressSetup) -> Result<usize> {
        let cfg = &setup.config;
        cfg.validate()?;
        Ok(cfg.h.len() * cfg.density_ratio.len() * cells_per_case(cfg))
    }

    fn budget(&self, setup: &ArtStressSetup) -> Budget {
        setup.config.budget
    }

    fn with_budget(&self, setup: ArtStressSetup, budget: Budget) -> ArtStressSetup {
        ArtStressSetup {
            config: ArtStressConfig {
                budget,
                ..setup.config
            },
            ..setup
        }
    }

    fn compute(
        &self,
        setup: &ArtStressSetup,
        shard: Shard,
        progress: &dyn Progress,
    ) -> Result<Vec<(usize, ArtStressCell)>> {
        compute_cells(setup, shard, progress)
    }

    fn report(
        &self,
        setup: &ArtStressSetup,
        cells: Vec<ArtStressCell>,
        _timing: Timing,
    ) -> Result<ArtStressReport> {
        assemble(setup, cells)
    }
}
