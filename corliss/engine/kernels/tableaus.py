"""The integrators' coefficients and the arithmetic of one step: Dormand-Prince 5(4)
(stages, error norm, Hermite output) and the Rosenbrock methods (:data:`ROS_TABLEAUS`:
Shampine's ``ros4``, RODAS3, RODAS4, and the ode23s pair's constants), with their
stage, solution and error arithmetic shared by the cycle and the turn loops.
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine.kernels.compiled import njit


# Dormand-Prince 5(4) tableau
DOPRI_NODES = np.array([0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0])


_A = np.array([
    [0, 0, 0, 0, 0, 0],
    [1 / 5, 0, 0, 0, 0, 0],
    [3 / 40, 9 / 40, 0, 0, 0, 0],
    [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
    [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
    [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0],
    [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84],
])


_B = np.array([35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0])


_E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


@njit(cache=True, _nrt=False)
def hermite(t0, y0, f0, t1, y1, f1, t, out):
    """Cubic Hermite interpolation on a step from its end states and derivatives.

    Parameters
    ----------
    t0, t1 : float
        The step's ends [rad].
    y0, y1 : ndarray
        The states there; shape (n,).
    f0, f1 : ndarray
        Their derivatives (per radian); shape (n,).
    t : float
        Where to interpolate [rad], between ``t0`` and ``t1``.
    out : ndarray
        Written: the interpolated state; shape (n,).
    """
    h = t1 - t0
    s = (t - t0) / h
    h00 = 2 * s ** 3 - 3 * s ** 2 + 1
    h10 = s ** 3 - 2 * s ** 2 + s
    h01 = -2 * s ** 3 + 3 * s ** 2
    h11 = s ** 3 - s ** 2
    for i in range(y0.shape[0]):
        out[i] = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i]


@njit(cache=True, _nrt=False)
def dopri_stage(y, K, s_, h, ytmp):
    """The state at a Dormand-Prince stage: ``y + h sum_j a_sj K_j``.

    Parameters
    ----------
    y : ndarray
        The state at the step's start; shape (n,).
    K : ndarray
        The stages' derivatives so far; shape (7, n).
    s_ : int
        The stage, 1 to 6.
    h : float
        The step [rad].
    ytmp : ndarray
        Written: the stage's state; shape (n,).
    """
    for i in range(y.shape[0]):
        acc = 0.0
        for j in range(s_):
            acc += _A[s_, j] * K[j, i]
        ytmp[i] = y[i] + h * acc


@njit(cache=True, _nrt=False)
def dopri_error(y, ynew, K, h, atol, rtol):
    """The 5(4) pair's scaled error.

    ``max_i |err_i| / (atol_i + rtol max(|y_i|, |ynew_i|))``, the error ``err`` being
    the difference of the fifth- and fourth-order results.

    Parameters
    ----------
    y : ndarray
        The state at the step's start; shape (n,).
    ynew : ndarray
        The fifth-order state at its end; shape (n,).
    K : ndarray
        The seven stages' derivatives; shape (7, n).
    h : float
        The step [rad].
    atol : ndarray
        Absolute tolerances, in each component's unit; shape (n,).
    rtol : float
        Relative tolerance [-].

    Returns
    -------
    float
        The error [-]: the step is accurate enough at 1 or less.
    """
    err = 0.0
    for i in range(y.shape[0]):
        e = 0.0
        for j in range(7):
            e += _E[j] * K[j, i]
        e = abs(h * e) / (atol[i] + rtol * max(abs(y[i]), abs(ynew[i])))
        if e > err:
            err = e
    return err


@njit(cache=True, inline="always")
def tableau_argument(y, U, tA, st, ytmp):
    """A Rosenbrock tableau's stage argument, ``ytmp = y + sum_j a_st,j u_j``
    (the steady and the transient loops' shared arithmetic).

    Parameters
    ----------
    y : ndarray
        The state at the step's start, shape (n,).
    U : ndarray
        The stages so far, shape (stages, n).
    tA : ndarray
        The tableau's a_ij, shape (stages, stages) [-].
    st : int
        The stage.
    ytmp : ndarray
        Written: the argument, shape (n,).
    """
    for i in range(y.shape[0]):
        acc = y[i]
        for j in range(st):
            acc += tA[st, j] * U[j, i]
        ytmp[i] = acc


@njit(cache=True, inline="always")
def tableau_stage_rhs(fp, T, U, tC, td, st, h, x):
    """The right-hand side of a tableau's stage equation,
    ``x = f + h d_st df/dt + sum_j c_st,j u_j / h``.

    Parameters
    ----------
    fp : ndarray
        The derivatives at the stage's argument, shape (n,).
    T : ndarray
        The derivatives' rate in crank angle, shape (n,).
    U : ndarray
        The stages so far, shape (stages, n).
    tC : ndarray
        The tableau's c_ij, shape (stages, stages) [-].
    td : ndarray
        The tableau's d_i, shape (stages,) [-].
    st : int
        The stage.
    h : float
        The step [rad].
    x : ndarray
        Written: the right-hand side, shape (n,).
    """
    for i in range(fp.shape[0]):
        acc = 0.0
        for j in range(st):
            acc += tC[st, j] * U[j, i]
        x[i] = fp[i] + h * td[st] * T[i] + acc / h


@njit(cache=True, inline="always")
def tableau_solution(y, U, tb, te, atol, rtol, ytmp):
    """A tableau step's solution ``ytmp = y + sum_i b_i u_i`` and its error against
    the tolerances, ``max_i |sum_j e_j u_j,i| / (atol_i + rtol max(|y_i|, |ytmp_i|))``.

    Parameters
    ----------
    y : ndarray
        The state at the step's start, shape (n,).
    U : ndarray
        The stages, shape (stages, n).
    tb, te : ndarray
        The tableau's weights b_i and error weights e_i, shape (stages,) [-].
    atol : ndarray
        Absolute tolerances, shape (n,).
    rtol : float
        Relative tolerance [-].
    ytmp : ndarray
        Written: the step's solution, shape (n,).

    Returns
    -------
    float
        The error norm [-] (at most 1 passes).
    """
    ns = tb.shape[0]
    err = 0.0
    for i in range(y.shape[0]):
        acc = y[i]
        e = 0.0
        for j in range(ns):
            acc += tb[j] * U[j, i]
            e += te[j] * U[j, i]
        ytmp[i] = acc
        e = abs(e) / (atol[i] + rtol * max(abs(y[i]), abs(acc)))
        if e > err:
            err = e
    return err


_D = 1.0 / (2.0 + math.sqrt(2.0))


_E32 = 6.0 + math.sqrt(2.0)


#: :func:`cycle_ros`'s ``kind``: the ode23s pair's own stages, or a tableau's.
KIND_ODE23S = 0


KIND_TABLEAU = 1


def _tableau(gamma, A, C, c, d, b, e, expo):
    """A Rosenbrock tableau as the arrays :func:`cycle_ros` takes, in the form
    ``(I/(gamma h) - J) u_i = f(t + c_i h, y + sum_j a_ij u_j) + sum_j c_ij u_j / h
    + d_i h df/dt``, ``y1 = y + sum_i b_i u_i``, error ``sum_i e_i u_i`` (Hairer and
    Wanner, *Solving Ordinary Differential Equations II*, Sec. IV.7, eq. 7.25), with the
    step's exponent of the error ``expo``.  ``same[i]`` says when stage i's argument is one already
    evaluated: 1 the step's start (no evaluation), 2 the stage before."""
    s_ = len(b)
    At = np.zeros((s_, s_))
    Ct = np.zeros((s_, s_))
    for i in range(1, s_):
        At[i, :i] = A[i - 1]
        Ct[i, :i] = C[i - 1]
    ct = np.array(c, dtype=float)
    same = np.zeros(s_, dtype=np.int64)
    for i in range(1, s_):
        if ct[i] == 0.0 and not At[i].any():
            same[i] = 1
        elif ct[i] == ct[i - 1] and np.array_equal(At[i, :i - 1], At[i - 1, :i - 1]) \
                and At[i, i - 1] == 0.0:
            same[i] = 2
    return (float(gamma), At, Ct, ct, np.array(d, dtype=float), np.array(b, dtype=float),
            np.array(e, dtype=float), same, float(expo))


#: Rosenbrock tableaus of :func:`cycle_ros` by method name.
#: ``ros4``: Shampine's 4(3) pair (ACM Trans. Math. Softw. 8, 1982; Press et al.,
#: *Numerical Recipes*, 2nd ed., Sec. 16.6): four stages, three evaluations, A-stable,
#: its stability function 1/3 at infinity.
#: ``rodas3``: Sandu et al.'s RODAS3 (Atmos. Environ. 31, 1997): four stages, two
#: evaluations (the second stage's argument is the step's start), order 3, L-stable
#: and stiffly accurate, its error the last stage.
#: ``rodas4``: Hairer and Wanner's RODAS4 (*Solving Ordinary Differential Equations II*,
#: Sec. VI.4): six stages, five evaluations, order 4, L-stable and stiffly accurate.
ROS_TABLEAUS = {
    "ros4": _tableau(0.5, [[2.0], [48.0 / 25.0, 6.0 / 25.0], [48.0 / 25.0, 6.0 / 25.0, 0.0]],
                     [[-8.0], [372.0 / 25.0, 12.0 / 5.0],
                      [-112.0 / 125.0, -54.0 / 125.0, -2.0 / 5.0]],
                     [0.0, 1.0, 0.6, 0.6], [0.5, -1.5, 121.0 / 50.0, 29.0 / 250.0],
                     [19.0 / 9.0, 0.5, 25.0 / 108.0, 125.0 / 108.0],
                     [17.0 / 54.0, 7.0 / 36.0, 0.0, 125.0 / 108.0], -0.25),
    "rodas3": _tableau(0.5, [[0.0], [2.0, 0.0], [2.0, 0.0, 1.0]],
                       [[4.0], [1.0, -1.0], [1.0, -1.0, -8.0 / 3.0]],
                       [0.0, 0.0, 1.0, 1.0], [0.5, 1.5, 0.0, 0.0], [2.0, 0.0, 1.0, 1.0],
                       [0.0, 0.0, 0.0, 1.0], -1.0 / 3.0),
    "rodas4": _tableau(
        0.25,
        [[1.544],
         [0.9466785280815826, 0.2557011698983284],
         [3.314825187068521, 2.896124015972201, 0.9986419139977817],
         [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895],
         [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895, 1.0]],
        [[-5.6688],
         [-2.430093356833875, -0.2063599157091915],
         [-0.1073529058151375, -9.594562251023355, -20.47028614809616],
         [7.496443313967647, -10.24680431464352, -33.99990352819905, 11.7089089320616],
         [8.083246795921522, -7.981132988064893, -31.52159432874371, 16.31930543123136,
          -6.058818238834054]],
        [0.0, 0.386, 0.21, 0.63, 1.0, 1.0], [0.25, -0.1043, 0.1035, -0.0362, 0.0, 0.0],
        [1.221224509226641, 6.019134481288629, 12.53708332932087, -0.687886036105895,
         1.0, 1.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, 1.0], -0.25),
}
