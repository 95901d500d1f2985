//! Scatter plots on log–log axes (the trade-off Pareto figure, the integrator panels) and
//! multi-panel line figures (the pairing study), in the shared styles.

use super::axes::{Frame, Scale};
use super::style::{
    Dash, GREY, Style, draw_line, draw_marker, draw_sample, plot_err, series_style, text, text_at,
    text_width, wrap,
};
use crate::error::{Error, Result};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

fn title_lines(
    root: &DrawingArea<super::canvas::Canvas<'_>, plotters::coord::Shift>,
    title: &str,
    width: f64,
) -> Result<f64> {
    let lines = wrap(title, ((width - 40.0) / (0.56 * 18.0)) as usize);
    for (k, line) in lines.iter().enumerate() {
        text_at(
            root,
            line,
            (width / 2.0, 10.0 + 23.0 * k as f64),
            18,
            (HPos::Center, VPos::Top),
            false,
        )?;
    }
    Ok(16.0 + 23.0 * lines.len() as f64)
}

fn title_height(title: &str, width: f64) -> f64 {
    16.0 + 23.0 * wrap(title, ((width - 40.0) / (0.56 * 18.0)) as usize).len() as f64
}

/// Style of group `g` of a scatter figure: [`series_style`] (colour and marker shape per group).
pub fn group_style(g: usize) -> Style {
    series_style(g, Dash::Solid)
}

/// Style of the Pareto front line (and of its legend sample).
pub const FRONT_STYLE: Style = Style {
    color: RGBColor(0, 0, 0),
    dash: Dash::Dashed,
    marker: super::style::Marker::Circle,
    filled: true,
    width: 1,
};

/// A log–log scatter of (group, x, y, filled) points: colour and marker shape per group
/// (legend), filled markers for `filled`, hollow otherwise (`fill_meaning` = the legend text of
/// filled and hollow); the lower-left Pareto front of the filled points is a dashed staircase.
pub fn pareto_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    pts: &[(String, f64, f64, bool)],
    fill_meaning: (&str, &str),
) -> Result<String> {
    let pts: Vec<&(String, f64, f64, bool)> = pts
        .iter()
        .filter(|p| p.1.is_finite() && p.2.is_finite() && p.1 > 0.0 && p.2 > 0.0)
        .collect();
    if pts.is_empty() {
        return Err(Error::Incompatible(
            "nothing to plot: no configuration has both a cost and an error".into(),
        ));
    }
    let mut groups: Vec<&str> = Vec::new();
    for p in &pts {
        if !groups.contains(&p.0.as_str()) {
            groups.push(&p.0);
        }
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for p in &pts {
        x0 = x0.min(p.1);
        x1 = x1.max(p.1);
        y0 = y0.min(p.2);
        y1 = y1.max(p.2);
    }
    let legend_w = 60.0
        + groups
            .iter()
            .map(|g| text_width(g, 13))
            .chain(
                [
                    fill_meaning.0,
                    fill_meaning.1,
                    "Pareto front of the filled points",
                ]
                .map(|s| text_width(s, 13)),
            )
            .fold(0.0f64, f64::max)
            .min(300.0);
    let width = 100.0 + 700.0 + 30.0 + legend_w + 15.0;
    let th = title_height(title, width);
    let frame = Frame {
        rect: (100.0, th + 8.0, 800.0, th + 8.0 + 480.0),
        x: Scale::log(x0 / 1.2, x1 * 1.2),
        y: Scale::log(y0 / 1.5, y1 * 1.5),
        grid: true,
    };
    let height = frame.rect.3 + 65.0;
    let mut svg = String::new();
    {
        let root =
            super::canvas::Canvas::new(&mut svg, super::print::Width::Double, (width, height))
                .into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        title_lines(&root, title, width)?;
        frame.draw(&root, x_desc, y_desc, None)?;
        // Pareto front of the filled points: sorted by cost, running minimum of the error
        let mut front: Vec<(f64, f64)> = pts.iter().filter(|p| p.3).map(|p| (p.1, p.2)).collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut stairs = Vec::new();
        let mut best = f64::INFINITY;
        for (x, y) in front {
            if y < best {
                if best.is_finite() {
                    stairs.push(frame.map(x, best));
                }
                stairs.push(frame.map(x, y));
                best = y;
            }
        }
        if stairs.len() > 1 {
            draw_line(&root, &stairs, &FRONT_STYLE)?;
        }
        // hollow (unstable) first, filled on top
        for filled in [false, true] {
            for (gi, g) in groups.iter().enumerate() {
                let style = Style {
                    filled,
                    ..group_style(gi)
                };
                for p in pts.iter().filter(|p| p.0 == *g && p.3 == filled) {
                    draw_marker(&root, frame.map(p.1, p.2), &style)?;
                }
            }
        }
        let lx = frame.rect.2 + 30.0;
        let mut y = frame.rect.1 + 6.0;
        for (gi, g) in groups.iter().enumerate() {
            draw_sample(&root, (lx, y + 7.0), 30.0, &group_style(gi), false, true)?;
            text(&root, g, (lx + 40.0, y), 13, BLACK)?;
            y += 21.0;
        }
        y += 8.0;
        let black = |filled| Style {
            color: BLACK,
            filled,
            ..group_style(0)
        };
        draw_sample(&root, (lx, y + 7.0), 30.0, &black(true), false, true)?;
        text(&root, fill_meaning.0, (lx + 40.0, y), 13, BLACK)?;
        y += 21.0;
        draw_sample(&root, (lx, y + 7.0), 30.0, &black(false), false, true)?;
        text(&root, fill_meaning.1, (lx + 40.0, y), 13, BLACK)?;
        y += 21.0;
        if stairs.len() > 1 {
            draw_sample(&root, (lx, y + 7.0), 30.0, &FRONT_STYLE, true, false)?;
            text(
                &root,
                "Pareto front of the filled points",
                (lx + 40.0, y),
                13,
                BLACK,
            )?;
            y += 21.0;
        }
        root.draw(&Rectangle::new(
            [
                ((lx - 8.0) as i32, frame.rect.1 as i32),
                ((lx + legend_w) as i32, (y + 4.0) as i32),
            ],
            GREY.stroke_width(1),
        ))
        .map_err(plot_err)?;
        root.present().map_err(plot_err)?;
    }
    super::print::finish(&svg, super::print::Width::Double)
}

/// One curve of a multi-panel figure ([`panels_svg`]); curve i of every panel is drawn in the
/// style of legend entry i.
#[derive(Clone, Debug)]
pub struct PanelCurve {
    /// Abscissae.
    pub x: Vec<f64>,
    /// Ordinates.
    pub y: Vec<f64>,
}

/// One panel of [`panels_svg`].
#[derive(Clone, Debug)]
pub struct Panel {
    /// Panel caption.
    pub title: String,
    /// Curves, indexed like the legend (an empty curve draws nothing).
    pub curves: Vec<PanelCurve>,
}

/// Panel size (pixels).
const PANEL_W: f64 = 400.0;
/// Panel height (pixels).
const PANEL_H: f64 = 330.0;

/// Style of legend entry i of [`panels_svg`]: [`series_style`], dashed from the eighth on.
pub fn panel_style(i: usize) -> Style {
    let s = series_style(i, if i >= 7 { Dash::Dashed } else { Dash::Solid });
    Style { width: 1, ..s }
}

fn legend_column(
    root: &DrawingArea<super::canvas::Canvas<'_>, plotters::coord::Shift>,
    legend: &[String],
    notes: &[Option<String>],
    style: impl Fn(usize) -> Style,
    line: bool,
    (lx, top): (f64, f64),
    w: f64,
) -> Result<()> {
    let mut y = top + 6.0;
    for (i, label) in legend.iter().enumerate() {
        draw_sample(root, (lx, y + 7.0), 36.0, &style(i), line, true)?;
        text(root, label, (lx + 44.0, y), 13, BLACK)?;
        y += 22.0;
        if let Some(Some(n)) = notes.get(i) {
            text(root, n, (lx + 44.0, y - 5.0), 11, GREY)?;
            y += 13.0;
        }
    }
    root.draw(&Rectangle::new(
        [
            ((lx - 8.0) as i32, top as i32),
            ((lx + w) as i32, (y + 4.0) as i32),
        ],
        GREY.stroke_width(1),
    ))
    .map_err(plot_err)?;
    Ok(())
}

/// A panel's title above its frame, then the frame (grid, box, ticks, axis descriptions).
fn draw_panel(
    root: &DrawingArea<super::canvas::Canvas<'_>, plotters::coord::Shift>,
    frame: &Frame,
    title: &str,
    x_desc: &str,
    y_desc: &str,
) -> Result<()> {
    text_at(
        root,
        title,
        ((frame.rect.0 + frame.rect.2) / 2.0, frame.rect.1 - 5.0),
        14,
        (HPos::Center, VPos::Bottom),
        false,
    )?;
    frame.draw(root, x_desc, y_desc, None)
}

fn panel_frame(col: usize, row: usize, top: f64, x: Scale, y: Scale) -> Frame {
    let (cx, cy) = (col as f64 * PANEL_W, top + row as f64 * PANEL_H);
    Frame {
        rect: (
            cx + 78.0,
            cy + 26.0,
            cx + PANEL_W - 14.0,
            cy + PANEL_H - 58.0,
        ),
        x,
        y,
        grid: true,
    }
}

/// A grid of panels (`cols` per row) sharing the x axis (log scale, positive x only) and, per
/// row, the y range (from 0), with one legend column on the right: curve i is drawn in
/// [`panel_style`] (colour-blind-safe colour, marker shape, dashed from the eighth on) at every
/// point — distinguishable in greyscale.
pub fn panels_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    legend: &[String],
    panels: &[Panel],
    cols: usize,
) -> Result<String> {
    let cols = cols.max(1);
    let rows = panels.len().div_ceil(cols).max(1);
    let pts = || {
        panels.iter().flat_map(|p| {
            p.curves
                .iter()
                .flat_map(|c| c.x.iter().copied().zip(c.y.iter().copied()))
        })
    };
    let (x0, x1) = pts()
        .filter(|(x, y)| x.is_finite() && *x > 0.0 && y.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(a, b), (x, _)| {
            (a.min(x), b.max(x))
        });
    if !(x0.is_finite() && x1 > 0.0) {
        return Err(Error::Incompatible(
            "nothing to plot: no finite points".into(),
        ));
    }
    let xs = Scale::log(x0 / 1.15, x1 * 1.15);
    let legend_w = 60.0 + legend.iter().map(|l| text_width(l, 13)).fold(0.0, f64::max);
    let width = PANEL_W * cols as f64 + 30.0 + legend_w;
    let th = title_height(title, width);
    let height = th + PANEL_H * rows as f64 + 5.0;
    let mut svg = String::new();
    {
        let root =
            super::canvas::Canvas::new(&mut svg, super::print::Width::Double, (width, height))
                .into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        title_lines(&root, title, width)?;
        for (pi, panel) in panels.iter().enumerate() {
            let (row, col) = (pi / cols, pi % cols);
            let ymax = panels[row * cols..((row + 1) * cols).min(panels.len())]
                .iter()
                .flat_map(|p| p.curves.iter().flat_map(|c| c.y.iter().copied()))
                .filter(|y| y.is_finite())
                .fold(0.0f64, f64::max);
            let ymax = if ymax > 0.0 { 1.06 * ymax } else { 1.0 };
            let frame = panel_frame(col, row, th, xs, Scale::Linear(-0.02 * ymax, ymax));
            draw_panel(&root, &frame, &panel.title, x_desc, y_desc)?;
            for (i, c) in panel.curves.iter().enumerate() {
                let style = panel_style(i);
                let line: Vec<(f64, f64)> =
                    c.x.iter()
                        .copied()
                        .zip(c.y.iter().copied())
                        .filter(|(x, y)| x.is_finite() && *x > 0.0 && y.is_finite())
                        .map(|(x, y)| frame.map(x, y))
                        .collect();
                draw_line(&root, &line, &style)?;
                for p in line {
                    draw_marker(&root, p, &style)?;
                }
            }
        }
        legend_column(
            &root,
            legend,
            &[],
            panel_style,
            true,
            (PANEL_W * cols as f64 + 20.0, th + 26.0),
            legend_w,
        )?;
        root.present().map_err(plot_err)?;
    }
    super::print::finish(&svg, super::print::Width::Double)
}

/// One panel of [`scatter_panels_svg`]: caption and points (legend index, x, y).
#[derive(Clone, Debug)]
pub struct ScatterPanel {
    /// Panel caption.
    pub title: String,
    /// Points: legend entry, x, y.
    pub points: Vec<(usize, f64, f64)>,
}

/// A marker is hidden when a marker drawn after it lies within this many pixels.
pub const COINCIDE_PX: f64 = 4.0;

/// Legend notes of a scatter figure (groups are drawn in legend order): entry i is "hidden
/// under" entry j > i when every marker of i has a marker of a later entry within
/// [`COINCIDE_PX`] in the same panel; j is the entry covering most of them.
pub fn coinciding_groups(
    legend: &[String],
    panels: &[ScatterPanel],
    frames: &[Frame],
) -> Vec<Option<String>> {
    let pos = |g: usize| -> Vec<(usize, (f64, f64))> {
        panels
            .iter()
            .zip(frames)
            .enumerate()
            .flat_map(|(k, (p, f))| {
                p.points
                    .iter()
                    .filter(move |q| {
                        q.0 == g && q.1.is_finite() && q.1 > 0.0 && q.2.is_finite() && q.2 > 0.0
                    })
                    .map(move |q| (k, f.map(q.1, q.2)))
            })
            .collect()
    };
    let all: Vec<Vec<(usize, (f64, f64))>> = (0..legend.len()).map(pos).collect();
    (0..legend.len())
        .map(|i| {
            if all[i].is_empty() {
                return None;
            }
            let mut count = vec![0usize; legend.len()];
            for (k, p) in &all[i] {
                let cover = ((i + 1)..legend.len()).find(|&j| {
                    all[j]
                        .iter()
                        .any(|(kj, q)| kj == k && (p.0 - q.0).hypot(p.1 - q.1) <= COINCIDE_PX)
                })?;
                count[cover] += 1;
            }
            let j = (0..legend.len()).max_by_key(|&j| (count[j], std::cmp::Reverse(j)))?;
            Some(format!("hidden under “{}”", legend[j]))
        })
        .collect()
}

/// A row of log–log scatter panels sharing both axis ranges, with one legend column on the
/// right: the points of legend entry i in [`group_style`] (colour and marker shape; filled for
/// the first ten entries, hollow for the next ten). Points that are not finite and positive
/// are left out.
pub fn scatter_panels_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    legend: &[String],
    panels: &[ScatterPanel],
) -> Result<String> {
    let ok = |p: &&(usize, f64, f64)| p.1.is_finite() && p.1 > 0.0 && p.2.is_finite() && p.2 > 0.0;
    let all: Vec<&(usize, f64, f64)> = panels
        .iter()
        .flat_map(|p| p.points.iter())
        .filter(ok)
        .collect();
    if all.is_empty() {
        return Err(Error::Incompatible(
            "nothing to plot: no finite positive points".into(),
        ));
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for p in &all {
        x0 = x0.min(p.1);
        x1 = x1.max(p.1);
        y0 = y0.min(p.2);
        y1 = y1.max(p.2);
    }
    let (xs, ys) = (
        Scale::log(x0 / 1.3, x1 * 1.3),
        Scale::log(y0 / 1.3, y1 * 1.3),
    );
    let cols = panels.len().max(1);
    let th0 = title_height(title, PANEL_W * cols as f64 + 200.0);
    let frames: Vec<Frame> = (0..cols).map(|c| panel_frame(c, 0, th0, xs, ys)).collect();
    let notes = coinciding_groups(legend, panels, &frames);
    let legend_w = 60.0
        + legend
            .iter()
            .map(|l| text_width(l, 13))
            .chain(notes.iter().flatten().map(|n| text_width(n, 11)))
            .fold(0.0, f64::max);
    let width = PANEL_W * cols as f64 + 30.0 + legend_w;
    let th = title_height(title, width);
    let height = th + PANEL_H + 5.0;
    let mut svg = String::new();
    {
        let root =
            super::canvas::Canvas::new(&mut svg, super::print::Width::Double, (width, height))
                .into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        title_lines(&root, title, width)?;
        for (col, panel) in panels.iter().enumerate() {
            let frame = panel_frame(col, 0, th, xs, ys);
            draw_panel(&root, &frame, &panel.title, x_desc, y_desc)?;
            for p in panel.points.iter().filter(ok) {
                draw_marker(&root, frame.map(p.1, p.2), &group_style(p.0))?;
            }
        }
        legend_column(
            &root,
            legend,
            &notes,
            group_style,
            false,
            (PANEL_W * cols as f64 + 20.0, th + 26.0),
            legend_w,
        )?;
        root.present().map_err(plot_err)?;
    }
    super::print::finish(&svg, super::print::Width::Double)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hidden_groups_are_named_and_log_axes_have_decades() {
        let legend: Vec<String> = ["kdk", "dkd", "rk4"].map(String::from).to_vec();
        let panels = vec![ScatterPanel {
            title: "p".into(),
            points: vec![
                (0, 100.0, 0.5),
                (1, 100.0, 0.5),
                (0, 1000.0, 0.05),
                (1, 1000.0, 0.05),
                (2, 100.0, 0.05),
            ],
        }];
        let f = panel_frame(0, 0, 0.0, Scale::log(10.0, 1e4), Scale::log(0.01, 1.0));
        let n = coinciding_groups(&legend, &panels, &[f]);
        assert_eq!(n, vec![Some("hidden under “dkd”".to_string()), None, None]);
        let svg = scatter_panels_svg("t", "x", "y", &legend, &panels).unwrap();
        assert!(svg.contains("hidden under “dkd”"));
        // decade labels on both log axes, no "100.0" or "1e2"
        for label in ["100", "10³", "0.1"] {
            assert!(svg.contains(&format!(">\n{label}\n</text>")), "{label}");
        }
        assert!(!svg.contains("100.0") && !svg.contains("1e2"));
    }

    #[test]
    fn pareto_legend_explains_fill_and_front() {
        let pts = vec![
            ("a".to_string(), 10.0, 0.1, true),
            ("a".to_string(), 20.0, 0.05, true),
            ("b".to_string(), 15.0, 0.2, false),
        ];
        let svg = pareto_svg("t", "x", "y", &pts, ("filled: stable", "hollow: unstable")).unwrap();
        for s in ["filled: stable", "hollow: unstable", "Pareto front"] {
            assert!(svg.contains(s), "{s}");
        }
    }
}
