//! Numbers as people read them: the one notation of every message and every line of text
//! output (data files keep the exact `{:e}` form). Plain notation for magnitudes in
//! [1e-4, 1e6) (`0.0001`, `2.27127`, `123456`), scientific outside (`1e308`, `5e-324`,
//! `-2.5e-7`), zero as `0` whatever its sign; never hundreds of digits.
//!
//! [`num`] keeps every digit of the value (the shortest that reads back to the same f64: for
//! values the user gave, so that a message shows exactly what was typed); [`num_sig`] rounds to
//! a number of significant digits (for results) and drops trailing zeros. Both share one
//! notation rule ([`notation`]). NaN and ±∞ are spelled `NaN`, `inf`, `-inf`: error messages
//! may show them (a value given as NaN); normal output never holds them.

/// The magnitudes printed in plain notation: [`PLAIN_MIN`, `PLAIN_MAX`).
pub const PLAIN_MIN: f64 = 1e-4;
/// See [`PLAIN_MIN`].
pub const PLAIN_MAX: f64 = 1e6;

/// `v` with all its digits (shortest round-trip form).
pub fn num(v: f64) -> String {
    notation(v, None)
}

/// `v` rounded to `digits` significant digits (at least 1), trailing zeros dropped.
pub fn num_sig(v: f64, digits: usize) -> String {
    notation(v, Some(digits.max(1)))
}

/// The notation of [`num`] (`digits` None) and [`num_sig`]: the decimal exponent after
/// rounding decides plain or scientific, so that 999999.7 at 6 digits reads `1e6`.
fn notation(v: f64, digits: Option<usize>) -> String {
    if v.is_nan() {
        return "NaN".into();
    }
    if v.is_infinite() {
        return if v > 0.0 { "inf" } else { "-inf" }.into();
    }
    if v == 0.0 {
        return "0".into();
    }
    // scientific form first: its exponent is the one of the rounded value
    let sci = match digits {
        Some(d) => trim_mantissa(&format!("{v:.prec$e}", prec = d - 1)),
        None => format!("{v:e}"),
    };
    let exp: i32 = sci
        .rsplit_once('e')
        .and_then(|(_, e)| e.parse().ok())
        .unwrap_or(0);
    let plain_range = PLAIN_MIN.log10() as i32..PLAIN_MAX.log10() as i32;
    if !plain_range.contains(&exp) {
        return sci;
    }
    match digits {
        None => format!("{v}"),
        Some(d) => {
            let decimals = (d as i32 - 1 - exp).max(0) as usize;
            let t = format!("{v:.decimals$}");
            if t.contains('.') {
                t.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                t
            }
        }
    }
}

/// `1.50000e6` → `1.5e6`, `1.00000e-7` → `1e-7`.
fn trim_mantissa(s: &str) -> String {
    match s.split_once('e') {
        Some((m, e)) if m.contains('.') => {
            format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
        }
        _ => s.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extremes_read_short() {
        assert_eq!(num(5e-324), "5e-324");
        assert_eq!(num(-5e-324), "-5e-324");
        assert_eq!(num(1e308), "1e308");
        assert_eq!(num(f64::MAX), "1.7976931348623157e308");
        assert_eq!(num(f64::MIN_POSITIVE), "2.2250738585072014e-308");
        // the smallest subnormal is 4.9406564584124654e-324: 5e-324 is its shortest spelling
        assert_eq!(num_sig(5e-324, 6), "4.94066e-324");
        assert_eq!(num_sig(1e308, 6), "1e308");
        assert_eq!(num_sig(f64::MAX, 6), "1.79769e308");
    }

    #[test]
    fn zero_has_no_sign() {
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(0.0), "0");
        assert_eq!(num_sig(-0.0, 6), "0");
        // a negative value that rounds to zero digits still shows its magnitude
        assert_eq!(num_sig(-1e-9, 6), "-1e-9");
    }

    #[test]
    fn plain_between_1e_minus_4_and_1e6() {
        assert_eq!(num(1e-4), "0.0001");
        assert_eq!(num(9.9e-5), "9.9e-5");
        assert_eq!(num(0.05), "0.05");
        assert_eq!(num(999999.0), "999999");
        assert_eq!(num(1e6), "1e6");
        assert_eq!(num(-2.5e-7), "-2.5e-7");
        assert_eq!(num(0.1 + 0.2), "0.30000000000000004");
        assert_eq!(num_sig(1e-4, 6), "0.0001");
        assert_eq!(num_sig(9.99999e-5, 6), "9.99999e-5");
        // rounding moves the value across a boundary: the notation follows the rounded value
        assert_eq!(num_sig(9.999999e-5, 6), "0.0001");
        assert_eq!(num_sig(999999.7, 6), "1e6");
        assert_eq!(num_sig(2.271274839201, 6), "2.27127");
        assert_eq!(num_sig(1.5e6, 6), "1.5e6");
        assert_eq!(num_sig(100.0, 6), "100");
        assert_eq!(num_sig(0.020058442, 6), "0.0200584");
    }

    #[test]
    fn non_finite_is_spelled() {
        assert_eq!(num(f64::NAN), "NaN");
        assert_eq!(num(f64::INFINITY), "inf");
        assert_eq!(num_sig(f64::NEG_INFINITY, 3), "-inf");
    }

    /// Every output is short and reads back to a value within the rounding.
    #[test]
    fn never_long_and_round_trips() {
        let mut x = 5e-324;
        while x < 1e308 {
            for v in [x, -x, x * 1.2345678901] {
                let s = num(v);
                assert!(s.len() <= 24, "{v}: {s}");
                assert_eq!(s.parse::<f64>().unwrap(), v, "{s}");
                let r = num_sig(v, 6);
                assert!(r.len() <= 13, "{v}: {r}");
                let back: f64 = r.parse().unwrap();
                assert!((back - v).abs() <= 5e-6 * v.abs(), "{v}: {r}");
            }
            x *= 7.3;
        }
    }
}
