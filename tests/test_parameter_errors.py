"""Errors carry the parameter's name as data; each command line names its option from a
table (issue 26.2)."""

from __future__ import annotations

import pickle

import pytest

from evapcool import limits
from evapcool.limits import ParameterError


def test_the_name_is_data_and_the_line_reads_as_before():
    with pytest.raises(ParameterError) as info:
        limits.N_ATOMS.check("n_atoms", 0)
    exc = info.value
    assert isinstance(exc, ValueError)
    assert exc.parameter == "n_atoms"
    assert str(exc) == "n_atoms must be a whole number from 1 to 1000000 (got 0)"
    assert exc.render({"n_atoms": "--atoms"}) == (
        "--atoms must be a whole number from 1 to 1000000 (got 0)"
    )


def test_a_joint_limit_names_the_options_that_command_has():
    exc = ParameterError("n_atoms", "99 atoms do not fit", joint=("radius", "curvature"), sep=": ")
    assert str(exc) == "n_atoms: 99 atoms do not fit"
    assert exc.parameters == ("n_atoms", "radius", "curvature")
    applet = {"n_atoms": "--atoms", "radius": "--radius"}
    lab = {**applet, "curvature": "--curvature"}
    assert exc.render(applet) == "--atoms and --radius: 99 atoms do not fit"
    assert exc.render(lab) == "--atoms, --radius and --curvature: 99 atoms do not fit"


def test_it_survives_pickling_as_sweeps_send_it_between_processes():
    exc = ParameterError("radius", "must be > 0", joint=("n_atoms",), sep=": ")
    back = pickle.loads(pickle.dumps(exc))
    assert (back.parameter, back.detail, back.joint, back.sep) == (
        "radius",
        "must be > 0",
        ("n_atoms",),
        ": ",
    )
    assert str(back) == str(exc)
