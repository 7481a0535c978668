"""Packed args: parts come back as they went in, and every model of the engine shares one type of args."""

from __future__ import annotations

import numba
import numpy as np
from numba import types

from numerics.jit import jit
from numerics.packed import pack, part, parts


@jit
def _sum_of_part(args, i):
    """What compiled code reads of part ``i``: its sum and size."""
    view = part(args, i)
    return view.sum(), view.size


def test_parts_come_back_as_views_of_what_was_packed(rng):
    arrays = [rng.normal(size=3), np.empty(0), rng.normal(size=(2, 2)), [7.0]]
    args = pack(*arrays)
    back = parts(args)
    assert len(back) == 4
    for i, (got, given) in enumerate(zip(back, arrays)):
        np.testing.assert_array_equal(got, np.ravel(given))
        assert _sum_of_part(args, i) == (np.sum(given), np.size(given))  # the compiled reader agrees
    np.testing.assert_array_equal(args[:3], arrays[0])  # the first part from index 0
    back[3][0] = 8.0
    assert _sum_of_part(args, 3) == (8.0, 1)  # views, not copies


def test_a_single_part_and_no_part():
    assert parts(pack()) == []
    np.testing.assert_array_equal(parts(pack([1.0, 2.0]))[0], [1.0, 2.0])


def test_every_model_hands_the_engine_one_type_of_args():
    """One compiled driver serves them all: the engine compiles its driver once per type of args."""
    from dynamics.apparatus import STEEL
    from dynamics.contact.full import FullContactRun
    from dynamics.contact.reduced import ContactParams
    from dynamics.contact.rough import phase_args
    from dynamics.contact.roughness import RoughContact
    from dynamics.equations import full, reduced
    from dynamics.equations.limits import Limits
    from lubrication.registry import kernel_model

    model = kernel_model("closed-form")
    params = STEEL.reduced_params
    surfaces = ContactParams(0.98, 0.3)
    found = {
        "reduced": reduced.run_args(params, gap_floor=1e-9),
        "full": full.run_args(STEEL, model, gap_floor=1e-9),
        "full, in contact": FullContactRun(STEEL, model, surfaces, Limits(), 1e-8).contact_args(True, 0.0),
        "reduced, rough surfaces": phase_args(params, RoughContact.from_seed(surfaces, 0.002, 0.3, 0.3, seed=1)),
    }
    for name, args in found.items():
        assert numba.typeof(args) == types.float64[::1], name
