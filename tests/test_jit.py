"""lubrication._jit.specialise: a template compiled with the functions it calls bound by name."""

import numpy as np
import pytest

from lubrication._jit import jit, sources_hash, specialise


@jit
def _double(x):
    return 2.0 * x


@jit
def _square(x):
    return x * x


def _template(values):
    out = np.empty(values.size)
    for i in range(values.size):
        out[i] = KERNEL(values[i]) + 1.0  # noqa: F821 - bound by specialise
    return out


def test_each_copy_calls_its_own_function():
    values = np.array([0.5, 3.0])
    doubled = specialise(_template, "double", KERNEL=_double)
    squared = specialise(_template, "square", KERNEL=_square)
    np.testing.assert_array_equal(doubled(values), [2.0, 7.0])
    np.testing.assert_array_equal(squared(values), [1.25, 10.0])
    assert doubled.py_func.__qualname__ == "_template_double"


def test_a_name_taken_by_other_globals_is_refused():
    """Numba files a copy under its name: a second meaning of one name would load the first's code."""
    specialise(_template, "twice", KERNEL=_double)
    specialise(_template, "twice", KERNEL=_double)  # the same globals: accepted
    with pytest.raises(ValueError, match="_template_twice is already compiled with other globals"):
        specialise(_template, "twice", KERNEL=_square)


def test_the_sources_hash_follows_every_byte(tmp_path):
    first, second = tmp_path / "a.py", tmp_path / "b.py"
    first.write_text("x = 1\n")
    second.write_text("y = 2\n")
    before = sources_hash(first, second)
    assert sources_hash(first, second) == before
    second.write_text("y = 3\n")
    assert sources_hash(first, second) != before


def test_the_equations_are_filed_under_the_kernels_sources():
    """Compiled with a force kernel from another file, the equations' copies carry that file's hash in their name."""
    from dynamics.contact import full as contact
    from dynamics.equations import forces, full

    copies = [*full.model_functions(forces.CLOSED), full.rhs, full.jacobian, contact.contact_rhs,
              *contact.contact_functions(forces.EXACT)]
    assert all(c.py_func.__qualname__.endswith(forces.KERNELS_HASH) for c in copies)
