"""Each kernel compiles once for its kind of arguments: read-only inputs (``np.broadcast_to``'s
views, frozen arrays, pyarrow's columns) and prange's unsigned indices reach no kernel
(:func:`tumble.jit.kernel_array`). In a cold run of the suite they had compiled 30 kernels a second
time, the engine's ``dop853`` and ``fixed_rk8`` among them (10-16 CPU-s each).

numba types an array by its dtype, dimensions, layout and whether it is read-only: a dispatcher's
``signatures`` list every type it compiled (or loaded) in this process, so each is checked here
after a run with read-only inputs, together with whatever the rest of the suite ran in this worker.
"""

from __future__ import annotations

import numpy as np
import pytest

from tumble.dynamics.engine.front import _kernels, run_body
from tumble.dynamics.methods.exact_batch import free_rotation_batch
from tumble.dynamics.methods.exact_parameters import compiled_kernels
from tumble.dynamics.models.drag import drag_omega
from tumble.jit import kernel_array


def _frozen(*values) -> list[np.ndarray]:
    out = []
    for v in values:
        a = np.array(v, dtype=float)
        a.setflags(write=False)
        out.append(a)
    return out


def _kinds(dispatcher) -> list[str]:
    """The argument types of every signature compiled that no kernel should see: read-only arrays,
    unsigned integers, arrays that are not C-contiguous."""
    from numba import types

    bad = []
    for signature in dispatcher.signatures:
        for a in signature:
            if (isinstance(a, types.Array) and (not a.mutable or a.layout != "C")) or (
                    isinstance(a, types.Integer) and not a.signed):
                bad.append(f"{dispatcher.__name__}: {a}")
    return bad


def test_a_frozen_body_and_frozen_times_run_on_the_kernels_of_plain_arrays():
    I, w, q, t = _frozen([1.0, 2.0, 3.0], [0.1, 2.0, 0.1], [0.0, 0.0, 0.0, 1.0], np.linspace(0.0, 1.0, 5))
    form = (1, (0.0, 0.0, 0.3))  # a constant body torque
    frozen = run_body("rk8", I, w, q, t, form, step=0.05)
    plain = run_body("rk8", I.copy(), w.copy(), q.copy(), t.copy(), form, step=0.05)
    assert np.array_equal(frozen[0], plain[0]) and np.array_equal(frozen[1], plain[1])
    run_body("rk8", I, w, q, t, form, step=1)  # a whole number of seconds: the step goes in as a float
    k = _kernels()
    assert _kinds(k.fixed_rk8) == []
    assert len(k.fixed_rk8.signatures) == 1


def test_the_exact_batch_and_the_drag_integration_take_read_only_inputs_as_plain_ones():
    I, w, q, t = _frozen([[1.0, 2.0, 3.0]] * 3, [[0.1, 2.0, 0.1]] * 3, [[0.0, 0.0, 0.0, 1.0]] * 3,
                         np.linspace(0.0, 2.0, 7))
    omega, quat = free_rotation_batch(I, w, q, t)
    again, _ = free_rotation_batch(I.copy(), w.copy(), q.copy(), t.copy())
    assert np.array_equal(omega, again)
    assert _kinds(compiled_kernels().motion_serial) == [] and _kinds(compiled_kernels().motion_body) == []
    # the fits' drag, with the times broadcast to every body (a read-only view before kernel_array)
    w1 = drag_omega(I, w, t, quadratic=np.broadcast_to([1e-3, 2e-3, 3e-3], (3, 3)))
    from tumble.dynamics.models import fit_kernels

    assert w1.shape == (3, 7, 3) and _kinds(fit_kernels.drag_integrate) == []


@pytest.mark.parametrize("make", [
    lambda: np.broadcast_to(np.ones(3), (3,)),          # read-only, the shape unchanged
    lambda: np.ones((3, 2))[:, 0],                       # not contiguous
    lambda: np.ones(3, dtype=np.float32),                # another dtype
    lambda: [1.0, 1.0, 1.0],                             # not an array
])
def test_kernel_array_gives_one_kind_of_array(make):
    a = kernel_array(make())
    assert a.dtype == np.float64 and a.flags.c_contiguous and a.flags.writeable and a.tolist() == [1.0, 1.0, 1.0]


def test_kernel_array_keeps_a_plain_array_and_broadcasts_to_a_shape():
    a = np.arange(3.0)
    assert kernel_array(a) is a
    b = kernel_array(a, (2, 3))
    assert b.tolist() == [[0.0, 1.0, 2.0]] * 2 and b.flags.writeable and b.flags.c_contiguous
    b[0, 0] = 5.0  # a copy, not a view of a
    assert a[0] == 0.0


def test_the_check_sees_a_kernel_compiled_for_a_read_only_array():
    from numba import njit

    first = njit(lambda a: a[0])
    frozen = np.ones(2)
    frozen.setflags(write=False)
    assert first(np.ones(2)) == first(frozen) == 1.0
    assert len(first.signatures) == 2 and len(_kinds(first)) == 1
