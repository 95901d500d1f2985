//! The pairing study in shards ([`crate::studies::shard`]): a cell is a row, kernel × lattice
//! × h/Δx × σ̄ in the report's order.

use super::config::{PairingConfig, plan};
use super::report::{PairingReport, PairingRow};
use super::run::{assemble, compute_rows};
use crate::budget::Budget;
use crate::error::Result;
use crate::progress::Progress;
use crate::studies::shard::{Shard, Sharded, Timing};

/// The pairing study as a [`Sharded`] study (`sphstab pairing --shard i/n`).
pub struct PairingStudy;

impl Sharded for PairingStudy {
    const STUDY: &'static str = "pairing";
    type Config = PairingConfig;
    type Cell = PairingRow;
    type Report = PairingReport;

    fn cells(&self, cfg: &PairingConfig) -> Result<usize> {
        Ok(plan(cfg)?.rows())
    }

    fn budget(&self, cfg: &PairingConfig) -> Budget {
        cfg.budget
    }

    fn with_budget(&self, cfg: PairingConfig, budget: Budget) -> PairingConfig {
        PairingConfig { budget, ..cfg }
    }

    fn compute(
        &self,
        cfg: &PairingConfig,
        shard: Shard,
        progress: &dyn Progress,
    ) -> Result<Vec<(usize, PairingRow)>> {
        compute_rows(cfg, shard, progress)
    }

    fn report(
        &self,
        cfg: &PairingConfig,
        rows: Vec<PairingRow>,
        timing: Timing,
    ) -> Result<PairingReport> {
        assemble(cfg, rows, timing)
    }
}
