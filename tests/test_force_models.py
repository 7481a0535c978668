"""The force models as the equations of motion take them (a kernel and one packed array) against the faces.

:func:`lubrication.registry.kernel_model` packs a model's options into one float64
array (:mod:`lubrication.kernels`), which its compiled kernel unpacks. The forces
through it must be those of the lubrication package's own faces, which take the
same discretisation from their arguments rather than from the packed array: the
same numerics, so equal to rounding (a few ulp, checked at rel 1e-12). The
finite-length and inertial compositions have their own tests
(tests/test_ends_cli.py, tests/test_inertia_force_model.py); the registry's rules,
tests/test_registry.py.
"""

import numpy as np
import pytest

from dynamics.equations import full
from lubrication.cavitation import cavitating_forces
from lubrication.closed_form import closed_form_forces
from lubrication.geometry import Annulus, Motion
from lubrication.registry import kernel_model
from lubrication.reynolds import reynolds_forces
from lubrication.stokes_exact import stokes_exact_forces

from apparatus import OIL, STEEL

MOTIONS = (Motion(eps_dot=-3e-4, chi_dot=0.4, omega_a=1.1, omega_b=-0.7),
           Motion(eps_dot=2e-3, chi_dot=-0.2, omega_a=0.3, omega_b=0.9))


@pytest.mark.parametrize("kappa", [0.0, 0.3, 0.9, 0.999])
@pytest.mark.parametrize(("model", "reference"), [
    (("closed-form", {}), closed_form_forces),
    (("stokes-exact", {}), stokes_exact_forces),
    (("reynolds", {"n": 16}), lambda *state: reynolds_forces(*state, n=16, points_per_cell=1)),
    (("reynolds", {"n": 24, "grid": "uniform", "profile": "eccentric", "points_per_cell": 3}),
     lambda *state: reynolds_forces(*state, n=24, grid="uniform", profile="eccentric", points_per_cell=3)),
    (("reynolds", {"n": 32, "cavitation": "jfo", "p_cav": 1e5, "p_ref": 1.2e5}),
     lambda *state: cavitating_forces(*state, "jfo", n=32, points_per_cell=1, p_cav=1e5, p_ref=1.2e5)),
    (("reynolds", {"n": 16, "cavitation": "half-sommerfeld", "points_per_cell": 2}),
     lambda *state: cavitating_forces(*state, "half-sommerfeld", n=16, points_per_cell=2)),
], ids=["closed-form", "stokes-exact", "reynolds", "reynolds-uniform-eccentric", "jfo", "half-sommerfeld"])
def test_packed_model_gives_the_lubrication_packages_forces(model, reference, kappa):
    name, options = model
    packed = kernel_model(name, **options)
    annulus = Annulus.from_kappa(0.0127, 0.0179, kappa, length=0.1)
    for motion in MOTIONS:
        got = np.array(packed.forces(annulus, motion, OIL).as_tuple())
        want = np.array(reference(annulus, motion, OIL).as_tuple())
        np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-14 * np.max(np.abs(want)))


def test_a_kernel_is_compiled_into_the_equations_once_for_all_its_options():
    """The options are data: the closed forms with and without open ends take the same compiled functions,
    and the right-hand side sees the data it is given (the ends change the forces, so the rates)."""
    ap = STEEL
    infinite = kernel_model("closed-form")
    open_ends = kernel_model("closed-form", ends="open", length_over_a=ap.length / ap.a)
    assert full.model_functions(infinite) is full.model_functions(open_ends)
    assert full.model_functions(infinite) is not full.model_functions(kernel_model("stokes-exact"))
    y = full.initial_state(ap, 0.6, 1.0, 0.1, 0.3, 2.0, -1.0)
    rhs = full.model_functions(infinite).rhs
    assert not np.array_equal(rhs(0.0, y, full.run_args(ap, infinite, gap_floor=1e-9)),
                              rhs(0.0, y, full.run_args(ap, open_ends, gap_floor=1e-9)))
