# %% [markdown]
# # sphstab from Python: a first session
#
# Three questions a user of SPH asks before a run, answered with the `sphstab` module
# (`pip install ./python`, see docs/python.md) and drawn with matplotlib:
#
# 1. the dispersion of three SPH forms in tension: which one has a growing mode, and where;
# 2. a stability map over the 2D zone: which wave vectors grow;
# 3. the Swegle test: a perturbed block in tension, its measured growth against the predicted one.
#
# Every number is in normalised units (Δx = c = 1): κΔx, ω²Δx²/c², growth rates in c/Δx, time
# in Δx/c. This file is also `example.ipynb` (the same cells); the tests run this script.
# Usage: `python analysis/python/example.py [FIGURE.png]`.

# %%
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed: the figure is written to a file
import matplotlib.pyplot as plt
import numpy as np

import sphstab

# the figure: the first argument (a notebook's kernel passes its own, not a file name)
args = [a for a in sys.argv[1:] if a.endswith((".png", ".pdf", ".svg"))]
out = args[0] if args else "example.png"
plt.rcParams.update({"font.size": 7, "legend.fontsize": 6})  # print size: 170 mm wide
fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(170 / 25.4, 60 / 25.4), layout="constrained")

# %% [markdown]
# ## 1. Dispersion of three forms in tension (1D, cubic spline, h = 1.2Δx, σ̄ = 0.1)
#
# ω² < 0 is a growing mode, at rate √(−ω²). The classical (Eulerian-kernel) form goes
# negative near κ = π: the tensile instability. The total-Lagrangian form does not.

# %%
for form in ("classical", "nonlocal", "total-lagrangian"):
    d = sphstab.dispersion(form=form, kernel="m4", h=1.2, stress=0.1, points=200)
    ax1.plot(d["kappa"][:, 0] / np.pi, d["omega2"], label=form)
ax1.plot(d["kappa"][:, 0] / np.pi, d["omega2_continuum"], "k--", lw=0.8, label="continuum")
ax1.axhline(0, color="grey", lw=0.5)
ax1.set(xlabel="κΔx/π", ylabel="ω²Δx²/c²", ylim=(-0.5, 2.5))
ax1.legend()
for form in ("classical", "nonlocal", "total-lagrangian"):
    q = sphstab.query(form=form, kernel="m4", h=1.2, stress=0.1)
    kinds = ", ".join(i["kind"] for i in q["instabilities"]) or "none"
    print(f"{form:17s} stable={q['stable']!s:5s} growth={q['max_growth_rate']:.4f} c/Δx ({kinds})")

# %% [markdown]
# ## 2. Stability map: classical form, 2D square lattice, fluid (hydro) in tension σ̄ = 0.1
#
# `growth[i, j]` is the growth rate at (kx[i], ky[j]); white is stable.

# %%
m = sphstab.stability_map(form="classical", material="hydro", stress=0.1, n=64)
im = ax2.pcolormesh(m["kx"] / np.pi, m["ky"] / np.pi, m["growth"].T, cmap="Reds",
                    vmin=0, shading="nearest")
fig.colorbar(im, ax=ax2, label="growth rate (c/Δx)")
ax2.set(xlabel="κxΔx/π", ylabel="κyΔx/π", aspect="equal")
print(f"map: largest growth {m['growth'].max():.4f} c/Δx")

# %% [markdown]
# ## 3. The Swegle test: 21 × 21 particles at ρ/ρ0 = 0.99 (tension), centre particle kicked
#
# The largest speed grows as e^(γt). The dashed line is the predicted γ of the box (the exact
# operator of the particle set), drawn through the first point of the fit window.

# %%
s = sphstab.swegle(form="classical", kernel="m4", h=1.2, density_ratio=0.99)
unit = s["sound_speed_physical"] / s["dx_physical"]  # test's time units → Δx/c
t = s["history"]["t"] * unit
v = s["history"]["max_abs_v_free"]
ax3.semilogy(t, v, label="max |v| (run)")
gamma = s["predicted_growth_rate_box"]
if s["fit"] is not None:
    t0 = s["fit"]["window"][0] * unit
    v0 = np.interp(t0, t, v)
    ax3.semilogy(t, v0 * np.exp(gamma * (t - t0)), "k--", lw=0.8,
                 label=f"predicted γ = {gamma:.3f} c/Δx")
    ax3.set_ylim(v.min() / 2, v.max() * 2)
ax3.set(xlabel="t (Δx/c)", ylabel="max |v| (test units)")
ax3.legend(loc="upper left")
measured = s["measured_growth_rate"]
print(f"swegle: measured {measured:.4f} c/Δx, predicted (box) {gamma:.4f} c/Δx, "
      f"ratio {s['ratio_box']:.4f}")

# %%
fig.savefig(out, dpi=200)
print(f"wrote {out}")
