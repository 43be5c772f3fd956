"""Steam properties (tiers behind one interface) and flow through ports."""

from corliss.thermo.numba_start import preload_cython_blas

preload_cython_blas()       # before any compiled function: numba's start without scipy.linalg

from corliss.thermo.orifice import kappa_of, mass_flux, port_flow  # noqa: E402
from corliss.thermo.steam import BACKENDS, HEOSSteam, State, Steam, make_steam  # noqa: E402

__all__ = ["BACKENDS", "HEOSSteam", "State", "Steam", "kappa_of", "make_steam", "mass_flux",
           "port_flow"]
