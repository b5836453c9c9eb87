"""The leaning rider: Moore 2012's rider-lean model, the rider's upper body hinged to the rear
frame about its roll axis, computed by the library's five-body non-linear model."""

from typing import Any, Dict, Mapping, Tuple

import numpy as np
import numpy.typing as npt

from . import _whipple
from ._bicycle import Bicycle


class RiderLean:
    """A bicycle whose rear frame holds the rider's lower body, with the rider's upper body G
    hinged to it (BicycleParameters' ``MooreRiderLean2012`` parameter set).

    The linearized model's states are ``[lean, steer, rider_lean, lean_rate, steer_rate,
    rider_lean_rate]`` (the rider's lean relative to the rear frame, right positive), its inputs
    ``[lean_torque, steer_torque, rider_lean_torque]`` (the last on the upper body about the
    hinge, its reaction on the rear frame)."""

    STATES = ("lean", "steer", "rider_lean", "lean_rate", "steer_rate", "rider_lean_rate")
    INPUTS = ("lean_torque", "steer_torque", "rider_lean_torque")

    def __init__(self, native: "_whipple.NativeRiderLean") -> None:
        self._native = native

    @classmethod
    def from_moore_rider_lean2012(cls, d: Mapping[str, Any]) -> "RiderLean":
        """From BicycleParameters' ``MooreRiderLean2012`` keys (``c9``, ``d1`` … ``d4``,
        ``ic11`` …, ``ig11``, ``ig22``, ``ig31``, ``ig33``, ``k9``, ``l1`` … ``l6``, ``mc`` …
        ``mg``, ``rf``, ``rr``, ``g``): every key once, ``v`` accepted and ignored; checked by
        the library (a hinge above the bicycle's top is refused, naming ``zHinge``)."""
        items = [(str(k), float(v)) for k, v in d.items()]
        return cls(_whipple.NativeRiderLean.from_moore_rider_lean2012(items))

    @classmethod
    def from_bicycle(cls, bike: Bicycle, hinge_stiffness: float = 0.0,
                     hinge_damping: float = 0.0) -> "RiderLean":
        """A bicycle with its rider (any form), Jason's upper body (48.8 kg, of the Browser with
        Jason set, Moore 2012) taken off its rear frame and hinged to it at Jason's hinge, with
        the hinge's stiffness [N m/rad] and damping [N m s/rad]; the rear frame keeps the frame
        and the rider's lower body. Raises ``whipple.InvalidParameter`` where Jason's upper
        body does not fit inside the bicycle's rider (the benchmark bicycle's, a bicycle
        without a rider). ``rigid()`` gives the bicycle back."""
        return cls(_whipple.NativeRiderLean.from_bicycle(
            bike._native, float(hinge_stiffness), float(hinge_damping)))

    def to_moore_rider_lean2012(self) -> Dict[str, float]:
        """BicycleParameters' ``MooreRiderLean2012`` keys and values."""
        return dict(self._native.moore_rider_lean2012())

    def rigid(self) -> Bicycle:
        """The rigid rider: the hinge locked, the upper body combined into the rear frame."""
        return Bicycle._wrap(self._native.rigid())

    def linearize(self, speed: float) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """A (6 × 6) and B (6 × 3) of the exact linearization about upright straight running
        at ``speed`` [m/s] (dual numbers through the non-linear five-body model)."""
        a, b = self._native.linearize(float(speed))
        return np.asarray(a), np.asarray(b)
