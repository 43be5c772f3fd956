"""Bookkeeping of clamped evaluations: which states the integrators visited or only tried
needed the property clamps of :mod:`corliss.engine.kernels.properties`, and what the
cycle integrator reports of them (``CL_*``).
"""

from __future__ import annotations

from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.properties import PR_CLAMP
from corliss.thermo.steam_table import CLAMP_HIGH_ENERGY


#: What the cycle integrator reports of clamps (the array it returns last): clamped
#: evaluations at visited states, at trial states, the codes of each (OR of the
#: bits), and the shaft angle [rad] and node of the first visited one.
CL_ACCEPTED, CL_REJECTED, CL_ACCEPTED_CODE, CL_REJECTED_CODE, CL_THETA, CL_NODE = range(6)


@njit(cache=True, _nrt=False)
def tally_clamps(pr, t, att):
    """Add the latest evaluation's clamps to a step attempt's tally.

    Parameters
    ----------
    pr : ndarray
        The node properties of the latest evaluation; row :data:`PR_CLAMP` is read.
    t : float
        The shaft angle of that evaluation [rad].
    att : ndarray
        Updated: a step attempt's clamp tally, shape (4,): clamped evaluations,
        the OR of their codes, shaft angle [rad] and node of the first.
    """
    c = 0
    first = -1
    for i in range(pr.shape[1]):
        ci = int(pr[PR_CLAMP, i])
        if ci != 0 and first < 0:
            first = i
        c |= ci
    if c != 0:
        if att[0] == 0.0:
            att[2] = t
            att[3] = first
        att[0] += 1.0
        att[1] = float(int(att[1]) | c)


@njit(cache=True, _nrt=False)
def settle_visited(att, clamps):
    """Move a step attempt's tally into the cycle's as evaluations at visited states.

    Parameters
    ----------
    att : ndarray
        A step attempt's clamp tally, shape (4,), cleared: clamped evaluations,
        the OR of their codes, shaft angle [rad] and node of the first.
    clamps : ndarray
        The cycle's clamp counts, shape (6,), updated, indexed by ``CL_*``.
    """
    if att[0] > 0.0:
        if clamps[CL_ACCEPTED] == 0.0:
            clamps[CL_THETA] = att[2]
            clamps[CL_NODE] = att[3]
        clamps[CL_ACCEPTED] += att[0]
        clamps[CL_ACCEPTED_CODE] = float(int(clamps[CL_ACCEPTED_CODE]) | int(att[1]))
    for k in range(4):
        att[k] = 0.0


@njit(cache=True, _nrt=False)
def settle_trial(att, clamps):
    """Move a step attempt's tally into the cycle's as evaluations at trial states.

    Parameters
    ----------
    att : ndarray
        A step attempt's clamp tally, shape (4,), cleared: clamped evaluations,
        the OR of their codes, shaft angle [rad] and node of the first.
    clamps : ndarray
        The cycle's clamp counts, shape (6,), updated, indexed by ``CL_*``.
    """
    if att[0] > 0.0:
        clamps[CL_REJECTED] += att[0]
        clamps[CL_REJECTED_CODE] = float(int(clamps[CL_REJECTED_CODE]) | int(att[1]))
    for k in range(4):
        att[k] = 0.0


@njit(cache=True, _nrt=False)
def settle_clamps(att, accepted, clamps):
    """Move a step attempt's tally into the cycle's, as visited or trial states.

    For a run-time flag; callers that know which use :func:`settle_visited` or
    :func:`settle_trial` (one compiled version each).

    Parameters
    ----------
    att : ndarray
        A step attempt's clamp tally, shape (4,), cleared: clamped evaluations,
        the OR of their codes, shaft angle [rad] and node of the first.
    accepted : bool
        Whether the step was accepted (its end a visited state).
    clamps : ndarray
        The cycle's clamp counts, shape (6,), updated, indexed by ``CL_*``.
    """
    if accepted:
        settle_visited(att, clamps)
    else:
        settle_trial(att, clamps)


@njit(cache=True, _nrt=False)
def visited_clamp_off(att_end):
    """The clamp bits of a step's end that make it no step of the physical path.

    Every clamp but steam overheated by the walls (code 8), which is not the step's
    doing.

    Parameters
    ----------
    att_end : ndarray
        The clamp tally of the evaluation at the step's end; shape (4,).

    Returns
    -------
    int
        The bits (0: the end is a physical state).
    """
    if att_end[0] > 0.0:
        return int(att_end[1]) & ~CLAMP_HIGH_ENERGY
    return 0
