//! The command-line side of the `analysis/` studies (`tradeoff`, `pairing`): `--config` read and
//! parsed, `--from` read back, the figure drawn to `--plot` and, for a config with `output`, the
//! figure and its data written into `figures/`. The library side is [`sphstab::studies::config`].

use crate::export::Export;
use anyhow::{Context, Result};
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::path::{Path, PathBuf};

/// `--plot` and the formats it is written in (`--format`, `--dpi`).
pub type Plot<'a> = (&'a Path, &'a Export);

/// The files of a study command: `--config` and `--from` read, `--plot` written in every format
/// of `export` (checked with [`crate::files::Files::check`]).
pub fn files(
    config: Option<&PathBuf>,
    from: Option<&PathBuf>,
    plot: Option<&PathBuf>,
    export: &Export,
) -> crate::files::Files {
    let mut f = crate::files::Files::new();
    if let Some(p) = config {
        f = f.input("--config", p);
    }
    if let Some(p) = from {
        f = f.input("--from", p);
    }
    if let Some(p) = plot {
        f = export.output(f, "--plot", p);
    }
    f
}

/// `files` with what a config's `output` regenerates ([`write_figure_and_data`]): the figure
/// figures/<name> and its data next to it.
pub fn with_config_output(files: crate::files::Files, name: &str) -> crate::files::Files {
    let svg = PathBuf::from("figures").join(name);
    let data = svg.with_extension("json");
    files
        .regenerated("--config (its `output`)", svg)
        .regenerated("--config (its `output`, the data)", data)
}

/// Reads and parses `--config` with the study's parser (errors name the file and the field).
pub fn read_config<T>(
    path: &Path,
    parse: impl Fn(&str, &str) -> sphstab::error::Result<T>,
) -> Result<T> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("--config: cannot read {}", path.display()))?;
    Ok(parse(&path.display().to_string(), &text)?)
}

/// Reads a stored report (`--from`: a JSON written by `--json` or `--config`).
pub fn read_report<T: DeserializeOwned>(from: &Path) -> Result<T> {
    let text = std::fs::read_to_string(from)
        .with_context(|| format!("--from: cannot read {}", from.display()))?;
    Ok(sphstab::studies::config::parse_json(
        &from.display().to_string(),
        &text,
    )?)
}

/// `--from` needs `--plot`: where to draw.
pub fn plot_path(plot: Option<&PathBuf>) -> Result<&Path> {
    plot.map(PathBuf::as_path).ok_or_else(|| {
        sphstab::error::Error::Incompatible("--from needs --plot (where to draw)".into()).into()
    })
}

/// Writes a drawn figure to `path` (the `--plot` file, in the formats of `export`, or the
/// config's figure).
pub fn write_plot(svg: sphstab::error::Result<String>, (path, export): Plot<'_>) -> Result<()> {
    export.write("--plot", &svg?, path)?;
    Ok(())
}

/// A config's `output`: the figure `figures/<name>` and the report next to it
/// (`figures/<name>.json`, pretty JSON with its "units"), reported on stderr.
pub fn write_figure_and_data<T: Serialize>(
    report: &T,
    name: &str,
    draw: impl Fn(&T) -> sphstab::error::Result<String>,
) -> Result<()> {
    let svg = PathBuf::from("figures").join(name);
    write_plot(draw(report), (&svg, &Export::default()))?;
    let data = svg.with_extension("json");
    let text = sphstab::units::json(report, sphstab::units::System::Normalised, true)?;
    std::fs::write(&data, text + "\n")
        .with_context(|| format!("cannot write {}", data.display()))?;
    eprintln!("wrote {} and {}", svg.display(), data.display());
    Ok(())
}

/// Where a study's report goes: `--out` (JSON with its units), `--plot`, a config's `output`
/// (the figure and its data in figures/), then `--json` or the text on stdout.
pub struct Outputs<'a> {
    pub out: Option<&'a Path>,
    pub json: bool,
    pub plot: Option<Plot<'a>>,
    pub config_out: Option<&'a str>,
}

/// Writes and prints a study's report (the one path of every study and of `merge`): `draw`
/// makes its figure, `text` its table.
pub fn output<T: Serialize>(
    report: &T,
    to: Outputs<'_>,
    draw: impl Fn(&T) -> sphstab::error::Result<String>,
    text: impl FnOnce(&T) -> String,
) -> Result<()> {
    use sphstab::units::{self, System};
    if let Some(path) = to.out {
        crate::shard::write_json(path, &units::with_units(report, System::Normalised)?)?;
    }
    if let Some(plot) = to.plot {
        write_plot(draw(report), plot)?;
    }
    if let Some(name) = to.config_out {
        write_figure_and_data(report, name, &draw)?;
    }
    if to.json {
        println!("{}", units::json(report, System::Normalised, false)?);
    } else {
        print!("{}", text(report));
    }
    Ok(())
}

/// `--from FILE --plot FILE`: redraws a stored report with `draw`, refusing the other flags
/// (`others`: whether `--config`, `--json` or a study flag was given).
pub fn redraw<T: DeserializeOwned>(
    from: &Path,
    plot: Option<&PathBuf>,
    export: &Export,
    others: bool,
    draw: impl Fn(&T) -> sphstab::error::Result<String>,
) -> Result<()> {
    if others {
        anyhow::bail!(
            "--from redraws stored data: it takes only --plot (not --config, --json or the study flags)"
        );
    }
    let path = plot_path(plot)?;
    let rep: T = read_report(from)?;
    write_plot(draw(&rep), (path, export))
}
