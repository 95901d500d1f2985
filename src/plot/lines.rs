//! Line plots: several curves against one abscissa, every curve in its own [`Style`], legend
//! outside the data, automatic vertical range ([`auto_range`]), clipping marked, coinciding
//! curves named.

use super::axes::{Frame, Scale, auto_range, clip_polyline};
use super::style::{
    Dash, GREY, Style, draw_line, draw_marker, draw_sample, plot_err, series_style, text,
    text_width, wrap,
};
use crate::error::{Error, Result};
use plotters::prelude::*;

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
    /// Title (wrapped to the figure width).
    pub title: String,
    /// Abscissa description with unit.
    pub x_desc: String,
    /// Ordinate description with unit.
    pub y_desc: String,
    /// Curves, styled by index ([`curve_style`]).
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
}

/// Style of curve `i` of a line plot: [`series_style`] with a dashed line for dashed curves.
/// The legend draws its sample with this same style.
pub fn curve_style(i: usize, c: &Curve) -> Style {
    series_style(i, if c.dashed { Dash::Dashed } else { Dash::Solid })
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
pub fn legend_entries(curves: &[Curve], lo: f64, hi: f64) -> Vec<LegendEntry> {
    let tol = COINCIDE_TOL * (hi - lo);
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
                style: curve_style(j, c),
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

/// Plot width (pixels) of the data box.
const BOX_W: f64 = 700.0;
/// Plot height (pixels) of the data box.
const BOX_H: f64 = 440.0;

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

    /// The vertical range drawn (with 4 % padding when automatic).
    pub fn y_limits(&self) -> (f64, f64) {
        if let Some(r) = self.y_range {
            return r;
        }
        let inside: Vec<Vec<f64>> = self
            .curves
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
        let r = auto_range(&ys, self.zero_line);
        let pad = 0.04 * (r.hi - r.lo);
        (r.lo - pad, r.hi + pad)
    }

    /// Renders the plot to an SVG string.
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
        let (lo, hi) = self.y_limits();
        let entries = legend_entries(&self.curves, lo, hi);
        // legend column width from its longest label (wrapped beyond 46 characters)
        let longest = entries
            .iter()
            .map(|e| {
                let note = e.note.as_ref().map_or(0, |n| n.chars().count() * 11 / 13);
                e.label.chars().count().max(note)
            })
            .chain(self.band.iter().map(|b| b.2.chars().count()))
            .max()
            .unwrap_or(10)
            .min(46);
        let legend_w = 60.0 + text_width(&"x".repeat(longest), 13);
        let left = 95.0;
        let width = left + BOX_W + 25.0 + legend_w + 15.0;
        let title = wrap(&self.title, ((width - 40.0) / (0.56 * 18.0)) as usize);
        let top0 = 18.0 + 23.0 * title.len() as f64 + 8.0;
        // mark labels: one row above the box, a further row wherever two would overlap
        let map_x = |v: f64| left + (v - x0) / (x1 - x0) * BOX_W;
        let mut rows_end: Vec<f64> = Vec::new();
        let mut marks: Vec<(f64, &str, usize)> = Vec::new();
        let mut sorted: Vec<&(f64, String)> = self.x_marks.iter().collect();
        sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
        for (v, label) in sorted {
            let (px, w) = (map_x(*v), text_width(label, 12));
            let row = rows_end
                .iter()
                .position(|&end| px - w / 2.0 > end + 6.0)
                .unwrap_or(rows_end.len());
            if row == rows_end.len() {
                rows_end.push(0.0);
            }
            rows_end[row] = px + w / 2.0;
            marks.push((px, label, row));
        }
        let top = top0 + 16.0 * rows_end.len() as f64;
        let bottom = top + BOX_H;
        let frame = Frame {
            rect: (left, top, left + BOX_W, bottom),
            x: Scale::Linear(x0, x1),
            y: Scale::Linear(lo, hi),
            grid: true,
        };
        let note_chars = ((width - 40.0) / (0.56 * 13.0)) as usize;
        let notes: Vec<String> = self
            .notes
            .iter()
            .flat_map(|n| wrap(n, note_chars))
            .collect();
        let mut height = bottom + 62.0 + 18.0 * notes.len() as f64;
        // legend height
        let label_chars = ((legend_w - 55.0) / (0.56 * 13.0)) as usize;
        let note_chars_l = ((legend_w - 55.0) / (0.56 * 11.0)) as usize;
        let mut lh = 0.0;
        for e in &entries {
            lh += 17.0 * wrap(&e.label, label_chars).len() as f64 + 5.0;
            if let Some(n) = &e.note {
                lh += 14.0 * wrap(n, note_chars_l).len() as f64;
            }
        }
        if self.band.is_some() {
            lh += 22.0;
        }
        height = height.max(top + lh + 20.0);
        let mut svg = String::new();
        {
            let root =
                super::canvas::Canvas::new(&mut svg, super::print::Width::Double, (width, height))
                    .into_drawing_area();
            root.fill(&WHITE).map_err(plot_err)?;
            for (k, line) in title.iter().enumerate() {
                super::style::text_at(
                    &root,
                    line,
                    (width / 2.0, 12.0 + 23.0 * k as f64),
                    18,
                    (
                        plotters::style::text_anchor::HPos::Center,
                        plotters::style::text_anchor::VPos::Top,
                    ),
                    false,
                )?;
            }
            let (l, t, r, b) = frame.rect;
            if let Some((a, c, _)) = &self.band {
                let (pa, pc) = (frame.map(*a, lo).0, frame.map(*c, lo).0);
                root.draw(&Rectangle::new(
                    [(pa.max(l) as i32, t as i32), (pc.min(r) as i32, b as i32)],
                    RGBColor(235, 235, 235).filled(),
                ))
                .map_err(plot_err)?;
            }
            draw_frame(
                &root,
                &frame,
                &self.x_desc,
                &self.y_desc,
                self.x_ticks.as_deref(),
            )?;
            for &(px, label, row) in &marks {
                let dots = Style {
                    color: GREY,
                    dash: Dash::Dotted,
                    width: 1,
                    ..series_style(0, Dash::Dotted)
                };
                draw_line(&root, &[(px, t), (px, b)], &dots)?;
                super::style::text_at(
                    &root,
                    label,
                    (px, top0 + 16.0 * (rows_end.len() - 1 - row) as f64),
                    12,
                    (
                        plotters::style::text_anchor::HPos::Center,
                        plotters::style::text_anchor::VPos::Top,
                    ),
                    false,
                )?;
            }
            if self.zero_line && lo < 0.0 && hi > 0.0 {
                let y = frame.map(x0, 0.0).1;
                root.draw(&PathElement::new(
                    [(l as i32, y.round() as i32), (r as i32, y.round() as i32)],
                    GREY.stroke_width(1),
                ))
                .map_err(plot_err)?;
            }
            let n = self.curves.len();
            for (i, (c, e)) in self.curves.iter().zip(&entries).enumerate() {
                let pts: Vec<(f64, f64)> =
                    c.x.iter()
                        .zip(&c.y)
                        .map(|(&x, &y)| {
                            if x.is_finite() && y.is_finite() {
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
                        let edge = if (q.1 - t).abs() < 0.5 {
                            Some(-1.0)
                        } else if (q.1 - b).abs() < 0.5 {
                            Some(1.0)
                        } else {
                            None
                        };
                        if let Some(s) = edge {
                            // an arrowhead inside the box pointing out through the edge
                            let base = (q.1 - s * 9.0).round() as i32;
                            let (ax, ay) = (q.0.round() as i32, q.1.round() as i32);
                            root.draw(&Polygon::new(
                                vec![(ax, ay), (ax - 5, base), (ax + 5, base)],
                                e.style.color.filled(),
                            ))
                            .map_err(plot_err)?;
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
                    if p.0.is_finite() && frame.contains(p, 0.5) {
                        draw_marker(&root, p, &e.style)?;
                    }
                }
            }
            // legend column, outside the data
            let lx = r + 25.0;
            let mut y = t + 4.0;
            root.draw(&Rectangle::new(
                [
                    ((lx - 8.0) as i32, (t - 2.0) as i32),
                    ((lx + legend_w) as i32, (t + lh + 6.0) as i32),
                ],
                GREY.stroke_width(1),
            ))
            .map_err(plot_err)?;
            for e in &entries {
                draw_sample(&root, (lx, y + 7.0), 36.0, &e.style, true, true)?;
                for line in wrap(&e.label, label_chars) {
                    text(&root, &line, (lx + 44.0, y), 13, BLACK)?;
                    y += 17.0;
                }
                if let Some(nt) = &e.note {
                    for line in wrap(nt, note_chars_l) {
                        text(&root, &line, (lx + 44.0, y), 11, GREY)?;
                        y += 14.0;
                    }
                }
                y += 5.0;
            }
            if let Some((_, _, label)) = &self.band {
                root.draw(&Rectangle::new(
                    [
                        (lx as i32, (y + 1.0) as i32),
                        ((lx + 36.0) as i32, (y + 13.0) as i32),
                    ],
                    RGBColor(225, 225, 225).filled(),
                ))
                .map_err(plot_err)?;
                text(&root, label, (lx + 44.0, y), 13, BLACK)?;
            }
            for (k, line) in notes.iter().enumerate() {
                text(
                    &root,
                    line,
                    (20.0, bottom + 58.0 + 18.0 * k as f64),
                    13,
                    GREY,
                )?;
            }
            root.present().map_err(plot_err)?;
        }
        super::print::finish(&svg, super::print::Width::Double)
    }
}

/// The frame of a line plot, with named abscissae when given (vertical lines at each).
fn draw_frame(
    area: &DrawingArea<super::canvas::Canvas<'_>, plotters::coord::Shift>,
    frame: &Frame,
    x_desc: &str,
    y_desc: &str,
    named: Option<&[(f64, String)]>,
) -> Result<()> {
    frame.draw(area, x_desc, y_desc, named)
}

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
pub const KAPPA_DESC: &str = "wave number κΔx/π (dimensionless; 1 is the cut-off κ = π/Δx)";
/// Ordinate description of every dispersion plot.
pub const OMEGA2_DESC: &str = "ω²Δx²/c² (squared frequency in units of c²/Δx²; < 0: growth)";

/// Axis description of every damping plot.
pub const DAMPING_DESC: &str = "Re s Δx/c (damping rate in units of c/Δx; < 0: damped)";

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
        let e = legend_entries(&cs, -1.0, 3.0);
        for (i, (c, e)) in cs.iter().zip(&e).enumerate() {
            assert_eq!(e.style, curve_style(i, c));
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
        let e = legend_entries(&cs, lo, hi);
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
        // one row of 16 layout px each, drawn at the canvas zoom
        assert!(one > none);
        assert_eq!(far, one);
        assert!(
            (close - one).abs_diff(one - none) <= 1,
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
