"""The Python module against the CLI (the same document, to the last bit) and against the
papers' closed forms."""

import json
import os
import subprocess

import numpy as np
import pytest

import sphstab

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def cli(*args):
    exe = os.environ.get("SPHSTAB_BIN", os.path.join(ROOT, "target", "release", "sphstab"))
    out = subprocess.run([exe, *args], capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def test_issue_acceptance_classical_m4_in_tension_is_unstable():
    assert sphstab.query(form="classical", kernel="m4", h=1.2, stress=0.01)["stable"] is False


def test_query_equals_the_cli_json():
    for kw, flags in [
        (dict(form="classical", kernel="m4", h=1.2, stress=0.01),
         ["--form", "classical", "--kernel", "m4", "--h", "1.2", "--stress", "0.01"]),
        (dict(form="lnl", kernel="wendland-c2", h=1.5, stress=-0.2, c=0.25),
         ["--form", "lnl", "--kernel", "wendland-c2", "--h", "1.5", "--stress", "-0.2", "--c", "0.25"]),
        (dict(dim=2, material="hydro", stress=0.05, grid=16),
         ["--dim", "2", "--material", "hydro", "--stress", "0.05", "--grid", "16"]),
    ]:
        doc = sphstab.query(**kw)
        ref = cli("query", "--json", *flags)
        # runtime fields differ run to run
        for d in (doc, ref):
            d.pop("runtime_s", None)
        assert doc == ref


def test_bad_input_raises_value_error_naming_the_argument():
    with pytest.raises(ValueError, match=r"^c does not apply with form classical"):
        sphstab.query(form="classical", c=0.3)
    with pytest.raises(ValueError, match=r"support = 0.5 is out of range"):
        sphstab.query(support=0.5)
    with pytest.raises(ValueError, match=r"^unknown keyword argument `hh`, expected one of `form`.*`grid`, `max_memory`, `max_steps`, `integrator`, `euler_every`$"):
        sphstab.query(hh=1.2)
    with pytest.raises(ValueError, match="invalid type"):
        sphstab.query(h="large")
    # counts: out of range on either side, never a crash or an OverflowError
    for p in (-1, 0, 1, 10**9):
        with pytest.raises(ValueError, match=r"^points = .* is out of range"):
            sphstab.dispersion(points=p)


def test_dispersion_equals_the_cli_json_and_has_arrays():
    d = sphstab.dispersion(form="classical", kernel="m4", h=1.2, stress=0.0, points=16)
    ref = cli("dispersion", "--json", "--form", "classical", "--kernel", "m4", "--h", "1.2",
              "--stress", "0", "--points", "16")
    assert d["omega2"].dtype == np.float64 and d["omega2"].shape[0] == 16
    for key, value in ref.items():
        got = d[key]
        if isinstance(got, np.ndarray):
            assert got.tolist() == value, key
        else:
            assert got == value, key


def test_dispersion_reports_the_continuum_of_b00_eq_32():
    # B00 eq 32: the continuum ω²Δx²/c² = (1 + σ̄)(κΔx)², analytic
    d = sphstab.dispersion(form="classical", kernel="m4", h=1.2, stress=0.3, points=64)
    kappa = d["kappa"].reshape(len(d["kappa"]), -1)[:, 0]
    cont = d["omega2_continuum"].reshape(len(kappa), -1)[:, 0]
    assert np.allclose(cont, 1.3 * kappa**2, rtol=1e-12, atol=0)


def test_kernels_equal_the_cli_and_m4_is_normalised():
    rows = sphstab.kernels()
    assert rows == cli("kernels", "--json")
    m4 = next(r for r in rows if r["name"] == "m4")
    # Monaghan & Lattanzio (1985): σ = 2/3, 10/(7π), 1/π for the cubic spline, support 2h
    assert m4["zeta"] == 2
    assert abs(m4["sigma_1"] - 2 / 3) < 1e-15
    assert abs(m4["sigma_2"] - 10 / (7 * np.pi)) < 1e-15
    assert abs(m4["sigma_3"] - 1 / np.pi) < 1e-15
