//! Axes: automatic ranges, tick positions and labels (linear and log), and a [`Frame`] that
//! maps data to pixels and draws the box, grid, ticks and axis descriptions.

use super::print::{FRAME_LINE_PT, LABEL_PT, TICK_PT};
use super::style::{GREY, outline, stroke, text_at, text_width};
use crate::error::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// A curve is left out of the automatic range (and drawn clipped, with a mark) only when it
/// reaches further beyond the range of the other curves than this many times that range.
pub const DIVERGE_FACTOR: f64 = 20.0;

/// Vertical range chosen by [`auto_range`].
#[derive(Clone, Debug, PartialEq)]
pub struct AutoRange {
    /// Lower end (before padding).
    pub lo: f64,
    /// Upper end (before padding).
    pub hi: f64,
    /// Per curve: it does not fit in [lo, hi] and is drawn clipped.
    pub clipped: Vec<bool>,
}

fn extent(ys: &[f64]) -> Option<(f64, f64)> {
    ys.iter()
        .copied()
        .filter(|y| y.is_finite())
        .fold(None, |r, y| match r {
            None => Some((y, y)),
            Some((a, b)) => Some((a.min(y), b.max(y))),
        })
}

/// The vertical range that holds every finite value of every curve (and 0 when
/// `include_zero`), except curves that diverge: a curve reaching beyond the range of all the
/// others together by more than [`DIVERGE_FACTOR`] × that range is left out (marked in
/// `clipped`; a range of zero width never counts as diverged from), and
/// the range then extends a quarter beyond the others so the clipped curve visibly leaves it.
pub fn auto_range(curves: &[&[f64]], include_zero: bool) -> AutoRange {
    let ext: Vec<Option<(f64, f64)>> = curves.iter().map(|c| extent(c)).collect();
    let mut out = vec![false; curves.len()];
    let union = |skip: &[bool], also: Option<usize>| {
        let mut r: Option<(f64, f64)> = include_zero.then_some((0.0, 0.0));
        for (i, e) in ext.iter().enumerate() {
            if skip[i] || Some(i) == also {
                continue;
            }
            if let Some((a, b)) = e {
                r = Some(r.map_or((*a, *b), |(x, y)| (x.min(*a), y.max(*b))));
            }
        }
        r
    };
    // one pass against the union of all the other curves (no cascade: excluding one curve
    // never makes another look divergent)
    let none = vec![false; curves.len()];
    for i in 0..curves.len() {
        let (Some((a, b)), Some((lo, hi))) = (ext[i], union(&none, Some(i))) else {
            continue;
        };
        let span = hi - lo;
        if span > 0.0 && ((b - hi).max(lo - a)) > DIVERGE_FACTOR * span {
            out[i] = true;
        }
    }
    let (mut lo, mut hi) = union(&out, None).unwrap_or((0.0, 1.0));
    if out.iter().any(|&c| c) {
        let span = (hi - lo).max(1e-12);
        for (i, e) in ext.iter().enumerate() {
            if let (true, Some((a, b))) = (out[i], e) {
                if *b > hi {
                    hi += 0.25 * span;
                }
                if *a < lo {
                    lo -= 0.25 * span;
                }
            }
        }
    }
    if hi - lo < 1e-12 {
        let m = hi.abs().max(1.0);
        lo -= 0.5 * m;
        hi += 0.5 * m;
    }
    let clipped = ext
        .iter()
        .map(|e| e.is_some_and(|(a, b)| a < lo - 1e-12 * (hi - lo) || b > hi + 1e-12 * (hi - lo)))
        .collect();
    AutoRange { lo, hi, clipped }
}

/// Tick values of a linear axis: multiples of 1, 2 or 5 × 10^k inside [lo, hi], at most
/// `max_n` of them (at least two when the range allows).
pub fn nice_ticks(lo: f64, hi: f64, max_n: usize) -> Vec<f64> {
    if hi <= lo || !lo.is_finite() || !hi.is_finite() {
        return Vec::new();
    }
    let raw = (hi - lo) / max_n.max(2) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| (hi - lo) / s <= max_n as f64)
        .unwrap_or(10.0 * mag);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|k| k as f64 * step).collect()
}

/// Label of a linear tick: as many decimals as the step needs, a true minus sign, no "-0".
pub fn tick_label(v: f64, step: f64) -> String {
    let dec = if step > 0.0 {
        (-(step.log10() + 1e-9).floor()).clamp(0.0, 8.0) as usize
    } else {
        0
    };
    let dec = if step > 0.0
        && ((step * 10f64.powi(dec as i32)).round() - step * 10f64.powi(dec as i32)).abs() > 1e-6
    {
        dec + 1
    } else {
        dec
    };
    let s = format!("{:.*}", dec, v);
    let s = if s
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        s.trim_start_matches('-').to_string()
    } else {
        s
    };
    s.replace('-', "−")
}

/// A number to two significant digits, in scientific notation beyond [0.01, 10⁴), with a
/// true minus: 1e−6, 2.9e−6, 0.5, 10.
pub fn sci(v: f64) -> String {
    if v != 0.0 && (v.abs() < 1e-2 || v.abs() >= 1e4) {
        format!("{v:.1e}").replace(".0e", "e").replace('-', "−")
    } else {
        let s = format!("{v:.2}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.replace('-', "−")
    }
}

/// Exponents e of the decades 10^e inside [lo, hi] (lo, hi > 0): the major ticks of a log axis.
pub fn log_decades(lo: f64, hi: f64) -> Vec<i32> {
    let a = (lo.log10() - 1e-9).ceil() as i32;
    let b = (hi.log10() + 1e-9).floor() as i32;
    (a..=b).collect()
}

/// Label of the decade 10^e: 0.01, 0.1, 1, 10, 100, then 10³, 10⁴, … and 10⁻³, 10⁻⁴, ….
pub fn log_label(e: i32) -> String {
    match e {
        -2 => "0.01".into(),
        -1 => "0.1".into(),
        0 => "1".into(),
        1 => "10".into(),
        2 => "100".into(),
        _ => {
            const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
            let mut s = String::from("10");
            if e < 0 {
                s.push('⁻');
            }
            for d in e.unsigned_abs().to_string().chars() {
                s.push(SUP[d as usize - '0' as usize]);
            }
            s
        }
    }
}

/// Scale of one axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scale {
    /// Linear over [lo, hi].
    Linear(f64, f64),
    /// Logarithmic over [10^a, 10^b] (a, b: log10 of the ends).
    Log(f64, f64),
}

impl Scale {
    /// A log scale over [lo, hi] (lo, hi > 0).
    pub fn log(lo: f64, hi: f64) -> Self {
        Scale::Log(lo.log10(), hi.log10())
    }

    fn t(&self, v: f64) -> f64 {
        match *self {
            Scale::Linear(a, b) => (v - a) / (b - a),
            Scale::Log(a, b) => (v.log10() - a) / (b - a),
        }
    }

    /// Major ticks (value, label) and minor tick values; `max_n`: most labels that fit.
    pub fn ticks(&self, max_n: usize) -> (Vec<(f64, String)>, Vec<f64>) {
        match *self {
            Scale::Linear(a, b) => {
                let t = nice_ticks(a, b, max_n);
                let step = if t.len() > 1 { t[1] - t[0] } else { b - a };
                (
                    t.iter().map(|&v| (v, tick_label(v, step))).collect(),
                    Vec::new(),
                )
            }
            Scale::Log(a, b) => {
                let (lo, hi) = (10f64.powf(a), 10f64.powf(b));
                let dec = log_decades(lo, hi);
                let every = dec.len().div_ceil(max_n.max(1)).max(1) as i32;
                let d0 = dec.first().copied().unwrap_or(0);
                let mut major: Vec<(f64, String)> = dec
                    .iter()
                    .filter(|e| (*e - d0) % every == 0)
                    .map(|&e| (10f64.powi(e), log_label(e)))
                    .collect();
                let inside = |v: f64| v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9);
                let mut minor = Vec::new();
                for e in (a.floor() as i32)..=(b.ceil() as i32) {
                    let p = 10f64.powi(e);
                    if every > 1 && (e - d0) % every != 0 && inside(p) {
                        minor.push(p);
                    }
                    if every == 1 {
                        for m in 2..10 {
                            let v = m as f64 * p;
                            if !inside(v) {
                                continue;
                            }
                            // fewer than two decades: label 2× and 5× as well
                            if dec.len() < 2 && (m == 2 || m == 5) {
                                major.push((
                                    v,
                                    format!("{}", (v / p).round() * p).replace('-', "−"),
                                ));
                            } else {
                                minor.push(v);
                            }
                        }
                    }
                }
                major.sort_by(|x, y| x.0.total_cmp(&y.0));
                (major, minor)
            }
        }
    }

    /// Whether `v` can be placed on this axis.
    pub fn accepts(&self, v: f64) -> bool {
        v.is_finite() && (matches!(self, Scale::Linear(..)) || v > 0.0)
    }
}

/// A plotting box in points with the scales of its two axes.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    /// Left, top, right, bottom (points).
    pub rect: (f64, f64, f64, f64),
    /// Horizontal scale.
    pub x: Scale,
    /// Vertical scale.
    pub y: Scale,
    /// Light grid lines at the major ticks (off for heat maps).
    pub grid: bool,
}

impl Frame {
    /// Pixel of a data point (not clipped).
    pub fn map(&self, x: f64, y: f64) -> (f64, f64) {
        let (l, t, r, b) = self.rect;
        (l + self.x.t(x) * (r - l), b - self.y.t(y) * (b - t))
    }

    /// Whether the pixel lies inside the box (with a tolerance of `tol` px).
    pub fn contains(&self, p: (f64, f64), tol: f64) -> bool {
        let (l, t, r, b) = self.rect;
        p.0 >= l - tol && p.0 <= r + tol && p.1 >= t - tol && p.1 <= b + tol
    }

    /// Major and minor ticks of the two axes as [`Frame::draw`] places them (`named_x`
    /// replaces the horizontal ones).
    #[allow(clippy::type_complexity)]
    fn ticks(
        &self,
        named_x: Option<&[(f64, String)]>,
    ) -> (
        (Vec<(f64, String)>, Vec<f64>),
        (Vec<(f64, String)>, Vec<f64>),
    ) {
        let (l, t, r, b) = self.rect;
        let per = |s: &Scale| {
            if matches!(s, Scale::Log(..)) {
                X_TICK_LOG_PT
            } else {
                X_TICK_PT
            }
        };
        let (mut xmaj, mut xmin) = self.x.ticks(((r - l) / per(&self.x)) as usize);
        if let Some(named) = named_x {
            xmaj = named.to_vec();
            xmin.clear();
        }
        ((xmaj, xmin), self.y.ticks(((b - t) / Y_TICK_PT) as usize))
    }

    /// Room (points) left of the box for the tick labels and the axis description `y_desc`
    /// of `y` on a box `box_h` points high: what [`Frame::draw`] uses.
    pub fn left_margin(y: Scale, box_h: f64, y_desc: &str) -> f64 {
        let (maj, _) = y.ticks((box_h / Y_TICK_PT) as usize);
        let w = maj
            .iter()
            .map(|(_, s)| text_width(s, TICK_PT))
            .fold(0.0f64, f64::max);
        let lines = desc_lines(y_desc, box_h).len() as f64;
        TICK_LEN + TICK_GAP + w + DESC_GAP + LABEL_PT * (1.0 + 1.2 * (lines - 1.0)) + 1.0
    }

    /// Draws the grid, the box, ticks with labels and the two axis descriptions (ticks
    /// [`TICK_PT`], descriptions [`LABEL_PT`]; the room they take: [`Frame::left_margin`] and
    /// [`BOTTOM_MARGIN`]).
    pub fn draw(
        &self,
        area: &DrawingArea<super::canvas::Canvas<'_>, Shift>,
        x_desc: &str,
        y_desc: &str,
        named_x: Option<&[(f64, String)]>,
    ) -> Result<()> {
        let (l, t, r, b) = self.rect;
        let grid = RGBColor(220, 220, 220);
        let ((xmaj, xmin), (ymaj, ymin)) = self.ticks(named_x);
        let xgrid = if named_x.is_some() { GREY } else { grid };
        for &(v, _) in xmaj.iter().filter(|_| self.grid || named_x.is_some()) {
            let x = self.map(v, 1.0).0;
            stroke(area, &[(x, t), (x, b)], xgrid, FRAME_LINE_PT)?;
        }
        for &(v, _) in ymaj.iter().filter(|_| self.grid) {
            let y = self.map(1.0, v).1;
            stroke(area, &[(l, y), (r, y)], grid, FRAME_LINE_PT)?;
        }
        outline(area, self.rect, BLACK, FRAME_LINE_PT)?;
        for &(v, ref s) in &xmaj {
            let x = self.map(v, 1.0).0;
            stroke(area, &[(x, b), (x, b + TICK_LEN)], BLACK, FRAME_LINE_PT)?;
            text_at(
                area,
                s,
                (x, b + TICK_LEN + TICK_GAP),
                TICK_PT,
                (HPos::Center, VPos::Top),
                false,
            )?;
        }
        for &v in &xmin {
            let x = self.map(v, 1.0).0;
            stroke(area, &[(x, b), (x, b + MINOR_LEN)], BLACK, FRAME_LINE_PT)?;
        }
        for &(v, ref s) in &ymaj {
            let y = self.map(1.0, v).1;
            stroke(area, &[(l - TICK_LEN, y), (l, y)], BLACK, FRAME_LINE_PT)?;
            text_at(
                area,
                s,
                (l - TICK_LEN - TICK_GAP, y),
                TICK_PT,
                (HPos::Right, VPos::Center),
                false,
            )?;
        }
        for &v in &ymin {
            let y = self.map(1.0, v).1;
            stroke(area, &[(l - MINOR_LEN, y), (l, y)], BLACK, FRAME_LINE_PT)?;
        }
        for (k, line) in desc_lines(x_desc, r - l + 20.0).iter().enumerate() {
            text_at(
                area,
                line,
                (
                    (l + r) / 2.0,
                    b + TICK_LEN + TICK_GAP + TICK_PT + DESC_GAP + LABEL_PT * 1.2 * k as f64,
                ),
                LABEL_PT,
                (HPos::Center, VPos::Top),
                false,
            )?;
        }
        let ylab_w = ymaj
            .iter()
            .map(|(_, s)| text_width(s, TICK_PT))
            .fold(0.0f64, f64::max);
        let lines = desc_lines(y_desc, b - t);
        let n = lines.len();
        for (k, line) in lines.iter().enumerate() {
            // the last line nearest the ticks
            let off = LABEL_PT * 1.2 * (n - 1 - k) as f64;
            text_at(
                area,
                line,
                (
                    l - TICK_LEN - TICK_GAP - ylab_w - DESC_GAP - off,
                    (t + b) / 2.0,
                ),
                LABEL_PT,
                (HPos::Center, VPos::Bottom),
                true,
            )?;
        }
        Ok(())
    }
}

/// An axis description set along `len` points: one line when it fits, else broken into
/// lines that do (at spaces, a parenthesis starting a line where it can).
pub fn desc_lines(desc: &str, len: f64) -> Vec<String> {
    if text_width(desc, LABEL_PT) <= len {
        return vec![desc.to_string()];
    }
    let chars = ((len / (0.6 * LABEL_PT)) as usize).max(8);
    if let Some(i) = desc.find(" (") {
        let (a, b) = (&desc[..i], &desc[i + 1..]);
        if a.chars().count() <= chars && b.chars().count() <= chars {
            return vec![a.to_string(), b.to_string()];
        }
    }
    super::style::wrap(desc, chars)
}

/// Length of a major tick, pt.
pub const TICK_LEN: f64 = 3.0;
/// Length of a minor tick, pt.
pub const MINOR_LEN: f64 = 1.5;
/// Gap between a tick and its label, pt.
pub const TICK_GAP: f64 = 1.5;
/// Gap between tick labels and the axis description, pt.
pub const DESC_GAP: f64 = 2.5;
/// Least room per labelled tick of a linear horizontal axis, pt.
const X_TICK_PT: f64 = 40.0;
/// Least room per labelled decade of a log horizontal axis, pt.
const X_TICK_LOG_PT: f64 = 20.0;
/// Least room per labelled tick of a vertical axis, pt.
const Y_TICK_PT: f64 = 22.0;
/// Room (points) under the box for the tick labels and a one-line axis description.
pub const BOTTOM_MARGIN: f64 = TICK_LEN + TICK_GAP + TICK_PT + DESC_GAP + LABEL_PT * 1.2 + 1.0;

/// Room (points) under a box `box_w` wide for the tick labels and the description `x_desc`
/// ([`BOTTOM_MARGIN`] and a line more per further line of the description).
pub fn bottom_margin(x_desc: &str, box_w: f64) -> f64 {
    BOTTOM_MARGIN + LABEL_PT * 1.2 * (desc_lines(x_desc, box_w + 20.0).len() as f64 - 1.0)
}

/// Liang–Barsky clipping of a polyline (pixels) to `rect` (left, top, right, bottom): the
/// pieces inside; a non-finite point breaks the line.
pub fn clip_polyline(pts: &[(f64, f64)], rect: (f64, f64, f64, f64)) -> Vec<Vec<(f64, f64)>> {
    let (l, t, r, b) = rect;
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Vec<(f64, f64)> = Vec::new();
    for w in pts.windows(2) {
        let (p, q) = (w[0], w[1]);
        if !(p.0.is_finite() && p.1.is_finite() && q.0.is_finite() && q.1.is_finite()) {
            if cur.len() >= 2 {
                out.push(std::mem::take(&mut cur));
            }
            cur.clear();
            continue;
        }
        let (dx, dy) = (q.0 - p.0, q.1 - p.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        let mut inside = true;
        for (pp, qq) in [(-dx, p.0 - l), (dx, r - p.0), (-dy, p.1 - t), (dy, b - p.1)] {
            if pp == 0.0 {
                if qq < 0.0 {
                    inside = false;
                }
            } else {
                let u = qq / pp;
                if pp < 0.0 {
                    t0 = t0.max(u);
                } else {
                    t1 = t1.min(u);
                }
            }
        }
        if !inside || t0 > t1 {
            if cur.len() >= 2 {
                out.push(std::mem::take(&mut cur));
            }
            cur.clear();
            continue;
        }
        let a = (p.0 + t0 * dx, p.1 + t0 * dy);
        let c = (p.0 + t1 * dx, p.1 + t1 * dy);
        if cur.is_empty() || t0 > 0.0 {
            if cur.len() >= 2 {
                out.push(std::mem::take(&mut cur));
            }
            cur = vec![a];
        }
        cur.push(c);
        if t1 < 1.0 {
            out.push(std::mem::take(&mut cur));
        }
    }
    if cur.len() >= 2 {
        out.push(cur);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ticks_are_decades_with_clean_labels() {
        assert_eq!(log_decades(12.0, 6000.0), vec![2, 3]);
        assert_eq!(log_decades(1e-5, 0.9), vec![-5, -4, -3, -2, -1]);
        assert_eq!(log_decades(10.0, 100.0), vec![1, 2]);
        assert!(log_decades(2.0, 3.0).is_empty());
        let labels: Vec<String> = (-4..=4).map(log_label).collect();
        assert_eq!(
            labels,
            [
                "10⁻⁴", "10⁻³", "0.01", "0.1", "1", "10", "100", "10³", "10⁴"
            ]
        );
        assert_eq!(log_label(12), "10¹²");
        // a major tick at each decade, minor ticks at 2…9 × each decade inside the range
        let (maj, min) = Scale::log(8.0, 20000.0).ticks(10);
        let v: Vec<f64> = maj.iter().map(|m| m.0).collect();
        assert_eq!(v, vec![10.0, 100.0, 1000.0, 10000.0]);
        assert_eq!(maj[3].1, "10⁴");
        assert_eq!(min.len(), 2 + 3 * 8 + 1); // 8, 9, then 20…90, …, 2e4
        // many decades, little room: every other decade labelled, the others still ticked
        let (maj, min) = Scale::log(1e-6, 1e6).ticks(7);
        assert_eq!(maj.len(), 7);
        assert_eq!(maj.len() + min.len(), 13);
        // less than a decade: 2× and 5× are labelled too
        let (maj, _) = Scale::log(1.5, 8.0).ticks(10);
        let v: Vec<&str> = maj.iter().map(|m| m.1.as_str()).collect();
        assert_eq!(v, vec!["2", "5"]);
    }

    #[test]
    fn short_numbers() {
        assert_eq!(sci(1e-6), "1e−6");
        assert_eq!(sci(2.93847e-6), "2.9e−6");
        assert_eq!(sci(0.5), "0.5");
        assert_eq!(sci(10.0), "10");
        assert_eq!(sci(-0.25), "−0.25");
    }

    #[test]
    fn linear_ticks_and_labels() {
        assert_eq!(
            nice_ticks(0.0, 1.0, 5),
            vec![0.0, 0.2, 0.4, 0.6000000000000001, 0.8, 1.0]
        );
        let t = nice_ticks(-1.3, 2.2, 8);
        assert_eq!(t.first(), Some(&-1.0));
        assert!(t.len() <= 8 && t.len() >= 4);
        assert_eq!(tick_label(-1.0, 0.5), "−1.0");
        assert_eq!(tick_label(2.0, 1.0), "2");
        assert_eq!(tick_label(-0.0, 0.5), "0.0");
        assert_eq!(tick_label(0.25, 0.25), "0.25");
        assert_eq!(tick_label(1000.0, 500.0), "1000");
    }

    #[test]
    fn auto_range_includes_all_finite_data() {
        let a = [0.0, 1.0, 1.6, f64::NAN];
        let b = [0.0, 4.0, 10.9]; // a continuum 7× above the discrete curve: kept whole
        let c = [-0.2, -5.0, f64::INFINITY];
        let r = auto_range(&[&a, &b, &c], true);
        assert_eq!((r.lo, r.hi), (-5.0, 10.9));
        assert_eq!(r.clipped, vec![false, false, false]);
        // a diverging curve is the only one left out, and flagged; a curve that is exactly
        // zero (a fluid's shear continuum) makes no other curve diverge
        let z = [0.0, 0.0, 0.0];
        let small = [0.0, -0.03, 0.01];
        let r = auto_range(&[&z, &small, &[0.0, 0.79], &[0.0, 10.0]], true);
        assert_eq!(r.clipped, vec![false, false, false, false]);
        let d = [0.0, 1e6];
        let r = auto_range(&[&a, &d], false);
        assert!(r.hi >= 1.6 && r.hi < 3.0 && r.lo <= 0.0);
        assert_eq!(r.clipped, vec![false, true]);
        // constant data gets a non-empty range
        let r = auto_range(&[&[2.0, 2.0][..]], false);
        assert!(r.lo < 2.0 && r.hi > 2.0);
    }

    #[test]
    fn clipping_keeps_the_inside_pieces() {
        let rect = (0.0, 0.0, 10.0, 10.0);
        let p = clip_polyline(&[(1.0, 5.0), (5.0, 15.0), (9.0, 5.0)], rect);
        assert_eq!(p.len(), 2);
        assert!((p[0][1].1 - 10.0).abs() < 1e-12);
        assert!((p[1][0].1 - 10.0).abs() < 1e-12);
        let q = clip_polyline(&[(1.0, 1.0), (2.0, 2.0), (3.0, 3.0)], rect);
        assert_eq!(q, vec![vec![(1.0, 1.0), (2.0, 2.0), (3.0, 3.0)]]);
    }
}
