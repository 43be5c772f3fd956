"""The ideal indicator card: the algebraic model level (``[run] model = "ideal"``).

For each end, over its own stroke fraction f (volume ``V = V_c + V_s f``):
admission at supply pressure from dead centre to cut-off f_c, expansion to release
f_r, release to back pressure, exhaust at back pressure on the return to
compression f_k, compression to dead centre, and admission again.  The expansion
and compression laws:

* ``"hyperbolic"``: pV = const, the period hand calculation (Marks Art. 72-73, who
  finds that it "coincides, with great accuracy" with good indicator cards);
* ``"isentropic"``: real steam at constant entropy, with the filling, blow-down and
  mixing of :mod:`corliss.engine.equilibrium` (the limit of large ports).

The work is the card's area, integrated from the card itself (a closed polygon
sampled finely along each process), not taken from a closed form.  Steam per cycle
for the hyperbolic card is Marks's "indicated steam" (Art. 73, eq. 219b): the steam
present at cut-off at supply density less the cushion steam shut in at compression,
dry saturated at back pressure.
"""

from __future__ import annotations

import numpy as np

from corliss.thermo.steam import State

_N = 2000  # samples per process


def card_area(V: np.ndarray, p: np.ndarray) -> float:
    """The area of a card: the closed-path integral of ``p dV``.

    Trapezoids along the polygon, closed from the last point back to the first.

    Parameters
    ----------
    V : ndarray
        Volumes around the card [m3]; shape (n,).
    p : ndarray
        Pressures at those volumes [Pa]; shape (n,).

    Returns
    -------
    float
        The work [J]: positive for a card traced clockwise in (V, p) (the engine's).
    """
    return float(np.sum(0.5 * (p[1:] + p[:-1]) * np.diff(V))
                 + 0.5 * (p[0] + p[-1]) * (V[0] - V[-1]))


def hyperbolic_card(V_clear: float, V_swept: float, f_cut: float, f_rel: float,
                    f_comp: float, p_supply: float, p_back: float):
    """The card of one end with hyperbolic expansion and compression.

    Parameters
    ----------
    V_clear, V_swept : float
        Clearance and swept volume of the end [m3].
    f_cut, f_rel, f_comp : float
        Cut-off, release and compression as fractions of the stroke from this
        end's dead centre [-] (``f_comp`` on the return stroke).
    p_supply, p_back : float
        Absolute supply and back pressure [Pa].

    Returns
    -------
    frac : ndarray
        Stroke fraction from this end's dead centre [-] around the card (admission,
        expansion, release, exhaust, compression; 2000 points each).
    V : ndarray
        Volume [m3] at those points.
    p : ndarray
        Absolute pressure [Pa] at those points.
    """
    f_rel = max(f_rel, f_cut)
    f_comp = min(max(f_comp, 0.0), f_rel)
    V1 = V_clear + V_swept * f_cut
    Vk = V_clear + V_swept * f_comp
    fa = np.linspace(0.0, f_cut, _N)
    fe = np.linspace(f_cut, f_rel, _N)
    fx = np.linspace(f_rel, 1.0, _N)
    fr = np.linspace(1.0, f_comp, _N)
    fk = np.linspace(f_comp, 0.0, _N)
    vol = lambda f: V_clear + V_swept * f  # noqa: E731
    frac = np.concatenate([fa, fe, fx, fr, fk])
    p = np.concatenate([
        np.full(_N, p_supply),
        p_supply * V1 / vol(fe),
        np.full(_N, p_back),
        np.full(_N, p_back),
        p_back * Vk / vol(fk),
    ])
    return frac, vol(frac), p


def indicated_steam_kg(V_clear: float, V_swept: float, f_cut: float, f_comp: float,
                       supply: State, cushion: State) -> float:
    """Marks's indicated steam per stroke (Art. 73, eq. 219b).

    The steam present at cut-off at the supply's density less the cushion shut in at
    compression at the cushion's density.

    Parameters
    ----------
    V_clear, V_swept : float
        Clearance and swept volume of the end [m3].
    f_cut, f_comp : float
        Cut-off and compression as fractions of the stroke from this end's dead
        centre [-].
    supply : State
        The steam at cut-off (supply pressure).
    cushion : State
        The steam shut in at compression (dry saturated at back pressure).

    Returns
    -------
    float
        The indicated steam per stroke [kg].
    """
    return (V_clear + V_swept * f_cut) * supply.rho - (V_clear + V_swept * f_comp) * cushion.rho
