"""whipple: dynamics of the Whipple bicycle, from Python.

The benchmark bicycle of Meijaard, Papadopoulos, Ruina & Schwab 2007 (Proc. R. Soc. A
463:1955–1982), the linearized model (M, C₁, K₀, K₂, A(v), eigenvalues, certified critical
speeds, exact sensitivities and uncertainty) and the fully non-linear multibody bicycle
(simulation, exact linearization), computed by the Rust library ``whipple``; results are numpy
arrays. SI units and radians.

>>> import whipple
>>> bike = whipple.Bicycle.preset("benchmark")
>>> round(bike.critical_speeds().v_w, 6)
4.292383
"""

from . import _whipple
from ._bicycle import BENCHMARK_KEYS, Bicycle, formats, parameter_table, presets
from ._errors import (AccuracyLostError, ArgumentError, LimitError, NoSteadyTurnError,
                      NumericalError, ParameterError, ParameterWarning, ParseError, StrictError,
                      UnknownPresetError, WhippleError)
from ._control import (ClosedLoop, Controllability, GroundPath, Lqr, ManoeuvreComparison,
                       ModalControllability, TimeResponse, UncontrollableSpeeds)
from ._design import DesignMap, design_map_dask
from ._human import (ExtrapolationWarning, GainLookup, GainTable, HumanController, HumanEigen,
                     HumanLoop, LoopTransferFunction, RiderLoop, hess_gains, human_eigenvalues,
                     read_gains)
from ._handling import HandlingQuality, OptimalHandling, handling_quality, optimal_handling
from ._lane_change import lane_change
from ._measure import Measurement, measure
from ._period import PeriodFit, fit_period, read_period
from ._plot import plot_bode, plot_eigenvalues
from ._rider_lean import RiderLean
from ._results import Comparison, CriticalSpeeds, Eigen, Sensitivities, Simulation
from ._system import FrequencyResponse, LinearSystem, Signal, TransferFunction
from ._turns import SteadyTurn, TurnFamily, Turns, WheelContact

__version__ = _whipple.__version__

__all__ = [
    "Bicycle", "CriticalSpeeds", "Eigen", "Simulation", "Sensitivities", "Comparison",
    "SteadyTurn", "Turns", "TurnFamily", "WheelContact",
    "LinearSystem", "TransferFunction", "FrequencyResponse", "Signal",
    "TimeResponse", "GroundPath", "Lqr", "Controllability", "ModalControllability",
    "UncontrollableSpeeds", "ClosedLoop", "ManoeuvreComparison",
    "PeriodFit", "fit_period", "read_period", "RiderLean",
    "HumanController", "HumanLoop", "RiderLoop", "LoopTransferFunction", "GainTable",
    "GainLookup", "read_gains", "hess_gains", "human_eigenvalues", "HumanEigen",
    "ExtrapolationWarning",
    "HandlingQuality", "handling_quality", "OptimalHandling", "optimal_handling",
    "lane_change",
    "DesignMap", "design_map_dask", "measure", "Measurement", "plot_eigenvalues", "plot_bode", "presets", "formats", "parameter_table", "BENCHMARK_KEYS",
    "WhippleError", "ParameterError", "StrictError", "ParseError", "UnknownPresetError",
    "ArgumentError", "LimitError", "NumericalError", "AccuracyLostError", "NoSteadyTurnError",
    "ParameterWarning",
]
