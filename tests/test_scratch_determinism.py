"""A run computes the same numbers whatever the process did before it.

The compiled loops keep, from one right-hand-side evaluation to the next, each node's
properties on a scratch array (``pr``, rows ``PR_*`` of
:mod:`corliss.engine.kernels.properties`): the temperature found there starts the
steam table's wet-state Newton iteration (:func:`corliss.thermo.steam_table.lookup_near`,
whose answer agrees from any start to 1e-12 K, not to the bit), and the angle and state
found there let the Jacobian reuse a lookup.  Allocated with ``np.empty``, that array
held what the allocator last freed: in a process that had run other things, a governed
transient at ``fast`` took 110,868 right-hand-side evaluations one time and 150,472
another (porter-throttling-governor, 0.1 s), the watt-throttling governor 94,563,
98,923 or 99,286.  An adaptive integrator magnifies a last-bit difference into another
sequence of steps, so the whole run moved.

The test makes the allocator's leftovers what they were in those runs: before each
turn (and each cycle) a compiled function frees a block of the scratch's shape filled
with a temperature inside the wet bracket (373.15 K: what a previous turn of a
saturated engine leaves), or with NaN (what is never read).  The run must not see the
difference: the same evaluation count and the same bytes in every column.  With the
scratch taken from ``np.empty`` the two runs of the throttling governor differed (the
evaluation counts by thousands); allocated with NaN ("not known"), they agree.
"""

from __future__ import annotations

import hashlib
import math

import numpy as np
import pytest
from numba import njit

from corliss.engine import crank_resolved, transient
from corliss.engine.kernels import cycle
from corliss.engine.kernels.properties import PR_ROWS
from corliss.engine.simulate import simulate
from corliss.scene import bundled_scenes, load_scene

#: A temperature inside the wet iteration's bracket (triple point to saturation) [K].
WET_K = 373.15


@njit(cache=True)
def _leave(rows, cols, value):
    """Allocate a (rows, cols) block filled with ``value`` and free it: the next block
    of that size the allocator hands out holds ``value``."""
    a = np.full((rows, cols), value)
    return a[0, 0]


def _fingerprint(result) -> tuple[int, str]:
    frame = result.timeseries.select_dtypes("number")
    data = np.ascontiguousarray(frame.to_numpy(dtype=float))
    return int(result.rhs_evaluations), hashlib.sha256(data.tobytes()).hexdigest()


def _run_after_leaving(scene, value: float, monkeypatch) -> tuple[int, str]:
    """The scene's fingerprint with a ``value``-filled scratch-sized block freed before
    every compiled turn and cycle."""
    make_turn = transient._turn_integrator
    real_cycle = cycle.integrate_cycle

    def turn_integrator(method, network):
        turn = make_turn(method, network)
        nv = network.n_nodes

        def poisoned(*args):
            _leave(PR_ROWS, nv, value)
            return turn(*args)
        return poisoned

    def poisoned_cycle(y0, stops, out_theta, method, rtol, atol, step, net, *rest):
        _leave(PR_ROWS, net.node_kind.shape[0], value)
        return real_cycle(y0, stops, out_theta, method, rtol, atol, step, net, *rest)

    monkeypatch.setattr(transient, "_turn_integrator", turn_integrator)
    monkeypatch.setattr(crank_resolved.cycle, "integrate_cycle", poisoned_cycle)
    try:
        return _fingerprint(simulate(scene))
    finally:
        monkeypatch.undo()


@pytest.mark.parametrize("name, fidelity, transient_s", [
    ("porter-throttling-governor", "fast", 0.06),    # the run seen to move
    ("buckeye-governor", "fast", 0.06),              # a shaft governor's cut-off loop
    ("default", "standard", None),                   # the steady cycle's loops
])
def test_a_run_does_not_read_what_the_allocator_left(name, fidelity, transient_s,
                                                     monkeypatch):
    scene = load_scene(bundled_scenes()[name]).with_fidelity(fidelity)
    scene = (scene.replace_run(duration_s=transient_s) if transient_s is not None
             else scene.replace_run(cycles=2))
    clean = _run_after_leaving(scene, math.nan, monkeypatch)
    wet = _run_after_leaving(scene, WET_K, monkeypatch)
    assert wet == clean
