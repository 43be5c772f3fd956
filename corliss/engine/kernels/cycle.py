"""One steady cycle by the method a run names: :func:`integrate_cycle` dispatches to the
step loop of :mod:`corliss.engine.kernels.dopri5` or
:mod:`corliss.engine.kernels.rosenbrock`.
"""

from __future__ import annotations

from corliss.engine.kernels.dopri5 import _dopri5_steps, cycle_dopri5, cycle_rk4
from corliss.engine.kernels.rosenbrock import (JACOBIAN_AGE, ROS_METHODS, _ODE23S_ARGS,
                                               _ros_steps, cycle_ros)
from corliss.engine.kernels.tableaus import KIND_ODE23S, KIND_TABLEAU, ROS_TABLEAUS


#: The compiled integrators by code (0 dopri5, 1 rk4, 2 Rosenbrock ode23s, 3 and on
#: the tableaus of :data:`ROS_METHODS`): separate functions, so that a run compiles
#: only the one it uses; one, :func:`_ros_steps` (called by :func:`cycle_ros`), for
#: every Rosenbrock method.
CYCLE_KERNELS = (_dopri5_steps, cycle_rk4, _ros_steps, _ros_steps, _ros_steps, _ros_steps)


def integrate_cycle(y0, stops, out_theta, method, rtol, atol, step, net, tier, tab, perf,
                    color, owner, max_rhs):
    """Integrate from ``stops[0]`` to ``stops[-1]``, restarting at every stop.

    Hands over to the compiled integrator of ``method`` (:data:`CYCLE_KERNELS`).

    Parameters
    ----------
    y0 : ndarray
        The state at ``stops[0]``; shape (n_state,).
    stops : ndarray
        Shaft angles [rad], increasing: the segments between them are integrated
        with a restart at each (:meth:`corliss.engine.network.Network.stops`).
    out_theta : ndarray
        Shaft angles [rad] where the state is sampled, increasing.
    method : int
        0 dopri5, 1 rk4, 2 Rosenbrock ode23s, 3 and on the Rosenbrock tableaus of
        :data:`ROS_METHODS` (``ros4``, ``rodas3``, ``rodas4``).
    rtol : float
        Relative tolerance [-] (the adaptive methods).
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n_state,).
    step : float
        The largest step of rk4 [rad].
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    tier : int
        The compiled property tier: :data:`TIER_TABLE` or :data:`TIER_PERFECT`.
    tab : tuple
        The steam table's arrays (:meth:`corliss.thermo.steam_table.SteamTable.arrays`).
    perf : ndarray
        The perfect tier's gas constant [J/(kg K)], ``cv`` [J/(kg K)] and ``u_ref``
        [J/kg]; shape (3,) (unused on the table tier).
    color : ndarray of int64
        The colour of each dynamic column (Rosenbrock;
        :meth:`corliss.engine.network.Network.column_colors`).
    owner : ndarray of int64
        Which column of each colour moves each row; shape (colours, n_state).
    max_rhs : int
        The run-time budget: most right-hand-side evaluations.

    Returns
    -------
    y_end : ndarray
        The state at ``stops[-1]``; shape (n_state,).
    samples : ndarray
        ``samples[:, k]`` the state at ``out_theta[k]``; shape (n_state, outputs).
    nfev : int
        Right-hand-side evaluations spent.
    ok : bool
        False when the step size collapsed, the state went non-finite or more than
        ``max_rhs`` evaluations were spent.
    clamps : ndarray
        Evaluations that clamped a state, shape (6,), indexed by ``CL_*``: at visited
        states (the ends of accepted steps) and at trial states (stages, probes,
        rejected steps) apart.
    """
    if method == 0:
        return cycle_dopri5(y0, stops, out_theta, rtol, atol, net, tier, tab, perf, max_rhs)
    if method == 1:
        return cycle_rk4(y0, stops, out_theta, step, net, tier, tab, perf, max_rhs)
    if method >= 3:
        tableau, kind = ROS_TABLEAUS[ROS_METHODS[method - 3]], KIND_TABLEAU
    else:
        tableau, kind = _ODE23S_ARGS, KIND_ODE23S
    return cycle_ros(y0, stops, out_theta, rtol, atol, net, tier, tab, perf, color, owner,
                     max_rhs, JACOBIAN_AGE, *tableau, kind)
