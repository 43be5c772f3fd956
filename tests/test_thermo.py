"""Steam properties against steam tables; port flow against its closed forms."""

import math

import numpy as np
import pytest

from corliss.thermo import HEOSSteam, kappa_of, mass_flux, port_flow


@pytest.fixture(scope="module")
def steam():
    return HEOSSteam()


def test_saturation_against_iapws_if97_tables(steam):
    """IAPWS-IF97 saturation table (Wagner and Kretzschmar, *International Steam Tables*,
    2008): 100 degC -> 101.418 kPa, v_g 1.67186 m3/kg, h_g 2675.57 kJ/kg; 1 MPa ->
    179.88 degC, v_g 0.19436 m3/kg, h_g 2777.1 kJ/kg.  Tolerance 0.05 %: IF97 and
    IAPWS-95 (CoolProp HEOS) agree to about 1e-4 in this region, and the tables round."""
    st = steam.pt(101.418e3, 373.15 + 1e-3)  # a hair above saturation: vapour
    assert st.h == pytest.approx(2675.57e3, rel=5e-4)
    g = steam.px(1e6, 1.0)
    assert g.T - 273.15 == pytest.approx(179.88, abs=0.02)
    assert 1 / g.rho == pytest.approx(0.19436, rel=5e-4)
    assert g.h == pytest.approx(2777.1e3, rel=5e-4)


def test_superheated_against_tables(steam):
    """1 MPa, 300 degC: v = 0.25799 m3/kg, h = 3051.6 kJ/kg (IF97 superheat table)."""
    st = steam.pt(1e6, 573.15)
    assert 1 / st.rho == pytest.approx(0.25799, rel=5e-4)
    assert st.h == pytest.approx(3051.6e3, rel=5e-4)
    assert st.superheated and st.x == 1.0


def test_density_energy_round_trip_across_saturation(steam):
    """The control volume's inputs (density, internal energy) give back the state they
    came from, wet or superheated, from condenser vacuum to above boiler pressure, and
    near saturation at 0.18 bar (where a tabular backend once crashed the process)."""
    cases = []
    for p in np.geomspace(8e3, 2.5e6, 12):
        for x in (0.6, 0.9, 0.999):
            cases.append(steam.px(p, x))
        t_sat = steam.t_sat(p)
        for dT in (0.5, 1.0, 5.0, 80.0):
            cases.append(steam.pt(p, t_sat + dT))
    cases.append(steam.pt(0.18e5, steam.t_sat(0.18e5) + 1.0))
    for st in cases:
        back = steam.du(st.rho, st.u)
        assert back.p == pytest.approx(st.p, rel=1e-7)
        assert back.h == pytest.approx(st.h, rel=1e-9)
        assert back.x == pytest.approx(st.x, abs=1e-7)


def test_choked_flux_closed_form():
    """Below the critical ratio the flux is G* = sqrt(kappa p0 rho0 (2/(kappa+1))^((kappa+1)/(kappa-1))),
    independent of the downstream pressure (Saint-Venant and Wantzel); for dry
    saturated steam kappa = 1.135 gives the critical ratio 0.577 of the steam-nozzle
    literature.  Tolerance: rounding only."""
    k = kappa_of(1.0, False)
    assert k == pytest.approx(1.135)
    r_crit = (2 / (k + 1)) ** (k / (k - 1))
    assert r_crit == pytest.approx(0.5774, abs=2e-4)
    p0, rho0 = 7.9e5, 4.1
    g_star = math.sqrt(k * p0 * rho0 * (2 / (k + 1)) ** ((k + 1) / (k - 1)))
    for r in (0.1, 0.3, 0.55):
        assert mass_flux(p0, rho0, r * p0, k) == pytest.approx(g_star, rel=1e-12)
    assert mass_flux(p0, rho0, 0.8 * p0, k) < g_star


def test_subcritical_flux_and_regularised_band():
    """Above the critical ratio: G = sqrt(2k/(k-1) p0 rho0 (r^(2/k) - r^((k+1)/k))).
    In the band 0.99 < r < 1 the flux is the straight line to zero, continuous at the
    band edge; reverse flow is the mirror image."""
    k, p0, rho0 = 1.3, 5e5, 2.0
    r = 0.8
    g = math.sqrt(2 * k / (k - 1) * p0 * rho0 * (r ** (2 / k) - r ** ((k + 1) / k)))
    assert mass_flux(p0, rho0, r * p0, k) == pytest.approx(g, rel=1e-12)
    edge = mass_flux(p0, rho0, 0.99 * p0, k)
    assert mass_flux(p0, rho0, (0.99 + 1e-12) * p0, k) == pytest.approx(edge, rel=1e-6)
    assert mass_flux(p0, rho0, 0.995 * p0, k) == pytest.approx(edge / 2, rel=1e-9)
    assert mass_flux(p0, rho0, p0, k) == 0.0
    f = port_flow(1e-3, 0.7, p0, rho0, k, 3e5, 1.5, 1.2)
    b = port_flow(1e-3, 0.7, 3e5, 1.5, 1.2, p0, rho0, k)
    assert f > 0 and b == pytest.approx(-f, rel=1e-15)
