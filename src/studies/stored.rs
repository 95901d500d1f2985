//! The stored data of a study: the report a study's `--config` writes next to its figure
//! (`figures/<name>.json` beside `figures/<name>.svg`), read back without knowing which study
//! wrote it. Each study's report has fields the others lack (`tradeoff`: `dim` and `scene`;
//! `pairing`: `onsets`; `art-stress`: `cases`), so the data is read as every study's report and
//! recognised by the one that reads it: the report types themselves decide, no list of keys
//! to keep in step with them.

use crate::error::{Error, Result};
use crate::studies::art_stress::ArtStressReport;
use crate::studies::hourglass::HourglassReport;
use crate::studies::pairing::PairingReport;
use crate::studies::tradeoff::TradeoffReport;
use serde::Deserialize;

/// A study's stored report.
#[derive(Clone, Debug)]
pub enum Stored {
    /// `sphstab tradeoff`.
    Tradeoff(Box<TradeoffReport>),
    /// `sphstab pairing`.
    Pairing(Box<PairingReport>),
    /// `sphstab art-stress`.
    ArtStress(Box<ArtStressReport>),
    /// `sphstab hourglass`.
    Hourglass(Box<HourglassReport>),
}

/// The studies whose data can be stored, by command name.
pub const STUDIES: [&str; 4] = ["tradeoff", "pairing", "art-stress", "hourglass"];

impl Stored {
    /// Reads the JSON `text` of the file `file` as the report of the one study it is; an error
    /// names the file when it is no study's report (or, impossibly, several).
    pub fn parse(file: &str, text: &str) -> Result<Stored> {
        let value: serde_json::Value =
            serde_json::from_str(text).map_err(|e| crate::error::json_error(file, text, &e))?;
        let found: Vec<Stored> = [
            TradeoffReport::deserialize(&value)
                .ok()
                .map(|r| Stored::Tradeoff(Box::new(r))),
            PairingReport::deserialize(&value)
                .ok()
                .map(|r| Stored::Pairing(Box::new(r))),
            ArtStressReport::deserialize(&value)
                .ok()
                .map(|r| Stored::ArtStress(Box::new(r))),
            HourglassReport::deserialize(&value)
                .ok()
                .map(|r| Stored::Hourglass(Box::new(r))),
        ]
        .into_iter()
        .flatten()
        .collect();
        let mut found = found.into_iter();
        match (found.next(), found.next()) {
            (Some(s), None) => Ok(s),
            (first, _) => Err(Error::Config {
                file: file.into(),
                msg: format!(
                    "{} of the studies' reports ({}) reads this data: it is not one study's stored report",
                    if first.is_some() {
                        "more than one"
                    } else {
                        "none"
                    },
                    STUDIES.join(", ")
                ),
            }),
        }
    }

    /// The command of the study that wrote it (`tradeoff`, `pairing`, `art-stress`).
    pub fn study(&self) -> &'static str {
        match self {
            Stored::Tradeoff(_) => STUDIES[0],
            Stored::Pairing(_) => STUDIES[1],
            Stored::ArtStress(_) => STUDIES[2],
            Stored::Hourglass(_) => STUDIES[3],
        }
    }
}
