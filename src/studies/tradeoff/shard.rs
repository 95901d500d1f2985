//! The trade-off study in shards ([`crate::studies::shard`]): a cell is one configuration
//! (form × kernel × h/Δx, the grid's order) with its integrator rows.
//!
//! The cost columns are measured with a clock on the machine that runs the shard: they compare
//! across cells only when every shard runs on the same kind of machine, one at a time (GNU
//! parallel `-j 1`, or array tasks on identical nodes with the cores to themselves). Everything
//! else merges bit for bit.

use super::config::{TradeoffConfig, grid};
use super::integrators::IntegratorRow;
use super::report::{Row, TradeoffReport};
use super::run::{assemble, compute_cells};
use crate::budget::Budget;
use crate::error::Result;
use crate::progress::Progress;
use crate::studies::shard::{Shard, Sharded, Timing};
use crate::studies::throughput::MemoryProbe;
use serde::{Deserialize, Serialize};

/// One configuration of the study: its row and its integrator rows (one per integrator of
/// the config, in its order; empty without integrators).
#[derive(Clone, Debug, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct TradeoffCell {
    /// The configuration's row.
    pub row: Row,
    /// Its integrator rows.
    pub integrator_rows: Vec<IntegratorRow>,
}

/// The trade-off study as a [`Sharded`] study (`sphstab tradeoff --shard i/n`), with the probe
/// of the caller's allocator that measures `bytes_per_particle` (None: not measured).
#[derive(Clone, Copy, Default)]
pub struct TradeoffStudy<'a> {
    /// The allocator probe.
    pub probe: Option<&'a dyn MemoryProbe>,
}

impl Sharded for TradeoffStudy<'_> {
    const STUDY: &'static str = "tradeoff";
    type Config = TradeoffConfig;
    type Cell = TradeoffCell;
    type Report = TradeoffReport;

    fn cells(&self, cfg: &TradeoffConfig) -> Result<usize> {
        Ok(grid(cfg)?.len())
    }

    fn budget(&self, cfg: &TradeoffConfig) -> Budget {
        cfg.budget
    }

    fn with_budget(&self, cfg: TradeoffConfig, budget: Budget) -> TradeoffConfig {
        TradeoffConfig { budget, ..cfg }
    }

    fn compute(
        &self,
        cfg: &TradeoffConfig,
        shard: Shard,
        progress: &dyn Progress,
    ) -> Result<Vec<(usize, TradeoffCell)>> {
        compute_cells(cfg, shard, self.probe, progress)
    }

    fn report(
        &self,
        cfg: &TradeoffConfig,
        cells: Vec<TradeoffCell>,
        timing: Timing,
    ) -> Result<TradeoffReport> {
        Ok(assemble(cfg, cells, timing))
    }
}
