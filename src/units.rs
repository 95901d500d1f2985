//! The units of every JSON output, in one place: [`TABLE`] names the unit of each dimensional
//! key a report can hold, and [`with_units`] (or [`json`]) adds to a document a `"units"` object
//! with the unit of every such key it contains (at any depth), so no command writes its units
//! by hand.
//!
//! The convention (the crate docs' "Conventions", `sphstab --help`): lengths in Δx (`dx`), times
//! and time steps in Δx/c (`dx/c`), growth rates and frequencies in c/Δx (`c/dx`), wave numbers
//! as κΔx (`1/dx`), stresses as σ̄ = σ/C (`sigma/C`, positive in tension), speeds in c. The CFL
//! number is c Δt/h (`c*dt/h`, h in the kernel's own convention). A document with physical units
//! (a `simulate` scene in SI, the Swegle test in its own units) names them in [`System`]: its
//! measured values (`t`, `stress`, `max_velocity`, the fit's `rate` and `window`, …) and every
//! key ending in `_physical` are in those units, everything else is normalised.

use serde_json::{Map, Value};

/// What a number measures: its normalised unit, and its physical one in a document that has
/// physical units.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Dim {
    Time,
    Rate,
    Length,
    Speed,
    Stress,
}

impl Dim {
    fn normalised(self) -> &'static str {
        match self {
            Dim::Time => DT,
            Dim::Rate => RATE,
            Dim::Length => LENGTH,
            Dim::Speed => "c",
            Dim::Stress => STRESS,
        }
    }
}

/// The unit of a key.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Unit {
    /// The same in every document.
    Fixed(&'static str),
    /// In the document's physical units (a key ending in `_physical`).
    Physical(Dim),
    /// A value a run measures: physical in a document with physical units, else normalised.
    Run(Dim),
}

/// Time and time step: Δx/c.
pub const DT: &str = "dx/c";
/// Growth rate, frequency, decay rate: c/Δx.
pub const RATE: &str = "c/dx";
/// Length (h, support, spacing): Δx.
pub const LENGTH: &str = "dx";
/// Stress σ̄ = σ/C, positive in tension.
pub const STRESS: &str = "sigma/C";
/// A wave number κ, given as κΔx.
const WAVE: &str = "1/dx";
/// ω² Δx²/c².
const OMEGA2: &str = "(c/dx)^2";
/// The argument of `interpolate`'s test function (its interval's units).
const ARG: &str = "argument";
/// Wall-clock seconds.
const WALL: &str = "s (wall clock)";

use Unit::{Fixed, Physical, Run};

/// Every dimensional key of the reports, with its unit (dimensionless keys — ratios, fractions,
/// counts, ε, δ, ν — have none). A key means one quantity in every report.
const TABLE: &[(&str, Unit)] = &[
    // time steps (Δx/c)
    ("dt", Fixed(DT)),
    ("critical_dt", Fixed(DT)),
    ("critical_dt_closed_form", Fixed(DT)),
    ("critical_dt_from_omega_max", Fixed(DT)),
    ("critical_dt_eq120", Fixed(DT)),
    ("critical_dt_inviscid", Fixed(DT)),
    ("spurious_growth_dt", Fixed(DT)),
    ("predicted_dt", Fixed(DT)),
    ("predicted_dt_at_resolution", Fixed(DT)),
    ("inviscid_dt", Fixed(DT)),
    ("measured_dt", Fixed(DT)),
    ("dt_used", Fixed(DT)),
    // the CFL number
    ("critical_cfl", Fixed("c*dt/h")),
    // growth rates, frequencies, decay rates (c/Δx)
    ("growth", Fixed(RATE)),
    ("growth_rate", Fixed(RATE)),
    ("growth_tol", Fixed(RATE)),
    ("max_growth_rate", Fixed(RATE)),
    ("spurious_growth_rate", Fixed(RATE)),
    ("physical_growth_rate", Fixed(RATE)),
    ("allowed_growth_rate", Fixed(RATE)),
    ("box_growth_rate", Fixed(RATE)),
    ("weak_growth_rate", Fixed(RATE)),
    ("omega_max", Fixed(RATE)),
    ("omega_dx_over_c", Fixed(RATE)),
    ("decay_rate_max", Fixed(RATE)),
    ("damping_rate", Fixed(RATE)),
    ("measured_growth_rate", Fixed(RATE)),
    ("predicted_growth_rate_box", Fixed(RATE)),
    ("predicted_growth_rate_body", Fixed(RATE)),
    ("predicted_growth_rate_infinite", Fixed(RATE)),
    ("pairing_growth_rate", Fixed(RATE)),
    ("transverse_growth_rate", Fixed(RATE)),
    ("max_pairing_growth", Fixed(RATE)),
    ("growth_at_reference", Fixed(RATE)),
    ("infinite", Fixed(RATE)),
    ("in_box", Fixed(RATE)),
    ("measured", Fixed(RATE)),
    ("predicted_box", Fixed(RATE)),
    ("min_infinite", Fixed("[eps, c/dx]")),
    ("min_box", Fixed("[eps, c/dx]")),
    // ω²
    ("omega2", Fixed(OMEGA2)),
    ("omega2_continuum", Fixed(OMEGA2)),
    ("omega2_max", Fixed(OMEGA2)),
    ("unstressed_omega2", Fixed(OMEGA2)),
    // wave numbers (κΔx) and the path coordinate of a dispersion curve
    ("kappa", Fixed(WAVE)),
    ("kappa_dx", Fixed(WAVE)),
    ("kappa_at_max", Fixed(WAVE)),
    ("kappa_min", Fixed(WAVE)),
    ("kappa_max", Fixed(WAVE)),
    ("pole_at", Fixed(WAVE)),
    ("box_kappa", Fixed(WAVE)),
    ("kx", Fixed(WAVE)),
    ("ky", Fixed(WAVE)),
    ("path", Fixed(WAVE)),
    ("labels", Fixed("[point, 1/dx]")),
    ("predicted_kappa_box", Fixed(WAVE)),
    ("dominant_kappa", Fixed("[1/dx per axis, power share]")),
    ("infinite_kappa", Fixed(WAVE)),
    ("pairing_kappa", Fixed(WAVE)),
    ("transverse_kappa", Fixed(WAVE)),
    ("wstar_first_negative_kdx", Fixed(WAVE)),
    ("kappa_abs_over_pi", Fixed("pi/dx")),
    ("k_at_min", Fixed("1/h")),
    ("first_negative_k", Fixed("1/h")),
    ("k_max", Fixed("1/h")),
    ("wstar_k_max", Fixed("1/h")),
    // `stiffness --body`: a finite body's largest eigenvalue
    ("lambda_max_lumped", Fixed(OMEGA2)),
    ("lambda_max_consistent", Fixed(OMEGA2)),
    ("critical_dt_lumped", Fixed(DT)),
    ("d_max", Fixed(LENGTH)),
    ("bounds", Fixed("[name, (c/dx)^2]")),
    // `galerkin`: lengths in the units of [B98]'s problems (E = 1000, unit load)
    ("node_spacing", Fixed("length (B98's units)")),
    ("probe", Fixed("length (B98's units)")),
    ("probe_displacement", Fixed("length (B98's units)")),
    ("exact_probe_displacement", Fixed("length (B98's units)")),
    // `interpolate`: the test function's argument, and its derivatives
    ("interval", Fixed(ARG)),
    ("spacing", Fixed(ARG)),
    ("position", Fixed(ARG)),
    ("gradient_x", Fixed("1/argument")),
    ("gradient_x_approx", Fixed("1/argument")),
    ("laplacian_exact", Fixed("1/argument^2")),
    ("laplacian_approx", Fixed("1/argument^2")),
    ("gradient_peak_width", Fixed(LENGTH)),
    // lengths (Δx)
    ("h", Fixed(LENGTH)),
    ("h_over_dx", Fixed(LENGTH)),
    ("h_values", Fixed(LENGTH)),
    ("h_max_computed", Fixed(LENGTH)),
    ("support_over_dx", Fixed(LENGTH)),
    ("nearest_neighbour_over_dx", Fixed(LENGTH)),
    ("customary_h", Fixed(LENGTH)),
    ("h_step", Fixed(LENGTH)),
    ("scan_h", Fixed(LENGTH)),
    ("max_support_2d", Fixed(LENGTH)),
    // the h/Δx intervals of the kernel guide
    ("from", Fixed(LENGTH)),
    ("to", Fixed(LENGTH)),
    ("first_growth", Fixed("[dx, neighbours]")),
    ("first_pairing", Fixed("[dx, neighbours]")),
    // stresses σ̄ = σ/C
    ("stress", Run(Dim::Stress)),
    ("stresses", Fixed(STRESS)),
    ("stress_range", Fixed(STRESS)),
    ("compression_stress", Fixed(STRESS)),
    ("onset", Fixed(STRESS)),
    ("last_stable", Fixed(STRESS)),
    ("sigma_bar", Fixed(STRESS)),
    ("max_stable_tension", Fixed(STRESS)),
    ("onset_stress", Fixed(STRESS)),
    // speeds
    ("max_speed_end", Fixed("c")),
    ("amplitude", Fixed("c")),
    // what a run with physical units measures
    ("t", Run(Dim::Time)),
    ("window", Run(Dim::Time)),
    ("rate", Run(Dim::Rate)),
    ("max_velocity", Run(Dim::Speed)),
    // a scene's probes
    ("probe_t", Run(Dim::Time)),
    ("extent_t", Run(Dim::Time)),
    ("extent_length", Run(Dim::Length)),
    ("extent_radius", Run(Dim::Length)),
    ("reference_position", Run(Dim::Length)),
    ("across", Run(Dim::Length)),
    ("displacement", Run(Dim::Length)),
    ("velocity", Run(Dim::Speed)),
    ("exact_velocity", Run(Dim::Speed)),
    ("exact_stress", Run(Dim::Stress)),
    ("max_velocity_end", Run(Dim::Speed)),
    // the oscillation of an experiment of `hourglass`
    ("mode_velocity", Run(Dim::Speed)),
    ("period", Run(Dim::Time)),
    ("period_theory", Run(Dim::Time)),
    ("period_body", Run(Dim::Time)),
    ("departed_at", Run(Dim::Time)),
    ("stopped_at", Run(Dim::Time)),
    ("first_peak_displacement", Run(Dim::Length)),
    // the physical scales of a run with physical units
    ("dt_physical", Physical(Dim::Time)),
    ("t_end_physical", Physical(Dim::Time)),
    ("dx_physical", Physical(Dim::Length)),
    ("sound_speed_physical", Physical(Dim::Speed)),
    ("modulus_physical", Physical(Dim::Stress)),
    // cost
    ("runtime_s", Fixed(WALL)),
    ("seconds_per_step", Fixed(WALL)),
    ("seconds_per_step_repeats", Fixed(WALL)),
    (
        "ns_per_particle_step",
        Fixed("ns (wall clock) per particle-step"),
    ),
    (
        "ns_per_evaluation",
        Fixed("ns (wall clock) per rate evaluation"),
    ),
    (
        "ns_per_particle_time",
        Fixed("ns (wall clock) per particle per dx/c of simulated time"),
    ),
    ("particle_steps_per_second", Fixed("1/s (wall clock)")),
    ("bytes_per_particle", Fixed("bytes")),
    ("state_bytes_per_particle", Fixed("bytes")),
];

/// The physical units of a document.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum System {
    /// Normalised units only (the analysis, the studies).
    Normalised,
    /// A `simulate` scene: SI (s, m, m/s, Pa).
    Si,
    /// The Swegle test in its own units (Δx = 0.1, c = √(K/ρ0) ≈ 0.495).
    SwegleTest,
}

impl System {
    /// The physical unit of `d` (the normalised one for [`System::Normalised`]).
    fn physical(self, d: Dim) -> &'static str {
        match (self, d) {
            (System::Normalised, d) => d.normalised(),
            (System::Si, Dim::Time) => "s",
            (System::Si, Dim::Rate) => "1/s",
            (System::Si, Dim::Length) => "m",
            (System::Si, Dim::Speed) => "m/s",
            (System::Si, Dim::Stress) => "Pa",
            (System::SwegleTest, Dim::Time) => "time (test units)",
            (System::SwegleTest, Dim::Rate) => "1/time (test units)",
            (System::SwegleTest, Dim::Length) => "length (test units)",
            (System::SwegleTest, Dim::Speed) => "length/time (test units)",
            (System::SwegleTest, Dim::Stress) => "stress (test units)",
        }
    }

    /// The unit of `key` in a document of this system, if it has one.
    fn unit(self, key: &str) -> Option<&'static str> {
        let (_, u) = TABLE.iter().find(|(k, _)| *k == key)?;
        Some(match *u {
            Fixed(s) => s,
            Physical(d) | Run(d) => self.physical(d),
        })
    }
}

/// Whether `v` holds a number (at any depth): strings, booleans and nulls have no unit.
fn has_number(v: &Value) -> bool {
    match v {
        Value::Number(_) => true,
        Value::Array(a) => a.iter().any(has_number),
        Value::Object(o) => o.values().any(has_number),
        _ => false,
    }
}

/// Collects the unit of every key of `v` (at any depth) that holds a number and has one.
fn collect(v: &Value, system: System, out: &mut Map<String, Value>) {
    match v {
        Value::Object(o) => {
            for (k, x) in o {
                if has_number(x)
                    && let Some(u) = system.unit(k)
                {
                    out.entry(k.clone()).or_insert_with(|| u.into());
                }
                collect(x, system, out);
            }
        }
        Value::Array(a) => a.iter().for_each(|x| collect(x, system, out)),
        _ => {}
    }
}

/// The `"units"` object of `doc`: the unit of every dimensional key it contains.
pub fn of(doc: &Value, system: System) -> Map<String, Value> {
    let mut out = Map::new();
    collect(doc, system, &mut out);
    out
}

/// A document with its `"units"` object, written after the document's own fields, which keep
/// their order ([`with_units`]).
pub struct WithUnits<'a, T> {
    value: &'a T,
    /// None: the document is not a JSON object (a list of dimensionless rows): written as it is.
    units: Option<Map<String, Value>>,
}

/// The fields of `value`, then `"units"`.
#[derive(serde::Serialize)]
struct Flat<'a, T> {
    #[serde(flatten)]
    value: &'a T,
    units: &'a Map<String, Value>,
}

impl<T: serde::Serialize> serde::Serialize for WithUnits<'_, T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match &self.units {
            Some(units) => Flat {
                value: self.value,
                units,
            }
            .serialize(s),
            None => self.value.serialize(s),
        }
    }
}

/// `value` with the `"units"` of the keys it contains.
pub fn with_units<T: serde::Serialize>(
    value: &T,
    system: System,
) -> serde_json::Result<WithUnits<'_, T>> {
    let doc = serde_json::to_value(value)?;
    Ok(WithUnits {
        value,
        units: doc.is_object().then(|| of(&doc, system)),
    })
}

/// `value` serialised with its `"units"`: pretty-printed or on one line.
pub fn json<T: serde::Serialize>(
    value: &T,
    system: System,
    pretty: bool,
) -> serde_json::Result<String> {
    let doc = with_units(value, system)?;
    Ok(if pretty {
        serde_json::to_string_pretty(&doc)?
    } else {
        serde_json::to_string(&doc)?
    })
}

/// A physical value with its normalised one: `0.0404 time units (0.2 Δx/c)`.
pub fn both(physical: f64, unit: &str, normalised: f64, normalised_unit: &str) -> String {
    format!(
        "{} {unit} ({} {normalised_unit})",
        crate::display::num_sig(physical, 4),
        crate::display::num_sig(normalised, 4)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn every_key_is_listed_once() {
        for (k, _) in TABLE {
            assert_eq!(TABLE.iter().filter(|(x, _)| x == k).count(), 1, "{k}");
        }
    }

    #[test]
    fn units_of_nested_keys_and_physical_documents() {
        let doc = json!({
            "stress": 0.01, "form": "classical", "rate": "jaumann", "critical_dt": null,
            "instabilities": [{"growth_rate": 0.1, "kappa_at_max": [3.0]}],
            "series": [{"timestep": {"critical_dt": 2.2}}]
        });
        let u = of(&doc, System::Normalised);
        assert_eq!(u["stress"], "sigma/C");
        assert_eq!(u["growth_rate"], "c/dx");
        assert_eq!(u["kappa_at_max"], "1/dx");
        assert_eq!(u["critical_dt"], "dx/c");
        assert!(!u.contains_key("rate") && !u.contains_key("form"));
        let sim = of(
            &json!({"t": 1.0, "stress": {"min": 1.0}, "dt": 0.2, "dt_physical": 1e-6}),
            System::Si,
        );
        assert_eq!(sim["t"], "s");
        assert_eq!(sim["stress"], "Pa");
        assert_eq!(sim["dt"], "dx/c");
        assert_eq!(sim["dt_physical"], "s");
        assert_eq!(
            json(&json!([1, 2]), System::Normalised, false).unwrap(),
            "[1,2]"
        );
        // the document's fields keep their order, "units" comes last
        #[derive(serde::Serialize)]
        struct R {
            z: f64,
            critical_dt: f64,
        }
        let text = json(
            &R {
                z: 1.0,
                critical_dt: 2.0,
            },
            System::Normalised,
            false,
        )
        .unwrap();
        assert_eq!(
            text,
            r#"{"z":1.0,"critical_dt":2.0,"units":{"critical_dt":"dx/c"}}"#
        );
    }
}
