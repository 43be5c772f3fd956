"""The crank train and the ports as the compiled kernels see them: piston position and
its derivatives by the slider crank, each node's volume and its rate, and the port
areas read from the tabulated port map (:class:`corliss.engine.network.Network`).
"""

from __future__ import annotations

import math

import numpy as np

from corliss.engine.kernels.compiled import njit
from corliss.engine.kernels.data import (GEO_ANGULARITY, GEO_AREA_CRANK, GEO_AREA_HEAD,
                                         GEO_CLEAR_CRANK, GEO_CLEAR_HEAD, GEO_CRANK, GEO_ROD,
                                         GEO_STROKE)


TWO_PI = 2.0 * math.pi


@njit(cache=True, inline="always")
def slider_crank(R, L, sn, cs, angular):
    """The slider crank, written once: piston travel and its first two derivatives.

    Marks, *The Steam Engine*, Art. 96 III, eqs. 239-241: with crank radius R,
    connecting rod L and crank angle a from head dead centre,
    ``s = R (1 - cos a) + L - sqrt(L^2 - R^2 sin^2 a)`` (without rod angularity, an
    infinite rod, ``R (1 - cos a)``), and its derivatives with a.  The compiled kernels
    call it on floats (:func:`piston_position`, :func:`piston_kinematics`); the
    Python paths (:class:`corliss.engine.geometry.CylinderGeometry`,
    :mod:`corliss.engine.crank_effort`) call its Python form (``slider_crank.py_func``)
    on arrays: the same operations in the same order, so the same bits.

    Parameters
    ----------
    R : float
        Crank radius [m].
    L : float
        Connecting rod [m].
    sn, cs : float or ndarray
        ``sin a``, ``cos a`` of the cylinder's crank angle [-].
    angular : bool or float
        True (non-zero): the exact slider crank; False (0): an infinite rod.

    Returns
    -------
    s : float or ndarray
        Travel from head dead centre [m].
    ds : float or ndarray
        ``ds/da`` [m/rad].
    d2s : float or ndarray
        ``d2s/da2`` [m/rad2].
    """
    s = R * (1.0 - cs)
    ds = R * sn
    d2s = R * cs
    if angular:
        root = np.sqrt(L * L - R * R * sn * sn)
        s = s + (L - root)
        ds = ds + R * R * sn * cs / root
        d2s = d2s + (R * R * (cs * cs - sn * sn) / root + (R * R * sn * cs) ** 2 / root ** 3)
    return s, ds, d2s


@njit(cache=True, inline="always")
def piston_position(th, net, c):
    """Piston travel from head dead centre and its derivative with crank angle.

    :func:`slider_crank` at the cylinder's own angle ``th + phase``.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    c : int
        The cylinder.

    Returns
    -------
    s : float
        Travel [m].
    ds : float
        ds/dtheta [m/rad].
    """
    geo, phase = net.geometry, net.phase
    a = th + phase[c]
    s, ds, _ = slider_crank(geo[c, GEO_CRANK], geo[c, GEO_ROD], math.sin(a), math.cos(a),
                            geo[c, GEO_ANGULARITY] > 0.0)
    return s, ds


@njit(cache=True, inline="always")
def piston_kinematics(th, net, c):
    """Piston velocity and acceleration per crank angle of one cylinder.

    :func:`slider_crank` at the cylinder's own angle ``th + phase``.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    c : int
        The cylinder.

    Returns
    -------
    ds : float
        ``ds/dtheta`` [m/rad].
    d2s : float
        ``d2s/dtheta2`` [m/rad2].
    """
    geo, phase = net.geometry, net.phase
    a = th + phase[c]
    _, ds, d2s = slider_crank(geo[c, GEO_CRANK], geo[c, GEO_ROD], math.sin(a), math.cos(a),
                            geo[c, GEO_ANGULARITY] > 0.0)
    return ds, d2s


@njit(cache=True, inline="always")
def end_volume(net, c, end, s, ds):
    """Volume of one end of a cylinder and its derivative, from the piston's travel.

    Parameters
    ----------
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    c : int
        The cylinder.
    end : int
        0 the head end, 1 the crank end.
    s : float
        Piston travel from head dead centre [m] (:func:`piston_position`).
    ds : float
        ds/dtheta [m/rad].

    Returns
    -------
    V : float
        Volume [m3].
    dV : float
        dV/dtheta [m3/rad].
    """
    geo = net.geometry
    if end == 0:
        return geo[c, GEO_CLEAR_HEAD] + geo[c, GEO_AREA_HEAD] * s, geo[c, GEO_AREA_HEAD] * ds
    return (geo[c, GEO_CLEAR_CRANK] + geo[c, GEO_AREA_CRANK] * (geo[c, GEO_STROKE] - s),
            -geo[c, GEO_AREA_CRANK] * ds)


@njit(cache=True, inline="always")
def node_volume(th, net, i):
    """Volume of a node and its derivative with crank angle.

    The slider crank of :mod:`corliss.engine.geometry`, at the cylinder's own angle
    ``th + phase`` (:func:`piston_position`, :func:`end_volume`); a vessel's volume is
    fixed.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    i : int
        The node.

    Returns
    -------
    V : float
        Volume [m3].
    dV : float
        dV/dtheta [m3/rad].
    """
    kind, cyl, end, fixedV = net.node_kind, net.node_cyl, net.node_end, net.node_V
    if kind[i] == 1:
        return fixedV[i], 0.0
    s, ds = piston_position(th, net, cyl[i])
    return end_volume(net, cyl[i], end[i], s, ds)


@njit(cache=True, inline="always")
def port_areas(th, net, pa):
    """Open area of every port of every cylinder, from the PortMap tables.

    Linear interpolation at the cylinder's own angle, one search per cylinder.

    Parameters
    ----------
    th : float
        Shaft crank angle [rad].
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    pa : ndarray
        Written: the areas [m2], shape (cylinders, 4), ports in PortMap order (head
        steam, head exhaust, crank steam, crank exhaust).
    """
    phase, grid, npts, area = net.phase, net.port_grid, net.port_npts, net.port_area
    for c in range(npts.shape[0]):
        n = npts[c]
        t = (th + phase[c]) % TWO_PI
        k = np.searchsorted(grid[c, :n], t) - 1
        if k < 0:
            k = 0
        if k > n - 2:
            k = n - 2
        g0 = grid[c, k]
        w = (t - g0) / (grid[c, k + 1] - g0)
        for p in range(4):
            pa[c, p] = area[c, p, k] * (1.0 - w) + area[c, p, k + 1] * w


@njit(cache=True, inline="always")
def edge_area(net, e, pa):
    """Open area of an edge: a fixed orifice's, or its port's; for a linear leak
    (:data:`corliss.engine.network.LINEAR_EDGE`), its rate of leak [kg/(s Pa)].

    Parameters
    ----------
    net : NetworkArrays
        The network's arrays (:meth:`corliss.engine.network.Network.arrays`).
    e : int
        The edge.
    pa : ndarray
        The port areas [m2], shape (cylinders, 4) (:func:`port_areas`).

    Returns
    -------
    float
        The area [m2] (a linear leak's rate [kg/(s Pa)]).
    """
    ekind, ecyl, eport, earea = net.edge_kind, net.edge_cyl, net.edge_port, net.edge_area
    if ekind[e] >= 1:
        return earea[e]
    return pa[ecyl[e], eport[e]]


@njit(cache=True, inline="always")
def _port_area_slopes(th, net, out):
    """d(area)/dtheta [m2/rad] of every port, shape (cylinders, 4), on the cell of the
    PortMap table that lies ahead of ``th`` (the side a forward step takes at a kink)."""
    phase, grid, npts, area = net.phase, net.port_grid, net.port_npts, net.port_area
    for c in range(npts.shape[0]):
        n = npts[c]
        t = (th + phase[c]) % TWO_PI
        k = np.searchsorted(grid[c, :n], t, side="right") - 1
        if k < 0:
            k = 0
        if k > n - 2:
            k = n - 2
        dg = grid[c, k + 1] - grid[c, k]
        for p in range(4):
            out[c, p] = (area[c, p, k + 1] - area[c, p, k]) / dg


@njit(cache=True, inline="always")
def _volume_curvature(th, net, i):
    """d2V/dtheta2 of a node [m3/rad2]: the slider crank of :func:`node_volume`
    differentiated once more (:func:`piston_kinematics`; 0 for a vessel)."""
    geo, kind, cyl, end = net.geometry, net.node_kind, net.node_cyl, net.node_end
    if kind[i] == 1:
        return 0.0
    c = cyl[i]
    d2s = piston_kinematics(th, net, c)[1]
    if end[i] == 0:
        return geo[c, GEO_AREA_HEAD] * d2s
    return -geo[c, GEO_AREA_CRANK] * d2s
