"""timestep, stability_map, swegle and simulate against the CLI (the same documents and
histories, to the last bit), against analytic values, and their arrays, errors, budget and
Ctrl-C; the example script of analysis/python runs and is the notebook's code.

Run: `SPHSTAB_BIN=target/release/sphstab pytest -q python/tests` (from the repository root).
`python python/tests/test_runs.py --write-notebook` rewrites analysis/python/example.ipynb from
the script."""

import csv
import json
import os
import re
import signal
import subprocess
import sys
import time

import numpy as np
import pytest

import sphstab

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLE = os.path.join(ROOT, "analysis", "python", "example.py")
NOTEBOOK = os.path.join(ROOT, "analysis", "python", "example.ipynb")


def exe():
    return os.environ.get("SPHSTAB_BIN", os.path.join(ROOT, "target", "release", "sphstab"))


def cli(*args):
    out = subprocess.run([exe(), *args], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def cli_error(*args):
    """The CLI's one-line error (exit status 2), without its `error: ` prefix."""
    out = subprocess.run([exe(), *args], capture_output=True, text=True)
    assert out.returncode == 2, out
    return out.stderr.strip().removeprefix("error: ")


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


def without_runtime(doc):
    doc = dict(doc)
    doc.pop("runtime_s", None)
    return doc


# ---------- query: the solid forms and the pre-stress shapes

def test_query_solid_forms_equal_the_cli_json():
    for kw, flags in [
        (dict(dim=2, form="classical", prestress="uniaxial", stress=0.05, grid=16),
         ["--dim", "2", "--form", "classical", "--prestress", "uniaxial", "--stress", "0.05",
          "--grid", "16"]),
        (dict(dim=2, form="enog", prestress="shear", stress=0.1, hourglass=3.0, grid=16),
         ["--dim", "2", "--form", "enog", "--prestress", "shear", "--stress", "0.1",
          "--hourglass", "3", "--grid", "16"]),
        (dict(dim=3, form="tl-enog", stress=0.0, grid=4),
         ["--dim", "3", "--form", "tl-enog", "--stress", "0", "--grid", "4"]),
    ]:
        r = sphstab.query(**kw)
        assert without_runtime(r) == without_runtime(cli("query", "--json", *flags))
    kinds = [i["kind"] for i in sphstab.query(dim=2, prestress="uniaxial", stress=0.05,
                                              grid=16)["instabilities"]]
    assert kinds == ["hourglass", "tensile"]


# ---------- timestep

def test_timestep_equals_the_cli_json():
    for kw, flags in [
        (dict(form="nonlocal", h=1.3, av_alpha=1.0),
         ["--form", "nonlocal", "--h", "1.3", "--av-alpha", "1"]),
        (dict(dim=2, form="total-lagrangian", stress=0.0, grid=16, integrator="rk4"),
         ["--dim", "2", "--form", "total-lagrangian", "--stress", "0", "--grid", "16",
          "--integrator", "rk4"]),
        (dict(dim=3, lattice="bcc", form="total-lagrangian", stress=0.0, grid=6,
              integrator="verlet-euler", euler_every=10),
         ["--dim", "3", "--lattice", "bcc", "--form", "total-lagrangian", "--stress", "0",
          "--grid", "6", "--integrator", "verlet-euler", "--euler-every", "10"]),
    ]:
        assert sphstab.timestep(**kw) == cli("timestep", "--json", *flags)


def test_timestep_verify_equals_the_cli_and_the_leapfrog_limit():
    kw = dict(form="total-lagrangian", stress=0.0, verify=True)
    doc = sphstab.timestep(**kw)
    ref = cli("timestep", "--json", "--form", "total-lagrangian", "--stress", "0", "--verify")
    assert without_runtime(doc.pop("verify")) == without_runtime(ref.pop("verify"))
    assert doc == ref
    # analytic: an undamped linear system integrated by leapfrog (kdk) is stable up to
    # Δt = 2/ω_max exactly
    assert doc["critical_dt"] == pytest.approx(2 / doc["omega_max"], rel=1e-6)


# ---------- stability_map

def test_stability_map_equals_the_cli_json_in_2d_and_3d():
    for kw, flags in [
        (dict(form="classical", material="hydro", stress=0.1, n=12),
         ["--form", "classical", "--material", "hydro", "--stress", "0.1", "--n", "12"]),
        (dict(dim=3, plane="diagonal", form="classical", stress=0.05, n=6),
         ["--dim", "3", "--plane", "diagonal", "--form", "classical", "--stress", "0.05",
          "--n", "6"]),
    ]:
        m = sphstab.stability_map(**kw)
        ref = cli("map", "--json", *flags)
        n = kw["n"]
        assert m["growth"].shape == (n, n) and m["growth"].dtype == np.float64
        assert m["kx"].shape == (n,) and m["ky"].shape == (n,) and m["kx"].dtype == np.float64
        assert m["growth"].tolist() == ref.pop("growth")
        assert m["kx"].tolist() == ref.pop("kx") and m["ky"].tolist() == ref.pop("ky")
        assert {k: v for k, v in m.items() if k not in ("growth", "kx", "ky")} == ref


def test_stability_map_is_the_dispersion_growth_on_an_axis():
    # an independent route within the engine: the map's κy = 0 row (n odd puts one there) is
    # the growth of `dispersion`'s Γ–X segment. With n = 11 the map's κx > 0 are 2πk/11 and the
    # path with 11 points per segment samples πj/11, so they meet at j = 2k: the same wave
    # vector (to rounding), the same growth (to rounding)
    n = 11
    m = sphstab.stability_map(form="classical", material="hydro", stress=0.1, n=n)
    assert abs(m["ky"][n // 2]) < 1e-15
    d = sphstab.dispersion(dim=2, form="classical", material="hydro", stress=0.1, points=n)
    on_gx = (d["kappa"][:, 1] == 0) & (d["kappa"][:, 0] > 0)
    k, g = d["kappa"][on_gx, 0], d["growth_rate"][on_gx]
    assert g.max() > 0.5  # the row holds growing modes: the test compares something
    for i in range(n // 2 + 1, n):
        j = np.argmin(np.abs(k - m["kx"][i]))
        assert abs(k[j] - m["kx"][i]) < 1e-14
        assert m["growth"][i, n // 2] == pytest.approx(g[j], rel=1e-12, abs=1e-15), m["kx"][i]


# ---------- dispersion eigenvectors

def test_polarisations_are_unit_and_longitudinal_along_gamma_x():
    d = sphstab.dispersion(dim=2, form="total-lagrangian", stress=0.0, points=32,
                           eigenvectors=True)
    p = d["polarisation"]
    assert p.shape == (len(d["path"]), 2, 2) and p.dtype == np.complex128
    # analytic: orthonormal polarisations (degenerate branches, as at Γ, get an orthonormal
    # basis of their span); on Γ–X (κ ∥ x̂) of the square lattice the mirror
    # y → −y separates the branches: the upper (P) is x̂, the lower (S) ŷ
    gram = np.einsum("pbi,pci->pbc", p.conj(), p)
    assert np.allclose(gram, np.eye(2), atol=1e-10)
    on_gx = (d["kappa"][:, 1] == 0) & (d["kappa"][:, 0] > 0) & (d["kappa"][:, 0] < np.pi)
    assert on_gx.sum() > 10
    assert np.allclose(np.abs(p[on_gx, 1, 0]), 1, atol=1e-12)
    assert np.allclose(np.abs(p[on_gx, 0, 1]), 1, atol=1e-12)


# ---------- swegle

SWEGLE_KW = dict(form="classical", h=1.2, density_ratio=0.99, t_end=10)
SWEGLE_FLAGS = ["--form", "classical", "--h", "1.2", "--density-ratio", "0.99", "--t-end", "10"]


def test_swegle_equals_the_cli_json_and_history_csv(tmp_path):
    s = sphstab.swegle(**SWEGLE_KW)
    ref = cli("swegle", "--json", "--out", str(tmp_path), *SWEGLE_FLAGS)
    hist, fin = s.pop("history"), s.pop("final")
    assert without_runtime(s) == without_runtime(ref)
    header, rows = read_csv(tmp_path / "history.csv")
    assert list(hist) == header
    for j, name in enumerate(header):
        assert hist[name].dtype == np.float64 and hist[name].shape == (len(rows),)
        # the CSV prints every value to the last bit (shortest round trip)
        assert hist[name].tolist() == rows[:, j].tolist(), name
    n = 21 * 21
    assert fin["positions"].shape == (n, 2) and fin["velocities"].shape == (n, 2)
    assert fin["density"].shape == (n,)
    assert all(a.dtype == np.float64 for a in fin.values())


def test_swegle_measures_the_growth_it_predicts():
    # the published test in tension: the run's growth against the engine's prediction for the
    # same box (an independent route: eigenvalues of the operator vs a time integration)
    s = sphstab.swegle(form="classical", density_ratio=0.99)
    assert s["measured_growth_rate"] == pytest.approx(s["predicted_growth_rate_box"], rel=0.05)


def test_swegle_3d_particles_have_3d_shapes():
    s = sphstab.swegle(dim=3, size=9, t_end=1)
    assert s["final"]["positions"].shape == (9**3, 3)


# ---------- simulate

def test_simulate_equals_the_cli_json_and_history_csv(tmp_path):
    scene_file = os.path.join(ROOT, "analysis", "scenes", "rod-in-tension.json")
    with open(scene_file) as f:
        scene = json.load(f)
    r = sphstab.simulate(scene)
    ref = cli("simulate", scene_file, "--json", "--out", str(tmp_path))
    hist, fin = r.pop("history"), r.pop("final")
    assert without_runtime(r) == without_runtime(ref)
    header, rows = read_csv(tmp_path / "history.csv")
    assert list(hist) == header
    for j, name in enumerate(header):
        assert hist[name].tolist() == rows[:, j].tolist(), name
    n = scene["particles"]
    assert fin["positions"].shape == (n, 1) and fin["velocities"].shape == (n, 1)
    for key in ("stress", "local_stress"):
        if key in fin:
            assert fin[key].shape == (n, 1, 1) and fin[key].dtype == np.float64


def test_simulate_a_dict_scene_follows_the_analytic_strain():
    # [V21 §7.1] the uniform bar, written here as a dict: v = g X with g = 0.001, the 3 end
    # particles held at their initial velocity. Uniform strain means uniform stress and no
    # acceleration, so every particle keeps v = g X (analytic); total-Lagrangian SPH
    # reproduces a linear field, up to the boundary layers' truncation
    scene = {
        "name": "uniform-bar", "form": "total-lagrangian", "kernel": "m4", "h_over_dx": 1.3,
        "modulus": 2.0, "rho0": 8.0, "particles": 100, "origin": -0.5, "length": 1.0,
        "initial_velocity": {"kind": "linear", "gradient": 0.001},
        "left": {"layers": 3, "velocity": None}, "right": {"layers": 3, "velocity": None},
        "t_end": 10.0, "dt": 0.2, "analytic": "uniform-strain",
    }
    r = sphstab.simulate(scene)
    x0 = np.linspace(-0.5, 0.5, 100)
    v = r["final"]["velocities"][:, 0]
    free = slice(3, 97)
    err = np.linalg.norm(v[free] - 0.001 * x0[free]) / np.linalg.norm(0.001 * x0[free])
    assert err < 1e-3
    # the scene's own error norm is the same relative L2 over the free particles
    assert r["velocity_error_l2"] == pytest.approx(err, rel=1e-9)


# ---------- errors, budget, Ctrl-C

@pytest.mark.parametrize("call, flags", [
    (lambda: sphstab.stability_map(dim=1), ["map", "--dim", "1"]),
    (lambda: sphstab.stability_map(dt=0.5), ["map", "--dt", "0.5"]),
    (lambda: sphstab.timestep(av_beta=1.0), ["timestep", "--av-beta", "1"]),
    (lambda: sphstab.query(av_beta=1.0), ["query", "--av-beta", "1"]),
    (lambda: sphstab.swegle(size=5), ["swegle", "--size", "5"]),
    (lambda: sphstab.swegle(density_ratio=2.0), ["swegle", "--density-ratio", "2"]),
    (lambda: sphstab.swegle(boundary_density="x"), ["swegle", "--boundary-density", "x"]),
    (lambda: sphstab.swegle(euler_every=3), ["swegle", "--euler-every", "3"]),
    (lambda: sphstab.timestep(viscosity="two-sided"), ["timestep", "--viscosity", "two-sided"]),
])
def test_errors_are_the_cli_message_with_keyword_names(call, flags):
    with pytest.raises(ValueError) as e:
        call()
    # the CLI's flags (--density-ratio) are the keyword arguments (density_ratio)
    expected = re.sub(r"--([a-z][a-z0-9-]*)", lambda m: m.group(1).replace("-", "_"),
                      cli_error(*flags))
    assert str(e.value) == expected


def test_bad_scenes_and_budgets_raise_value_error():
    with pytest.raises(ValueError, match=r"unknown field `bad`"):
        sphstab.simulate({"bad": 1})
    with pytest.raises(ValueError, match=r"unknown scene `nope`"):
        sphstab.simulate("nope")
    with pytest.raises(ValueError, match=r"sphstab.swegle"):
        sphstab.simulate("swegle")
    with pytest.raises(ValueError, match=r"^max_memory: unknown unit `x`"):
        sphstab.query(max_memory="1x")
    with pytest.raises(ValueError, match=r"max_steps"):
        sphstab.swegle(max_steps=1000)


@pytest.mark.parametrize("call", [
    # a Swegle run of 1.6e5 particles for 2.5e5 steps (the solver's time loop)
    "sphstab.swegle(size=401, t_end=1e4, max_steps=1e14)",
    # a 3D query of minutes: 128³ wave vectors of an fcc lattice with 3Δx smoothing (the
    # analysis, stopped per wave vector)
    "sphstab.query(dim=3, lattice='fcc', h=3.0, grid=128)",
])
def test_ctrl_c_stops_a_long_run(call):
    # Ctrl-C (SIGINT) must end the call within seconds, as KeyboardInterrupt, and the
    # interpreter must survive it, and the next call must run (the interruption is cleared)
    # (a Python started with SIGINT ignored, as a background job is, installs no handler:
    # install the interactive interpreter's one)
    code = ("import signal, sphstab\nsignal.signal(signal.SIGINT, signal.default_int_handler)\n"
            "print('start', flush=True)\n"
            f"try:\n    {call}\n"
            "except KeyboardInterrupt:\n    print('interrupted', flush=True)\n"
            "print(sphstab.query()['stable'], flush=True)\n")
    p = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "start"
    time.sleep(1.5)
    t = time.time()
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=60)
    assert out.split() == ["interrupted", "False"] and p.returncode == 0
    assert time.time() - t < 10


# ---------- stubs and help

def test_stubs_and_signatures_name_the_same_arguments():
    # the .pyi (IDEs) and the runtime signatures (help()) list the same keyword arguments,
    # and every argument help() shows is documented in the docstring
    import ast
    import inspect
    stub = os.path.join(os.path.dirname(sphstab.__file__), "__init__.pyi")
    with open(stub) as f:
        tree = ast.parse(f.read())
    stubs = {fn.name: [a.arg for a in fn.args.args + fn.args.kwonlyargs]
             for fn in tree.body if isinstance(fn, ast.FunctionDef)}
    assert sorted(stubs) == sorted(sphstab.__all__)
    for name in sphstab.__all__:
        f = getattr(sphstab, name)
        params = list(inspect.signature(f).parameters)
        assert sorted(params) == sorted(stubs[name]), name
        for p in params:
            assert re.search(rf"\b{p}\b", f.__doc__), (name, p)


# ---------- the example

def notebook_cells(script):
    """The notebook cells of a percent-format script: (kind, source) per `# %%` marker."""
    cells = []
    for chunk in re.split(r"^# %%", script, flags=re.M)[1:]:
        head, _, body = chunk.partition("\n")
        body = body.strip("\n")
        if head.strip() == "[markdown]":
            body = "\n".join(line[2:] if line.startswith("# ") else line.lstrip("#")
                             for line in body.split("\n"))
            cells.append(("markdown", body))
        else:
            cells.append(("code", body))
    return cells


def test_example_script_writes_its_figure_and_is_the_notebook(tmp_path):
    fig = tmp_path / "example.png"
    out = subprocess.run([sys.executable, EXAMPLE, str(fig)], capture_output=True, text=True,
                         cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert fig.stat().st_size > 10_000 and fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "classical         stable=False" in out.stdout
    with open(NOTEBOOK) as f:
        nb = json.load(f)
    got = [(c["cell_type"], "".join(c["source"])) for c in nb["cells"]]
    with open(EXAMPLE) as f:
        assert got == notebook_cells(f.read()), \
            "example.ipynb differs from example.py: python python/tests/test_runs.py --write-notebook"


if __name__ == "__main__" and sys.argv[1:] == ["--write-notebook"]:
    with open(EXAMPLE) as f:
        cells = notebook_cells(f.read())
    nb = {"cells": [], "metadata": {"kernelspec": {"display_name": "Python 3",
                                                   "language": "python", "name": "python3"},
                                    "language_info": {"name": "python"}},
          "nbformat": 4, "nbformat_minor": 5}
    for i, (kind, src) in enumerate(cells):
        lines = src.split("\n")
        cell = {"cell_type": kind, "id": f"cell-{i + 1}", "metadata": {},
                "source": [line + "\n" for line in lines[:-1]] + [lines[-1]]}
        if kind == "code":
            cell.update(execution_count=None, outputs=[])
        nb["cells"].append(cell)
    with open(NOTEBOOK, "w") as f:
        json.dump(nb, f, indent=1, ensure_ascii=False)
        f.write("\n")
