//! The Python extension `sphstab._sphstab`: the library's questions by name, answered as the
//! CLI answers them (the same [`QuerySpec`] and [`SwegleSpec`], the same JSON documents with
//! their units). The Python package `sphstab` wraps these functions (keyword arguments, dicts,
//! numpy arrays); errors are `ValueError` with the CLI's one-line message, the fields named as
//! the keyword arguments. Every computation runs without the GIL; the long ones (a map, a Swegle
//! run, a scene, the time-domain Δt check) run on a worker thread while the calling thread
//! watches for Ctrl-C, and stop at their next step or row when it comes.

use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::{Map, Value};
use sphstab::analysis::QuerySpec;
use sphstab::analysis::spec::Command;
use sphstab::budget::Budget;
use sphstab::error::Error;
use sphstab::forms::State;
use sphstab::progress::Progress;
use sphstab::solver::output::FinalState;
use sphstab::studies::swegle::SwegleSpec;
use sphstab::units::{self, System};
use std::sync::atomic::{AtomicBool, Ordering};

/// Field → keyword argument (a field not listed is its own name).
const KWARGS: &[(&str, &str)] = &[("c_partition", "c"), ("h_over_dx", "h")];

fn kwarg(field: &'static str) -> &'static str {
    KWARGS
        .iter()
        .find(|(f, _)| *f == field)
        .map_or(field, |(_, k)| k)
}

fn value_error(e: Error) -> PyErr {
    match e {
        Error::Cancelled => pyo3::exceptions::PyKeyboardInterrupt::new_err("cancelled"),
        e => PyValueError::new_err(e.render(&kwarg)),
    }
}

/// A scene's error: its fields are the JSON keys the user wrote, printed as they are.
fn scene_error(e: Error) -> PyErr {
    if let Error::Cancelled = e {
        return value_error(e);
    }
    PyValueError::new_err(e.render(&|f| f))
}

/// A keyword argument serde refused (unknown name, wrong type), without its JSON position.
fn json_error(e: serde_json::Error) -> PyErr {
    PyValueError::new_err(json_message(&e))
}

fn json_message(e: &serde_json::Error) -> String {
    let msg = e.to_string();
    let msg = msg.split(" at line ").next().unwrap_or(&msg);
    msg.replacen("unknown field", "unknown keyword argument", 1)
}

/// The keyword arguments (a JSON object) without the ones a function takes itself, which it
/// reads with [`Kwargs::take`]; the rest become a [`QuerySpec`] or [`SwegleSpec`].
struct Kwargs(Map<String, Value>, Vec<&'static str>);

impl Kwargs {
    fn parse(json: &str) -> PyResult<Self> {
        match serde_json::from_str(json).map_err(json_error)? {
            Value::Object(m) => Ok(Self(m, Vec::new())),
            _ => Err(PyValueError::new_err("keyword arguments must be a mapping")),
        }
    }

    /// Removes `key` and reads it as `T` (None when absent or null).
    fn take<T: serde::de::DeserializeOwned>(&mut self, key: &'static str) -> PyResult<Option<T>> {
        self.1.push(key);
        match self.0.remove(key) {
            None | Some(Value::Null) => Ok(None),
            Some(v) => serde_json::from_value(v)
                .map(Some)
                .map_err(|e| PyValueError::new_err(format!("{key}: {e}"))),
        }
    }

    /// The budget: the machine's default (as the CLI's), with `max_memory` (bytes, or a string
    /// with a K/M/G/T suffix) and `max_steps` (particle-steps) if given.
    fn budget(&mut self) -> PyResult<Budget> {
        let mut b = Budget::for_machine();
        let text = |v: Value| match v {
            Value::String(s) => s,
            v => v.to_string(),
        };
        if let Some(v) = self.take::<Value>("max_memory")? {
            b.max_memory = sphstab::budget::parse_bytes(&text(v))
                .map_err(|e| PyValueError::new_err(format!("max_memory: {e}")))?;
        }
        if let Some(v) = self.take::<Value>("max_steps")? {
            b.max_steps = sphstab::budget::parse_steps(&text(v))
                .map_err(|e| PyValueError::new_err(format!("max_steps: {e}")))?;
        }
        Ok(b)
    }

    /// The time integrator of `integrator` and `euler_every` (default kdk).
    fn integrator(&mut self) -> PyResult<sphstab::integrator::Integrator> {
        let name: Option<String> = self.take("integrator")?;
        let every: Option<usize> = self.take("euler_every")?;
        sphstab::integrator::Integrator::by_names(name.as_deref(), every).map_err(value_error)
    }

    /// The remaining keyword arguments as `T` (an unknown one is an error naming it).
    /// An unknown keyword's message lists the function's own arguments too.
    fn rest<T: serde::de::DeserializeOwned>(self) -> PyResult<T> {
        serde_json::from_value(Value::Object(self.0)).map_err(|e| {
            let msg = json_message(&e);
            let own: Vec<String> = self.1.iter().map(|k| format!("`{k}`")).collect();
            match msg.starts_with("unknown keyword argument") && !own.is_empty() {
                true => PyValueError::new_err(format!("{msg}, {}", own.join(", "))),
                false => PyValueError::new_err(msg),
            }
        })
    }
}

/// The solver's view of an interruption ([`sphstab::progress::interrupt`]): its time loops and
/// studies ask [`Progress::cancelled`] between steps; the analysis checks per wave vector.
#[derive(Clone, Copy, Default)]
struct Cancel;

impl Progress for Cancel {
    fn advance(&self, _fraction: f64) {}
    fn cancelled(&self) -> bool {
        sphstab::progress::interrupted().is_err()
    }
}

/// Runs `work` on a worker thread without the GIL while this thread checks for signals every
/// few milliseconds; on Ctrl-C (a signal handler raising) the computation is interrupted
/// ([`sphstab::progress::interrupt`]: it stops at its next wave vector, time step or row), and
/// the handler's exception (KeyboardInterrupt) is raised once it has stopped.
fn interruptible<T: Send>(
    py: Python<'_>,
    render: fn(Error) -> PyErr,
    work: impl FnOnce(Cancel) -> sphstab::error::Result<T> + Send,
) -> PyResult<T> {
    let _running = sphstab::progress::Interruptible::new();
    let finished = AtomicBool::new(false);
    let out = std::thread::scope(|s| {
        let worker = {
            let finished = &finished;
            s.spawn(move || {
                let r = work(Cancel);
                finished.store(true, Ordering::Release);
                r
            })
        };
        let mut raised = None;
        let mut wait = std::time::Duration::from_micros(200);
        while !finished.load(Ordering::Acquire) {
            py.allow_threads(|| {
                let t = std::time::Instant::now();
                while !finished.load(Ordering::Acquire) && t.elapsed() < wait {
                    std::thread::sleep(std::time::Duration::from_micros(100));
                }
            });
            wait = (wait * 2).min(std::time::Duration::from_millis(20));
            if raised.is_none()
                && let Err(e) = py.check_signals()
            {
                sphstab::progress::interrupt();
                raised = Some(e);
            }
        }
        let r = worker.join();
        (r, raised)
    });
    match out {
        (_, Some(e)) => Err(e),
        (Ok(r), None) => r.map_err(render),
        (Err(_), None) => Err(PyRuntimeError::new_err("sphstab: the computation panicked")),
    }
}

fn spec_dim(spec: &QuerySpec) -> PyResult<u8> {
    spec.dim().map_err(value_error)
}

/// A report as the CLI prints it with `--json` in the normalised units.
fn normalised<T: serde::Serialize>(r: &T) -> PyResult<String> {
    units::json(r, System::Normalised, true).map_err(json_error)
}

fn query_in<const D: usize>(
    spec: &QuerySpec,
    integ: sphstab::integrator::Integrator,
    budget: &Budget,
) -> sphstab::error::Result<sphstab::analysis::QueryReport> {
    let mut q = spec.query::<D>(budget)?;
    q.integrator = integ;
    sphstab::analysis::query(&q)
}

/// `sphstab query --json` for the keyword arguments in `kwargs` (JSON): the same document.
#[pyfunction]
fn query_json(py: Python<'_>, kwargs: &str) -> PyResult<String> {
    let mut kw = Kwargs::parse(kwargs)?;
    let budget = kw.budget()?;
    let integ = kw.integrator()?;
    let s: QuerySpec = kw.rest()?;
    s.check_for(Command::Query).map_err(value_error)?;
    let dim = spec_dim(&s)?;
    let r = interruptible(py, value_error, |_| match dim {
        1 => query_in::<1>(&s, integ, &budget),
        2 => query_in::<2>(&s, integ, &budget),
        _ => query_in::<3>(&s, integ, &budget),
    })?;
    normalised(&r)
}

/// The report and, if asked, the polarisations flattened `[point][branch][component]`.
type Dispersion = (
    sphstab::analysis::DispersionReport,
    Option<Vec<numpy::Complex64>>,
);

fn dispersion_in<const D: usize>(
    spec: &QuerySpec,
    points: usize,
    b: &Budget,
    eigenvectors: bool,
) -> sphstab::error::Result<Dispersion> {
    let q = spec.query::<D>(b)?;
    let r = sphstab::analysis::dispersion(&q, points)?;
    let modes = match eigenvectors {
        true => Some(
            sphstab::analysis::polarisations(&q, &r.kappa)?
                .into_iter()
                .flatten()
                .flatten()
                .collect(),
        ),
        false => None,
    };
    Ok((r, modes))
}

/// A count that must be a non-negative integer, as a ValueError naming `field` otherwise.
fn count(field: &'static str, v: Option<i64>, default: usize) -> PyResult<usize> {
    match v {
        None => Ok(default),
        Some(v) => usize::try_from(v).map_err(|_| {
            value_error(Error::OutOfRange {
                field,
                value: v as f64,
                range: "must be a non-negative integer".into(),
            })
        }),
    }
}

/// `sphstab dispersion --json` for the keyword arguments in `kwargs` (JSON, with `points`),
/// and with `eigenvectors` the unit polarisations of the branches at each point (complex,
/// points × D branches × D components).
#[pyfunction]
fn dispersion_json<'py>(
    py: Python<'py>,
    kwargs: &str,
) -> PyResult<(String, Option<Bound<'py, PyAny>>)> {
    let mut kw = Kwargs::parse(kwargs)?;
    let points = count("points", kw.take("points")?, 256)?;
    let eigenvectors = kw.take::<bool>("eigenvectors")?.unwrap_or(false);
    let budget = kw.budget()?;
    let s: QuerySpec = kw.rest()?;
    if s.grid.is_some() {
        return Err(PyValueError::new_err(
            "grid does not apply with dispersion (it samples the high-symmetry path: use points)",
        ));
    }
    s.check_for(Command::Dispersion).map_err(value_error)?;
    let dim = spec_dim(&s)?;
    let (r, modes) = interruptible(py, value_error, |_| match dim {
        1 => dispersion_in::<1>(&s, points, &budget, eigenvectors),
        2 => dispersion_in::<2>(&s, points, &budget, eigenvectors),
        _ => dispersion_in::<3>(&s, points, &budget, eigenvectors),
    })?;
    let doc = normalised(&r)?;
    let modes = match modes {
        Some(m) => {
            let d = dim as usize;
            let n = m.len() / (d * d);
            Some(PyArray1::from_vec(py, m).reshape([n, d, d])?.into_any())
        }
        None => None,
    };
    Ok((doc, modes))
}

/// What `timestep` asks: the question, and the time-domain check's viscosity pairs if asked.
struct TimestepAsk {
    spec: QuerySpec,
    integ: sphstab::integrator::Integrator,
    budget: Budget,
    verify: bool,
    viscosity: Option<String>,
}

/// The analysis' report, and the time-domain check's if `verify`.
type Timestep = (
    sphstab::analysis::TimestepReport,
    Option<sphstab::studies::stable_dt::StableDtReport>,
);

fn timestep_in<const D: usize>(
    a: &TimestepAsk,
    cancel: Cancel,
) -> sphstab::error::Result<Timestep> {
    let mut q = a.spec.query::<D>(&a.budget)?;
    q.integrator = a.integ;
    let pairs = sphstab::studies::stable_dt::viscosity_pairs(
        a.verify,
        a.viscosity.as_deref(),
        q.av.is_some(),
    )?;
    let r = sphstab::analysis::timestep(&q)?;
    let v = match a.verify {
        true => Some(sphstab::studies::stable_dt::stable_dt(&q, pairs, &cancel)?),
        false => None,
    };
    Ok((r, v))
}

/// `sphstab timestep --json` for the keyword arguments in `kwargs` (JSON, with `integrator`,
/// `euler_every`, `verify`, `viscosity`).
#[pyfunction]
fn timestep_json(py: Python<'_>, kwargs: &str) -> PyResult<String> {
    let mut kw = Kwargs::parse(kwargs)?;
    let budget = kw.budget()?;
    let integ = kw.integrator()?;
    let verify = kw.take::<bool>("verify")?.unwrap_or(false);
    let viscosity = kw.take::<String>("viscosity")?;
    let spec: QuerySpec = kw.rest()?;
    spec.check_for(Command::Timestep { verify })
        .map_err(value_error)?;
    let dim = spec_dim(&spec)?;
    let ask = TimestepAsk {
        spec,
        integ,
        budget,
        verify,
        viscosity,
    };
    let (r, verified) = interruptible(py, value_error, |cancel| match dim {
        1 => timestep_in::<1>(&ask, cancel),
        2 => timestep_in::<2>(&ask, cancel),
        _ => timestep_in::<3>(&ask, cancel),
    })?;
    let mut doc = serde_json::to_value(&r).map_err(json_error)?;
    if let (Some(v), Some(map)) = (verified, doc.as_object_mut()) {
        map.insert(
            "verify".into(),
            serde_json::to_value(v).map_err(json_error)?,
        );
    }
    normalised(&doc)
}

/// A 1D numpy array of `v`.
fn array1<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyAny> {
    PyArray1::from_vec(py, v).into_any()
}

/// A numpy array of shape `shape` holding `v` (row-major).
fn array<'py>(py: Python<'py>, v: Vec<f64>, shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, v).reshape(shape)?.into_any())
}

fn map_in<const D: usize>(
    spec: &QuerySpec,
    n: usize,
    plane: sphstab::analysis::Plane,
    budget: &Budget,
    cancel: Cancel,
) -> sphstab::error::Result<sphstab::analysis::GrowthMap> {
    let q = spec.query::<D>(budget)?;
    sphstab::analysis::growth_map(&q, n, plane, &cancel)
}

/// `sphstab map --json` for the keyword arguments in `kwargs` (JSON, with `n` and `plane`): the
/// document without its arrays, and the arrays `kx`, `ky` (n) and `growth` (n × n).
#[pyfunction]
fn map_json<'py>(py: Python<'py>, kwargs: &str) -> PyResult<(String, Bound<'py, PyDict>)> {
    use sphstab::analysis::Plane;
    let mut kw = Kwargs::parse(kwargs)?;
    let n = count("n", kw.take("n")?, 128)?;
    let plane: Option<String> = kw.take("plane")?;
    let budget = kw.budget()?;
    let spec: QuerySpec = kw.rest()?;
    let dim = spec.map_dim().map_err(value_error)?;
    let plane = match (dim, plane.as_deref()) {
        (2, Some(_)) => {
            return Err(value_error(sphstab::analysis::spec::not_applicable(
                sphstab::error::field("plane"),
                sphstab::error::field("dim") + " 2 (it is a 3D argument)",
            )));
        }
        (_, Some(p)) => Plane::by_name(p).map_err(value_error)?,
        (_, None) => Plane::Xy,
    };
    let spec = QuerySpec {
        dim: Some(dim),
        ..spec
    };
    let m = interruptible(py, value_error, |cancel| match dim {
        2 => map_in::<2>(&spec, n, plane, &budget, cancel),
        _ => map_in::<3>(&spec, n, plane, &budget, cancel),
    })?;
    let arrays = PyDict::new(py);
    let rows = m.growth.len();
    let growth: Vec<f64> = m.growth.iter().flatten().copied().collect();
    arrays.set_item("growth", array(py, growth, &[rows, rows])?)?;
    arrays.set_item("kx", array1(py, m.kx.clone()))?;
    arrays.set_item("ky", array1(py, m.ky.clone()))?;
    // the units of the whole document (the arrays' too), then the document without the arrays
    let mut doc = serde_json::to_value(&m).map_err(json_error)?;
    let u = units::of(&doc, System::Normalised);
    if let Some(o) = doc.as_object_mut() {
        for k in ["growth", "kx", "ky"] {
            o.remove(k);
        }
        o.insert("units".into(), Value::Object(u));
    }
    let doc = doc.to_string();
    Ok((doc, arrays))
}

/// The particles of `z` as arrays: positions and velocities (N × D), density (N, if carried),
/// stress σ and the local stress τ of the mixed forms (N × D × D, if carried).
fn particles<'py, const D: usize>(
    py: Python<'py>,
    z: &State<f64, D>,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let n = z.x.len();
    let vectors = |v: &[[f64; D]]| v.iter().flatten().copied().collect::<Vec<f64>>();
    out.set_item("positions", array(py, vectors(&z.x), &[n, D])?)?;
    out.set_item("velocities", array(py, vectors(&z.v), &[n, D])?)?;
    if !z.rho.is_empty() {
        out.set_item("density", array1(py, z.rho.clone()))?;
    }
    for (name, t) in [("stress", &z.sigma), ("local_stress", &z.tau)] {
        if !t.is_empty() {
            let flat: Vec<f64> = t.iter().flatten().flatten().copied().collect();
            out.set_item(name, array(py, flat, &[t.len(), D, D])?)?;
        }
    }
    Ok(out)
}

/// Named columns of a history (rows of `columns.len()` values) as 1D arrays.
fn history<'py>(
    py: Python<'py>,
    columns: &[&str],
    rows: impl Iterator<Item = Vec<f64>>,
) -> PyResult<Bound<'py, PyDict>> {
    let mut cols = vec![Vec::new(); columns.len()];
    for row in rows {
        for (c, v) in cols.iter_mut().zip(row) {
            c.push(v);
        }
    }
    let out = PyDict::new(py);
    for (name, c) in columns.iter().zip(cols) {
        out.set_item(*name, array1(py, c))?;
    }
    Ok(out)
}

/// `sphstab swegle --json` for the keyword arguments in `kwargs` (JSON): the document, its
/// history (the columns of `history.csv`) and the final particles, as arrays.
#[pyfunction]
fn swegle_json<'py>(
    py: Python<'py>,
    kwargs: &str,
) -> PyResult<(String, Bound<'py, PyDict>, Bound<'py, PyDict>)> {
    let mut kw = Kwargs::parse(kwargs)?;
    let budget = kw.budget()?;
    let spec: SwegleSpec = kw.rest()?;
    let cfg = spec.config(&budget).map_err(value_error)?;
    let r = interruptible(py, value_error, |cancel| {
        sphstab::studies::swegle::run_swegle(&cfg, cancel)
    })?;
    let hist = history(
        py,
        &sphstab::studies::swegle::HISTORY_COLUMNS,
        r.history_full.iter().map(|row| row.to_vec()),
    )?;
    let fin = match &r.final_state {
        Some(FinalState::One(z)) => particles(py, z)?,
        Some(FinalState::Two(z)) => particles(py, z)?,
        Some(FinalState::Three(z)) => particles(py, z)?,
        None => PyDict::new(py),
    };
    let mut doc = serde_json::to_value(&r).map_err(json_error)?;
    if let Some(o) = doc.as_object_mut() {
        o.remove("history");
    }
    let doc = units::json(&doc, System::SwegleTest, true).map_err(json_error)?;
    Ok((doc, hist, fin))
}

/// `sphstab simulate SCENE --json` for a scene (a JSON object, the schema of the scene files,
/// or a built-in scene's name as a JSON string): the document, the history and the final
/// particles.
#[pyfunction]
fn simulate_json<'py>(
    py: Python<'py>,
    scene: &str,
    kwargs: &str,
) -> PyResult<(String, Bound<'py, PyDict>, Bound<'py, PyDict>)> {
    let mut kw = Kwargs::parse(kwargs)?;
    let budget = kw.budget()?;
    kw.rest::<Empty>()?;
    let mut scene = match serde_json::from_str::<Value>(scene).map_err(json_error)? {
        Value::String(name) if name == "swegle" || name == "thesis-wave" => {
            return Err(PyValueError::new_err(format!(
                "scene `{name}` is not a scene file: {}",
                if name == "swegle" {
                    "run it with sphstab.swegle(...)"
                } else {
                    "its four runs are `sphstab simulate thesis-wave` in the CLI"
                }
            )));
        }
        Value::String(name) => sphstab::solver::scene::builtin(&name).map_err(scene_error)?,
        v @ Value::Object(_) => {
            sphstab::solver::scene::parse("scene", &v.to_string()).map_err(scene_error)?
        }
        _ => {
            return Err(PyValueError::new_err(
                "scene must be a dict (the schema of the JSON scene files) or a built-in scene's name",
            ));
        }
    };
    scene.budget = budget;
    // the scene's fields are the keys the user wrote: its errors name them as such
    let r = interruptible(py, scene_error, |cancel| scene.run(cancel))?;

    let hist = history(
        py,
        &sphstab::solver::scene::HISTORY_COLUMNS,
        r.history.iter().map(|&(t, v, e)| vec![t, v, e]),
    )?;
    let fin = match &r.final_state {
        Some(FinalState::One(z)) => particles(py, z)?,
        Some(FinalState::Two(z)) => particles(py, z)?,
        Some(FinalState::Three(z)) => particles(py, z)?,
        None => PyDict::new(py),
    };
    let doc = units::json(&r, System::Si, true).map_err(json_error)?;
    Ok((doc, hist, fin))
}

/// No keyword arguments left (any is unknown).
#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Empty {}

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
    m.add_function(wrap_pyfunction!(timestep_json, m)?)?;
    m.add_function(wrap_pyfunction!(map_json, m)?)?;
    m.add_function(wrap_pyfunction!(swegle_json, m)?)?;
    m.add_function(wrap_pyfunction!(simulate_json, m)?)?;
    m.add_function(wrap_pyfunction!(kernels_json, m)?)?;
    Ok(())
}
