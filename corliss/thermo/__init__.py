"""Steam properties (tiers behind one interface) and flow through ports."""

from corliss.thermo.orifice import kappa_of, mass_flux, port_flow
from corliss.thermo.steam import BACKENDS, HEOSSteam, State, Steam, make_steam

__all__ = ["BACKENDS", "HEOSSteam", "State", "Steam", "kappa_of", "make_steam", "mass_flux",
           "port_flow"]
