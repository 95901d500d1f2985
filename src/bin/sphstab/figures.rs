//! `sphstab figures`: regenerate every figure, from its config (analysis/configs) or from a
//! study's stored data (the report next to the study figure, redrawn as `--from … --plot`
//! does), in the formats of `--format`, and the captions file `<out>/README.md`.

use crate::export::ExportArgs;
use anyhow::{Context, Result};
use sphstab::budget::Budget;
use sphstab::studies::stored::Stored;
use std::path::{Path, PathBuf};

/// Flags of `figures`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Directory of figure configs (*.json).
    #[arg(long, default_value = "analysis/configs")]
    configs: PathBuf,
    /// Directory of the studies' stored data (*.json: the reports a study's --config writes
    /// next to its figure), each redrawn as `<study> --from DIR/X.json --plot OUT/X.svg` does;
    /// the study is recognised by the report's fields.
    #[arg(long, default_value = "figures")]
    data: PathBuf,
    /// Directory of the study configs (*.json): the one whose `output` names a study figure
    /// gives its caption (`note`) and its regeneration command.
    #[arg(long, default_value = "analysis")]
    studies: PathBuf,
    /// Output directory for the figures and README.md (their captions). The figures are
    /// regenerated: a file of the same name there is replaced (no --force needed; never an
    /// input).
    #[arg(long, default_value = "figures")]
    out: PathBuf,
    #[command(flatten)]
    export: ExportArgs,
}

/// The `*.json` files of a directory (not its subdirectories), in name order.
fn json_files(dir: &Path, flag: &str) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("{flag}: cannot read {}", dir.display()))?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_file() && p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    Ok(files)
}

/// What a figure is drawn from.
enum Source {
    /// A figure config.
    Config(Box<sphstab::figures::FigureConfig>),
    /// A study's stored report.
    Study(Stored),
}

/// One figure: its file name in `--out`, what it is drawn from, and its caption.
struct Figure {
    /// File name of the SVG (`b00_fig3a_eq74.svg`).
    output: String,
    /// The config or data file, as given.
    file: PathBuf,
    source: Source,
    /// Short heading (a config's `title`), if any.
    title: Option<String>,
    /// The caption (the config's `note`).
    note: String,
    /// The study config whose `output` is this figure, if found.
    study_config: Option<PathBuf>,
}

/// A study config's `output` and `note` (study configs are parsed by their study; only these
/// two fields matter for the captions).
#[derive(serde::Deserialize)]
struct StudyCaption {
    output: Option<String>,
    #[serde(default)]
    note: String,
}

impl Figure {
    /// The commands that regenerate the figure, as Markdown.
    fn commands(&self, a: &Args) -> String {
        let out = a.out.join(&self.output);
        match &self.source {
            Source::Config(_) => format!(
                "Regenerate: `sphstab figures --configs {} --out {}` (config `{}`).",
                a.configs.display(),
                a.out.display(),
                self.file.display()
            ),
            Source::Study(s) => {
                let mut t = format!(
                    "Redraw from the stored data: `sphstab {} --from {} --plot {}`.",
                    s.study(),
                    self.file.display(),
                    out.display()
                );
                if let Some(c) = &self.study_config {
                    t += &format!(
                        " Recompute the data and the figure: `sphstab {} --config {}`.",
                        s.study(),
                        c.display()
                    );
                }
                t
            }
        }
    }

    /// The figure's SVG, drawn as `figures` (a config) or `--from … --plot` (a study) draws it.
    fn draw(&self) -> Result<String> {
        let svg = match &self.source {
            Source::Config(cfg) => sphstab::figures::render(cfg),
            Source::Study(Stored::Tradeoff(r)) => crate::tradeoff::draw(r),
            Source::Study(Stored::Pairing(r)) => sphstab::studies::pairing::figure_svg(r),
            Source::Study(Stored::ArtStress(r)) => sphstab::studies::art_stress::figure_svg(r),
            Source::Study(Stored::Hourglass(r)) => sphstab::studies::hourglass::figure_svg(r),
        };
        svg.with_context(|| self.file.display().to_string())
    }
}

/// The captions file: per figure (in file-name order) a heading with its name, the image,
/// its title and caption, and the commands that regenerate it.
fn readme(figures: &[Figure], a: &Args) -> String {
    let mut s = String::from(
        "# Figures\n\nWritten by `sphstab figures` (do not edit: edit the configs and rerun it): \
         every figure with its caption and the commands that regenerate it. \
         `--format pdf,png` writes each also as a vector PDF and a PNG (300 dpi by default).\n",
    );
    for f in figures {
        s += &format!("\n## {}\n\n![]({})\n\n", f.output, f.output);
        if let Some(t) = &f.title {
            s += &format!("**{t}**\n\n");
        }
        if !f.note.is_empty() {
            s += &format!("{}\n\n", f.note.trim());
        }
        s += &f.commands(a);
        s += "\n";
    }
    s
}

pub fn run(a: Args, budget: &Budget) -> Result<()> {
    let export = a.export.resolve(true, "")?;
    let configs = json_files(&a.configs, "--configs")?;
    let data = json_files(&a.data, "--data")?;
    let study_configs = json_files(&a.studies, "--studies")?;
    std::fs::create_dir_all(&a.out)
        .with_context(|| format!("--out: cannot create {}", a.out.display()))?;
    // every config and data file read and every output checked before the first figure is drawn
    let mut check = crate::files::Files::new();
    for f in &configs {
        check = check.input("--configs", f);
    }
    for f in &data {
        check = check.input("--data", f);
    }
    for f in &study_configs {
        check = check.input("--studies", f);
    }
    let read = |f: &Path| {
        std::fs::read_to_string(f).with_context(|| format!("cannot read {}", f.display()))
    };
    let mut figures = Vec::with_capacity(configs.len() + data.len());
    for f in configs {
        let name = f.display().to_string();
        let cfg = sphstab::figures::FigureConfig {
            budget: *budget,
            ..sphstab::figures::parse(&name, &read(&f)?)?
        };
        figures.push(Figure {
            output: cfg.output.clone(),
            title: Some(cfg.title.clone()),
            note: cfg.note.clone(),
            study_config: None,
            source: Source::Config(Box::new(cfg)),
            file: f,
        });
    }
    // the study configs by the figure they name
    let mut captions = Vec::new();
    for f in study_configs {
        let c: StudyCaption =
            sphstab::studies::config::parse_json(&f.display().to_string(), &read(&f)?)
                .context("--studies")?;
        if let Some(o) = c.output {
            captions.push((o, c.note, f));
        }
    }
    for f in data {
        let stored = Stored::parse(&f.display().to_string(), &read(&f)?).context("--data")?;
        let output = format!(
            "{}.svg",
            f.file_stem().map_or("".into(), |s| s.to_string_lossy())
        );
        let (note, study_config) = match captions.iter().find(|(o, ..)| *o == output) {
            Some((_, note, c)) => (note.clone(), Some(c.clone())),
            None => match &stored {
                Stored::ArtStress(r) => (r.config.note.clone(), None),
                _ => (String::new(), None),
            },
        };
        figures.push(Figure {
            output,
            title: None,
            note,
            study_config,
            source: Source::Study(stored),
            file: f,
        });
    }
    figures.sort_by(|x, y| x.output.cmp(&y.output));
    for f in &figures {
        check = export.regenerated(check, "--out", &a.out.join(&f.output));
    }
    let readme_path = a.out.join("README.md");
    check = check.regenerated("--out (the captions, README.md)", &readme_path);
    check.check()?;
    let mut drawn = Vec::with_capacity(figures.len());
    for f in &figures {
        drawn.push((f.draw()?, a.out.join(&f.output)));
    }
    let written = export.write_all("--out", &drawn)?;
    for (f, files) in figures.iter().zip(written) {
        let shown: Vec<String> = files.iter().map(|p| p.display().to_string()).collect();
        println!("{} -> {}", f.file.display(), shown.join(", "));
    }
    std::fs::write(&readme_path, readme(&figures, &a))
        .with_context(|| format!("--out: cannot write {}", readme_path.display()))?;
    println!("captions -> {}", readme_path.display());
    Ok(())
}
