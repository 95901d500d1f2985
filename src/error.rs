//! Library error type. Every variant names where the problem is and the allowed range, so the
//! binary can print it as a one-line message and exit with status 2.
//!
//! The library names what the user gave by its *field* — the field of the question or config
//! struct (`h_over_dx`, `stress`, `density_ratio`), or the key of a JSON config or scene — never
//! by a command-line flag. A message that names fields is a [`Text`]: plain text with field
//! references ([`field`]). [`Error`]'s `Display` writes the field names; the binary renders the
//! same error with [`Error::render`] and its one table of field → flag, so that its messages
//! name the flag the user typed (`h_over_dx` → `--h`).

use crate::display::{num, num_sig};
use std::fmt;
use std::ops::Add;

/// How a message names a field: the library by the field itself, the binary by its flag.
pub type Names<'a> = &'a dyn Fn(&'static str) -> &'static str;

/// Names every field by itself (what `Display` does).
fn as_field(f: &'static str) -> &'static str {
    f
}

/// One piece of a [`Text`].
#[derive(Clone, Debug, PartialEq)]
enum Part {
    /// Plain text.
    Str(String),
    /// A field, named when the text is rendered.
    Field(&'static str),
}

/// Message text with field references: built with `+` from strings and [`field`]s,
/// e.g. `field("form") + " nonlocal is not available with " + field("dim") + " 2"`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Text(Vec<Part>);

/// A reference to the field `name` in a message (a struct field or a JSON key).
pub fn field(name: &'static str) -> Text {
    Text(vec![Part::Field(name)])
}

/// Field references joined by `/` (the fields that drive a budget estimate, e.g.
/// `size/h_over_dx`).
pub fn fields(names: &[&'static str]) -> Text {
    let mut t = Text::default();
    for (i, n) in names.iter().enumerate() {
        if i > 0 {
            t = t + "/";
        }
        t = t + field(n);
    }
    t
}

impl Text {
    /// The text with every field named by `names`.
    pub fn render(&self, names: Names) -> String {
        let mut s = String::new();
        for p in &self.0 {
            match p {
                Part::Str(t) => s.push_str(t),
                Part::Field(f) => s.push_str(names(f)),
            }
        }
        s
    }

    /// The fields the text names, in order.
    pub fn fields(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.0.iter().filter_map(|p| match p {
            Part::Field(f) => Some(*f),
            Part::Str(_) => None,
        })
    }
}

impl From<&str> for Text {
    fn from(s: &str) -> Self {
        Text(vec![Part::Str(s.to_string())])
    }
}

impl From<String> for Text {
    fn from(s: String) -> Self {
        Text(vec![Part::Str(s)])
    }
}

impl<T: Into<Text>> Add<T> for Text {
    type Output = Text;
    fn add(mut self, rhs: T) -> Text {
        self.0.extend(rhs.into().0);
        self
    }
}

impl fmt::Display for Text {
    /// Fields by their names.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render(&as_field))
    }
}

/// Errors raised by the library. `Display` names fields by themselves ([`Error::render`]).
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[error("{}", self.render(&as_field))]
#[non_exhaustive]
pub enum Error {
    /// A name (kernel, form, shape family, ...) that is not known:
    /// "unknown {what} `{given}`; valid: {valid}".
    UnknownName {
        /// What kind of name (e.g. "kernel").
        what: Text,
        /// The name given.
        given: String,
        /// Comma-separated list of valid names.
        valid: Text,
    },
    /// A number outside its allowed range (or NaN): "{field} = {value} is out of range: {range}".
    OutOfRange {
        /// The field that holds it.
        field: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, in words.
        range: Text,
    },
    /// A combination of options that has no meaning (e.g. a shape family a form cannot use).
    Incompatible(Text),
    /// A moment matrix (MLS / corrected derivative) that cannot be inverted.
    SingularMoment {
        /// Which matrix.
        what: &'static str,
        /// Evaluation point (in the system's length units).
        x: f64,
        /// Determinant found.
        det: f64,
    },
    /// A malformed configuration file (unknown field, bad value), with where it happened:
    /// "{file}: {msg}".
    Config {
        /// File name.
        file: String,
        /// What is wrong (names the field).
        msg: String,
    },
    /// Shard files that do not make up one study ([`crate::studies::shard::merge`]), naming the
    /// file and the cell at fault: "merge: {file}: cell {cell}: {problem}".
    Merge {
        /// The file at fault (None: the set of files, e.g. one missing from it).
        file: Option<String>,
        /// The cell at fault (its index in the study).
        cell: Option<usize>,
        /// What is wrong.
        problem: Text,
    },
    /// A numerical result that is not finite.
    NonFinite(&'static str),
    /// A run whose estimated memory or time steps exceed the resource budget
    /// ([`crate::budget`]): "{fields}: {what} needs about {estimate}, more than the limit
    /// {limit}".
    Budget {
        /// The fields that drive the estimate.
        fields: Text,
        /// What would be allocated or run.
        what: String,
        /// The estimate, with its unit.
        estimate: String,
        /// The limit, its unit and the budget field that raises it.
        limit: Text,
    },
    /// A time integration that blew up: the first non-finite value or a runaway.
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
    /// A figure that could not be converted to another format ([`crate::plot::export`]):
    /// "{format}: {problem}".
    Export {
        /// The format being written (`svg` when the SVG itself cannot be read).
        format: &'static str,
        /// What went wrong.
        problem: String,
    },
    /// Long work stopped because its [`crate::progress::Progress`] asked it to.
    Cancelled,
    /// An iterative method that did not reach its tolerance within its iteration limit.
    NotConverged {
        /// What was being computed, and by which method.
        what: &'static str,
        /// Iterations (operator products) done.
        iterations: usize,
        /// The best residual reached, in units of the tolerance (> 1).
        residual: f64,
    },
}

impl Error {
    /// The one-line message with every field named by `names` (the binary passes its
    /// field → flag table; `Display` names the fields themselves).
    pub fn render(&self, names: Names) -> String {
        match self {
            Error::UnknownName { what, given, valid } => format!(
                "unknown {} `{given}`; valid: {}",
                what.render(names),
                valid.render(names)
            ),
            Error::OutOfRange {
                field,
                value,
                range,
            } => format!(
                "{} = {} is out of range: {}",
                names(field),
                num(*value),
                range.render(names)
            ),
            Error::Incompatible(t) => t.render(names),
            Error::SingularMoment { what, x, det } => format!(
                "singular {what} at x = {} (determinant {}): the support covers too few neighbours",
                num(*x),
                num_sig(*det, 3)
            ),
            Error::Config { file, msg } => format!("{file}: {msg}"),
            Error::Merge {
                file,
                cell,
                problem,
            } => {
                let mut s = String::from("merge: ");
                if let Some(f) = file {
                    s += &format!("{f}: ");
                }
                if let Some(c) = cell {
                    s += &format!("cell {c}: ");
                }
                s + &problem.render(names)
            }
            Error::NonFinite(what) => format!("non-finite result in {what}"),
            Error::Budget {
                fields,
                what,
                estimate,
                limit,
            } => format!(
                "{}: {what} needs about {estimate}, more than the limit {}",
                fields.render(names),
                limit.render(names)
            ),
            Error::Diverged {
                step,
                t,
                what,
                max_amplitude,
            } => format!(
                "DIVERGED at step {step} (t = {t:.6e}): {what} (max |v| = {max_amplitude:.3e}); the run was stopped"
            ),
            Error::Export { format, problem } => format!("{format} export: {problem}"),
            Error::Cancelled => "cancelled".into(),
            Error::NotConverged {
                what,
                iterations,
                residual,
            } => format!(
                "{what} did not converge in {iterations} iterations: residual {residual:.2e} × its tolerance"
            ),
        }
    }
}

/// Library result type.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` (of the field `field`) is finite and inside `[lo, hi]` (inclusive
/// bounds as flagged).
pub fn check_range(
    field: &'static str,
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
        let fmt = num;
        Err(Error::OutOfRange {
            field,
            value,
            range: format!("must be a finite number in {l}{}, {}{r}", fmt(lo), fmt(hi)).into(),
        })
    }
}

/// Looks `given` up in a table of (value, name); the error lists every valid name.
pub fn lookup<T: Copy>(what: &'static str, table: &[(T, &'static str)], given: &str) -> Result<T> {
    table
        .iter()
        .find(|(_, n)| *n == given)
        .map(|(v, _)| *v)
        .ok_or_else(|| Error::UnknownName {
            what: what.into(),
            given: given.to_string(),
            valid: table
                .iter()
                .map(|(_, n)| *n)
                .collect::<Vec<_>>()
                .join(", ")
                .into(),
        })
}

/// The name of `v` in a table of (value, name).
pub fn name_in<T: Copy + PartialEq>(table: &[(T, &'static str)], v: T) -> &'static str {
    table
        .iter()
        .find(|(x, _)| *x == v)
        .map(|(_, n)| *n)
        .unwrap_or("?")
}

/// Parses the JSON document `text` of `file`; an error names the file and, where serde's own
/// message does not (a value of the wrong type: `invalid type: string "NaN", expected f64`), the
/// key the value belongs to, found from the error's position in the text.
pub fn parse_json<T: serde::de::DeserializeOwned>(file: &str, text: &str) -> Result<T> {
    serde_json::from_str(text).map_err(|e| json_error(file, text, &e))
}

/// The [`Error::Config`] of a JSON error `e` in `text` ([`parse_json`]).
pub fn json_error(file: &str, text: &str, e: &serde_json::Error) -> Error {
    let msg = e.to_string();
    let key = (e.classify() == serde_json::error::Category::Data && !msg.contains("field `"))
        .then(|| key_before(text, e.line(), e.column()))
        .flatten();
    Error::Config {
        file: file.into(),
        msg: match key {
            Some(k) => format!("field `{k}`: {msg}"),
            None => msg,
        },
    }
}

/// The last `"key":` before line `line`, column `column` (1-based) of `text`.
fn key_before(text: &str, line: usize, column: usize) -> Option<String> {
    let start: usize = text
        .split_inclusive('\n')
        .take(line.saturating_sub(1))
        .map(str::len)
        .sum();
    let mut end = (start + column).min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let before = &text[..end];
    let colon = before.rfind("\":")?;
    let open = before[..colon].rfind('"')?;
    Some(before[open + 1..colon].to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_type_errors_name_the_key() {
        let text = "{\"a\": 1,\n  \"t_end\": \"NaN\", \"b\": 2}";
        let e = parse_json::<std::collections::BTreeMap<String, f64>>("f.json", text)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("f.json: field `t_end`: invalid type"), "{e}");
        // serde's own message names the field: kept as it is
        #[derive(Debug, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        #[allow(dead_code)]
        struct S {
            a: f64,
        }
        let e = parse_json::<S>("f.json", "{\"a\": 1, \"colour\": 2}")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("f.json: unknown field `colour`"), "{e}");
    }

    #[test]
    fn range_errors_print_numbers_short() {
        let e = check_range("x", 5e-324, 1.0, 2.0, true, true).unwrap_err();
        assert_eq!(
            e.to_string(),
            "x = 5e-324 is out of range: must be a finite number in [1, 2]"
        );
    }
}
