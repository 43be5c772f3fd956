"""The knobs of a run: effects a scene may name, and fidelity presets.

Effects are switched by the scene alone; the model is assembled from those named
(``docs/architecture.md``, "The engine"; the README lists them).  Fidelity presets
are documented sets of knobs, each knob also settable alone in ``[run]``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

#: Effects a scene may name, with what each does.  Only these are implemented; any
#: other name is refused.
EFFECTS: dict[str, str] = {
    "port_flow": "finite port areas with discharge coefficient, choking and reverse flow; "
                 "without it, admission and exhaust are at chest and back pressure",
    "rod_angularity": "exact slider crank with the finite connecting rod; without it, an "
                      "infinite rod",
    "inertia": "reciprocating masses ([engine] reciprocating_mass) in the crank effort "
               "(Marks Art. 35)",
    "steam_chest": "a steam chest of finite volume ([supply] chest_volume) fed from the boiler "
                   "through a steam pipe ([supply] pipe_diameter) and its throttle valve "
                   "([supply] throttle, throttle_law)",
    "leakage": "leaks past the valve into each end ([engine] valve_leakage_area) and past the "
               "piston ([engine] piston_leakage_area), as orifices of equivalent area; or "
               "by the period's law (leakage_model = \"period\": a rate of leak times the "
               "pressure difference, chest to exhaust, past each closed steam and exhaust "
               "edge of the valve, past the piston)",
    "wall_heat": "heat between the steam and the cylinder walls: initial condensation and "
                 "re-evaporation ([engine] wall_heat_model = \"skin\" (a wall whose surface "
                 "temperature and water film are states, heat only down the temperature "
                 "difference; condensing_coefficient, jacket, wall_thickness), \"marks\" "
                 "(Marks's law of condensation as a schedule, Arts. 74-75), \"english\" "
                 "(English's law, DPJ 267, 1888, p. 302, on the same schedule; jacket), "
                 "\"conductance\" "
                 "(his constant as a surface conductance, Art. 82) or \"adair\" (Adair et al. "
                 "1972); without port_flow, the skin wall only)",
    "friction": "engine friction torque ([engine] friction_torque, friction_torque_per_speed): "
                "brake power and mechanical efficiency",
}

#: Effects of the design that this version does not have yet.
PLANNED_EFFECTS: tuple[str, ...] = ()

#: Keys of [engine] that an effect needs.
EFFECT_KEYS = {"inertia": ("reciprocating_mass",), "friction": ("friction_torque",),
               "steam_chest": ("supply.chest_volume", "supply.pipe_diameter")}

MODELS = ("crank_resolved", "ideal", "mean_value")
EXPANSION_LAWS = ("hyperbolic", "isentropic")
#: Integrators: scipy's (any property tier, Python right-hand side) and the compiled
#: kernel's (``dopri5`` adaptive explicit, ``rk4`` fixed step, ``rosenbrock`` adaptive
#: L-stable of order 2, ``ros4`` adaptive A-stable Rosenbrock of order 4; tiers with a
#: compiled form only).
SCIPY_METHODS = ("LSODA", "BDF", "Radau", "RK45", "DOP853")
COMPILED_METHODS = ("dopri5", "rk4", "rosenbrock", "ros4", "rodas3", "rodas4")
METHODS = SCIPY_METHODS + COMPILED_METHODS
#: Integrators of the transient loop (:mod:`corliss.engine.kernels.loop`): ``dopri5``,
#: and the Rosenbrock methods of :data:`corliss.engine.kernels.tableaus.ROS_TABLEAUS`.
TRANSIENT_METHODS = ("dopri5", "ros4", "rodas3", "rodas4")


@dataclass(frozen=True)
class Fidelity:
    """One set of accuracy knobs.

    Parameters
    ----------
    name : str
        Preset it came from (or ``"custom"``).
    properties : str
        Steam-property tier (``heos``, ``table`` or ``perfect``).
    method : str
        Integrator: a ``scipy.integrate.solve_ivp`` method (:data:`SCIPY_METHODS`), or
        the compiled ``"dopri5"`` (adaptive), ``"rk4"`` (fixed step),
        ``"rosenbrock"`` (adaptive, L-stable, order 2) or ``"ros4"`` (adaptive,
        A-stable, order 4).
    rtol : float
        Relative tolerance of the adaptive integrators [-].
    portmap_points : int
        Uniform crank-angle intervals of the PortMap (kinks are added) [-].
    convergence_tolerance : float
        A steady run is periodic when its distance from periodic is below this
        fraction [-]: the cycle-to-cycle change of indicated work, and crank-resolved
        also of the masses, energies, mass balance and wall temperatures, each against
        its own scale (``SteadyResult.periodicity``).
    max_cycles : int
        Give up (with a warning in the summary) after this many cycles.
    output_step_deg : float
        Crank-angle step of the time series and cards [deg].
    step_deg : float
        Crank-angle step of the fixed-step ``rk4`` integrator [deg].
    transient_method : str or None
        Integrator of a transient run's loop (:data:`TRANSIENT_METHODS`), at ``rtol``;
        None: ``method`` (``dopri5`` when the loop does not have it).
    exact_method : str or None
        Integrator of a steady crank-resolved run whose Rosenbrock Jacobian is exact
        (:meth:`steady_integrator`): a compiled Rosenbrock method, at ``exact_rtol``;
        None: ``method`` everywhere.  A preset's own: a fidelity changed in any field
        (a scene's ``method`` or ``rtol``, ``dataclasses.replace``) integrates with
        ``method`` at ``rtol``, as it says.
    exact_rtol : float or None
        Relative tolerance of ``exact_method`` [-].
    """

    name: str
    properties: str
    method: str
    rtol: float
    portmap_points: int
    convergence_tolerance: float
    max_cycles: int
    output_step_deg: float
    step_deg: float = 1.0
    transient_method: str | None = None
    exact_method: str | None = None
    exact_rtol: float | None = None

    def steady_integrator(self, exact_jacobian: bool) -> tuple[str, float]:
        """The integrator of a steady crank-resolved run, and its tolerance.

        For a preset as it stands, ``exact_method`` at ``exact_rtol`` where the run's
        Jacobian is exact (the compiled Rosenbrock methods differentiate the
        right-hand side analytically unless a wall's heat depends on the state: the
        skin, conductance and Adair models, whose switches at the saturation
        temperature a finite-difference Jacobian straddles, so that these methods
        crawl there); otherwise ``method`` at ``rtol``.

        Parameters
        ----------
        exact_jacobian : bool
            Whether the run's network has an exact Jacobian
            (:func:`corliss.engine.kernels.jacobians.exact_jacobian_covers`).

        Returns
        -------
        method : str
            The integrator (:data:`METHODS`).
        rtol : float
            Its relative tolerance [-].
        """
        if (exact_jacobian and self.exact_method is not None and self.exact_rtol is not None
                and PRESETS.get(self.name) == self):
            return self.exact_method, float(self.exact_rtol)
        return self.method, self.rtol


#: The presets.  ``reference``: IAPWS-95 through HEOS at every call, LSODA at 1e-9;
#: ``standard``: the steam table, and RODAS4 at rtol 2e-6 where the Jacobian is exact
#: (within 0.006 % of the reference in power and steam on the accuracy study's three
#: scenes, at about half dopri5's time; at 10 rpm 2,000 evaluations a cycle where dopri5
#: needed 84,000), else the compiled adaptive dopri5 at 1e-6 (a skin, conductance or
#: Adair wall: there, on a finite-difference Jacobian, RODAS4 at 2e-6 needed 14 and 30
#: times dopri5's evaluations on the skin and conductance walls of the default engine,
#: RODAS3 at 5e-6 3.6 and 2.6 times, the switches at the saturation temperature
#: defeating their error estimates);
#: ``fast``: the steam table and the compiled L-stable Rosenbrock method (the ode23s
#: pair, its steps by Gustafsson's predictive controller) at rtol 5e-5 (the explicit
#: methods are held to small steps by the stiff pressure equalisation through an open
#: port, whatever their tolerance).  Within 0.26 % of the reference in power and steam
#: on the accuracy study's three scenes; at 7e-5 12 % fewer evaluations and 0.30 %, at
#: 1e-4 0.37 % on the short cut-off, and the crank end's admission pressure of the
#: default card 0.31 % of supply off a converged run (tests/test_rosenbrock_tableaus.py
#: holds it within 0.25 %).  Its measured price is on the accuracy page (docs/accuracy.md,
#: benchmarks/accuracy_vs_time.py).  (Before the predictive controller, at 1e-4 its
#: steam on the default card scattered between +0.11 % and +0.29 % of a converged run
#: as the tolerance moved by a thousandth: the error-only control walked onto a false
#: solution of the pair at that admission, and its cycle was not periodic.)  The
#: higher-order Rosenbrock methods (``ros4``, ``rodas3``, ``rodas4``) reach either
#: preset's accuracy on the study's three scenes (``fast``'s at rtol 1e-4 with
#: ``rodas4``: 730 evaluations a cycle of the default card, against the pair's 1,030
#: before its predictive controller and 340 after it; ``standard``'s with ``ros4`` at
#: 7e-6: 1,870 against dopri5's 4,022), but on ports 1000 times too large
#: (tests/test_property_tiers.py) both ran out of the run-time budget with a finite-difference Jacobian (with the
#: analytic one, now used wherever the wall heat does not depend on the state, they
#: settle in 3 cycles of 3,000 and 6,700 evaluations), and ``ros4`` at rtol 1e-8 on
#: a compound with every effect (whose conductance wall heat keeps the finite
#: differences): the presets keep the methods that cope.  (Diagnosed on the ports,
#: with the finite-difference Jacobian:
#: RODAS4's stages, whose coefficients reach 12.5, leave the steam table's range and
#: are clamped in every step of the blow-down, which holds it to steps of 0.001 deg;
#: ``ros4`` and RODAS3 clamp nothing there but reject every other step at about
#: 0.01 deg, their error estimates failing as the flux through the huge ports turns
#: nonlinear within a step.)
#:
#: A transient run's loop integrates with dopri5 at ``standard`` and with ``ros4`` at
#: ``fast`` (``transient_method``).  On the 60-second load step of
#: benchmarks/load_step.py dopri5 is held by the stiff port flow to steps of 1 to 2 deg
#: over three quarters of each turn (the step times the largest eigenvalue, -60 to
#: -330 per radian, at 2.2 to 3.1, the edge of its stability), so that at 5e-5 it
#: needed more evaluations than at 1e-6; ``ros4`` steps over the stiffness, and at
#: 5e-5 took half of dopri5's evaluations there (1,020 a turn against 1,940) with a
#: fifth of its speed error; on the ten governed scenes (20 s each) it was faster on
#: nine, four to eight times on the throttling ones.  At ``standard``'s accuracy the
#: port flow's own pace holds every method to such steps on that engine, and ``ros4``,
#: nine evaluations a step with its Jacobian, needed 2,100 a turn at 5e-6 against
#: dopri5's 1,640 at 1e-6 for a speed error no larger (RODAS3, RODAS4, the W-method
#: ROS34PW2 and a Jacobian kept for two or three steps all cost more); on two
#: throttling scenes, whose steam chest is stiffer still, it took about 40 % of dopri5's
#: time for that accuracy, so a scene may name ``method = "ros4"``.
PRESETS: dict[str, Fidelity] = {
    "reference": Fidelity("reference", "heos", "LSODA", 1e-9, 5760, 1e-6, 60, 0.25),
    "standard": Fidelity("standard", "table", "dopri5", 1e-6, 1440, 1e-4, 40, 1.0,
                         exact_method="rodas4", exact_rtol=2e-6),
    "fast": Fidelity("fast", "table", "rosenbrock", 5e-5, 720, 1e-3, 20, 2.0,
                     transient_method="ros4"),
}


#: A transient run's time series records every output step (``record = "degree"``) when
#: its duration is at most this many turns at the run speed, and once a turn (``"cycle"``)
#: when longer, unless the scene's ``[run] record`` says which: at the standard 1 degree,
#: 300 turns are 108 000 rows (about 8 MB of CSV, and a second to write and draw).
RECORD_DEGREE_MAX_TURNS = 300


def record_of(run) -> str:
    """What a run's time series records.

    The scene's ``[run] record``, or by default ``"degree"`` for a duration of up to
    :data:`RECORD_DEGREE_MAX_TURNS` turns at ``run.speed`` and ``"cycle"`` beyond (a
    run ``until_settled`` follows its duration's choice); a steady run's default is
    ``"degree"`` (every cycle at every output step), and its ``"cycle"`` records each
    cycle once and the last at every output step.

    Parameters
    ----------
    run : RunSpec
        The scene's ``[run]``: ``record``, ``duration_s`` [s] and ``speed_rad_s``
        [rad/s].

    Returns
    -------
    str
        ``"step"``, ``"degree"`` or ``"cycle"``.
    """
    if run.record is not None:
        return run.record
    turns = (run.duration_s or 0.0) * run.speed_rad_s / (2.0 * math.pi)
    return "degree" if turns <= RECORD_DEGREE_MAX_TURNS else "cycle"
