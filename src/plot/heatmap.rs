//! Heat maps with a colour bar, laid out in points on an 85 mm page.

use super::axes::{
    DESC_GAP, Frame, Scale, TICK_GAP, TICK_LEN, bottom_margin, nice_ticks, tick_label,
};
use super::print::{FRAME_LINE_PT, LABEL_PT, NOTE_PT, PAD, TICK_PT, TITLE_PT, Width, page_pt};
use super::style::{fill_rect, outline, plot_err, stroke, text, text_at, text_width, wrap};
use crate::error::{Error, Result};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// Sequential colour map (white → yellow → orange → red → dark purple; monotone in lightness,
/// readable with colour-vision deficiencies and in greyscale): anchors at t = 0, ¼, ½, ¾, 1.
const RAMP: [(f64, f64, f64); 5] = [
    (255.0, 255.0, 255.0),
    (253.0, 219.0, 100.0),
    (240.0, 130.0, 40.0),
    (190.0, 30.0, 45.0),
    (70.0, 10.0, 80.0),
];

/// Colour of t ∈ [0, 1] on the heat-map scale (0: white).
pub fn ramp(t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let s = t * (RAMP.len() - 1) as f64;
    let k = (s.floor() as usize).min(RAMP.len() - 2);
    let f = s - k as f64;
    let (a, b) = (RAMP[k], RAMP[k + 1]);
    let c = |u: f64, v: f64| (u + f * (v - u)).round() as u8;
    RGBColor(c(a.0, b.0), c(a.1, b.1), c(a.2, b.2))
}

/// A vertical colour bar at (left, top, width, height) (points): `colour(t)` from t = 0 at
/// the bottom to 1 at the top, framed, with a tick and its label at each (t, label) of
/// `marks`.
fn colour_bar(
    root: &DrawingArea<super::canvas::Canvas<'_>, plotters::coord::Shift>,
    (bl, bt, bw, bh): (f64, f64, f64, f64),
    colour: impl Fn(f64) -> RGBColor,
    marks: &[(f64, String)],
) -> Result<()> {
    // 100 bands overlapping by a hair, so no seam shows between them
    let n = 100;
    for k in 0..n {
        let t = (k as f64 + 0.5) / n as f64;
        let ya = bt + bh * (1.0 - (k + 1) as f64 / n as f64);
        let yb = bt + bh * (1.0 - k as f64 / n as f64);
        fill_rect(root, (bl, ya - 0.05, bl + bw, yb + 0.05), colour(t))?;
    }
    outline(root, (bl, bt, bl + bw, bt + bh), BLACK, FRAME_LINE_PT)?;
    for (t, label) in marks {
        let y = bt + bh * (1.0 - t);
        stroke(
            root,
            &[(bl + bw, y), (bl + bw + TICK_LEN, y)],
            BLACK,
            FRAME_LINE_PT,
        )?;
        text_at(
            root,
            label,
            (bl + bw + TICK_LEN + TICK_GAP, y),
            TICK_PT,
            (HPos::Left, VPos::Center),
            false,
        )?;
    }
    Ok(())
}

/// A heat map of z over a rectangular (x, y) grid (cell centres, z\[i\]\[j\] at (x\[i\], y\[j\])) with
/// a colour bar labelled `z_desc` (quantity and unit) from 0 to max z.
pub fn heatmap_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    z_desc: &str,
    x: &[f64],
    y: &[f64],
    z: &[Vec<f64>],
) -> Result<String> {
    if x.len() < 2 || y.len() < 2 {
        return Err(Error::Incompatible(
            "heat map: need at least 2 × 2 cells".into(),
        ));
    }
    let (dx, dy) = (x[1] - x[0], y[1] - y[0]);
    let (x0, x1) = (x[0] - 0.5 * dx, x[x.len() - 1] + 0.5 * dx);
    let (y0, y1) = (y[0] - 0.5 * dy, y[y.len() - 1] + 0.5 * dy);
    let zmax = z
        .iter()
        .flatten()
        .filter(|v| v.is_finite())
        .fold(0.0f64, |m, &v| m.max(v));
    let page = page_pt(Width::Single);
    let title_lines = if title.is_empty() {
        Vec::new()
    } else {
        wrap(title, ((page - 2.0 * PAD) / (0.6 * TITLE_PT)) as usize)
    };
    let top = PAD + TITLE_PT * 1.25 * title_lines.len() as f64 + TICK_PT;
    let zt = if zmax > 0.0 { zmax } else { 1.0 };
    let ticks = nice_ticks(0.0, zt, 6);
    let step = if ticks.len() > 1 {
        ticks[1] - ticks[0]
    } else {
        zt
    };
    let bar_labels = ticks
        .iter()
        .map(|&v| text_width(&tick_label(v, step), TICK_PT))
        .fold(0.0f64, f64::max);
    let bar_w = 7.0;
    let right = 8.0 + bar_w + TICK_LEN + TICK_GAP + bar_labels + DESC_GAP + LABEL_PT + PAD;
    let side0 = page - PAD - 45.0 - right;
    let left = PAD + Frame::left_margin(Scale::Linear(y0, y1), side0, y_desc);
    let side = page - left - right;
    let frame = Frame {
        rect: (left, top, left + side, top + side),
        x: Scale::Linear(x0, x1),
        y: Scale::Linear(y0, y1),
        grid: false,
    };
    let height = top + side + bottom_margin(x_desc, side) + PAD;
    let mut svg = String::new();
    {
        let root =
            super::canvas::Canvas::new(&mut svg, Width::Single, (page, height)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        for (k, line) in title_lines.iter().enumerate() {
            text(
                &root,
                line,
                (PAD, PAD + TITLE_PT * 1.25 * k as f64),
                TITLE_PT,
                BLACK,
            )?;
        }
        // cells overlap by a hair so no seam shows between them
        let eps = 0.05;
        for (i, &xi) in x.iter().enumerate() {
            for (j, &yj) in y.iter().enumerate() {
                let v = z[i][j];
                let t = if zmax > 0.0 && v.is_finite() {
                    v / zmax
                } else {
                    0.0
                };
                let a = frame.map(xi - dx / 2.0, yj + dy / 2.0);
                let b = frame.map(xi + dx / 2.0, yj - dy / 2.0);
                fill_rect(&root, (a.0 - eps, a.1 - eps, b.0 + eps, b.1 + eps), ramp(t))?;
            }
        }
        frame.draw(&root, x_desc, y_desc, None)?;
        // the colour bar
        let (bl, bt, bh) = (left + side + 8.0, top, side);
        let marks: Vec<(f64, String)> = ticks
            .iter()
            .map(|&v| (v / zt, tick_label(v, step)))
            .collect();
        colour_bar(&root, (bl, bt, bar_w, bh), ramp, &marks)?;
        let top_label = if zmax > 0.0 {
            format!("max {}", tick_label(zmax, zmax / 1000.0))
        } else {
            "0 everywhere".to_string()
        };
        text_at(
            &root,
            &top_label,
            (page - PAD, bt - 1.5),
            TICK_PT,
            (HPos::Right, VPos::Bottom),
            false,
        )?;
        text_at(
            &root,
            z_desc,
            (
                bl + bar_w + TICK_LEN + TICK_GAP + bar_labels + DESC_GAP,
                bt + bh / 2.0,
            ),
            LABEL_PT,
            (HPos::Center, VPos::Top),
            true,
        )?;
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}

/// One panel of [`strips_svg`]: its title and, per row, the samples (x, value); a value
/// that is `None` (not computed) is drawn grey.
#[derive(Clone, Debug)]
pub struct StripPanel {
    /// Panel title (after its letter).
    pub title: String,
    /// Per row label: samples (x > 0, value).
    pub rows: Vec<Vec<(f64, Option<f64>)>>,
}

/// Grey of samples not computed.
const MISSING: RGBColor = RGBColor(190, 190, 190);

/// Lowest position on the colour ramp of an unstable value: visibly coloured, never white.
const LEVEL_MIN: f64 = 0.15;

/// Colour position of `v` on a log scale of two decades below `vmax`, from [`LEVEL_MIN`]
/// (values below the two decades too) to 1; values at or below `stable_below` are stable:
/// `None`, drawn white.
fn log_level(v: f64, vmax: f64, stable_below: f64) -> Option<f64> {
    (v > stable_below).then(|| {
        let lo = (vmax * 1e-2).log10();
        let u = ((v.log10() - lo) / (vmax.log10() - lo)).clamp(0.0, 1.0);
        LEVEL_MIN + (1.0 - LEVEL_MIN) * u
    })
}

/// Strip charts: in each panel one row per label, each sample (x on a log axis) a cell from
/// halfway to its neighbours, coloured by its value on the heat-map scale (log, two decades
/// below the maximum over all panels; white at or below `stable_below`, grey where not
/// computed), so where a row turns from white to colour — an onset — reads at a glance.
/// Panels `cols` to a row (lettered), a heading over each row of panels (`row_titles`), row
/// labels left of the first column, one colour bar.
pub fn strips_svg(
    x_desc: &str,
    z_desc: &str,
    labels: &[String],
    panels: &[StripPanel],
    cols: usize,
    row_titles: &[String],
    stable_below: f64,
) -> Result<String> {
    let cols = cols.max(1);
    let xs = || {
        panels
            .iter()
            .flat_map(|p| p.rows.iter().flatten().map(|q| q.0))
            .filter(|x| x.is_finite() && *x > 0.0)
    };
    let (x0, x1) = xs().fold((f64::INFINITY, 0.0f64), |(a, b), x| (a.min(x), b.max(x)));
    if !(x0.is_finite() && x1 > x0) {
        return Err(Error::Incompatible("nothing to plot: no samples".into()));
    }
    let vmax = panels
        .iter()
        .flat_map(|p| p.rows.iter().flatten().filter_map(|q| q.1))
        .filter(|v| v.is_finite())
        .fold(0.0f64, f64::max);
    let vmax = if vmax > stable_below { vmax } else { 1.0 };
    let page = page_pt(Width::Double);
    let label_w = labels
        .iter()
        .map(|l| text_width(l, TICK_PT))
        .fold(0.0f64, f64::max)
        + 3.0;
    let bar_w = 7.0;
    let bar_room = 8.0
        + bar_w
        + TICK_LEN
        + TICK_GAP
        + text_width("0.001", TICK_PT)
        + DESC_GAP
        + LABEL_PT
        + PAD;
    let gap = 10.0;
    let panel_w = (page - PAD - label_w - bar_room - gap * (cols - 1) as f64) / cols as f64;
    let row_h = 9.0;
    let box_h = row_h * labels.len() as f64;
    let prow = panels.len().div_ceil(cols);
    let head = LABEL_PT * 1.4;
    let cell_h = head + LABEL_PT * 1.5 + box_h + bottom_margin(x_desc, panel_w);
    let height = PAD + cell_h * prow as f64 + PAD;
    let xscale = Scale::log(x0 / 1.15, x1 * 1.15);
    let mut svg = String::new();
    {
        let root =
            super::canvas::Canvas::new(&mut svg, Width::Double, (page, height)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        for (pi, panel) in panels.iter().enumerate() {
            let (r, c) = (pi / cols, pi % cols);
            let l = PAD + label_w + c as f64 * (panel_w + gap);
            let t = PAD + r as f64 * cell_h + head + LABEL_PT * 1.5;
            if let (0, Some(rt)) = (c, row_titles.get(r)) {
                text(
                    &root,
                    rt,
                    (PAD, t - LABEL_PT * 1.35 - head),
                    LABEL_PT,
                    BLACK,
                )?;
            }
            // rows are labelled, not ticked: an empty vertical range has no ticks (and only
            // the horizontal mapping is used)
            let frame = Frame {
                rect: (l, t, l + panel_w, t + box_h),
                x: xscale,
                y: Scale::Linear(0.0, 0.0),
                grid: false,
            };
            text(
                &root,
                &format!("{} {}", super::scatter::panel_letter(pi), panel.title),
                (l, t - LABEL_PT * 1.35),
                LABEL_PT,
                BLACK,
            )?;
            for (k, row) in panel.rows.iter().enumerate() {
                let (yt, yb) = (t + row_h * k as f64 + 0.8, t + row_h * (k + 1) as f64 - 0.8);
                let mut pts: Vec<(f64, Option<f64>)> =
                    row.iter().copied().filter(|q| q.0 > 0.0).collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                // repeated x (several h at one N_H): the largest value
                pts.dedup_by(|b, a| {
                    if a.0 == b.0 {
                        a.1 = match (a.1, b.1) {
                            (Some(p), Some(q)) => Some(p.max(q)),
                            (p, q) => p.or(q),
                        };
                        true
                    } else {
                        false
                    }
                });
                for (j, &(x, v)) in pts.iter().enumerate() {
                    let lx = if j == 0 {
                        x / 1.08
                    } else {
                        (x * pts[j - 1].0).sqrt()
                    };
                    let rx = if j + 1 == pts.len() {
                        x * 1.08
                    } else {
                        (x * pts[j + 1].0).sqrt()
                    };
                    let color = match v {
                        None => MISSING,
                        Some(v) => log_level(v, vmax, stable_below).map_or(WHITE, ramp),
                    };
                    let (a, b) = (frame.map(lx, 0.0).0, frame.map(rx, 0.0).0);
                    fill_rect(&root, (a - 0.05, yt, b + 0.05, yb), color)?;
                }
                if c == 0 {
                    text_at(
                        &root,
                        &labels[k],
                        (l - 3.0, (yt + yb) / 2.0),
                        TICK_PT,
                        (HPos::Right, VPos::Center),
                        false,
                    )?;
                }
                if k > 0 {
                    stroke(
                        &root,
                        &[
                            (l, t + row_h * k as f64),
                            (l + panel_w, t + row_h * k as f64),
                        ],
                        RGBColor(225, 225, 225),
                        FRAME_LINE_PT,
                    )?;
                }
            }
            frame.draw(&root, x_desc, "", None)?;
        }
        // the colour bar: two decades below the maximum, log
        let bl = page - bar_room + 8.0;
        let (bt, bh) = (
            PAD + LABEL_PT * 1.5,
            (box_h * prow as f64).max(box_h).min(200.0),
        );
        let lo = vmax * 1e-2;
        let (maj, _) = Scale::log(lo, vmax).ticks(4);
        let marks: Vec<(f64, String)> = maj
            .into_iter()
            .map(|(v, label)| {
                (
                    (v.log10() - lo.log10()) / (vmax.log10() - lo.log10()),
                    label,
                )
            })
            .collect();
        colour_bar(
            &root,
            (bl, bt, bar_w, bh),
            |t| ramp(LEVEL_MIN + (1.0 - LEVEL_MIN) * t),
            &marks,
        )?;
        for (k, line) in ["white:", "stable"].iter().enumerate() {
            text_at(
                &root,
                line,
                (bl, bt + bh + 2.0 + NOTE_PT * 1.2 * k as f64),
                NOTE_PT,
                (HPos::Left, VPos::Top),
                false,
            )?;
        }
        text_at(
            &root,
            z_desc,
            (page - PAD - LABEL_PT, bt + bh / 2.0),
            LABEL_PT,
            (HPos::Center, VPos::Top),
            true,
        )?;
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_is_white_at_zero_and_darkens() {
        assert_eq!(ramp(0.0), RGBColor(255, 255, 255));
        let lum = |c: RGBColor| 0.299 * c.0 as f64 + 0.587 * c.1 as f64 + 0.114 * c.2 as f64;
        let mut last = f64::INFINITY;
        for k in 0..=20 {
            let l = lum(ramp(k as f64 / 20.0));
            assert!(l < last + 1e-9, "lightness must fall monotonically");
            last = l;
        }
        assert_eq!(ramp(f64::NAN), ramp(0.0));
    }
}
