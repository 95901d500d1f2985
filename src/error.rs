//! Library error type. Every variant names where the problem is and the allowed range,
//! so the binary can print it as a one-line message and exit with status 2.

/// Errors raised by the library.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// A name (kernel, form, shape family, ...) that is not known.
    #[error("unknown {what} `{given}`; valid: {valid}")]
    UnknownName {
        /// What kind of name (e.g. "kernel").
        what: &'static str,
        /// The name given.
        given: String,
        /// Comma-separated list of valid names.
        valid: String,
    },
    /// A number outside its allowed range (or NaN).
    #[error("{name} = {} is out of range: {range}", fmt_num(*.value))]
    OutOfRange {
        /// Parameter (flag or field) name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        range: String,
    },
    /// A combination of options that has no meaning (e.g. a shape family a form cannot use).
    #[error("{0}")]
    Incompatible(String),
    /// A moment matrix (MLS / corrected derivative) that cannot be inverted.
    #[error(
        "singular {what} at x = {x} (determinant {det:e}): the support covers too few neighbours"
    )]
    SingularMoment {
        /// Which matrix.
        what: &'static str,
        /// Evaluation point (in the system's length units).
        x: f64,
        /// Determinant found.
        det: f64,
    },
    /// A malformed configuration file (unknown field, bad value), with where it happened.
    #[error("{file}: {msg}")]
    Config {
        /// File name.
        file: String,
        /// What is wrong (names the field).
        msg: String,
    },
    /// A numerical result that is not finite.
    #[error("non-finite result in {0}")]
    NonFinite(&'static str),
    /// A run whose estimated memory or time steps exceed the resource budget
    /// ([`crate::budget`]); names the flags that drive the estimate.
    #[error("{flags}: {what} needs about {estimate}, more than the limit {limit}")]
    Budget {
        /// The flag(s) or field(s) that drive the estimate.
        flags: &'static str,
        /// What would be allocated or run.
        what: String,
        /// The estimate, with its unit.
        estimate: String,
        /// The limit and the flag that raises it.
        limit: String,
    },
    /// A time integration that blew up: the first non-finite value or a runaway.
    #[error(
        "DIVERGED at step {step} (t = {t:.6e}): {what} (max |v| = {max_amplitude:.3e}); the run was stopped"
    )]
    Diverged {
        /// Time step index.
        step: usize,
        /// Simulated time.
        t: f64,
        /// The criterion that fired.
        what: &'static str,
        /// Largest velocity magnitude at that point (may be non-finite).
        max_amplitude: f64,
    },
}

/// Library result type.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite and inside `[lo, hi]` (inclusive bounds as flagged).
pub fn check_range(
    name: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    lo_inclusive: bool,
    hi_inclusive: bool,
) -> Result<f64> {
    let ok_lo = if lo_inclusive {
        value >= lo
    } else {
        value > lo
    };
    let ok_hi = if hi_inclusive {
        value <= hi
    } else {
        value < hi
    };
    if value.is_finite() && ok_lo && ok_hi {
        Ok(value)
    } else {
        let l = if lo_inclusive { "[" } else { "(" };
        let r = if hi_inclusive { "]" } else { ")" };
        let fmt = fmt_num;
        Err(Error::OutOfRange {
            name,
            value,
            range: format!("must be a finite number in {l}{}, {}{r}", fmt(lo), fmt(hi)),
        })
    }
}

/// Looks `given` up in a table of (value, CLI name); the error lists every valid name.
pub fn lookup<T: Copy>(what: &'static str, table: &[(T, &'static str)], given: &str) -> Result<T> {
    table
        .iter()
        .find(|(_, n)| *n == given)
        .map(|(v, _)| *v)
        .ok_or_else(|| Error::UnknownName {
            what,
            given: given.to_string(),
            valid: table.iter().map(|(_, n)| *n).collect::<Vec<_>>().join(", "),
        })
}

/// The CLI name of `v` in a table of (value, name).
pub fn name_in<T: Copy + PartialEq>(table: &[(T, &'static str)], v: T) -> &'static str {
    table
        .iter()
        .find(|(x, _)| *x == v)
        .map(|(_, n)| *n)
        .unwrap_or("?")
}

/// A number as a user reads it in a message: the shortest round-trip form for ordinary
/// magnitudes, scientific notation (`1e308`, `2.5e-7`) for very large or small ones.
pub fn fmt_num(v: f64) -> String {
    if v.is_nan() {
        "NaN".into()
    } else if v.is_infinite() {
        if v > 0.0 { "inf".into() } else { "-inf".into() }
    } else if v != 0.0 && (v.abs() >= 1e6 || v.abs() < 1e-4) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}
