//! The atlas in shards ([`crate::studies::shard`]): a cell is one form × kernel × h/Δx × σ̄ of
//! the sweep, in sweep order; a stored cell is checked against the sweep before it is merged
//! ([`super::check`]).

use super::check::check_cell;
use super::config::{AtlasConfig, Sweep};
use super::report::{AtlasReport, Cell, assemble};
use super::run::compute_cells;
use crate::budget::Budget;
use crate::error::Result;
use crate::progress::Progress;
use crate::studies::shard::{CellCheck, Shard, Sharded, Timing};

/// The atlas as a [`Sharded`] study (`sphstab atlas --shard i/n`).
pub struct AtlasStudy;

impl Sharded for AtlasStudy {
    const STUDY: &'static str = "atlas";
    type Config = AtlasConfig;
    type Cell = Cell;
    type Report = AtlasReport;

    fn cells(&self, cfg: &AtlasConfig) -> Result<usize> {
        Ok(Sweep::new(cfg)?.len())
    }

    fn budget(&self, cfg: &AtlasConfig) -> Budget {
        cfg.budget
    }

    fn with_budget(&self, cfg: AtlasConfig, budget: Budget) -> AtlasConfig {
        AtlasConfig { budget, ..cfg }
    }

    fn compute(
        &self,
        cfg: &AtlasConfig,
        shard: Shard,
        progress: &dyn Progress,
    ) -> Result<Vec<(usize, Cell)>> {
        compute_cells(cfg, shard, progress)
    }

    fn report(&self, cfg: &AtlasConfig, cells: Vec<Cell>, timing: Timing) -> Result<AtlasReport> {
        Ok(assemble(cfg, cells, timing))
    }

    fn check_cell<'a>(&'a self, cfg: &'a AtlasConfig) -> Result<CellCheck<'a, Cell>> {
        let sweep = Sweep::new(cfg)?;
        let kappas = cfg.kappas;
        Ok(Box::new(move |index, cell| {
            check_cell(&sweep, kappas, index, cell)
        }))
    }
}
