//! The Python extension `sphstab._sphstab`: the library's questions by name, answered as the
//! CLI answers them (the same [`sphstab::analysis::QuerySpec`], the same JSON document with its
//! units). The Python package `sphstab` wraps these functions (keyword arguments, dicts, numpy
//! arrays); errors are `ValueError` with the CLI's one-line message, the fields named as the
//! keyword arguments.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use sphstab::analysis::QuerySpec;
use sphstab::budget::Budget;
use sphstab::error::Error;
use sphstab::units::{self, System};

/// Field → keyword argument (a field not listed is its own name).
const KWARGS: &[(&str, &str)] = &[("c_partition", "c"), ("h_over_dx", "h")];

fn kwarg(field: &'static str) -> &'static str {
    KWARGS
        .iter()
        .find(|(f, _)| *f == field)
        .map_or(field, |(_, k)| k)
}

fn value_error(e: Error) -> PyErr {
    PyValueError::new_err(e.render(&kwarg))
}

/// A keyword argument serde refused (unknown name, wrong type), without its JSON position.
fn json_error(e: serde_json::Error) -> PyErr {
    let msg = e.to_string();
    let msg = msg.split(" at line ").next().unwrap_or(&msg);
    PyValueError::new_err(msg.replacen("unknown field", "unknown keyword argument", 1))
}

/// The question of `spec` (a JSON object of keyword arguments), integrator `integrator`.
fn spec_of(spec: &str) -> PyResult<QuerySpec> {
    serde_json::from_str(spec).map_err(json_error)
}

fn integrator(name: &str) -> PyResult<sphstab::integrator::Integrator> {
    sphstab::integrator::Integrator::from_name(name, sphstab::integrator::DEFAULT_EULER_EVERY)
        .map_err(value_error)
}

fn query_in<const D: usize>(spec: &QuerySpec, integ: &str) -> PyResult<String> {
    let mut q = spec.query::<D>(&Budget::default()).map_err(value_error)?;
    q.integrator = integrator(integ)?;
    let r = sphstab::analysis::query(&q).map_err(value_error)?;
    units::json(&r, System::Normalised, true).map_err(json_error)
}

/// `sphstab query --json` for the keyword arguments in `spec` (JSON): the same document.
#[pyfunction]
fn query_json(py: Python<'_>, spec: &str, integrator: &str) -> PyResult<String> {
    let s = spec_of(spec)?;
    let dim = s.dim().map_err(value_error)?;
    py.allow_threads(|| match dim {
        1 => query_in::<1>(&s, integrator),
        2 => query_in::<2>(&s, integrator),
        _ => query_in::<3>(&s, integrator),
    })
}

fn dispersion_in<const D: usize>(spec: &QuerySpec, points: usize) -> PyResult<String> {
    let q = spec.query::<D>(&Budget::default()).map_err(value_error)?;
    let r = sphstab::analysis::dispersion(&q, points).map_err(value_error)?;
    units::json(&r, System::Normalised, true).map_err(json_error)
}

/// `sphstab dispersion --json --points POINTS` for the keyword arguments in `spec` (JSON).
#[pyfunction]
fn dispersion_json(py: Python<'_>, spec: &str, points: i64) -> PyResult<String> {
    // a negative count is a ValueError like any other (the library checks the range)
    let points = usize::try_from(points).map_err(|_| {
        value_error(Error::OutOfRange {
            field: "points",
            value: points as f64,
            range: "must be a non-negative integer".into(),
        })
    })?;
    let s = spec_of(spec)?;
    if s.grid.is_some() {
        return Err(PyValueError::new_err(
            "grid does not apply with dispersion (it samples the high-symmetry path: use points)",
        ));
    }
    let dim = s.dim().map_err(value_error)?;
    py.allow_threads(|| match dim {
        1 => dispersion_in::<1>(&s, points),
        2 => dispersion_in::<2>(&s, points),
        _ => dispersion_in::<3>(&s, points),
    })
}

/// `sphstab kernels --json`: the kernel table.
#[pyfunction]
fn kernels_json() -> PyResult<String> {
    serde_json::to_string_pretty(&sphstab::kernel::table()).map_err(json_error)
}

/// The extension module.
#[pymodule]
fn _sphstab(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(query_json, m)?)?;
    m.add_function(wrap_pyfunction!(dispersion_json, m)?)?;
    m.add_function(wrap_pyfunction!(kernels_json, m)?)?;
    Ok(())
}
