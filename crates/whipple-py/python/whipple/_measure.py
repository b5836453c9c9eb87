"""``whipple.measure``: a bicycle from BicycleParameters' raw bench measurements."""

from __future__ import annotations

import os
from typing import Any, Dict, List, Optional, Tuple, Union

import numpy as np

from . import _whipple
from ._bicycle import BENCHMARK_KEYS, Bicycle
from ._errors import LimitError, ParseError


class Measurement:
    """A bicycle computed from bench measurements (Moore 2012 ch. 2; BicycleParameters'
    ``calculate_from_measured``), with everything the computation found on the way. Made by
    :func:`whipple.measure`.

    Attributes:
        bicycle: the :class:`Bicycle` in the benchmark form, each parameter with its σ.
        steps: every number the pipeline derived, in the order computed: dicts with ``key``
            (``'rR'``, ``'betaB1'``, ``'k'``), ``description``, ``function`` (the core's step
            function; ``''`` for a value taken as measured), ``unit``, ``value``, ``sigma``
            (``None`` where not carried: the hanging lines' residuals), ``inputs`` (the
            measurements it depends on) and ``benchmark`` (whether it is one of the 26
            parameters).
        keys: the 26 benchmark keys, the order of :attr:`covariance`'s rows and columns.
        inputs: the measurements' keys, the order of :attr:`jacobian`'s columns.
        jacobian: ∂ parameter / ∂ measurement, shape ``(26, len(inputs))``, exact (dual
            numbers).
        covariance: the parameters' covariance J diag(σ²) Jᵀ, shape ``(26, 26)``, the
            measurements independent (BicycleParameters keeps only its diagonal).
        fitted: the periods the raw file lacked, fitted from records (``periods=``): dicts
            with ``key`` (``'TcH1'``), ``value`` and ``sigma`` [s] and ``source`` (the record
            files).
        rider: with a rider (``measure(..., rider=, configuration=)``), the rider alone as a
            dict: ``mass`` (kg), ``center_of_mass`` (m, benchmark axes: x forward, y right, z
            down), ``inertia`` (3 × 3, kg m², about its mass centre), ``configuration`` (the 21
            angles seated on the bicycle, rad), ``iterations`` and ``residual`` (m) of the
            joint-angle solve; else ``None``.
    """

    __slots__ = ("bicycle", "steps", "keys", "inputs", "jacobian", "covariance", "fitted",
                 "rider",
                 "_correlations")

    def __init__(self, native: Dict[str, Any]) -> None:
        """Use :func:`whipple.measure`."""
        self.bicycle: Bicycle = Bicycle._wrap(native["bicycle"])
        self.steps: List[Dict[str, Any]] = list(native["steps"])
        self.keys: Tuple[str, ...] = BENCHMARK_KEYS
        self.inputs: List[str] = list(native["inputs"])
        self.jacobian: np.ndarray = np.asarray(native["jacobian"], dtype=np.float64)
        self.covariance: np.ndarray = np.asarray(native["covariance"], dtype=np.float64)
        self.fitted: List[Dict[str, Any]] = [
            dict(zip(("key", "value", "sigma", "source"), f)) for f in native["fitted"]]
        self._correlations: List[Dict[str, Any]] = list(native["correlations"])
        rider = native.get("rider")
        self.rider: Optional[Dict[str, Any]] = None if rider is None else dict(rider)

    def step(self, key: str) -> Dict[str, Any]:
        """The step of that key (``'k'``, ``'xB'``, ``'residualH'``); ``KeyError`` if none."""
        for s in self.steps:
            if s["key"] == key:
                return s
        raise KeyError(key)

    def correlation(self) -> np.ndarray:
        """The correlation matrix of the parameters, shape ``(26, 26)`` in :attr:`keys`' order;
        NaN in the rows and columns of a parameter with σ = 0."""
        sigma = np.sqrt(np.clip(np.diag(self.covariance), 0.0, None))
        with np.errstate(divide="ignore", invalid="ignore"):
            rho = self.covariance / np.outer(sigma, sigma)
        rho[np.outer(sigma, sigma) == 0.0] = np.nan
        return np.asarray(rho)

    def largest_correlations(self, count: int = 10) -> List[Tuple[str, str, float]]:
        """The ``count`` largest correlations (by |ρ|) between distinct parameters, as
        ``(key, key, ρ)``, largest first (computed by the core, as ``whipple measure
        --correlations`` prints them)."""
        return [(c["a"], c["b"], float(c["rho"])) for c in self._correlations[:max(count, 0)]]

    def __repr__(self) -> str:
        return f"<Measurement of {self.bicycle.label}: {len(self.steps)} steps>"


def _text(source: Union[str, "os.PathLike[str]"], marker: str, what: str) -> Tuple[str, str]:
    """A file's text and base name, or ``source`` itself when it is text (holds a newline or
    ``marker``)."""
    if isinstance(source, str) and ("\n" in source or marker in source):
        return source, ""
    path = os.fspath(source)
    limit = _whipple.MAX_FILE_BYTES
    with open(path, "rb") as f:
        data = f.read(limit + 1)
    if len(data) > limit:
        raise LimitError(f"{path}: longer than {limit >> 20} MiB, the most {what} may hold",
                         field="path", value=path,
                         rule=f"{what} holds at most {limit} bytes")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        raise ParseError(f"{path}: the file is not UTF-8 text", field=None, value=None,
                         rule=f"{what} is UTF-8 text", format="unknown",
                         line=0, column=0) from error
    return text, os.path.basename(path)


def measure(source: Union[str, "os.PathLike[str]"], strict: bool = False,
            rider: Optional[Union[str, "os.PathLike[str]"]] = None,
            configuration: Optional[Union[str, "os.PathLike[str]"]] = None,
            periods: Union[None, str, "os.PathLike[str]"] = None) -> Measurement:
    """A bicycle from BicycleParameters' raw bench measurements (``<Name>Measured.txt``:
    ``key = value+/-sigma`` lines): the benchmark parameters with their exact first-order σ,
    every step of the computation and the parameters' covariance (see :class:`Measurement`).

    ``source`` is the file's path, or its text (a string holding a newline or an ``=``). The
    bicycle's name comes from the file's name (``BrowserMeasured.txt`` is ``'Browser'``). A
    missing measurement raises :class:`whipple.ParseError` naming it and what it feeds; a
    negative period, mass or length :class:`whipple.ParameterError` naming the key and line.

    With ``rider`` (a ``<Rider>YeadonMeas.txt``: Yeadon's 95 measurements) and
    ``configuration`` (its ``<Rider><Bike>YeadonCFG.txt``), paths or texts, the rider is
    seated on the bicycle — its hips, knees, shoulders and elbows solved so that the feet reach
    the bottom bracket and the hands the grips, from the file's ``lcs``, ``hbb``, ``lsp``,
    ``lst``, ``lamst``, ``whb``, ``LhbF`` and ``LhbR`` — and added to the rear frame, as
    BicycleParameters' ``add_rider``; the bicycle's σ is carried through the rider's place,
    the rider's body is taken as exact. A rider who cannot reach raises
    :class:`whipple.ParameterError` whose ``field`` names the measurements and keys involved.

    For example, ``whipple.measure("BrowserMeasured.txt").bicycle.critical_speeds()`` gives
    Browser's critical speeds, with their σ, from the raw file alone.

    ``periods``, a directory, holds rate-gyro records named as BicycleParameters names them
    (``BrowserFrameCompoundFirst1.mat``, trials 1, 2, …): every period the file lacks is
    fitted from them (the trials' mean; see :attr:`Measurement.fitted`); a period with no
    record raises :class:`whipple.ParameterError` naming the key and the file looked for.
    """
    folder = None if periods is None else os.fspath(periods)
    if (rider is None) != (configuration is None):
        raise TypeError("measure: give rider and configuration together (the rider's "
                        "measurements and its configuration on this bicycle)")
    text, name = _text(source, "=", "a measurements file")
    if rider is None:
        return Measurement(_whipple.measure(text, name, strict, folder))
    rider_text, rider_file = _text(rider, ":", "a Yeadon measurements file")
    cfg_text, _ = _text(configuration, ":", "a Yeadon configuration file")
    rider_name = rider_file[: -len("YeadonMeas.txt")] if rider_file.endswith("YeadonMeas.txt") \
        else ""
    return Measurement(_whipple.measure(text, name, strict, folder,
                                        (rider_text, cfg_text, rider_name)))
