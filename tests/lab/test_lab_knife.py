"""Energy cuts: the RF knife, the rim, and the constant-eta schedule."""

from __future__ import annotations

import math

import numpy as np
import pytest

from evapcool import Simulation
from evapcool.lab import parse_schedule, run_experiment
from evapcool.lab import theory as th

G = 1.0 / 3.0


def _gas(n: int, escape: str, seed: int, **kw) -> Simulation:
    """A fairly dense thermal cloud (kT = 30, R = 2): many collisions per frame."""
    pos, vel = th.thermal_cloud(n, 2.0, 30.0, gravity=G, rng=np.random.default_rng(seed))
    return Simulation(
        n,
        2.0,
        1.0,
        gravity=G,
        trap_height=math.inf,
        escape=escape,
        seed=seed,
        engine="reference",
        positions=pos,
        velocities=vel,
        **kw,
    )


def test_knife_removes_exactly_the_atoms_above_mgh():
    sim = _gas(120, "knife", 11)
    sim.advance(30.0)
    idx, e = sim.trapped_indices, sim.energies()
    cut = float(np.quantile(e, 0.7))
    sim.trap_height = cut / G  # m = 1: the cut energy is m g H
    assert np.array_equal(sim.trapped_indices, idx[e <= G * sim.trap_height])
    assert sim.n_trapped == np.count_nonzero(e <= cut) < 120
    # Collisions keep pushing atoms over the cut; each goes at once, none survives above it.
    lost = 0
    for _ in range(60):
        n = sim.n_trapped
        sim.advance(1.0)
        lost += n - sim.n_trapped
        assert sim.energies().max() <= G * sim.trap_height * (1 + 1e-12)
    assert lost > 0
    # Raising the knife again removes nothing.
    n = sim.n_trapped
    sim.trap_height = 2 * sim.trap_height
    assert sim.n_trapped == n


def test_rim_keeps_atoms_above_the_rim_energy_and_knife_does_not():
    # Same start, same falling trap: over the rim only atoms that actually reach it go.
    common = dict(
        n_atoms=49, frames=300, every=10, seed=4, schedule="400@0,120@300", engine="reference"
    )
    rim = run_experiment(escape="rim", **common)
    knife = run_experiment(escape="knife", **common)
    cut = G * knife.trap_height[-1]
    assert knife.final_energies.max() <= cut * (1 + 1e-12)
    assert np.count_nonzero(rim.final_energies > cut) > 0
    k = len(knife)  # the knife run may stop early, at T < Tc
    assert np.all(knife.n_trapped <= rim.n_trapped[:k])
    assert knife.n_trapped[-1] < rim.n_trapped[k - 1]


def test_constant_eta_schedule_tracks_its_target_while_n_falls():
    target = 5.0
    sim = _gas(150, "knife", 5, win=False)  # no win: collisions continue below Tc
    schedule = parse_schedule(f"eta={target}")
    schedule.apply(sim, 0.0)
    n_start = sim.n_trapped
    # The cut is self-consistent: eta = m g H / kT, kT from the mean energy of the law cut
    # at eta kT, for the atoms that remain.
    kt = sim.temperature / th.truncated_mean_energy(target)
    assert th.truncation_eta(sim.trap_height, kt, 1.0, G) == pytest.approx(target, rel=1e-12)
    assert th.eta_from_cut(sim.temperature, G * sim.trap_height) == pytest.approx(target, 1e-12)
    etas = []
    for frame in range(1, 1000):
        sim.advance(1.0)
        # eta just before the schedule moves H again: the drift within one frame.
        etas.append(th.eta_from_cut(sim.temperature, G * sim.trap_height))
        schedule.apply(sim, float(frame))
        if sim.n_trapped <= n_start // 2:
            break
    etas = np.array(etas)
    print(
        f"N {n_start} -> {sim.n_trapped} in {frame} frames; eta in "
        f"[{etas.min():.3f}, {etas.max():.3f}]"
    )
    assert sim.n_trapped <= n_start // 2 and not sim.won
    assert np.all(np.abs(etas / target - 1.0) < 0.10)


def test_eta_schedule_in_a_run():
    r = run_experiment(
        n_atoms=49,
        frames=150,
        every=10,
        seed=4,
        schedule="eta=6",
        escape="knife",
        engine="reference",
    )
    np.testing.assert_allclose(r.eta, 6.0, rtol=1e-9)
    assert r.n_trapped[-1] < 49
