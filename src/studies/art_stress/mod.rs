//! The artificial-stress study (`sphstab art-stress`): how much Monaghan–Gray artificial stress
//! (R = −ε σ⁺/ρ², force Σ m (R_I + R_J) fⁿ ∇W, f = W(r)/W(Δx)) slows the Swegle growth of the
//! classical form in a zero-shear material under tension, predicted by the engine on the
//! infinite lattice and for the finite Swegle box, and measured by Swegle runs — all three from
//! the one rate function of [`crate::forms`] ([`crate::studies::swegle`]).
//!
//! For every h/Δx and density ratio f of the config, the growth rate is computed on a grid of ε
//! (infinite lattice: the fastest mode over the zone with its polarisation; box: the dense
//! operator of the same finite particle set), and Swegle runs are made at a subset of ε. A
//! stored set of runs of another code (PySPH, `analysis/pysph/results-art-stress.json`) can be
//! drawn next to them. The figure has one panel per (h, f). The published study (~1.5 min of
//! CPU) splits into shards for a job array with [`ArtStressStudy`] ([`crate::studies::shard`]).

mod config;
mod figure;
mod report;
mod run;
mod shard;

pub use config::{ArtStressConfig, parse_config};
pub use figure::figure_svg;
pub use report::{ArtStressReport, Case, ComparePoint, Comparison, Point, RunPoint, table};
pub use run::{comparison_from_pysph, run};
pub use shard::{ArtStressCell, ArtStressSetup, ArtStressStudy};
