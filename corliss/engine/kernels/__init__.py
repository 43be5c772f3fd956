"""The compiled kernels: right-hand sides and integrators of the crank-resolved model.

Their modules, by concern: :mod:`~corliss.engine.kernels.mechanism` (slider crank,
volumes, port areas), :mod:`~corliss.engine.kernels.properties` (node properties and
their clamps), :mod:`~corliss.engine.kernels.balances` (the right-hand side and the
wall's laws), :mod:`~corliss.engine.kernels.loop` (the governed speed loop's
right-hand side), :mod:`~corliss.engine.kernels.clamps`,
:mod:`~corliss.engine.kernels.tableaus` and :mod:`~corliss.engine.kernels.stepping`
(the step arithmetic and its control), :mod:`~corliss.engine.kernels.jacobians`, the
step loops of each method (:mod:`~corliss.engine.kernels.dopri5`,
:mod:`~corliss.engine.kernels.rosenbrock`: one loop per method serves a steady cycle
and a turn of the governed loop, the turn passed as an optional last argument, None
for a cycle, which numba compiles as a version of its own), the dispatch by method
(:mod:`~corliss.engine.kernels.cycle`) and the cache (:mod:`~corliss.engine.kernels.cache`).

The equations are those of :mod:`corliss.engine.network`: control volumes (cylinder
ends, chest) joined by ports, each with a mass and energy balance.  The network is a
tuple of plain arrays (:meth:`corliss.engine.network.Network.arrays`); one call
integrates a whole cycle.  :func:`derivatives` takes the properties of every node as
given, so the reference path (HEOS, called from Python) and the compiled tiers share
one implementation of the physics.  The integrators:

* ``"dopri5"``: Dormand-Prince 5(4), adaptive, with the usual error norm
  ``max |err_i| / (atol_i + rtol |y_i|)``, step-size control with safety 0.9 and
  limits 0.2-5, FSAL; restarted at every kink of the port areas, so a port opening
  never lies inside a step (no storm of rejected steps);
* ``"rk4"``: classical fourth-order Runge-Kutta at a fixed crank-angle step, each
  segment between kinks divided into equal steps no longer than the step asked for;
* ``"rosenbrock"``: the L-stable Rosenbrock 2(3) pair of Shampine and Reichelt
  (MATLAB's ode23s; SIAM J. Sci. Comput. 18, 1997), with the Jacobian over the
  dynamic states (the quadratures do not feed back) and the derivative in crank
  angle computed analytically (:func:`~corliss.engine.kernels.jacobians._jacobian_exact`: the steam table's and the
  port flow's own derivatives, no evaluation of the right-hand side) where the
  network has no state-dependent wall heat, else by finite differences, columns
  grouped by the network's structure (:meth:`Network.column_colors`).  Pressure
  equalisation through an open port is stiff (an eigenvalue near -300 per radian on
  the default engine), which holds the explicit methods to steps of about 0.6 deg
  whatever their tolerance; the Rosenbrock method steps over it;
* ``"ros4"``, ``"rodas3"``, ``"rodas4"``: Rosenbrock methods of higher order from
  their tableaus (:data:`~corliss.engine.kernels.tableaus.ROS_TABLEAUS`), on the same Jacobian and in the same
  compiled step loop as ode23s (:func:`~corliss.engine.kernels.rosenbrock.cycle_ros`, one integrator for every
  Rosenbrock method, so that a run of one compiles them all): Shampine's A-stable
  4(3) pair, and the L-stable, stiffly accurate RODAS3 (order 3) and RODAS4 (order
  4).  On the accuracy study's three
  scenes they reach either preset's accuracy for a half to two thirds of its
  evaluations (the README's "Accuracy and time").  On a very stiff network (ports
  1000 times too large) they ran out of the run-time budget with the
  finite-difference Jacobian; with the analytic one they settle in 3 cycles of
  3,000 (RODAS4) and 6,700 (``ros4``) evaluations.  They are offered, not presets.

Output samples between steps come from cubic Hermite interpolation on the states and
derivatives at the step ends (third-order, well inside the step error).

Compiled code is cached on disk by numba (``cache=True``): a run pays compilation
once per machine (measured in the accuracy study).  What it compiles is kept small:
the right-hand side is one compiled function (:func:`~corliss.engine.kernels.balances.rhs`, its parts and the property
lookups inlined into it once), called by one function per integrator
(:data:`~corliss.engine.kernels.cycle.CYCLE_KERNELS`), so that a run compiles the right-hand side once and only the
integrator it uses; inlining :func:`~corliss.engine.kernels.balances.rhs` itself at every stage of every method, as
before, made numba compile it ten times (2 min against 10 s on a loaded 2-core
machine).  The functions that take the network or the table tuple stay inlined inside
:func:`~corliss.engine.kernels.balances.rhs`: a call that passes those tuples costs more than the work of a small one.

:func:`~corliss.engine.kernels.balances.rhs` is compiled without numba's reference counting (``_nrt=False``, the flag
numba's own string functions use): every array it reads from the network and table
tuples would otherwise be counted up and down with an atomic instruction (over 200 in
its compiled code, many inside the loops over nodes and edges), which cost 0.76 of its
1.2 us on the default scene.  It allocates nothing and keeps no reference past its
return (its arrays are its caller's), so no count is needed; numba refuses to compile
an allocation there (a typing error, not a silent leak).  So are the integrators'
step loops (:func:`~corliss.engine.kernels.dopri5._dopri5_steps`, :func:`~corliss.engine.kernels.rosenbrock._ros_steps`, on scratch their Python callers
:func:`~corliss.engine.kernels.dopri5.cycle_dopri5` and :func:`~corliss.engine.kernels.rosenbrock.cycle_ros` allocate) and their helpers (clamp tallies,
copies, Hermite output, the Jacobians, W's inverse and solves, the first step): numba
counts a reference on every array argument on entry and exit of a compiled function,
and on every view of a scratch array, about 0.4 us of a ros4 step's 3.4 before.  The
private helpers only compiled code calls (the finite-difference Jacobian, W's
inverse and solves) have no CPython wrapper (``no_cpython_wrapper``: less to compile; a
call from Python would crash the interpreter).  The public ones keep theirs: without,
a first ``ros4`` call compiled 0.4-0.6 s less (16.2 and 15.9 against 16.5 and 16.5 s).

Numba keys a function's cache on the content of its own file alone, not on the
compiled functions it inlines from other modules (:mod:`corliss.thermo.orifice`,
:mod:`corliss.thermo.steam_table` and the kernels' own modules).  Every kernel is
compiled through :func:`corliss.engine.kernels.compiled.njit`, which keys its cache on
the content of every module it can inline instead: a change to any of them recompiles
the kernels that inline it, with no revision number to bump.
"""
