//! Plumbing shared by the studies that run from an `analysis/*.json` config and write their
//! figure and data into `figures/` (`sphstab tradeoff`, `sphstab pairing`): the config parsed
//! with its fields checked by name, the figure name it may give, and the stored report read
//! back to redraw the figure. The command-line side (reading the files, writing the figure and
//! its data) is `src/bin/sphstab/study.rs`.

use crate::error::{Error, Result};
use serde::de::DeserializeOwned;

/// Parses a study config or a stored report (JSON); `file` names it in errors, which name the
/// offending field (configs reject unknown fields with `#[serde(deny_unknown_fields)]`).
pub fn parse_json<T: DeserializeOwned>(file: &str, text: &str) -> Result<T> {
    serde_json::from_str(text).map_err(|e| Error::Config {
        file: file.into(),
        msg: e.to_string(),
    })
}

/// Checks a config's `output`: a plain file name ending in .svg (it goes into `figures/`, the
/// data next to it with the extension .json); `file` names the config in the error.
pub fn check_output(file: &str, output: Option<&str>) -> Result<()> {
    match output {
        Some(o)
            if o.is_empty()
                || o.contains(['/', '\\'])
                || o.contains("..")
                || !o.ends_with(".svg") =>
        {
            Err(Error::Config {
                file: file.into(),
                msg: format!(
                    "`output` = {o:?} must be a plain file name ending in .svg (it goes into figures/; no directory, no ..)"
                ),
            })
        }
        _ => Ok(()),
    }
}
