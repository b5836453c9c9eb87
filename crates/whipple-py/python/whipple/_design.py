"""Design maps: the critical speeds of a bicycle over one or two parameters, as 2-D arrays
(``xarray``-friendly: ``to_xarray()``), computed whole or shard by shard, and spread over a Dask
cluster with :func:`design_map_dask`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, Dict, List, Optional, Sequence, Tuple

import numpy as np

if TYPE_CHECKING:
    import xarray
    from matplotlib.axes import Axes

STATUS = np.array(["ok", "invalid", "accuracy_lost"], dtype=object)

QUANTITIES = ("v_d", "v_w", "v_c", "weave_frequency", "stable_width", "stable_from",
              "stable_to", "max_real", "stable", "unresolved")

#: The quantities of a map with a band (``band=(a, b)``): ``stable_over`` (1.0 where
#: self-stable at every speed of the band, 0.0 where not, NaN where undecided or not computed),
#: the margins by which the self-stable range reaches past the band's ends and the smaller one.
BAND_QUANTITIES = ("stable_over", "band_margin_below", "band_margin_above", "band_margin")


class DesignMap:
    """A study of a base bicycle over axis ``x`` (and ``y``): for every design its v_d (when
    asked for), v_w, v_c, weave frequency, stable width, stable_from/stable_to (the first
    self-stable range), max Re λ at ``speed``, ``stable`` and ``unresolved`` flags, as arrays of
    shape (ny, nx) (or (nx,) for one axis), NaN where a quantity does not exist or the design is
    refused (``status`` says why: ``ok``, ``invalid``, ``accuracy_lost``; ``reason`` the words).
    ``x``, ``y``: the axes' values in the user's units (``x_name``, ``x_unit``). With a band
    (``band``, (a, b) m/s): ``stable_over`` (1.0 self-stable at every speed of it, 0.0 not, NaN
    undecided), ``band_margin_below``, ``band_margin_above`` and ``band_margin`` (the smaller)."""

    def __init__(self, parts: Sequence[Dict[str, Any]]) -> None:
        first = parts[0]
        self.x_name: str = first["x_axis"]["name"]
        self.x_unit: str = first["x_axis"]["unit"]
        self.x: np.ndarray = first["x_axis"]["values"]
        y_axis = first["y_axis"]
        self.y_name: Optional[str] = y_axis["name"] if y_axis else None
        self.y_unit: Optional[str] = y_axis["unit"] if y_axis else None
        self.y: Optional[np.ndarray] = y_axis["values"] if y_axis else None
        base = first.get("base") or (None, None)
        #: The base bicycle's point on the axes (user units; None for a speed axis).
        self.base_x: Optional[float] = base[0]
        self.base_y: Optional[float] = base[1] if y_axis else None
        shape = (len(self.y), len(self.x)) if y_axis else (len(self.x),)
        # Each part holds the designs start..start + count in row-major order, so the parts in
        # order of `start`, end to end, are the grid: no scatter, and a whole map's columns are
        # only reshaped (no copy).
        parts = sorted(parts, key=lambda p: p["start"])
        seen = sum(p["count"] for p in parts)
        if seen != first["total"] or any(
                p["start"] + p["count"] != q["start"] for p, q in zip(parts, parts[1:])):
            raise ValueError(f"the parts hold {seen} designs of {first['total']}: a shard is "
                             "missing or given twice")

        def column(name: str) -> np.ndarray:
            if len(parts) == 1:
                return np.asarray(parts[0][name]).reshape(shape)
            return np.concatenate([p[name] for p in parts]).reshape(shape)

        #: The band asked for, (a, b) m/s, or None.
        self.band: Optional[Tuple[float, float]] = (tuple(first["band"])  # type: ignore[assignment]
                                                    if first.get("band") is not None else None)
        names = QUANTITIES + (BAND_QUANTITIES if self.band is not None else ())
        self.quantities: Dict[str, np.ndarray] = {name: column(name) for name in names}
        #: Why each design has no numbers: ``'ok'``, ``'invalid'``, ``'accuracy_lost'`` (an
        #: object array whose cells share the three strings).
        self.status: np.ndarray = column("status")
        #: The rule broken or the accuracy lost, in words, None where computed.
        self.reason: np.ndarray = column("reason")
    def __getattr__(self, name: str) -> np.ndarray:
        q = self.__dict__.get("quantities", {})
        if name in q:
            return q[name]
        raise AttributeError(name)

    def to_xarray(self) -> "xarray.Dataset":
        """An ``xarray.Dataset`` with the axes as coordinates (needs xarray)."""
        import xarray as xr

        dims = (self.y_name, self.x_name) if self.y is not None else (self.x_name,)
        coords = {self.x_name: self.x}
        if self.y is not None:
            coords[self.y_name] = self.y
        data = {name: (dims, grid) for name, grid in self.quantities.items()}
        data["status"] = (dims, self.status.astype(str))
        return xr.Dataset(data, coords=coords)

    def plot(self, ax: Optional["Axes"] = None, quantity: str = "stable_width") -> "Axes":
        """The command line's figures: over two axes a heat map of ``quantity`` (``'v_w'``,
        ``'v_c'``, ``'v_d'``, ``'stable_width'``, ``'weave_frequency'``, ``'max_real'`` on a
        diverging scale white at zero, ``'stable_over'``: the smaller margin, with a band) with
        a colour bar and its unit, the boundary of the designs that have a self-stable range
        (with ``'stable_over'``: of those self-stable over the band) and the base design marked; over one axis v_w and v_c against the parameter with the
        self-stable band shaded. Needs matplotlib; returns the axis."""
        from ._plot import plot_design_map

        return plot_design_map(self, ax=ax, quantity=quantity)

    def __repr__(self) -> str:
        shape = self.quantities["v_w"].shape
        axes = f"{self.x_name} [{self.x_unit}]" + (f" × {self.y_name} [{self.y_unit}]" if self.y_name else "")
        ok = int(np.sum(self.status == "ok"))
        return f"DesignMap({axes}, shape {shape}, {ok} designs computed)"


def design_map_dask(bike: Any, x: str, y: Optional[str] = None, *, client: Any,
                    shards: Optional[int] = None, **options: Any) -> DesignMap:
    """The same map as ``bike.design_map(x, y, **options)``, its shards
    (``bike.design_map_shard(x, y, shard=(k, n), **options)``) computed as tasks of a
    ``dask.distributed`` ``client`` (one per shard; by default two per worker thread) and
    assembled in order. Each task rebuilds the bicycle from its TOML text, so the workers need
    only ``whipple`` installed; the numbers are those of the single-process map, bit for bit."""
    if shards is None:
        threads = sum(client.nthreads().values()) or 1
        shards = 2 * threads
    text = bike.to_text("toml")
    futures = [client.submit(_shard, text, x, y, k, shards, options, pure=False)
               for k in range(shards)]
    return DesignMap(client.gather(futures))


def _shard(text: str, x: str, y: Optional[str], k: int, n: int,
           options: Dict[str, Any]) -> Dict[str, Any]:
    from ._bicycle import Bicycle

    return Bicycle.from_text(text, "toml").design_map_shard(x, y, shard=(k, n), **options)


def part(native: Dict[str, Any]) -> Dict[str, Any]:
    """The native module's columns of a shard with ``status`` and ``reason`` as object arrays
    (the status codes mapped to three shared strings; a reason only where a design has one)."""
    native["status"] = STATUS[native.pop("status_code")]
    reason = np.full(len(native["status"]), None, dtype=object)
    at = native.pop("reason_at")
    if len(at):
        texts = np.empty(len(at), dtype=object)
        texts[:] = native.pop("reason_text")
        reason[at] = texts
    else:
        native.pop("reason_text")
    native["reason"] = reason
    return native
