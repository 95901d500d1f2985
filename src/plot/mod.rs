//! Plots as pure functions returning SVG strings (plotters SVG backend, no system fonts), all
//! drawn by one layer: the styles of [`style`] (Okabe–Ito colours, marker shapes, dash
//! patterns; legend samples drawn by the same code as their series), the axes of [`axes`]
//! (automatic ranges from the data, decade ticks on log axes), legends outside the data;
//! the print geometry of [`mod@print`] (85 or 170 mm wide, type in points, one font family) and the
//! [`canvas`] every plot draws on (at 20 px/mm, curves at fractional coordinates).

pub mod axes;
pub mod canvas;
pub mod export;
mod heatmap;
mod lines;
pub mod print;
mod scatter;
mod stack;
pub mod style;

pub use heatmap::{StripPanel, heatmap_svg, ramp, strips_svg};
pub use lines::{
    COINCIDE_TOL, Curve, DAMPING_DESC, KAPPA_DESC, LegendEntry, LinePlot, MARKERS_PER_CURVE,
    OMEGA2_DESC, curve_styles, damping_plot, legend_entries, lines_svg,
};
pub use scatter::{
    COINCIDE_PX, Entry, FRONT_STYLE, Grid, ScatterPanel, coinciding_groups, colour_layers,
    draw_panel, draw_title, legend_block, legend_block_height, legend_column, legend_styles,
    legend_width, panel_letter, pareto_svg, scatter_panels_svg, title_block,
};
pub use stack::{stack_svg, svg_size};
