//! Scatter plots on log–log axes (the trade-off Pareto figure, the integrator panels), in
//! the shared styles, laid out in points on a 170 mm page: panels in a grid, one legend column on the right. Series are styled by meaning
//! ([`panel_styles`]); where more series than the seven colours would share a panel, the
//! series are split into layers of distinct colours, one row of panels per layer.

use super::axes::{BOTTOM_MARGIN, Frame, Scale};
use super::print::{
    FRAME_LINE_PT, LABEL_PT, LEGEND_LINE, LEGEND_PT, NOTE_LINE, NOTE_PT, PAD, SAMPLE_W, TITLE_PT,
    Width, page_pt,
};
use super::style::{
    Dash, GREY, Names, Style, draw_line, draw_marker, draw_sample, group, outline, panel_styles,
    plot_err, text, text_width, wrap,
};
use crate::error::{Error, Result};
use plotters::prelude::*;

/// Height (points) of a title of `title` on a 170 mm page, and its lines.
pub fn title_block(title: &str) -> (f64, Vec<String>) {
    if title.is_empty() {
        return (PAD, Vec::new());
    }
    let lines = wrap(
        title,
        ((page_pt(Width::Double) - 2.0 * PAD) / (0.6 * TITLE_PT)) as usize,
    );
    (PAD + TITLE_PT * 1.25 * lines.len() as f64, lines)
}

/// Draws the lines of [`title_block`] at the top left.
pub fn draw_title(
    root: &DrawingArea<super::canvas::Canvas<'_>, plotters::coord::Shift>,
    lines: &[String],
) -> Result<()> {
    for (k, line) in lines.iter().enumerate() {
        text(
            root,
            line,
            (PAD, PAD + TITLE_PT * 1.25 * k as f64),
            TITLE_PT,
            BLACK,
        )?;
    }
    Ok(())
}

/// Styles of the legend entries of a scatter or panel figure, by meaning ([`panel_styles`]).
pub fn legend_styles(legend: &[String], names: &Names) -> Vec<Style> {
    let labels: Vec<&str> = legend.iter().map(String::as_str).collect();
    panel_styles(&labels, &[], names)
}

/// Splits legend entries into layers in which no two share a colour (in legend order, each
/// entry into the first layer without its colour): one row of panels per layer.
pub fn colour_layers(styles: &[Style]) -> Vec<Vec<usize>> {
    let mut layers: Vec<Vec<usize>> = Vec::new();
    for (i, s) in styles.iter().enumerate() {
        match layers
            .iter_mut()
            .find(|l| l.iter().all(|&j| styles[j].color != s.color))
        {
            Some(l) => l.push(i),
            None => layers.push(vec![i]),
        }
    }
    layers
}

/// Style of the Pareto front line (and of its legend sample).
pub const FRONT_STYLE: Style = Style {
    color: RGBColor(0, 0, 0),
    dash: Dash::Dashed,
    marker: super::style::Marker::Circle,
    filled: true,
    width: FRAME_LINE_PT * 1.5,
};

/// Width (points) of a legend column for `labels` (and notes), capped.
pub fn legend_width(labels: &[&str], notes: &[&str]) -> f64 {
    let w = labels
        .iter()
        .map(|l| text_width(l, LEGEND_PT))
        .chain(notes.iter().map(|n| text_width(n, NOTE_PT)))
        .fold(0.0f64, f64::max)
        .min(text_width(&"x".repeat(LEGEND_CHARS), LEGEND_PT));
    SAMPLE_W + 4.0 + w + 2.0 * PAD
}

/// Longest legend line, characters (longer labels wrap).
const LEGEND_CHARS: usize = 30;

/// One legend entry: how it is drawn.
pub struct Entry<'a> {
    /// The series' style.
    pub style: Style,
    /// Label.
    pub label: &'a str,
    /// Second line, smaller and grey.
    pub note: Option<&'a str>,
    /// The sample shows the line.
    pub line: bool,
    /// The sample shows the marker.
    pub marker: bool,
}

/// Draws a framed legend column at `(lx, top)`, `w` wide; returns its bottom.
pub fn legend_column(
    root: &DrawingArea<super::canvas::Canvas<'_>, plotters::coord::Shift>,
    entries: &[Entry<'_>],
    (lx, top): (f64, f64),
    w: f64,
) -> Result<f64> {
    let chars = ((w - SAMPLE_W - 4.0 - 2.0 * PAD) / (0.6 * LEGEND_PT)) as usize;
    let nchars = ((w - SAMPLE_W - 4.0 - 2.0 * PAD) / (0.6 * NOTE_PT)) as usize;
    let tx = lx + PAD + SAMPLE_W + 4.0;
    let mut y = top + PAD;
    group(root, Some("legend"))?;
    for e in entries {
        draw_sample(
            root,
            (lx + PAD, y + LEGEND_PT * 0.55),
            SAMPLE_W,
            &e.style,
            e.line,
            e.marker,
        )?;
        for line in wrap(e.label, chars) {
            text(root, &line, (tx, y), LEGEND_PT, BLACK)?;
            y += LEGEND_LINE;
        }
        if let Some(n) = e.note {
            for line in wrap(n, nchars) {
                text(root, &line, (tx, y), NOTE_PT, GREY)?;
                y += NOTE_LINE;
            }
        }
        y += 1.5;
    }
    group(root, None)?;
    let bottom = y + PAD - 1.5;
    outline(root, (lx, top, lx + w, bottom), GREY, FRAME_LINE_PT)?;
    Ok(bottom)
}

/// Height (points) of [`legend_block`] for `entries` across `width` points.
pub fn legend_block_height(entries: &[Entry<'_>], width: f64) -> f64 {
    let (_, rows, _) = block_shape(entries, width);
    2.0 * PAD + rows as f64 * block_pitch(entries) - 1.5
}

/// Row pitch of a legend block: a label line, and a note line when any entry has a note.
fn block_pitch(entries: &[Entry<'_>]) -> f64 {
    let note = if entries.iter().any(|e| e.note.is_some()) {
        NOTE_LINE
    } else {
        0.0
    };
    LEGEND_LINE + note + 1.5
}

/// Columns, rows and column width of a legend block of `entries` across `width` points.
fn block_shape(entries: &[Entry<'_>], width: f64) -> (usize, usize, f64) {
    let col_w = entries
        .iter()
        .map(|e| text_width(e.label, LEGEND_PT).max(e.note.map_or(0.0, |n| text_width(n, NOTE_PT))))
        .fold(0.0f64, f64::max)
        + SAMPLE_W
        + 4.0
        + 8.0;
    let cols = (((width - 2.0 * PAD) / col_w).floor() as usize).clamp(1, entries.len().max(1));
    let rows = entries.len().div_ceil(cols);
    (cols, rows, (width - 2.0 * PAD) / cols as f64)
}

/// Draws a framed legend block of `entries` in columns (filled column by column) at
/// `(x, top)`, `width` wide; returns its bottom. Notes take one line under their label.
pub fn legend_block(
    root: &DrawingArea<super::canvas::Canvas<'_>, plotters::coord::Shift>,
    entries: &[Entry<'_>],
    (x, top): (f64, f64),
    width: f64,
) -> Result<f64> {
    let (_, rows, col_w) = block_shape(entries, width);
    let pitch = block_pitch(entries);
    group(root, Some("legend"))?;
    for (i, e) in entries.iter().enumerate() {
        let (c, r) = (i / rows, i % rows);
        let (lx, y) = (x + PAD + c as f64 * col_w, top + PAD + r as f64 * pitch);
        draw_sample(
            root,
            (lx, y + LEGEND_PT * 0.55),
            SAMPLE_W,
            &e.style,
            e.line,
            e.marker,
        )?;
        text(root, e.label, (lx + SAMPLE_W + 4.0, y), LEGEND_PT, BLACK)?;
        if let Some(n) = e.note {
            text(
                root,
                n,
                (lx + SAMPLE_W + 4.0, y + LEGEND_LINE),
                NOTE_PT,
                GREY,
            )?;
        }
    }
    group(root, None)?;
    let bottom = top + legend_block_height(entries, width);
    outline(root, (x, top, x + width, bottom), GREY, FRAME_LINE_PT)?;
    Ok(bottom)
}

/// A grid of panels left of a legend column on a 170 mm page.
#[derive(Clone, Copy, Debug)]
pub struct Grid {
    /// Top of the first row, pt.
    pub top: f64,
    /// Width and height of one cell, pt.
    pub cell: (f64, f64),
    /// Room left of each frame for its ticks and axis description, pt.
    pub left: f64,
}

impl Grid {
    /// `cols` cells per row under `top`, left of a legend `legend_w` wide; cell height
    /// `aspect` × width (110–260 pt).
    pub fn new(top: f64, cols: usize, legend_w: f64, aspect: f64) -> Self {
        let cw = (page_pt(Width::Double) - legend_w - 2.0 * PAD) / cols.max(1) as f64;
        Grid {
            top,
            cell: (cw, (cw * aspect).clamp(110.0, 260.0)),
            left: 40.0,
        }
    }

    /// Room left of each frame for the ticks of `y` and the description `y_desc`.
    pub fn fit_left(&mut self, y: Scale, y_desc: &str) {
        let box_h = self.cell.1 - TITLE_PT * 1.4 - BOTTOM_MARGIN - LABEL_PT * 1.2 - 2.0;
        self.left = Frame::left_margin(y, box_h, y_desc) + 2.0;
    }

    /// The frame of cell (col, row): a title line above it, ticks and description under it.
    pub fn frame(&self, col: usize, row: usize, x: Scale, y: Scale) -> Frame {
        let (cx, cy) = (
            PAD + col as f64 * self.cell.0,
            self.top + row as f64 * self.cell.1,
        );
        Frame {
            rect: (
                cx + self.left,
                cy + TITLE_PT * 1.4,
                cx + self.cell.0 - 6.0,
                cy + self.cell.1 - BOTTOM_MARGIN - LABEL_PT * 1.2 - 2.0,
            ),
            x,
            y,
            grid: true,
        }
    }

    /// Left edge of the legend column right of `cols` cells.
    pub fn legend_x(&self, cols: usize) -> f64 {
        PAD + cols as f64 * self.cell.0 + PAD
    }
}

/// A panel's title (its letter first) above its frame, then the frame.
pub fn draw_panel(
    root: &DrawingArea<super::canvas::Canvas<'_>, plotters::coord::Shift>,
    frame: &Frame,
    title: &str,
    x_desc: &str,
    y_desc: &str,
) -> Result<()> {
    text(
        root,
        title,
        (frame.rect.0 - 30.0, frame.rect.1 - TITLE_PT * 1.3),
        TITLE_PT,
        BLACK,
    )?;
    frame.draw(root, x_desc, y_desc, None)
}

/// The panel letter of panel `i`: (a), (b), …
pub fn panel_letter(i: usize) -> String {
    let c = (b'a' + (i % 26) as u8) as char;
    format!("({c})")
}

/// A log–log scatter of (group, x, y, filled) points: colour and marker shape per group
/// (legend, by meaning), filled markers for `filled`, hollow otherwise (`fill_meaning` = the
/// legend text of filled and hollow); the lower-left Pareto front of the filled points is a
/// dashed staircase.
pub fn pareto_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    pts: &[(String, f64, f64, bool)],
    fill_meaning: (&str, &str),
    names: &Names,
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
    let mut groups: Vec<String> = Vec::new();
    for p in &pts {
        if !groups.contains(&p.0) {
            groups.push(p.0.clone());
        }
    }
    let styles = legend_styles(&groups, names);
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for p in &pts {
        x0 = x0.min(p.1);
        x1 = x1.max(p.1);
        y0 = y0.min(p.2);
        y1 = y1.max(p.2);
    }
    let front_label = "Pareto front of the filled points";
    let mut labels: Vec<&str> = groups.iter().map(String::as_str).collect();
    labels.extend([fill_meaning.0, fill_meaning.1, front_label]);
    let legend_w = legend_width(&labels, &[]);
    let (th, tlines) = title_block(title);
    let mut grid = Grid::new(th, 1, legend_w, 0.62);
    let ys = Scale::log(y0 / 1.5, y1 * 1.5);
    grid.fit_left(ys, y_desc);
    let frame = grid.frame(0, 0, Scale::log(x0 / 1.2, x1 * 1.2), ys);
    let height = th + grid.cell.1 + PAD;
    let mut svg = String::new();
    {
        let root =
            super::canvas::Canvas::new(&mut svg, Width::Double, (page_pt(Width::Double), height))
                .into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        draw_title(&root, &tlines)?;
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
                    ..styles[gi]
                };
                for p in pts.iter().filter(|p| p.0 == *g && p.3 == filled) {
                    draw_marker(&root, frame.map(p.1, p.2), &style)?;
                }
            }
        }
        let black = |filled| Style {
            color: BLACK,
            filled,
            ..styles[0]
        };
        let mut entries: Vec<Entry<'_>> = groups
            .iter()
            .zip(&styles)
            .map(|(g, s)| Entry {
                style: *s,
                label: g,
                note: None,
                line: false,
                marker: true,
            })
            .collect();
        for (filled, label) in [(true, fill_meaning.0), (false, fill_meaning.1)] {
            entries.push(Entry {
                style: black(filled),
                label,
                note: None,
                line: false,
                marker: true,
            });
        }
        if stairs.len() > 1 {
            entries.push(Entry {
                style: FRONT_STYLE,
                label: front_label,
                note: None,
                line: true,
                marker: false,
            });
        }
        legend_column(&root, &entries, (grid.legend_x(1), frame.rect.1), legend_w)?;
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
}

/// One panel of [`scatter_panels_svg`]: caption and points (legend index, x, y).
#[derive(Clone, Debug)]
pub struct ScatterPanel {
    /// Panel caption.
    pub title: String,
    /// Points: legend entry, x, y.
    pub points: Vec<(usize, f64, f64)>,
}

/// A marker is hidden when a marker drawn after it lies within this many points.
pub const COINCIDE_PX: f64 = 1.5;

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

/// A row of log–log scatter panels sharing both axis ranges over the page width, the legend
/// in columns under them: the points of legend entry i in its style by meaning ([`legend_styles`]). Where two
/// entries share a colour, the row is drawn once per colour layer ([`colour_layers`]). Points
/// that are not finite and positive are left out; panels are lettered (a), (b), ….
pub fn scatter_panels_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    legend: &[String],
    panels: &[ScatterPanel],
    names: &Names,
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
    let styles = legend_styles(legend, names);
    let layers = colour_layers(&styles);
    let cols = panels.len().max(1);
    let (th, tlines) = title_block(title);
    let page = page_pt(Width::Double);
    // the panels over the full width, the legend in columns under them
    let mut grid = Grid::new(th, cols, 0.0, 0.85);
    grid.fit_left(ys, y_desc);
    let frames: Vec<Frame> = (0..cols).map(|c| grid.frame(c, 0, xs, ys)).collect();
    let notes = coinciding_groups(legend, panels, &frames);
    let entries: Vec<Entry<'_>> = legend
        .iter()
        .zip(&styles)
        .zip(&notes)
        .map(|((l, s), n)| Entry {
            style: *s,
            label: l,
            note: n.as_deref(),
            line: false,
            marker: true,
        })
        .collect();
    let legend_top = th + grid.cell.1 * layers.len() as f64 + 2.0;
    let legend_w = page - 2.0 * PAD;
    let height = legend_top + legend_block_height(&entries, legend_w) + PAD;
    let mut svg = String::new();
    {
        let root =
            super::canvas::Canvas::new(&mut svg, Width::Double, (page, height)).into_drawing_area();
        root.fill(&WHITE).map_err(plot_err)?;
        draw_title(&root, &tlines)?;
        let mut letter = 0;
        for (row, layer) in layers.iter().enumerate() {
            for (col, panel) in panels.iter().enumerate() {
                let frame = grid.frame(col, row, xs, ys);
                let t = format!("{} {}", panel_letter(letter), panel.title);
                letter += 1;
                draw_panel(&root, &frame, &t, x_desc, y_desc)?;
                for p in panel
                    .points
                    .iter()
                    .filter(ok)
                    .filter(|p| layer.contains(&p.0))
                {
                    draw_marker(&root, frame.map(p.1, p.2), &styles[p.0])?;
                }
            }
        }
        legend_block(&root, &entries, (PAD, legend_top), legend_w)?;
        root.present().map_err(plot_err)?;
    }
    Ok(svg)
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
        let f =
            Grid::new(0.0, 1, 100.0, 0.9).frame(0, 0, Scale::log(10.0, 1e4), Scale::log(0.01, 1.0));
        let n = coinciding_groups(&legend, &panels, &[f]);
        assert_eq!(n, vec![Some("hidden under “dkd”".to_string()), None, None]);
        let svg = scatter_panels_svg("t", "x", "y", &legend, &panels, &Names::default()).unwrap();
        assert!(svg.contains("hidden under “dkd”"));
        // decade labels on both log axes, no "100.0" or "1e2"
        for label in ["100", "10³", "0.1"] {
            assert!(svg.contains(&format!(">{label}</text>")), "{label}");
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
        let svg = pareto_svg(
            "t",
            "x",
            "y",
            &pts,
            ("filled: stable", "hollow: unstable"),
            &Names::default(),
        )
        .unwrap();
        for s in ["filled: stable", "hollow: unstable", "Pareto front"] {
            assert!(svg.contains(s), "{s}");
        }
    }
}
