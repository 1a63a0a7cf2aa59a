"""The lab's four-panel figure; matplotlib is imported here only, never by the rest of the lab."""

from __future__ import annotations

import os

import numpy as np

from evapcool.lab.theory import energy_pdf, kt_from_mean_energy


def plot_result(result, path: str | os.PathLike[str] | None = None):
    """N(t); T(t) with Tc(t); T against N (log-log) with T = Tc(N); final P(E) against theory."""
    from matplotlib.figure import Figure  # no pyplot: no GUI backend, safe headless
    from matplotlib.ticker import ScalarFormatter

    meta = result.metadata
    p = meta.get("parameters", {})
    t = result.frame / 30.0  # seconds at the game's 30 frames per second
    fig = Figure(figsize=(10, 7.5), layout="constrained")
    axes = fig.subplots(2, 2)
    title = (
        f"{p.get('atoms')} atoms, R = {p.get('radius')}, escape = {p.get('escape')}, "
        f"schedule = {p.get('schedule')}, Tc law = {p.get('tc_law')}, seed = {p.get('seed')}"
    )
    fig.suptitle(title, fontsize=10)

    ax = axes[0, 0]
    ax.plot(t, result.n_trapped, color="tab:blue")
    ax.set_xlabel("time (s = 30 frames)")
    ax.set_ylabel("atoms trapped N")
    ax.set_title("N(t)")
    ax.set_ylim(bottom=0)

    ax = axes[0, 1]
    ax.plot(t, result.temperature, color="tab:red", label="T (mean energy per atom)")
    ax.plot(t, result.critical_temperature, color="k", ls="--", label="Tc(N)")
    won = meta.get("won_frame")
    if won is not None:
        ax.axvline(won / 30.0, color="tab:green", lw=0.8, label="T < Tc (won)")
    ax.set_xlabel("time (s = 30 frames)")
    ax.set_ylabel("energy per atom")
    ax.set_title("T(t) and Tc(t)")
    ax.legend(fontsize=8)

    ax = axes[1, 0]
    ok = (result.n_trapped > 0) & (result.temperature > 0)
    n = result.n_trapped[ok]
    ax.loglog(n, result.temperature[ok], "o-", ms=3, color="tab:red", label="run")
    if n.size:
        n0 = float(p.get("atoms", n.max()))
        n_first = float(result.n_trapped[0])
        tc0 = float(result.critical_temperature[0]) / (n_first / n0) ** meta["tc_exponent"]
        grid = np.geomspace(max(n.min() / 2.0, 1.0), n0, 100)
        ax.loglog(grid, tc0 * (grid / n0) ** meta["tc_exponent"], "k--", label="T = Tc(N)")
    ax.invert_xaxis()  # evaporation runs right to left: N falls
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(ScalarFormatter())
        axis.set_minor_formatter(ScalarFormatter())
    ax.set_xlabel("atoms trapped N")
    ax.set_ylabel("T")
    ax.set_title("path to condensation")
    ax.legend(fontsize=8)

    ax = axes[1, 1]
    e = result.final_energies
    if e.size:
        kt = kt_from_mean_energy(float(e.mean()))
        ax.hist(
            e,
            bins=max(10, min(60, e.size // 20)),
            density=True,
            color="tab:cyan",
            edgecolor="k",
            lw=0.3,
            label=f"final, N = {e.size}",
        )
        cut = meta.get("mass", 1.0) * p.get("gravity", 0.0) * float(result.trap_height[-1])
        top = max(float(e.max()), 1e-12)
        if np.isfinite(cut) and cut < 2.0 * top:
            top = max(top, cut)
        grid = np.linspace(0.0, top * 1.05, 300)
        ax.plot(grid, energy_pdf(grid, kt), "k-", label="E^(3/2) exp(-E/kT), kT = 2/5 <E>")
        if np.isfinite(cut) and cut <= top:
            ax.axvline(cut, color="tab:purple", ls=":", label="m g H (cut)")
        ax.legend(fontsize=8)
    ax.set_xlabel("energy E = m v^2/2 + m g y")
    ax.set_ylabel("probability density")
    ax.set_title("final energy distribution")

    if path is not None:
        fig.savefig(path, dpi=100)
    return fig
