//! The one place where the library's field names become the flags the user typed: the library
//! names every field in its errors ([`sphstab::error::Text`]); [`message`] prints an error with
//! [`FLAGS`], so `h_over_dx = 0 is out of range` reads `--h = 0 is out of range`. An error in a
//! file the user wrote (a scene) already names what the user typed: [`InFile`] keeps its field
//! names and maps only the budget's.

use sphstab::error::Error;

/// Field → flag. A field not listed is printed as it is (a JSON key of a scene or config).
pub const FLAGS: &[(&str, &str)] = &[
    ("alpha_s", "--alpha-s"),
    ("amplitude", "--amplitude"),
    ("art_eps", "--art-eps"),
    ("art_n", "--art-n"),
    ("av", "--av"),
    ("av_alpha", "--av-alpha"),
    ("av_beta", "--av-beta"),
    ("boundary_density", "--boundary-density"),
    ("box", "--box"),
    ("c_partition", "--c"),
    ("delta", "--delta"),
    ("delta_form", "--delta-form"),
    ("density_ratio", "--density-ratio"),
    ("dim", "--dim"),
    ("dpi", "--dpi"),
    ("dt", "--dt"),
    ("edge_width", "--edge-width"),
    ("eps", "--eps"),
    ("euler_every", "--euler-every"),
    ("form", "--form"),
    ("formats", "--format"),
    ("forms", "--forms"),
    ("function", "--function"),
    ("gamma", "--gamma"),
    ("grid", "--grid"),
    ("h", "--h"),
    ("h_max", "--h-max"),
    ("h_min", "--h-min"),
    ("h_over_dx", "--h"),
    ("h_points", "--h-points"),
    ("h_step", "--h-step"),
    ("hourglass", "--hourglass"),
    ("integrator", "--integrator"),
    ("integrators", "--integrators"),
    ("interval", "--interval"),
    ("kappas", "--kappas"),
    ("kick", "--kick"),
    ("kernels", "--kernels"),
    ("lattice", "--lattice"),
    ("lattices", "--lattices"),
    ("material", "--material"),
    ("max_memory", "--max-memory"),
    ("max_steps", "--max-steps"),
    ("n", "--n"),
    ("nodes", "--body"),
    ("particles", "--particles"),
    ("points", "--points"),
    ("plane", "--plane"),
    ("poisson", "--poisson"),
    ("prestress", "--prestress"),
    ("quadrature", "--quadrature"),
    ("rate", "--rate"),
    ("repeats", "--repeats"),
    ("runs", "--runs"),
    ("safety", "--safety"),
    ("shape", "--shape"),
    ("shard", "--shard"),
    ("size", "--size"),
    ("skin", "--skin"),
    ("sizes", "--sizes"),
    ("steps", "--steps"),
    ("stress", "--stress"),
    ("stress_points", "--stress-points"),
    ("stress_range[0]", "--stress-min"),
    ("stress_range[1]", "--stress-max"),
    ("stresses", "--stresses"),
    ("support", "--support"),
    ("t_end", "--t-end"),
    ("threads", "--threads"),
    ("until_window", "--until-window"),
    ("verify", "--verify"),
    ("viscosity", "--viscosity"),
];

/// The flag of `field` (the field itself when no flag sets it).
pub fn flag(field: &'static str) -> &'static str {
    FLAGS
        .iter()
        .find(|(f, _)| *f == field)
        .map_or(field, |(_, flag)| flag)
}

/// The budget's fields by their flags, every other field by its name.
fn budget_flag(field: &'static str) -> &'static str {
    match field {
        "max_memory" | "max_steps" => flag(field),
        f => f,
    }
}

/// An error in a file the user wrote (a scene): printed with the file's field names.
#[derive(Debug)]
pub struct InFile(pub Error);

impl std::fmt::Display for InFile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0.render(&budget_flag))
    }
}

impl std::error::Error for InFile {}

/// A library error in which one field was given by another flag than its own (`grid` as
/// `--points` in 1D): printed with that flag.
#[derive(Debug)]
pub struct Alias {
    /// The error.
    pub error: Error,
    /// The field …
    pub field: &'static str,
    /// … and the flag the user gave it by.
    pub flag: &'static str,
}

impl std::fmt::Display for Alias {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.error.render(&|x| {
            if x == self.field { self.flag } else { flag(x) }
        }))
    }
}

impl std::error::Error for Alias {}

/// `e` naming `field` as `flag` when the user gave it so (`given`), else as usual.
pub fn alias(e: Error, field: &'static str, flag: &'static str, given: bool) -> anyhow::Error {
    if given {
        Alias {
            error: e,
            field,
            flag,
        }
        .into()
    } else {
        e.into()
    }
}

/// The library error in `e`'s chain, if any.
fn library_error<'a>(e: &'a (dyn std::error::Error + 'static)) -> Option<&'a Error> {
    e.downcast_ref::<Error>()
        .or_else(|| e.downcast_ref::<InFile>().map(|i| &i.0))
        .or_else(|| e.downcast_ref::<Alias>().map(|a| &a.error))
}

/// The one-line message of `e` and its causes (`outer: inner`), library errors naming flags.
pub fn message(e: &anyhow::Error) -> String {
    e.chain()
        .map(|c| match c.downcast_ref::<Error>() {
            Some(l) => l.render(&flag),
            None => c.to_string(),
        })
        .collect::<Vec<_>>()
        .join(": ")
        .replace('\n', " ")
}

/// Whether `e` is a time integration that blew up (a result, not bad input).
pub fn diverged(e: &anyhow::Error) -> bool {
    e.chain()
        .any(|c| matches!(library_error(c), Some(Error::Diverged { .. })))
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    /// Every flag of the table is a flag of some command, and every field is listed once.
    #[test]
    fn every_flag_exists() {
        let cmd = crate::Cli::command();
        let mut longs: Vec<String> = cmd
            .get_arguments()
            .filter_map(|a| a.get_long().map(str::to_string))
            .collect();
        for sub in cmd.get_subcommands() {
            longs.extend(
                sub.get_arguments()
                    .filter_map(|a| a.get_long().map(str::to_string)),
            );
        }
        for (field, flag) in FLAGS {
            assert!(
                longs.iter().any(|l| format!("--{l}") == *flag),
                "{field} → {flag}: no such flag"
            );
            assert_eq!(
                FLAGS.iter().filter(|(f, _)| f == field).count(),
                1,
                "{field} listed twice"
            );
        }
    }

    #[test]
    fn messages_name_flags_and_files_keep_fields() {
        let e = Error::OutOfRange {
            field: "h_over_dx",
            value: 0.0,
            range: "must be positive".into(),
        };
        assert_eq!(
            message(&anyhow::Error::from(e.clone())),
            "--h = 0 is out of range: must be positive"
        );
        assert_eq!(
            message(&anyhow::Error::from(InFile(e))),
            "h_over_dx = 0 is out of range: must be positive"
        );
    }
}
