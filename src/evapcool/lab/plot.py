"""The lab's figure; matplotlib is imported here only, never by the rest of the lab."""

from __future__ import annotations

import math
import os

import numpy as np

from evapcool.lab.theory import (
    energy_pdf,
    eta_from_cut,
    kt_from_mean_energy,
    truncated_energy_pdf,
)

MODEL_STYLE = dict(color="k", ls="--", lw=1.2)


def plot_result(result, path: str | os.PathLike[str] | None = None, *, theory=None):
    """N(t); T(t) with Tc(t); T against N (log-log) with T = Tc(N); final P(E) against theory.

    With a TheoryReport (LabResult.theory()) the model is drawn over the measurement:
    its slope alpha on the T-N path, and two more panels, the pair-collision rate and the
    atoms evaporated by collisions, measured against predicted, over the model's window.
    """
    from matplotlib.figure import Figure  # no pyplot: no GUI backend, safe headless

    p = result.metadata.get("parameters", {})
    fig = Figure(figsize=(10, 11.25 if theory else 7.5), layout="constrained")
    axes = fig.subplots(3 if theory else 2, 2)
    fig.suptitle(
        f"{p.get('n_atoms')} atoms, R = {p.get('radius')}, escape = {p.get('escape')}, "
        f"schedule = {p.get('schedule')}, Tc law = {p.get('tc_law')}, seed = {p.get('seed')}",
        fontsize=10,
    )
    seconds = result.frame / 30.0  # the game's 30 frames per second
    _atoms_panel(axes[0, 0], result, seconds)
    _temperature_panel(axes[0, 1], result, seconds)
    _path_panel(axes[1, 0], result, theory)
    _energy_panel(axes[1, 1], result)
    if theory:
        _collision_panel(axes[2, 0], result, theory)
        _evaporation_panel(axes[2, 1], result, theory)
    if path is not None:
        fig.savefig(path, dpi=100)
    return fig


def _atoms_panel(ax, result, seconds: np.ndarray) -> None:
    ax.plot(seconds, result.n_trapped, color="tab:blue")
    ax.set_xlabel("time (s = 30 frames)")
    ax.set_ylabel("atoms trapped N")
    ax.set_title("N(t)")
    ax.set_ylim(bottom=0)


def _temperature_panel(ax, result, seconds: np.ndarray) -> None:
    ax.plot(seconds, result.temperature, color="tab:red", label="T (mean energy per atom)")
    ax.plot(seconds, result.critical_temperature, color="k", ls="--", label="Tc(N)")
    won = result.metadata.get("won_frame")
    if won is not None:
        ax.axvline(won / 30.0, color="tab:green", lw=0.8, label="T < Tc (won)")
    ax.set_xlabel("time (s = 30 frames)")
    ax.set_ylabel("energy per atom")
    ax.set_title("T(t) and Tc(t)")
    ax.legend(fontsize=8)


def _path_panel(ax, result, theory) -> None:
    from matplotlib.ticker import ScalarFormatter

    meta, p = result.metadata, result.metadata.get("parameters", {})
    ok = (result.n_trapped > 0) & (result.temperature > 0)
    n = result.n_trapped[ok]
    ax.loglog(n, result.temperature[ok], "o-", ms=3, color="tab:red", label="run")
    if n.size:
        n0 = float(p.get("n_atoms", n.max()))
        n_first = float(result.n_trapped[0])
        tc0 = float(result.critical_temperature[0]) / (n_first / n0) ** meta["tc_exponent"]
        grid = np.geomspace(max(n.min() / 2.0, 1.0), n0, 100)
        ax.loglog(grid, tc0 * (grid / n0) ** meta["tc_exponent"], "k:", label="T = Tc(N)")
    if theory and "alpha" in {r.symbol for r in theory.rows}:
        # The model's slope through the window's first record (T ~ kT at constant eta).
        first = int(np.flatnonzero(theory.window)[0])
        last = int(np.flatnonzero(theory.window)[-1])
        grid = np.geomspace(float(result.n_trapped[last]), float(result.n_trapped[first]), 50)
        alpha = theory["alpha"].predicted
        start = (float(result.n_trapped[first]), float(result.temperature[first]))
        ax.loglog(
            grid,
            start[1] * (grid / start[0]) ** alpha,
            **MODEL_STYLE,
            label=f"model, alpha = {alpha:.2f}",
        )
    ax.invert_xaxis()  # evaporation runs right to left: N falls
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_major_formatter(ScalarFormatter())
        axis.set_minor_formatter(ScalarFormatter())
    ax.set_xlabel("atoms trapped N")
    ax.set_ylabel("T")
    ax.set_title("path to condensation")
    ax.legend(fontsize=8)


def _energy_panel(ax, result) -> None:
    meta, p = result.metadata, result.metadata.get("parameters", {})
    e = result.final_energies
    if e.size:
        cut = meta.get("mass", 1.0) * p.get("gravity", 0.0) * float(result.trap_height[-1])
        knife = p.get("escape") == "knife" and math.isfinite(cut)
        eta = eta_from_cut(float(e.mean()), cut) if knife else math.nan
        ax.hist(
            e,
            bins=max(10, min(60, e.size // 20)),
            density=True,
            color="tab:cyan",
            edgecolor="k",
            lw=0.3,
            label=f"final, N = {e.size}",
        )
        top = max(float(e.max()), 1e-12)
        if math.isfinite(cut) and cut < 2.0 * top:
            top = max(top, cut)
        grid = np.linspace(0.0, top * 1.05, 300)
        if math.isfinite(eta):  # the law cut at m g H with this mean energy
            kt = cut / eta
            label = f"E^(3/2) exp(-E/kT) cut at {eta:.2f} kT"
            ax.plot(grid, truncated_energy_pdf(grid, kt, cut), "k-", label=label)
        else:
            kt = kt_from_mean_energy(float(e.mean()))
            ax.plot(grid, energy_pdf(grid, kt), "k-", label="E^(3/2) exp(-E/kT), kT = 2/5 <E>")
        if math.isfinite(cut) and cut <= top:
            ax.axvline(cut, color="tab:purple", ls=":", label="m g H (cut)")
        ax.legend(fontsize=8)
    ax.set_xlabel("energy E = m v^2/2 + m g y")
    ax.set_ylabel("probability density")
    ax.set_title("final energy distribution")


def _collision_panel(ax, result, theory) -> None:
    w = theory.window
    frames = result.frame[w].astype(float)
    rate = np.diff(result.pair_collisions[w]) / np.diff(frames)
    ax.plot(
        0.5 * (frames[1:] + frames[:-1]) / 30.0,
        rate,
        ".",
        color="tab:blue",
        ms=4,
        label="measured, between records",
    )
    ax.plot(frames / 30.0, theory.track.pair_rate[w], **MODEL_STYLE, label="model")
    row = theory["Gamma_pair"]
    ax.set_title(f"pair collisions per frame (measured / model = {row.ratio:.3f})", fontsize=10)
    ax.set_xlabel("time (s = 30 frames)")
    ax.set_ylabel("pair collisions per frame")
    ax.set_ylim(bottom=0)
    ax.legend(fontsize=8)


def _evaporation_panel(ax, result, theory) -> None:
    w = theory.window
    seconds = result.frame[w] / 30.0
    evaporated = result.evaporated[w] - result.evaporated[w][0]
    ax.plot(seconds, evaporated, color="tab:blue", label="measured")
    if "Gamma_ev/gamma_el" in {r.symbol for r in theory.rows}:
        # Model: 2 (Gamma_ev / gamma_el) per measured pair collision, summed from the start.
        per_pair = 2.0 * theory.track.evaporation_per_collision[w]
        d_pairs = np.diff(result.pair_collisions[w])
        model = np.concatenate(([0.0], np.cumsum(0.5 * (per_pair[1:] + per_pair[:-1]) * d_pairs)))
        ratio = theory["Gamma_ev/gamma_el"].ratio
        ax.plot(seconds, model, **MODEL_STYLE, label="model: 2 (Gamma_ev/gamma_el) per collision")
        ax.set_title(f"evaporated by collisions (measured / model = {ratio:.3f})", fontsize=10)
    else:
        ax.set_title("evaporated by collisions")
    ax.set_xlabel("time (s = 30 frames)")
    ax.set_ylabel("atoms, from the window's start")
    ax.legend(fontsize=8)
