//! Resource budget: every command estimates the memory and the time steps it will need
//! *before* allocating or looping, and refuses with [`Error::Budget`] (exit status 2 in the
//! binary) when an estimate exceeds the budget — naming the flags that drive it, the estimate
//! and the limit — instead of exhausting the machine or running for hours.
//!
//! The budget is process-wide ([`set`], [`current`]): the binary sets it once from
//! `--max-memory` / `--max-steps`, and every validation path (CLI flags, scene files, figure
//! and trade-off configs, the library API) checks against the same values. Defaults:
//! memory [`DEFAULT_MAX_MEMORY`] (2 GiB, or a quarter of the machine's RAM if that is less —
//! see [`Budget::for_machine`]), time integration [`DEFAULT_MAX_STEPS`] particle-steps
//! (particles × time steps; the 2D solver does ~1e6 particle-steps per second per core here,
//! so the default is of the order of a minute). The atlas counts κ-evaluations (cells × κ
//! points, ~0.3 µs each) against 10 × `--max-steps`.
//!
//! Estimates are deliberately simple upper-bound-like formulas (documented where they are
//! computed); they only have to be right within a small factor to keep a run inside the
//! machine.

use crate::error::{Error, Result};
use std::sync::RwLock;

/// Default memory budget in bytes (2 GiB).
pub const DEFAULT_MAX_MEMORY: f64 = 2.0 * 1024.0 * 1024.0 * 1024.0;
/// Default cap on particle-steps (particles × time steps) of one time integration.
pub const DEFAULT_MAX_STEPS: f64 = 5e7;

/// The limits a command must stay within.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// Bytes of memory.
    pub max_memory: f64,
    /// Particle-steps (particles × time steps) of one time integration.
    pub max_steps: f64,
}

impl Default for Budget {
    fn default() -> Self {
        Self {
            max_memory: DEFAULT_MAX_MEMORY,
            max_steps: DEFAULT_MAX_STEPS,
        }
    }
}

static BUDGET: RwLock<Budget> = RwLock::new(Budget {
    max_memory: DEFAULT_MAX_MEMORY,
    max_steps: DEFAULT_MAX_STEPS,
});

/// Sets the process-wide budget (the binary does this once, from its flags).
pub fn set(b: Budget) {
    *BUDGET.write().unwrap_or_else(|e| e.into_inner()) = b;
}

/// The process-wide budget.
pub fn current() -> Budget {
    *BUDGET.read().unwrap_or_else(|e| e.into_inner())
}

impl Budget {
    /// The default budget on this machine: memory = min(2 GiB, MemTotal/4) where
    /// `/proc/meminfo` can be read, 2 GiB otherwise.
    pub fn for_machine() -> Self {
        let total = std::fs::read_to_string("/proc/meminfo").ok().and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("MemTotal:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<f64>().ok())
                .map(|kb| kb * 1024.0)
        });
        Self {
            max_memory: total.map_or(DEFAULT_MAX_MEMORY, |t| DEFAULT_MAX_MEMORY.min(t / 4.0)),
            max_steps: DEFAULT_MAX_STEPS,
        }
    }

    /// Refuses an estimated memory need above the budget.
    pub fn memory(&self, flags: &'static str, what: &str, bytes: f64) -> Result<()> {
        if bytes.is_finite() && bytes <= self.max_memory {
            return Ok(());
        }
        Err(Error::Budget {
            flags,
            what: what.to_string(),
            estimate: fmt_bytes(bytes),
            limit: format!("{} (--max-memory)", fmt_bytes(self.max_memory)),
        })
    }

    /// Refuses an estimated number of particle-steps above the budget.
    pub fn steps(&self, flags: &'static str, what: &str, particle_steps: f64) -> Result<()> {
        self.work(
            flags,
            what,
            particle_steps,
            "particle-steps",
            self.max_steps,
        )
    }

    /// Refuses `amount` units of work above `limit` (derived from `--max-steps`).
    pub fn work(
        &self,
        flags: &'static str,
        what: &str,
        amount: f64,
        unit: &str,
        limit: f64,
    ) -> Result<()> {
        if amount.is_finite() && amount <= limit {
            return Ok(());
        }
        Err(Error::Budget {
            flags,
            what: what.to_string(),
            estimate: format!("{} {unit}", fmt_count(amount)),
            limit: format!("{} {unit} (--max-steps)", fmt_count(limit)),
        })
    }
}

/// Checks memory against the process-wide budget.
pub fn check_memory(flags: &'static str, what: &str, bytes: f64) -> Result<()> {
    current().memory(flags, what, bytes)
}

/// Checks particle-steps against the process-wide budget.
pub fn check_steps(flags: &'static str, what: &str, particle_steps: f64) -> Result<()> {
    current().steps(flags, what, particle_steps)
}

/// `1.5 GiB`-style byte counts.
pub fn fmt_bytes(b: f64) -> String {
    if !b.is_finite() {
        return "an unbounded amount".into();
    }
    let units = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = b.max(0.0);
    let mut i = 0;
    while v >= 1024.0 && i + 1 < units.len() {
        v /= 1024.0;
        i += 1;
    }
    if i + 1 == units.len() && v >= 1024.0 {
        return format!("{b:.3e} B");
    }
    format!("{v:.1} {}", units[i])
}

/// Compact counts: `4.0e10`.
pub fn fmt_count(n: f64) -> String {
    if !n.is_finite() {
        return "unbounded".into();
    }
    if n < 1e6 {
        format!("{n:.0}")
    } else {
        format!("{n:.1e}")
    }
}

/// Parses a byte count with an optional binary suffix: `512M`, `2G`, `1.5GiB`, `3000000`.
pub fn parse_bytes(s: &str) -> std::result::Result<f64, String> {
    let t = s.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == 'e' || c == 'E' || c == '+'))
        .unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let v: f64 = num
        .parse()
        .map_err(|_| format!("`{s}` is not a byte count (e.g. 512M, 2G, 3000000)"))?;
    let mult = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" | "kib" => 1024.0,
        "m" | "mb" | "mib" => 1024.0 * 1024.0,
        "g" | "gb" | "gib" => 1024.0 * 1024.0 * 1024.0,
        "t" | "tb" | "tib" => 1024.0f64.powi(4),
        u => return Err(format!("unknown unit `{u}` in `{s}` (use K, M, G or T)")),
    };
    let b = v * mult;
    if b.is_finite() && b > 0.0 {
        Ok(b)
    } else {
        Err(format!("`{s}` must be a positive byte count"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_counts_parse_and_print() {
        assert_eq!(parse_bytes("2G").unwrap(), 2.0 * 1024.0 * 1024.0 * 1024.0);
        assert_eq!(parse_bytes("512M").unwrap(), 512.0 * 1024.0 * 1024.0);
        assert_eq!(parse_bytes("3000").unwrap(), 3000.0);
        assert!(parse_bytes("-1").is_err());
        assert!(parse_bytes("1X").is_err());
        assert_eq!(fmt_bytes(1536.0), "1.5 KiB");
        let b = Budget {
            max_memory: 1000.0,
            max_steps: 10.0,
        };
        assert!(b.memory("--x", "test", 999.0).is_ok());
        assert!(b.memory("--x", "test", 1001.0).is_err());
        assert!(b.memory("--x", "test", f64::NAN).is_err());
        assert!(b.steps("--x", "test", 11.0).is_err());
    }
}
