"""What the engine reads from a scene: its sections' specs and the scene's protocol.

The scene (:class:`corliss.scene.loader.Scene`) is read from TOML one layer above the
engine; the engine runs on what is declared here.  The specs of the sections the engine
reads (``[supply]``, ``[exhaust]``, ``[run]``, ``[compound]``) live here beside
:class:`~corliss.engine.geometry.EngineSpec`, and :class:`SceneSpec` is the protocol of
the scene as the engine and its results read it: ``Scene`` satisfies it by its fields,
without the engine importing it (layers point down).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from corliss.engine.flywheel import FlywheelSpec
from corliss.engine.geometry import EngineSpec
from corliss.engine.load import LoadSpec
from corliss.engine.options import Fidelity
from corliss.keys import units


@dataclass(frozen=True)
class SupplySpec:
    """Steam at the chest (all SI).

    Parameters
    ----------
    pressure_Pa : float
        Absolute pressure [Pa].
    temperature_K : float or None
        Superheated temperature [K]; None for saturated or wet steam.
    dryness : float
        Dryness fraction [-] when not superheated (1 = dry saturated).
    barometer_Pa : float
        Atmospheric pressure [Pa] that gauge readings were taken against.
    chest_volume_m3 : float or None
        Volume of the steam chest [m3] (``steam_chest`` effect); the supply state is
        then the boiler's, behind the steam pipe and throttle.
    pipe_diameter_m : float or None
        Bore of the steam pipe [m].
    pipe_discharge_coefficient : float
        Of the pipe taken as one orifice (its entry, bends and valve body) [-].
    throttle : float
        Opening of the throttle valve in the pipe, 0 (shut) to 1 (wide open) [-].
    throttle_law : str
        Open area against opening: ``"linear"`` (a gate or slide), or
        ``"butterfly"`` (a disc turned through 90 deg: A = A_pipe (1 - cos(90 deg x opening))).
    """

    pressure_Pa: float
    temperature_K: float | None
    dryness: float
    barometer_Pa: float
    chest_volume_m3: float | None = None
    pipe_diameter_m: float | None = None
    pipe_discharge_coefficient: float = 0.8
    throttle: float = 1.0
    throttle_law: str = "linear"


@dataclass(frozen=True)
class ExhaustSpec:
    """Back pressure: atmosphere, condenser or receiver, held constant.

    Parameters
    ----------
    pressure_Pa : float
        Absolute back pressure [Pa].
    """

    pressure_Pa: float


@dataclass(frozen=True)
class RunSpec:
    """What to simulate and how accurately.

    Parameters
    ----------
    mode : str
        ``"steady"`` (constant speed) or ``"transient"`` (speed a state, with the
        flywheel, load and governor of the scene).
    model : str
        ``"crank_resolved"`` or ``"ideal"``.
    speed_rad_s : float
        Crank speed [rad/s].
    effects : tuple of str
        Effects named by the scene.
    fidelity : Fidelity
        Accuracy knobs (a preset with any single knob overridden).
    cycles : int or None
        Simulate exactly this many cycles; None: run until periodic.
    expansion : str
        Expansion law of the ideal card: ``"hyperbolic"`` or ``"isentropic"``.
    duration_s : float or None
        Transient: simulated time [s] (rounded up to whole turns).
    record : str or None
        The time series: ``"step"`` (every integrator step, transient only),
        ``"degree"`` (every ``output_step`` of crank angle) or ``"cycle"`` (once per
        turn; a steady run's last cycle at every output step); None (not in the scene):
        a transient's by the run's length (:func:`corliss.engine.options.record_of`),
        a steady run's ``"degree"``.
    settling_band : float
        Transient: the speed band, as a fraction of the final mean speed, that the
        settling time is measured to [-].  By default 0.2 %: a fraction of the 1 to 5 %
        by which the period's governors let the speed change between loads (Marks
        Art. 70), so that the time measures the recovery, not the droop.
    warmup_cycles : int
        Transient: turns run at the initial speed with the governor held, before t = 0,
        so the cylinders start from a periodic state.
    start : str
        Transient: ``"equilibrium"`` (with a governor, the speed and governor position at
        which the governor balances the load at t = 0, found by steady turns along the
        governor's static characteristic), ``"run_speed"`` (at ``speed``, with the
        governor balanced for that speed, whatever the load) or ``"rest"`` (standing,
        the crank at ``start_angle_rad``, the governor down; see
        :mod:`corliss.engine.start_from_rest`).
    start_angle_rad : float
        Crank angle of a start from rest [rad].
    until_settled : bool
        Transient: run past ``duration`` until the speed has settled (see
        :mod:`corliss.engine.speed_metrics`), up to ``max_duration_s``.
    max_duration_s : float or None
        The longest a run ``until_settled`` goes on [s].
    """

    mode: str
    model: str
    speed_rad_s: float
    effects: tuple[str, ...]
    fidelity: Fidelity
    cycles: int | None
    expansion: str
    duration_s: float | None = None
    record: str | None = None
    settling_band: float = 0.002
    warmup_cycles: int = 3
    start: str = "equilibrium"
    until_settled: bool = False
    max_duration_s: float | None = None
    start_angle_rad: float = 0.0

    @property
    def speed_rpm(self) -> float:
        """Crank speed in revolutions a minute.

        Returns
        -------
        float
            The speed [rpm].
        """
        return self.speed_rad_s / units.RPM_RAD_S

    def has(self, effect: str) -> bool:
        """True when the scene names ``effect``.

        Parameters
        ----------
        effect : str
            An effect's name.

        Returns
        -------
        bool
            Whether ``run.effects`` holds it.
        """
        return effect in self.effects


@dataclass(frozen=True)
class CompoundSpec:
    """The low-pressure cylinder of a compound engine and its receiver (all SI).

    Parameters
    ----------
    lp_engine : EngineSpec
        The LP cylinder (bore, stroke, rod, clearance); other [engine] data as the HP's.
    lp_gear_type : str
        Its valve gear's registry name.
    lp_gear : object
        Its valve gear's spec.
    lp_phase_rad : float
        The LP crank's angle ahead of the HP crank [rad] (a crank that follows by
        90 deg is -pi/2).
    receiver_volume_m3 : float
        Receiver and passages between the cylinders [m3].
    """

    lp_engine: EngineSpec
    lp_gear_type: str
    lp_gear: object
    lp_phase_rad: float
    receiver_volume_m3: float


class SceneSpec(Protocol):
    """A scene as the engine reads it (:class:`corliss.scene.loader.Scene` is one):
    read-only, all SI.

    A run and its result hold the scene they were given; the engine reads the members
    below and no other.  A protocol: never made, its arguments are those of the class
    machinery.

    Parameters
    ----------
    *args, **kwargs
        Not taken: a protocol is not instantiated.
    """

    @property
    def title(self) -> str:
        """The scene's title.

        Returns
        -------
        str
            The title.
        """

    @property
    def name(self) -> str:
        """The scene's name (its file's stem).

        Returns
        -------
        str
            The name.
        """

    @property
    def engine(self) -> EngineSpec:
        """The cylinder (or identical cylinders); the HP cylinder of a compound.

        Returns
        -------
        EngineSpec
            Its size, rod, masses, friction, leaks and walls.
        """

    @property
    def supply(self) -> SupplySpec:
        """Steam at the chest (or at the boiler, with the steam chest).

        Returns
        -------
        SupplySpec
            The supply.
        """

    @property
    def exhaust(self) -> ExhaustSpec:
        """The back pressure.

        Returns
        -------
        ExhaustSpec
            The exhaust.
        """

    @property
    def gear_type(self) -> str:
        """The valve gear's registry name (:data:`corliss.valves.GEARS`).

        Returns
        -------
        str
            The name.
        """

    @property
    def gear(self) -> object:
        """The valve gear's spec, of the type its registry entry parses.

        Returns
        -------
        object
            The spec.
        """

    @property
    def run(self) -> RunSpec:
        """What to simulate and how accurately.

        Returns
        -------
        RunSpec
            The run's options.
        """

    @property
    def compound(self) -> CompoundSpec | None:
        """The LP cylinder of a compound engine.

        Returns
        -------
        CompoundSpec or None
            It, or None for a simple engine.
        """

    @property
    def governor_type(self) -> str | None:
        """The governor's registry name (:data:`corliss.governors.GOVERNORS`).

        Returns
        -------
        str or None
            The name, or None without a governor.
        """

    @property
    def governor(self) -> object | None:
        """The governor's spec, of the type its registry entry parses.

        Returns
        -------
        object or None
            The spec, or None without a governor.
        """

    @property
    def flywheel(self) -> FlywheelSpec | None:
        """A transient run's flywheel.

        Returns
        -------
        FlywheelSpec or None
            The flywheel, or None in a steady run.
        """

    @property
    def load(self) -> LoadSpec | None:
        """A transient run's shaft load and its schedule.

        Returns
        -------
        LoadSpec or None
            The load, or None in a steady run.
        """
