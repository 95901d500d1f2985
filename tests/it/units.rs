//! Issue 25, "Units and words": every JSON document names the unit of every dimensional field
//! in its `"units"` object (a field without one must be dimensionless: [`DIMENSIONLESS`]), the
//! same key has the same unit in every command, and a flag that sets Δt in Δx/c is `--dt` (the
//! CFL number is c Δt/h).

use crate::common::json;
use serde_json::Value;

/// Numeric keys that carry no unit: counts, indices, ratios, fractions, dimensionless
/// parameters (ε, δ, ν, γ, α, β, n), tolerances per step. `min`, `max` and `error_max` are the
/// entries of a scene's `stress`, which has the unit.
const DIMENSIONLESS: &[&str] = &[
    "period_error",
    "period_error_body",
    "energy_loss_per_period",
    "periods",
    "max_speed_ratio",
    "schema_version",
    "nodes",
    "displacement_error",
    "energy_error",
    "integrated_displacement_error",
    "integrated_energy_error",
    "displacement_rate",
    "energy_rate",
    "integrated_energy_rate",
    "max_plastic_strain",
    "dim",
    "grid",
    "points",
    "size",
    "steps",
    "step",
    "particles",
    "runs",
    "repeats",
    "threads",
    "samples",
    "euler_every",
    "art_n",
    "box_free_particles",
    "c_partition",
    "alpha_s",
    "poisson",
    "gamma",
    "square",
    "delta",
    "density_ratio",
    "art_eps",
    "av",
    "eps",
    "zeta",
    "n_h",
    "n_h_continuum",
    "zone_fraction",
    "longitudinal_fraction",
    "longitudinal",
    "vector",
    "max_amplification",
    "ratio",
    "ratio_box",
    "ratio_body",
    "ratio_infinite",
    "r2",
    "velocity_error_l2",
    "min",
    "max",
    "error_max",
    "max_asymmetry",
    "transverse_from",
    "computed",
    "skipped",
    "pairing_rows",
    "neighbours_per_particle",
    "allocations_per_step",
    "full_builds_per_step",
    "pair_refreshes_per_step",
    "scaling_exponent",
    "damping_ratio",
    "phase_error_10ppw",
    "phase_error_20ppw",
    "amplitude_error_10ppw",
    "amplitude_error_20ppw",
    "wave_l2_error",
    "order",
    "grid_2d",
    "kappa_points",
    "safety",
    "index",
    "total_cells",
    "kappas",
    "h_points",
    "stress_points",
    "evaluations_per_step",
    "rate_calls_per_step",
    "j",
    "k",
    "value",
    "reflected",
    "reflected_exact",
    "transmitted",
    "transmitted_exact",
    "ghosts",
];

/// Every number in `v` is under a key with a unit in `units` (its own or an enclosing one), or
/// under a dimensionless key.
fn check(args: &str, v: &Value, units: &serde_json::Map<String, Value>, key: &str, covered: bool) {
    match v {
        Value::Number(_) => assert!(
            covered || DIMENSIONLESS.contains(&key),
            "{args}: `{key}` holds a number but has no unit and is not listed as dimensionless"
        ),
        Value::Object(o) => {
            for (k, x) in o.iter().filter(|(k, _)| *k != "units") {
                check(args, x, units, k, covered || units.contains_key(k));
            }
        }
        Value::Array(a) => a.iter().for_each(|x| check(args, x, units, key, covered)),
        _ => {}
    }
}

/// The JSON of `args` with its units checked; returns the document.
fn doc(args: &[&str]) -> Value {
    let v = json(args);
    let units = v["units"]
        .as_object()
        .unwrap_or_else(|| panic!("{args:?}: no \"units\" object"))
        .clone();
    check(&args.join(" "), &v, &units, "", false);
    v
}

#[test]
fn every_json_output_names_its_units() {
    let cases = [
        "query --points 64 --dt 0.5 --json",
        "query --dim 2 --grid 8 --box 3 --json",
        "query --points 32 --vary h=1.2,2 --json",
        "dispersion --points 8 --av-alpha 1 --json",
        "dispersion --dim 2 --points 2 --json",
        "timestep --points 64 --av-alpha 1 --json",
        "timestep --points 64 --vary h=1.2,2 --json",
        "map --n 4 --json",
        "stiffness --theta 30 --points 2 --json",
        "galerkin --problem plate --methods mls,efg --levels 1,2 --json",
        "swegle --size 11 --t-end 2 --json",
        "simulate uniform-bar --json",
        "throughput --size 8 --steps 2 --repeats 1 --json",
        "pairing --kernels m4 --h-min 1 --h-max 1.2 --grid 4 --json",
        "art-stress --eps 0,0.3 --json",
        "tradeoff --forms classical --kernels m4 --h-points 1 --repeats 1 --json",
        "atlas --forms classical --kernels m4 --h-points 2 --stress-points 2 --kappas 16 --json",
        "kernels --table --kernels m4 --h-step 0.5 --json",
    ];
    for args in cases {
        doc(&args.split(' ').collect::<Vec<_>>());
    }
}

/// The same key has the same unit in every command: Δt in Δx/c, rates in c/Δx, lengths in Δx,
/// σ̄ = σ/C, the CFL number c Δt/h; a document with physical units says which.
#[test]
fn one_unit_per_quantity() {
    let q = doc(&["query", "--points", "64", "--stress", "-0.1", "--json"]);
    let t = doc(&["timestep", "--points", "64", "--json"]);
    for v in [&q, &t] {
        let u = &v["units"];
        assert_eq!(u["critical_dt"], "dx/c");
        assert_eq!(u["critical_cfl"], "c*dt/h");
        assert_eq!(u["h_over_dx"], "dx");
        assert_eq!(u["stress"], "sigma/C");
        // the CFL number is c Δt/h: critical_dt / (h/Δx)
        let cfl = v["critical_dt"].as_f64().unwrap() / v["h_over_dx"].as_f64().unwrap();
        assert_eq!(v["critical_cfl"].as_f64().unwrap(), cfl);
    }
    assert_eq!(q["units"]["max_growth_rate"], "c/dx");
    assert_eq!(t["units"]["omega_max"], "c/dx");
    let sw = doc(&["swegle", "--size", "11", "--t-end", "2", "--json"]);
    assert_eq!(sw["units"]["dt"], "dx/c");
    assert_eq!(sw["units"]["predicted_growth_rate_box"], "c/dx");
    assert_eq!(sw["units"]["dt_physical"], "time (test units)");
    assert_eq!(sw["dt"], 0.2);
    let f = |v: &Value, k: &str| v[k].as_f64().unwrap();
    assert_eq!(
        f(&sw, "dt_physical"),
        f(&sw, "dt") * f(&sw, "dx_physical") / f(&sw, "sound_speed_physical")
    );
    let sim = doc(&["simulate", "uniform-bar", "--json"]);
    assert_eq!(sim["units"]["t"], "s");
    assert_eq!(sim["units"]["stress"], "Pa");
    assert_eq!(sim["units"]["dt"], "dx/c");
    let dt = f(&sim, "dt_physical") * f(&sim, "sound_speed_physical") / f(&sim, "dx_physical");
    assert!((f(&sim, "dt") - dt).abs() < 1e-15, "{sim}");
    // an experiment of `hourglass` (normalised units; its oscillation stops early)
    let plate = doc(&["simulate", "analysis/scenes/plate-tlsph.json", "--json"]);
    assert_eq!(plate["units"]["period_theory"], "dx/c");
    assert_eq!(plate["units"]["first_peak_displacement"], "dx");
}

/// A flag or scene field that sets Δt in Δx/c is `dt`; `swegle --cfl` and a scene's `cfl`, the
/// old names of the same number, still read it.
#[test]
fn dt_is_the_time_step_and_cfl_its_old_name() {
    let run = |flag: &str| {
        json(&[
            "swegle", "--size", "11", "--t-end", "1", flag, "0.1", "--json",
        ])
    };
    let (new, old) = (run("--dt"), run("--cfl"));
    assert_eq!(new["dt"], 0.1);
    assert_eq!(new["steps"], old["steps"]);
    assert_eq!(new["max_velocity_end"], old["max_velocity_end"]);
    let dir = std::env::temp_dir().join(format!("sphstab-units-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = |key: &str| {
        let p = dir.join(format!("{key}.json"));
        // a bar at rest (nothing moves: only the step count and Δt matter here)
        let s = format!(
            r#"{{"name": "bar", "form": "nonlocal", "kernel": "m4", "h_over_dx": 1.3, "modulus": 2, "rho0": 8, "particles": 20, "origin": 0, "length": 1, "initial_velocity": {{"kind": "rest"}}, "t_end": 1, "{key}": 0.1}}"#
        );
        std::fs::write(&p, s).unwrap();
        json(&["simulate", p.to_str().unwrap(), "--json"])
    };
    let (new, old) = (scene("dt"), scene("cfl"));
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(new["steps"], old["steps"]);
    assert_eq!(new["dt_physical"], old["dt_physical"]);
    assert!((new["dt"].as_f64().unwrap() - 0.1).abs() < 1e-3, "{new}");
}
