//! `--format` and `--dpi`: the formats in which a command writes its figures, the flags of
//! every command that draws (`figures` and each `--plot`), in one struct flattened into theirs,
//! and the one function that writes a figure in them ([`Export::write`]), after the output
//! checks of [`crate::files`] ([`Export::output`], [`Export::regenerated`]).

use crate::files::Files;
use anyhow::{Context, Result};
use rayon::prelude::*;
use sphstab::plot::export::{self, DEFAULT_DPI, Format};
use std::path::{Path, PathBuf};

/// The flags `--format` and `--dpi`.
#[derive(clap::Args, Debug, Clone, Default)]
pub struct ExportArgs {
    /// Figure formats, a comma list of svg, pdf (vector, for LaTeX) and png (default: svg):
    /// each figure is written once per format, its file name's extension replaced by the
    /// format's (`--plot out.svg --format svg,pdf` writes out.svg and out.pdf).
    #[arg(long = "format", value_name = "LIST")]
    format: Option<String>,
    /// Resolution of the PNG figures, pixels per inch of their printed width (85 or 170 mm),
    /// in [72, 1200] (default 300: 170 mm → 2008 px). Needs png in --format.
    #[arg(long, value_name = "N")]
    dpi: Option<u32>,
}

/// The checked formats of a command's figures.
#[derive(Clone, Debug)]
pub struct Export {
    formats: Vec<Format>,
    dpi: f64,
    /// `--format` given: every file name takes its format's extension (without it, the one
    /// SVG goes to the path as given, as before the flag existed).
    by_extension: bool,
}

impl Default for Export {
    /// The SVG alone, to the path as given.
    fn default() -> Self {
        Export {
            formats: vec![Format::Svg],
            dpi: f64::from(DEFAULT_DPI),
            by_extension: false,
        }
    }
}

impl ExportArgs {
    /// The formats, checked. `draws` is false when the command writes no figure this time
    /// (no `--plot`; `why` says so): the flags are then an error, not ignored.
    pub fn resolve(&self, draws: bool, why: &str) -> Result<Export> {
        if !draws {
            for (given, flag) in [
                (self.format.is_some(), "--format"),
                (self.dpi.is_some(), "--dpi"),
            ] {
                if given {
                    return Err(crate::query::not_in(flag, why));
                }
            }
        }
        let dpi = export::check_dpi(f64::from(self.dpi.unwrap_or(DEFAULT_DPI)))?;
        let Some(list) = &self.format else {
            return Ok(Export {
                dpi,
                ..Export::default()
            });
        };
        let formats = Format::parse_list(list)?;
        if self.dpi.is_some() && !formats.contains(&Format::Png) {
            return Err(crate::query::not_in(
                "--dpi",
                "no png in --format (it sets the PNG resolution)",
            ));
        }
        Ok(Export {
            formats,
            dpi,
            by_extension: true,
        })
    }
}

impl Export {
    /// The files of the figure `path` (an SVG path): one per format.
    pub fn files(&self, path: &Path) -> Vec<(Format, PathBuf)> {
        self.formats
            .iter()
            .map(|&f| {
                let p = if self.by_extension {
                    path.with_extension(f.extension())
                } else {
                    path.to_path_buf()
                };
                (f, p)
            })
            .collect()
    }

    /// How a derived file is named in errors: `flag`, with the format when it is not the SVG.
    fn label(flag: &str, f: Format) -> String {
        match f {
            Format::Svg => flag.to_string(),
            _ => format!("{flag} (as {})", f.extension()),
        }
    }

    /// `files` with the figure `path` written (given by `flag`) in every format: each file is
    /// an output that needs `--force` to replace an existing one.
    pub fn output(&self, mut files: Files, flag: &str, path: &Path) -> Files {
        for (f, p) in self.files(path) {
            files = files.output(&Self::label(flag, f), p);
        }
        files
    }

    /// `files` with the figure `path` regenerated (`figures`, a study's config) in every format.
    pub fn regenerated(&self, mut files: Files, flag: &str, path: &Path) -> Files {
        for (f, p) in self.files(path) {
            files = files.regenerated(&Self::label(flag, f), p);
        }
        files
    }

    /// Writes the figure `svg` to `path` in every format (the files checked before with
    /// [`Export::output`] or [`Export::regenerated`]); errors name `flag` and the file.
    pub fn write(&self, flag: &str, svg: &str, path: &Path) -> Result<Vec<PathBuf>> {
        let mut written = Vec::new();
        for (f, p) in self.files(path) {
            let bytes = export::convert(svg, f, self.dpi)
                .with_context(|| format!("{flag}: {}", p.display()))?;
            std::fs::write(&p, bytes)
                .with_context(|| format!("{flag}: cannot write {}", p.display()))?;
            written.push(p);
        }
        Ok(written)
    }

    /// [`Export::write`] for many figures (`(svg, path)`), converted in parallel; the files
    /// written, per figure, in the order given.
    pub fn write_all(
        &self,
        flag: &str,
        figures: &[(String, PathBuf)],
    ) -> Result<Vec<Vec<PathBuf>>> {
        figures
            .par_iter()
            .map(|(svg, path)| self.write(flag, svg, path))
            .collect()
    }
}
