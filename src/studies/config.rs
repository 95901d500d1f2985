//! Plumbing shared by the studies that run from an `analysis/*.json` config and write their
//! figure and data into `figures/` (`sphstab tradeoff`, `sphstab pairing`): the config parsed
//! with its fields checked by name, the figure name it may give, the stored report read back
//! to redraw the figure, and lists that must not repeat a name. Reading and writing the files
//! is the caller's.

use crate::error::{Error, Result, field};
use serde::de::DeserializeOwned;

/// Parses a study config or a stored report (JSON); `file` names it in errors, which name the
/// offending field (configs reject unknown fields with `#[serde(deny_unknown_fields)]`).
pub fn parse_json<T: DeserializeOwned>(file: &str, text: &str) -> Result<T> {
    crate::error::parse_json(file, text)
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

/// Checks that the list held by `field` has `lo` to `hi` values (its length `n`).
pub fn check_len(field: &'static str, n: usize, lo: usize, hi: usize) -> Result<()> {
    if (lo..=hi).contains(&n) {
        Ok(())
    } else {
        Err(Error::OutOfRange {
            field,
            value: n as f64,
            range: format!("{lo} to {hi} values").into(),
        })
    }
}

/// Refuses a name given twice in the list held by `field_name` (e.g. `kernels`).
pub fn no_duplicates(field_name: &'static str, names: &[&str]) -> Result<()> {
    for (i, n) in names.iter().enumerate() {
        if names[..i].contains(n) {
            return Err(Error::Incompatible(
                field(field_name) + format!(": `{n}` is given twice"),
            ));
        }
    }
    Ok(())
}
