//! Line plots: several curves against one abscissa, every curve in its own [`Style`], legend
//! outside the data, automatic vertical range ([`auto_range`]), clipping marked, coinciding
//! curves named.

use super::axes::{Frame, Scale, auto_range, bottom_margin, clip_polyline};
use super::print::{
    FRAME_LINE_PT, LEGEND_LINE, LEGEND_PT, NOTE_LINE, NOTE_PT, PAD, SAMPLE_W, TICK_PT, TITLE_PT,
    Width, page_pt,
};
use super::style::{
    Dash, GREY, Names, Style, draw_line, draw_marker, draw_sample, fill_polygon, fill_rect, group,
    outline, panel_styles, plot_err, series_style, stroke, text, text_at, text_width, wrap,
};
use crate::error::{Error, Result};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// One curve of a line plot.
#[derive(Clone, Debug)]
pub struct Curve {
    /// Legend label.
    pub label: String,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates (a non-finite value leaves a gap).
    pub y: Vec<f64>,
    /// Dashed (a reference, prediction or continuum curve) rather than solid.
    pub dashed: bool,
}

/// Two curves coincide when their abscissae are equal and their ordinates differ by at most
/// this fraction of the plotted vertical range everywhere.
pub const COINCIDE_TOL: f64 = 2e-3;
/// Markers per curve (every point when the curve has fewer than twice as many points).
pub const MARKERS_PER_CURVE: usize = 10;

/// A line plot; [`LinePlot::svg`] draws it.
#[derive(Clone, Debug, Default)]
pub struct LinePlot {
    /// Title (wrapped to the figure width; empty: none, as in figures whose caption is set
    /// by the paper).
    pub title: String,
    /// Abscissa description with unit.
    pub x_desc: String,
    /// Ordinate description with unit.
    pub y_desc: String,
    /// Curves, styled by meaning ([`curve_styles`]).
    pub curves: Vec<Curve>,
    /// Fixed vertical range (None: [`auto_range`] over the points within the horizontal
    /// range); curves leaving it are marked as clipped.
    pub y_range: Option<(f64, f64)>,
    /// Fixed horizontal range (None: the data's); curves are clipped to it.
    pub x_range: Option<(f64, f64)>,
    /// Draw the line y = 0 and keep 0 inside the automatic range.
    pub zero_line: bool,
    /// Named abscissae (e.g. Γ, X, M of a dispersion path): tick labels instead of numbers,
    /// with a vertical line at each.
    pub x_ticks: Option<Vec<(f64, String)>>,
    /// A shaded abscissa interval with its legend label (e.g. a fit window).
    pub band: Option<(f64, f64, String)>,
    /// Marked abscissae (e.g. cut-off wave numbers): a dotted vertical line at each, its label
    /// above the data box (staggered into rows where labels would overlap); the numeric ticks
    /// stay.
    pub x_marks: Vec<(f64, String)>,
    /// Caption lines under the plot.
    pub notes: Vec<String>,
    /// Printed width: 170 mm with the legend right of the data (default), 85 mm with the
    /// legend under it.
    pub width: Width,
    /// The form, kernel and integrator names whose series have one style in every figure
    /// ([`Names`]; the default: none).
    pub names: Names,
    /// Logarithmic vertical axis (decades labelled; values ≤ 0 leave gaps); `y_range` is then
    /// in data units too.
    pub y_log: bool,
}

/// Styles of the curves of a line plot, by meaning ([`panel_styles`]: a curve labelled by a
/// form, kernel, integrator or reference name has that name's style in every figure; the others
/// take the remaining colours), dashed curves dashed. The legend draws its samples with these
/// same styles.
pub fn curve_styles(curves: &[Curve], names: &Names) -> Vec<Style> {
    let labels: Vec<&str> = curves.iter().map(|c| c.label.as_str()).collect();
    let dashed: Vec<bool> = curves.iter().map(|c| c.dashed).collect();
    panel_styles(&labels, &dashed, names)
}

/// A legend entry: sample style, label and an optional note (coincidence, clipping).
#[derive(Clone, Debug, PartialEq)]
pub struct LegendEntry {
    /// Style of the sample (that of the series).
    pub style: Style,
    /// Label.
    pub label: String,
    /// Second line, smaller.
    pub note: Option<String>,
}

/// What the plot of `curves` shows at vertical range `(lo, hi)`: the legend entries (style =
/// the series' style; notes name coinciding curves and where a curve is clipped).
pub fn legend_entries(curves: &[Curve], lo: f64, hi: f64, names: &Names) -> Vec<LegendEntry> {
    let tol = COINCIDE_TOL * (hi - lo);
    let styles = curve_styles(curves, names);
    curves
        .iter()
        .enumerate()
        .map(|(j, c)| {
            let mut notes = Vec::new();
            if let Some(i) = (0..j).find(|&i| coincide(&curves[i], c, tol)) {
                notes.push(format!("coincides with “{}”", curves[i].label));
            }
            let fin = c.y.iter().copied().filter(|v| v.is_finite());
            let (a, b) = fin.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(v), b.max(v))
            });
            if b > hi {
                notes.push(format!("clipped ▲: reaches {}", sig(b)));
            }
            if a < lo {
                notes.push(format!("clipped ▼: reaches {}", sig(a)));
            }
            LegendEntry {
                style: styles[j],
                label: c.label.clone(),
                note: (!notes.is_empty()).then(|| notes.join("; ")),
            }
        })
        .collect()
}

fn sig(v: f64) -> String {
    if v.abs() >= 1e4 || (v != 0.0 && v.abs() < 1e-3) {
        format!("{v:.3e}")
    } else {
        format!("{v:.4}")
    }
    .replace('-', "−")
}

fn coincide(a: &Curve, b: &Curve, tol: f64) -> bool {
    a.x.len() == b.x.len()
        && !a.x.is_empty()
        && a.x
            .iter()
            .zip(&b.x)
            .all(|(p, q)| (p - q).abs() <= 1e-12 * (1.0 + p.abs()))
        && a.y.iter().zip(&b.y).all(|(p, q)| {
            (p.is_finite() && q.is_finite() && (p - q).abs() <= tol)
                || (!p.is_finite() && !q.is_finite())
        })
}

impl LinePlot {
    /// A plot of `curves` with automatic range, no zero line, no extras.
    pub fn new(title: &str, x_desc: &str, y_desc: &str, curves: Vec<Curve>) -> Self {
        Self {
            title: title.into(),
            x_desc: x_desc.into(),
            y_desc: y_desc.into(),
            curves,
            ..Self::default()
        }
    }

    /// The vertical range drawn (with 4 % padding when automatic), in axis units: log10 of
    /// the data on a log axis.
    pub fn y_limits(&self) -> (f64, f64) {
        self.limits_of(&self.axis_curves())
    }

    /// The curves in axis units: log10 of the ordinates on a log axis (gaps at values ≤ 0).
    fn axis_curves(&self) -> Vec<Curve> {
        if !self.y_log {
            return self.curves.clone();
        }
        self.curves
            .iter()
            .map(|c| Curve {
                y: c.y
                    .iter()
                    .map(|&v| if v > 0.0 { v.log10() } else { f64::NAN })
                    .collect(),
                ..c.clone()
            })
            .collect()
    }

    fn limits_of(&self, curves: &[Curve]) -> (f64, f64) {
        if let Some((a, b)) = self.y_range {
            return if self.y_log {
                (a.log10(), b.log10())
            } else {
                (a, b)
            };
        }
        let inside: Vec<Vec<f64>> = curves
            .iter()
            .map(|c| {
                c.x.iter()
                    .zip(&c.y)
                    .filter(|(x, _)| self.x_range.is_none_or(|(a, b)| (a..=b).contains(*x)))
                    .map(|(_, y)| *y)
                    .collect()
            })
            .collect();
        let ys: Vec<&[f64]> = inside.iter().map(Vec::as_slice).collect();
        let r = auto_range(&ys, self.zero_line && !self.y_log);
        let pad = 0.04 * (r.hi - r.lo);
        (r.lo - pad, r.hi + pad)
    }

    /// Renders the plot to an SVG string, laid out in points at its printed [`Width`]:
    /// the title (if any) above the data box, the legend right of it (170 mm) or under it
    /// (85 mm), notes under everything.
    pub fn svg(&self) -> Result<String> {
        let xs = self
            .curves
            .iter()
            .flat_map(|c| c.x.iter().copied())
            .chain(self.band.iter().flat_map(|b| [b.0, b.1]))
            .chain(self.x_marks.iter().map(|m| m.0))
            .filter(|x| x.is_finite());
        let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        if !(x0.is_finite() && x1 > x0) {
            return Err(Error::Incompatible(
                "nothing to plot: no finite abscissae".into(),
            ));
        }
        // an abscissa starting just above 0 (κ grids in (0, π]) starts at 0
        let x0 = if x0 > 0.0 && x0 < 0.02 * (x1 - x0) {
            0.0
        } else {
            x0
        };
        let (x0, x1) = self.x_range.unwrap_or((x0, x1));
        let axis_curves = self.axis_curves();
        let (lo, hi) = self.limits_of(&axis_curves);
        let entries = legend_entries(&axis_curves, lo, hi, &self.names);
        let y_scale = if self.y_log {
            Scale::Log(lo, hi)
        } else {
            Scale::Linear(lo, hi)
        };
        let page = page_pt(self.width);
        let right = self.width == Width::Double;
        // the legend: a column right of the box (170 mm) or a block under it (85 mm)
        let max_chars = if right {
            LEGEND_CHARS
        } else {
            ((page - 2.0 * PAD - SAMPLE_W - 4.0) / (0.6 * LEGEND_PT)) as usize
        };
        let longest = entries
            .iter()
            .map(|e| {
                let note = e.note.as_ref().map_or(0, |n| {
                    (n.chars().count() as f64 * NOTE_PT / LEGEND_PT).ceil() as usize
                });
                e.label.chars().count().max(note)
            })
            .chain(self.band.iter().map(|b| b.2.chars().count()))
            .max()
            .unwrap_or(10)
            .min(max_chars);
        let text_w = text_width(&"x".repeat(longest), LEGEND_PT);
        let legend_w = SAMPLE_W + 4.0 + text_w + 2.0 * PAD;
        let label_chars = ((legend_w - SAMPLE_W - 4.0 - 2.0 * PAD) / (0.6 * LEGEND_PT)) as usize;
        let note_chars = ((legend_w - SAMPLE_W - 4.0 - 2.0 * PAD) / (0.6 * NOTE_PT)) as usize;
        let mut lh = PAD;
        for e in &entries {
            lh += LEGEND_LINE * wrap(&e.label, label_chars).len() as f64;
            if let Some(n) = &e.note {
                lh += NOTE_LINE * wrap(n, note_chars).len() as f64;
            }
            lh += 1.5;
        }
        if self.band.is_some() {
            lh += LEGEND_LINE + 1.5;
        }
        lh += PAD - 1.5;
        let title = if self.title.is_empty() {
            Vec::new()
        } else {
            wrap(
                &self.title,
                ((page - 2.0 * PAD) / (0.6 * TITLE_PT)) as usize,
            )
        };
        let top0 = PAD + TITLE_PT * 1.25 * title.len() as f64;
        // mark labels: one row above the box, a further row wherever two would overlap
        let box_w0 = if right {
            page - legend_w - 3.0 * PAD - 45.0
        } else {
            page - 2.0 * PAD - 45.0
        };
        let box_h = (box_w0 * if right { 0.62 } else { 0.72 }).clamp(110.0, 230.0);
        let left = PAD + Frame::left_margin(y_scale, box_h, &self.y_desc);
        // room right of the box for half a tick label
        let box_w = if right {
            page - left - legend_w - 2.0 * PAD - 6.0
        } else {
            page - left - PAD - 6.0
        };
        let map_x = |v: f64| left + (v - x0) / (x1 - x0) * box_w;
        let mut rows_end: Vec<f64> = Vec::new();
        let mut marks: Vec<(f64, f64, &str, usize)> = Vec::new();
        let mut sorted: Vec<&(f64, String)> = self.x_marks.iter().collect();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (v, label) in sorted {
            let w = text_width(label, TICK_PT);
            // a label stays on the page
            let px = map_x(*v).clamp(PAD + w / 2.0, page - PAD - w / 2.0);
            let row = rows_end
                .iter()
                .position(|&end| px - w / 2.0 > end + 3.0)
                .unwrap_or(rows_end.len());
            if row == rows_end.len() {
                rows_end.push(f64::NEG_INFINITY);
            }
            rows_end[row] = px + w / 2.0;
            marks.push((map_x(*v), px, label, row));
        }
        let mark_row = TICK_PT * 1.25;
        let top = top0 + mark_row * rows_end.len() as f64 + TICK_PT * 0.6;
        let bottom = top + box_h;
        let frame = Frame {
            rect: (left, top, left + box_w, bottom),
            x: Scale::Linear(x0, x1),
            y: y_scale,
            grid: true,
        };
        let under = bottom + bottom_margin(&self.x_desc, box_w);
        let legend_at = if right {
            (page - PAD - legend_w, top)
        } else {
            (PAD, under + 2.0)
        };
        let after_legend = if right { under } else { legend_at.1 + lh };
        let notes: Vec<String> = self
            .notes
            .iter()
            .flat_map(|n| wrap(n, ((page - 2.0 * PAD) / (0.6 * NOTE_PT)) as usize))
            .collect();
        let notes_top = after_legend.max(if right { top + lh } else { 0.0 }) + 2.0;
        let height = notes_top + NOTE_LINE * notes.len() as f64 + PAD;
        let mut svg = String::new();
        {
            let root = super::canvas::Canvas::new(&mut svg, self.width, (page, height))
                .into_drawing_area();
            root.fill(&WHITE).map_err(plot_err)?;
            for (k, line) in title.iter().enumerate() {
                text(
                    &root,
                    line,
                    (PAD, PAD + TITLE_PT * 1.25 * k as f64),
                    TITLE_PT,
                    BLACK,
                )?;
            }
            let (l, t, r, b) = frame.rect;
            if let Some((a, c, _)) = &self.band {
                let (pa, pc) = (frame.map(*a, 1.0).0, frame.map(*c, 1.0).0);
                fill_rect(&root, (pa.max(l), t, pc.min(r), b), BAND)?;
            }
            frame.draw(&root, &self.x_desc, &self.y_desc, self.x_ticks.as_deref())?;
            for &(mx, px, label, row) in &marks {
                let dots = Style {
                    color: GREY,
                    dash: Dash::Dotted,
                    width: FRAME_LINE_PT,
                    ..series_style(0, Dash::Dotted)
                };
                draw_line(&root, &[(mx, t), (mx, b)], &dots)?;
                text_at(
                    &root,
                    label,
                    (px, top0 + mark_row * (rows_end.len() - 1 - row) as f64),
                    TICK_PT,
                    (HPos::Center, VPos::Top),
                    false,
                )?;
            }
            if self.zero_line && !self.y_log && lo < 0.0 && hi > 0.0 {
                let y = frame.map(x0, 0.0).1;
                stroke(&root, &[(l, y), (r, y)], GREY, FRAME_LINE_PT)?;
            }
            let n = self.curves.len();
            for (i, (c, e)) in self.curves.iter().zip(&entries).enumerate() {
                let pts: Vec<(f64, f64)> =
                    c.x.iter()
                        .zip(&c.y)
                        .map(|(&x, &y)| {
                            if x.is_finite() && y_scale.accepts(y) {
                                frame.map(x, y)
                            } else {
                                (f64::NAN, f64::NAN)
                            }
                        })
                        .collect();
                let pieces = clip_polyline(&pts, frame.rect);
                for p in &pieces {
                    draw_line(&root, p, &e.style)?;
                }
                // clipping marks where a piece ends on the top or bottom edge
                for p in &pieces {
                    for q in [p[0], p[p.len() - 1]] {
                        let edge = if (q.1 - t).abs() < 0.05 {
                            Some(-1.0)
                        } else if (q.1 - b).abs() < 0.05 {
                            Some(1.0)
                        } else {
                            None
                        };
                        if let Some(s) = edge {
                            // an arrowhead inside the box pointing out through the edge
                            let base = q.1 - s * 4.0;
                            fill_polygon(
                                &root,
                                &[q, (q.0 - 2.2, base), (q.0 + 2.2, base)],
                                e.style.color,
                            )?;
                        }
                    }
                }
                // markers, shifted per curve so coinciding curves show both
                let np = pts.len();
                let idx: Vec<usize> = if np < 2 * MARKERS_PER_CURVE {
                    (0..np).collect()
                } else {
                    (0..MARKERS_PER_CURVE)
                        .map(|k| {
                            let f =
                                (k as f64 + (i as f64 + 0.5) / n as f64) / MARKERS_PER_CURVE as f64;
                            ((f * (np - 1) as f64).round() as usize).min(np - 1)
                        })
                        .collect()
                };
                for k in idx {
                    let p = pts[k];
                    if p.0.is_finite() && frame.contains(p, 0.05) {
                        draw_marker(&root, p, &e.style)?;
                    }
                }
            }
            // the legend, outside the data
            group(&root, Some("legend"))?;
            let (lx, ly) = legend_at;
            outline(&root, (lx, ly, lx + legend_w, ly + lh), GREY, FRAME_LINE_PT)?;
            let tx = lx + PAD + SAMPLE_W + 4.0;
            let mut y = ly + PAD;
            for e in &entries {
                draw_sample(
                    &root,
                    (lx + PAD, y + LEGEND_PT * 0.55),
                    SAMPLE_W,
                    &e.style,
                    true,
                    true,
                )?;
                for line in wrap(&e.label, label_chars) {
                    text(&root, &line, (tx, y), LEGEND_PT, BLACK)?;
                    y += LEGEND_LINE;
                }
                if let Some(nt) = &e.note {
                    for line in wrap(nt, note_chars) {
                        text(&root, &line, (tx, y), NOTE_PT, GREY)?;
                        y += NOTE_LINE;
                    }
                }
                y += 1.5;
            }
            if let Some((_, _, label)) = &self.band {
                fill_rect(
                    &root,
                    (lx + PAD, y + 0.5, lx + PAD + SAMPLE_W, y + LEGEND_PT),
                    BAND,
                )?;
                text(&root, label, (tx, y), LEGEND_PT, BLACK)?;
            }
            group(&root, None)?;
            for (k, line) in notes.iter().enumerate() {
                text(
                    &root,
                    line,
                    (PAD, notes_top + NOTE_LINE * k as f64),
                    NOTE_PT,
                    GREY,
                )?;
            }
            root.present().map_err(plot_err)?;
        }
        Ok(svg)
    }
}

/// Fill of a shaded abscissa band (and of its legend sample).
const BAND: RGBColor = RGBColor(228, 228, 228);
/// Longest legend line of a 170 mm plot, characters (longer labels wrap).
const LEGEND_CHARS: usize = 34;

/// A line plot of several curves (automatic range when `y_range` is None) with a zero line.
pub fn lines_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    curves: &[Curve],
    y_range: Option<(f64, f64)>,
) -> Result<String> {
    LinePlot {
        y_range,
        zero_line: true,
        ..LinePlot::new(title, x_desc, y_desc, curves.to_vec())
    }
    .svg()
}

/// Abscissa description of every 1D dispersion plot.
pub const KAPPA_DESC: &str = "wave number κΔx/π (1: the cut-off κ = π/Δx)";
/// Ordinate description of every dispersion plot.
pub const OMEGA2_DESC: &str = "squared frequency ω²Δx²/c² (< 0: growth)";

/// Axis description of every damping plot.
pub const DAMPING_DESC: &str = "damping rate Re s Δx/c (< 0: damped)";

/// The plot of damping curves Re s(x) of branches with labels (a null, an ambiguous
/// matching, leaves a gap); `x_ticks` names abscissae (symmetry points of a path).
pub fn damping_plot(
    title: &str,
    x_desc: &str,
    x: &[f64],
    branches: &[(String, Vec<Option<f64>>)],
    x_ticks: Option<Vec<(f64, String)>>,
) -> LinePlot {
    let curves: Vec<Curve> = branches
        .iter()
        .map(|(label, y)| Curve {
            label: label.clone(),
            x: x.to_vec(),
            y: y.iter().map(|v| v.unwrap_or(f64::NAN)).collect(),
            dashed: false,
        })
        .collect();
    LinePlot {
        zero_line: true,
        x_ticks,
        notes: vec![
            "Gaps: the eigenvalue-to-branch matching is ambiguous there (overdamped or at Γ)."
                .into(),
        ],
        ..LinePlot::new(title, x_desc, DAMPING_DESC, curves)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve(label: &str, y: Vec<f64>, dashed: bool) -> Curve {
        Curve {
            label: label.into(),
            x: (0..y.len()).map(|i| i as f64).collect(),
            y,
            dashed,
        }
    }

    #[test]
    fn legend_samples_carry_the_series_style() {
        let cs = vec![
            curve("a", vec![0.0, 1.0, 2.0], false),
            curve("b", vec![0.0, 2.0, 1.0], true),
        ];
        let e = legend_entries(&cs, -1.0, 3.0, &Names::default());
        for (e, s) in e.iter().zip(curve_styles(&cs, &Names::default())) {
            assert_eq!(e.style, s);
        }
        assert_eq!(e[1].style.dash, Dash::Dashed);
        assert_eq!(e[0].style.dash, Dash::Solid);
        assert_ne!(e[0].style.color, e[1].style.color);
        assert_ne!(e[0].style.marker, e[1].style.marker);
    }

    #[test]
    fn coinciding_and_clipped_curves_are_named() {
        let cs = vec![
            curve("engine", vec![0.0, 1.0, 2.0], false),
            curve("paper", vec![0.0, 1.0 + 1e-6, 2.0], true),
            curve("far", vec![0.0, 50.0, 1e6], false),
        ];
        let p = LinePlot::new("t", "x", "y", cs.clone());
        let (lo, hi) = p.y_limits();
        assert!(hi < 10.0 && lo < 0.0, "{lo} {hi}");
        let e = legend_entries(&cs, lo, hi, &Names::default());
        assert!(e[0].note.is_none());
        assert!(
            e[1].note
                .as_deref()
                .unwrap()
                .contains("coincides with “engine”")
        );
        assert!(e[2].note.as_deref().unwrap().contains("clipped ▲"));
        let svg = p.svg().unwrap();
        assert!(svg.contains("coincides with “engine”") && svg.contains("clipped ▲"));
    }

    #[test]
    fn x_marks_are_labelled_above_the_box_in_rows_that_do_not_overlap() {
        let cs = vec![curve("a", vec![0.0, 1.0, 2.0, 1.0, 0.0], false)];
        let height = |marks: Vec<(f64, String)>| {
            let svg = LinePlot {
                x_marks: marks,
                ..LinePlot::new("t", "x", "y", cs.clone())
            }
            .svg()
            .unwrap();
            crate::plot::svg_size(&svg).unwrap().1
        };
        let none = height(Vec::new());
        let one = height(vec![(1.0, "cut-off A".into())]);
        let far = height(vec![(1.0, "cut-off A".into()), (3.0, "cut-off B".into())]);
        let close = height(vec![(1.0, "cut-off A".into()), (1.05, "cut-off B".into())]);
        // one row per overlap
        assert!(one > none);
        assert!((far - one).abs() < 1e-9);
        assert!(
            ((close - one) - (one - none)).abs() < 0.02,
            "{none} {one} {close}"
        );
        let svg = LinePlot {
            x_marks: vec![(5.0, "beyond the data".into())],
            ..LinePlot::new("t", "x", "y", cs.clone())
        }
        .svg()
        .unwrap();
        assert!(svg.contains("beyond the data"));
    }
}
