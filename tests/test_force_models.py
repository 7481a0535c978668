"""The force models as the equations of motion see them (one packed array) against the lubrication package.

:attr:`dynamics.equations.forces.ForceModel.data` packs a model's scalars and
arrays into one float64 array, which the compiled right-hand sides unpack. The
forces through it must be those of the lubrication package's own functions,
which take the same discretisation from their arguments rather than from the
packed array: the same kernels, so equal to rounding (a few ulp, checked at
rel 1e-12). The equations of motion are compiled with each kind's kernel
(:func:`dynamics.equations.full.model_functions`) and, for any kind, with
:func:`dynamics.equations.forces.evaluate`: the same numbers. The finite-length and inertial parts have their own tests
(tests/test_ends_cli.py, tests/test_inertia_force_model.py).
"""

import dataclasses

import numpy as np
import pytest

from dynamics.apparatus import preset
from dynamics.equations import full
from dynamics.equations.forces import (
    CAVITATING,
    EXACT,
    REYNOLDS,
    closed_form,
    reynolds,
    stokes_exact,
)
from lubrication.cavitation import cavitating_forces
from lubrication.closed_form import closed_form_forces
from lubrication.geometry import Annulus, Fluid, Motion
from lubrication.reynolds import reynolds_forces
from lubrication.stokes_exact import exact_forces

FLUID = Fluid(nu=2e-4, rho=960.0)
MOTIONS = (Motion(eps_dot=-3e-4, chi_dot=0.4, omega_a=1.1, omega_b=-0.7),
           Motion(eps_dot=2e-3, chi_dot=-0.2, omega_a=0.3, omega_b=0.9))


@pytest.mark.parametrize("kappa", [0.0, 0.3, 0.9, 0.999])
@pytest.mark.parametrize(("model", "reference"), [
    (closed_form(), closed_form_forces),
    (stokes_exact(), exact_forces),
    (reynolds(n=16), lambda *state: reynolds_forces(*state, n=16, points_per_cell=1)),
    (reynolds(n=24, grid="uniform", profile="eccentric", points_per_cell=3),
     lambda *state: reynolds_forces(*state, n=24, grid="uniform", profile="eccentric", points_per_cell=3)),
    (reynolds(n=32, cavitation="jfo", p_cav=1e5, p_ref=1.2e5),
     lambda *state: cavitating_forces(*state, "jfo", n=32, points_per_cell=1, p_cav=1e5, p_ref=1.2e5)),
    (reynolds(n=16, cavitation="half-sommerfeld", points_per_cell=2),
     lambda *state: cavitating_forces(*state, "half-sommerfeld", n=16, points_per_cell=2)),
], ids=["closed-form", "stokes-exact", "reynolds", "reynolds-uniform-eccentric", "jfo", "half-sommerfeld"])
def test_packed_model_gives_the_lubrication_packages_forces(model, reference, kappa):
    annulus = Annulus.from_kappa(0.0127, 0.0179, kappa, length=0.1)
    for motion in MOTIONS:
        got = np.array(model.forces(annulus, motion, FLUID).as_tuple())
        want = np.array(reference(annulus, motion, FLUID).as_tuple())
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-14 * np.max(np.abs(want)))


MODELS = [closed_form(), stokes_exact(), reynolds(n=16), reynolds(n=32, cavitation="jfo", p_cav=1e5, p_ref=1.2e5),
          closed_form(ends="open", length_over_a=13.0), stokes_exact(inertia=True, rho=960.0)]


@pytest.mark.parametrize("model", MODELS, ids=lambda m: m.name)
def test_the_equations_compiled_for_a_kind_are_those_for_any_kind(model):
    """A run takes the functions compiled with its kind's kernel only: the numbers of the ones for any kind."""
    ap = preset("steel")
    args = full.run_args(ap, model, gap_floor=1e-9)
    own = full.model_functions(model.kind)
    rng = np.random.default_rng(3)
    for _ in range(3):
        y = full.initial_state(ap, rng.uniform(0.2, 0.95), rng.uniform(0, 6), 0.1, 0.3, 2.0, -1.0)
        np.testing.assert_array_equal(own.rhs(0.0, y, args), full.rhs(0.0, y, args))
        np.testing.assert_array_equal(own.jacobian(0.0, y, args), full.jacobian(0.0, y, args))
        polar = full.to_polar(ap, y)
        np.testing.assert_array_equal(own.polar_rhs(0.0, polar, args), full.polar_rhs(0.0, polar, args))
        np.testing.assert_array_equal(own.polar_jacobian(0.0, polar, args), full.polar_jacobian(0.0, polar, args))


@pytest.mark.parametrize("field", [{"inertia": (960.0, *stokes_exact(inertia=True, rho=960.0).inertia[1:])},
                                   {"length_over_a": 13.0}])
def test_a_reynolds_model_refuses_what_its_kernel_does_not_model(field):
    for kind in (REYNOLDS, CAVITATING):
        with pytest.raises(ValueError, match="closed forms and the exact Stokes forces only"):
            dataclasses.replace(reynolds(), kind=kind, **field)
    dataclasses.replace(stokes_exact(), kind=EXACT, **field)  # where it is modelled, accepted
