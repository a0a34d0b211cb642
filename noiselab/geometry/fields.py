"""Fields: any callable on points, plus octave sums and sampled (gridded) fields.

Everything in :mod:`noiselab.geometry` is driven by a *field*: any callable
that maps points of shape ``(n, k)`` to values of shape ``(n,)`` (scalar) or
``(n, m)`` (vector). A :class:`noiselab.LatticeNoise` is one, so is
``lambda p: noiselab.fractal_sum(noise, p, 4)``, so is a spectral volume
wrapped by :func:`sampled_field`, so is a plain numpy function.

A field may carry a ``max_frequency`` attribute: the highest frequency it
contains, in cycles (lattice periods) per unit of its input. The resolution
checks use it to decide whether a mesh samples the field finely enough; a
field without it is taken to have features one unit across (1 cycle/unit),
which is what a lattice noise of unit frequency has (a ``LatticeNoise`` with
its own ``frequency`` F counts that).
"""
from __future__ import annotations

import numpy as np

from .._core import check_finite_array, check_int, check_real

__all__ = ["octave_field", "sampled_field", "evaluate_field", "field_max_frequency"]


def field_max_frequency(field) -> float:
    """Highest frequency of ``field`` in cycles per input unit (its ``max_frequency``, else 1).

    Parameters
    ----------
    field : callable
        A field, e.g. a :class:`~noiselab.lattice.LatticeNoise` or an :func:`octave_field`.

    Returns
    -------
    float

    Examples
    --------
    >>> import numpy as np
    >>> field_max_frequency(lambda p: p[:, 0])
    1.0
    """
    value = getattr(field, "max_frequency", None)
    if value is None and hasattr(field, "dim_in") and hasattr(field, "table_size"):
        # a noiselab.LatticeNoise: its own frequency F (lattice cells per input unit, per axis)
        value = getattr(field, "frequency", None)
    if value is None:
        return 1.0
    value = np.asarray(value, dtype=float)
    return float(value.max())


def evaluate_field(field, points, *, name="field", components=None, chunk_size=1 << 20) -> np.ndarray:
    """Call ``field`` on ``points`` (n, k) in chunks and check what comes back.

    Returns float64 ``(n,)`` when ``components`` is 1 (a trailing axis of 1 is
    dropped), ``(n, components)`` for vector output, or whatever ``(n,)`` /
    ``(n, m)`` the field gives when ``components`` is None. Chunking bounds
    the field's temporaries; pointwise fields give the same values for any
    chunking.

    Parameters
    ----------
    field : callable
        Points ``(n, k)`` to values.
    points : array_like (n, k)
    name : str, default "field"
        How error messages call the field.
    components : int, optional
        The number of output components expected.
    chunk_size : int, default 1_048_576
        Points per call.

    Returns
    -------
    ndarray of float64, (n,) or (n, components)

    Raises
    ------
    ValueError
        For output of the wrong shape or with NaN or inf values.

    Examples
    --------
    >>> import numpy as np
    >>> evaluate_field(lambda p: p.sum(axis=1), np.ones((5, 3)), components=1).tolist()
    [3.0, 3.0, 3.0, 3.0, 3.0]
    """
    if not callable(field):
        raise TypeError(f"{name} must be callable on points of shape (n, k), got {type(field).__name__}")
    points = check_finite_array("points", points)
    if points.ndim != 2:
        raise ValueError(f"points must have shape (n, k), got {points.shape}")
    chunk_size = check_int("chunk_size", chunk_size, lo=1)
    if components is not None:
        components = check_int("components", components, lo=1)
    points = np.ascontiguousarray(points, dtype=np.float64)
    dim_in = getattr(field, "dim_in", None)
    if isinstance(dim_in, (int, np.integer)) and dim_in != points.shape[1]:
        raise ValueError(
            f"{name} takes {int(dim_in)}-D points but is evaluated here on {points.shape[1]}-D points"
            + (" (time adds a 4th coordinate)" if points.shape[1] == 4 else "")
        )
    n = points.shape[0]
    parts = []
    for start in range(0, max(n, 1), chunk_size):
        block = points[start:start + chunk_size]
        out = np.asarray(field(block), dtype=np.float64)
        if out.shape[:1] != (block.shape[0],) or out.ndim > 2:
            raise ValueError(
                f"{name} must return shape (n,) or (n, m) for points of shape {block.shape}, got {out.shape}"
            )
        parts.append(out)
    out = parts[0] if len(parts) == 1 else np.concatenate(parts, axis=0)
    if components == 1:
        if out.ndim == 2:
            if out.shape[1] != 1:
                raise ValueError(f"{name} must return a scalar per point here, got {out.shape[1]} components")
            out = out[:, 0]
    elif components is not None:
        if out.ndim != 2 or out.shape[1] < components:
            got = 1 if out.ndim == 1 else out.shape[1]
            raise ValueError(f"{name} must return at least {components} components per point, got {got}")
        out = out[:, :components]
    return check_finite_array(f"{name} output", out)


def _is_lattice(field):
    try:
        from ..lattice import LatticeNoise
    except ImportError:  # pragma: no cover
        return False
    return isinstance(field, LatticeNoise)


class _OctaveField:
    """sum_k gain^k * g(lacunarity^k * x), g = field (fractal, Eq. 9) or |field| (turbulence, Eq. 10)."""

    def __init__(self, field, octaves, kind, lacunarity, gain):
        self.field = field
        self.octaves = octaves
        self.kind = kind
        self.lacunarity = lacunarity
        self.gain = gain
        self.max_frequency = field_max_frequency(field) * lacunarity ** (octaves - 1)
        dim_in = getattr(field, "dim_in", None)
        if dim_in is not None:
            self.dim_in = dim_in

    def __call__(self, x):
        x = check_finite_array("points", x).astype(np.float64)
        if _is_lattice(self.field):
            # the lattice's own octave sum: the same sum, evaluated by its fused fast path
            from ..fractal import fractal_sum, turbulence

            sum_ = turbulence if self.kind == "turbulence" else fractal_sum
            return sum_(self.field, x, self.octaves, lacunarity=self.lacunarity, gain=self.gain)
        total = None
        scale, weight = 1.0, 1.0
        for _ in range(self.octaves):
            with np.errstate(over="ignore", invalid="ignore"):
                value = np.asarray(self.field(x * scale), dtype=np.float64)
                if self.kind == "turbulence":
                    value = np.abs(value)
                total = weight * value if total is None else total + weight * value
            scale *= self.lacunarity
            weight *= self.gain
        if total is not None and not np.isfinite(total).all():
            raise ValueError(f"field returned NaN or inf (or its octave sum overflowed) at {int((~np.isfinite(total)).sum())} "
                             "point(s); a field must return finite values")
        return total

    def __repr__(self):
        return (f"octave_field({self.field!r}, octaves={self.octaves}, kind={self.kind!r}, "
                f"lacunarity={self.lacunarity:g}, gain={self.gain:g})")


def octave_field(field, octaves, kind="fractal", *, lacunarity=2.0, gain=0.5):
    """Wrap a field into its fractal sum (Eq. 9) or turbulence (Eq. 10) over ``octaves`` octaves.

    ``fracsum(x) = sum_{k<n} gain^k noise(lacunarity^k x)``; turbulence sums
    ``|noise|`` instead. The defaults are the paper's (2 and 1/2). The result
    is a field itself, with ``max_frequency`` set to the top octave's, so the
    resolution checks of :func:`noiselab.geometry.displace` count the highest
    octave. ``octaves=1, kind="fractal"`` returns ``field`` unchanged.

    Parameters
    ----------
    field : callable
        Points (n, k) -> values (n,) or (n, m).
    octaves : int
        Number of octaves, 1 to 64.
    kind : {"fractal", "turbulence", "noise"}
        "noise" is an alias of a one-octave fractal sum (only ``octaves=1``).
    lacunarity, gain : float
        Frequency ratio (> 1) and amplitude ratio (in (0, 1]) between octaves.

    Examples
    --------
    >>> import numpy as np
    >>> f = lambda p: np.sin(p[:, 0])
    >>> g = octave_field(f, 3, "turbulence")
    >>> g.max_frequency
    4.0
    >>> float(g(np.zeros((1, 3)))[0])
    0.0
    """
    octaves = check_int("octaves", octaves, lo=1, hi=64)
    if kind not in ("fractal", "turbulence", "noise"):
        raise ValueError(f"kind must be 'noise', 'fractal' or 'turbulence', got {kind!r}")
    if kind == "noise" and octaves != 1:
        raise ValueError(f"kind='noise' means a single octave; use kind='fractal' for octaves={octaves}")
    lacunarity = check_real("lacunarity", lacunarity, lo=1.0, lo_open=True, hi=64.0)
    gain = check_real("gain", gain, lo=0.0, lo_open=True, hi=1.0)
    if not callable(field):
        raise TypeError(f"field must be callable on points of shape (n, k), got {type(field).__name__}")
    if octaves == 1 and kind in ("fractal", "noise"):
        return field
    return _OctaveField(field, octaves, "turbulence" if kind == "turbulence" else "fractal", lacunarity, gain)


class _SampledField:
    def __init__(self, values, origin, spacing, periodic, order, max_frequency=None):
        self.values = values
        self.origin = origin
        self.spacing = spacing
        self.periodic = periodic
        self.order = order
        self.dim_in = len(origin)
        # Nyquist of the grid unless told the band: features cannot be finer than two samples.
        self.max_frequency = float(0.5 / spacing.min()) if max_frequency is None else max_frequency

    def __call__(self, x):
        from scipy import ndimage

        x = check_finite_array("points", x).astype(np.float64)
        if x.ndim != 2 or x.shape[1] != self.dim_in:
            raise ValueError(f"sampled field takes points of shape (n, {self.dim_in}), got {x.shape}")
        coords = ((x - self.origin) / self.spacing).T
        mode = "grid-wrap" if self.periodic else "nearest"
        if self.values.ndim == self.dim_in:
            return ndimage.map_coordinates(self.values, coords, order=self.order, mode=mode, prefilter=True)
        return np.stack([ndimage.map_coordinates(self.values[..., c], coords, order=self.order, mode=mode)
                         for c in range(self.values.shape[-1])], axis=-1)


def sampled_field(values, extent=None, *, periodic=True, order=3, vector=False, max_frequency=None):
    """Turn a sampled array (a spectral-noise volume, an image) into a field by spline interpolation.

    ``values`` has one axis per input dimension (axis ``i`` is input
    coordinate ``i``), plus a trailing component axis when ``vector`` is true.
    ``extent`` gives one ``(start, stop)`` pair per input axis (stop excluded,
    as in ``numpy.arange``; default ``(0, n)``: one unit per sample): the
    array-axis order of every grid in :mod:`noiselab.geometry`, so
    ``sampled_field(height_map(f, shape, extent), extent)`` interpolates a
    height map at points ``(y, x)``.
    ``periodic`` wraps the grid (right for inverse-FFT output, which is
    periodic); otherwise points outside are clamped to the edge. ``order`` is
    the spline order (1 linear, 3 cubic). ``max_frequency`` (cycles per input
    unit) tells the resolution checks the field's band, e.g. a spectral noise
    of band ``(lo, hi)`` cycles per frame over an extent of width ``w`` has
    ``hi / w``; by default the grid's Nyquist frequency is assumed.

    Parameters
    ----------
    values : array_like
        One axis per input dimension (plus a trailing component axis with ``vector``).
    extent : sequence of (start, stop), optional
        One pair per input axis, stop excluded (default ``(0, n)``).
    periodic : bool, default True
        Wrap the grid; otherwise clamp points to its edge.
    order : int, default 3
        Spline order (1 linear, 3 cubic).
    vector : bool, default False
        The last axis of ``values`` holds components.
    max_frequency : float, optional
        The field's highest frequency in cycles per input unit (default: the grid's Nyquist).

    Returns
    -------
    callable
        A field: points ``(n, k)`` to values ``(n,)`` (``(n, m)`` with ``vector``),
        with a ``max_frequency`` attribute.

    Raises
    ------
    ValueError
        For non-finite values, an extent of the wrong length or an order out of range.

    Examples
    --------
    >>> import numpy as np
    >>> vol = np.random.default_rng(0).standard_normal((8, 8, 8))
    >>> f = sampled_field(vol)
    >>> bool(np.isclose(f(np.array([[2.0, 3.0, 4.0]]))[0], vol[2, 3, 4]))
    True
    """
    values = check_finite_array("values", values).astype(np.float64, copy=False)
    dims = values.ndim - (1 if vector else 0)
    if dims < 1:
        raise ValueError(f"values must have at least one spatial axis, got shape {values.shape}")
    order = check_int("order", order, lo=0, hi=5)
    shape = values.shape[:dims]
    if min(shape) < 2:
        raise ValueError(f"values needs at least 2 samples per axis, got shape {shape}")
    if extent is None:
        extent = [(0.0, float(n)) for n in shape]
    extent = check_finite_array("extent", extent).astype(np.float64)
    if extent.shape != (dims, 2):
        raise ValueError(f"extent must hold one (start, stop) pair per axis ({dims}), got shape {extent.shape}")
    if not np.all(np.isfinite(extent)) or np.any(extent[:, 1] <= extent[:, 0]):
        raise ValueError(f"extent must be finite with stop > start on every axis, got {extent.tolist()}")
    spacing = (extent[:, 1] - extent[:, 0]) / np.asarray(shape, dtype=np.float64)
    if max_frequency is not None:
        max_frequency = check_real("max_frequency", max_frequency, lo=0.0)
    return _SampledField(values, extent[:, 0].copy(), spacing, bool(periodic), order, max_frequency)
