//! The studies: questions answered by running the analysis, the solver or both over many
//! configurations, each in its own folder (config, run, report), sharing the config plumbing of
//! [`config`] and, for the studies that run longer than a minute, the shards of [`shard`].

pub mod art_stress;
pub mod atlas;
pub mod box_operator;
pub mod config;
pub mod kernel_guide;
pub mod pairing;
pub mod shard;
pub mod stable_dt;
pub mod stored;
pub mod swegle;
pub mod throughput;
pub mod tradeoff;
