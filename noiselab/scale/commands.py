"""The command line's chunked path: ``noiselab noise ... --output out.zarr [--chunks ...] [--scheduler ...]``."""
from __future__ import annotations

import numpy as np

__all__ = ["add_dask_arguments", "parse_axes", "write_noise_zarr", "write_snow_zarr"]

_DIMS = {1: ("x",), 2: ("y", "x"), 3: ("z", "y", "x")}


def add_dask_arguments(parser, chunks_help):
    """The ``--chunks`` and ``--scheduler`` options of a command that writes .zarr on dask."""
    parser.add_argument("--chunks", default=None, help=chunks_help)
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="with .zarr output: dask scheduler, threads (default), processes, synchronous, "
                             "or the address of a running dask.distributed scheduler, e.g. tcp://host:8786")


def parse_axes(name, text, dims, cast):
    """A per-axis option of the command line (``8``, ``480x640``, ``2,8,8``) as ``dims`` values of type ``cast``.

    One value applies to every axis. Shared by the in-memory commands
    (``--size``, ``--cells``) and the chunked path (``--chunks``); it lives
    here, below the command line, so that both can import it.

    Examples
    --------
    >>> parse_axes("--size", "48x128x128", 3, int)
    [48, 128, 128]
    >>> parse_axes("--cells", "8", 2, float)
    [8.0, 8.0]
    """
    parts = str(text).lower().replace(",", "x").split("x")
    try:
        values = [cast(p.strip()) for p in parts]   # an empty part ('10x', 'x8') is an error, not a default
    except ValueError:
        raise ValueError(f"{name} must be a number or {dims} numbers joined by 'x' (e.g. 8 or "
                         f"{'x'.join(['8'] * dims)}), got {text!r}") from None
    if len(values) == 1:
        values = values * dims
    if len(values) != dims:
        raise ValueError(f"{name} must have 1 or {dims} entries for a {dims}-D field, got {text!r}")
    return values


def _parse_chunks(text, dims):
    if text is None or str(text).strip().lower() == "auto":
        return "auto"
    values = parse_axes("--chunks", text, dims, int)
    if any(v < 1 for v in values):
        raise ValueError(f"--chunks entries must be >= 1, got {text!r}")
    return tuple(values)


def write_noise_zarr(args, noise, grid, summer, dtype, path):
    """Render ``summer(noise, grid, ...)`` lazily in ``--chunks`` and stream it into the zarr store ``path``.

    Prints one summary line; returns the exit status. The store's data array
    carries the command's parameters, the seed, the noiselab version and the
    units; the coordinates are the sample positions in lattice units.
    """
    from ..io.zarr import write_zarr
    from ..lattice import grid_coordinates

    if path.suffix.lower() != ".zarr":
        raise ValueError(f"--chunks and --scheduler need .zarr output, got {path.name!r}")
    dims = len(grid.shape)
    chunks = _parse_chunks(args.chunks, dims)
    try:
        field, used = summer(noise, grid, args.octaves, lacunarity=args.lacunarity, gain=args.gain, dtype=dtype,
                             return_octaves=True, chunks=chunks)
    except ImportError as exc:
        raise ValueError(str(exc)) from None
    bound = sum(args.gain ** o for o in range(used))
    lo, hi = (0.0 if args.kind == "turbulence" else -bound), bound
    params = {
        "command": "noiselab noise",
        "sum": args.kind, "dims": dims, "size": list(grid.shape), "extent": [list(e) for e in grid.extent],
        "kernel": noise.kernel.name, "basis": noise.basis, "table_size": noise.table_size,
        "alternation": noise.alternation, "period": noise.period.tolist() if noise.tileable else None,
        "octaves": args.octaves, "octaves_used": used, "lacunarity": args.lacunarity, "gain": args.gain,
        "dtype": np.dtype(dtype).name,
    }
    names = _DIMS[dims]
    coords = dict(zip(names, grid_coordinates(grid.shape, grid.extent)))
    path.parent.mkdir(parents=True, exist_ok=True)
    try:
        write_zarr(path, field, dims=names, coords=coords, params=params, rng=args.seed,
                   units="noise amplitude (dimensionless); coordinates in lattice cells",
                   attrs={"value_bound": [lo, hi]}, scheduler=args.scheduler)
    except (ImportError, FileExistsError) as exc:
        raise ValueError(str(exc)) from None
    chunk_shape = tuple(max(c) for c in field.chunks)
    print(f"noiselab noise: wrote {path} shape={field.shape} chunks={chunk_shape} ({field.npartitions} task{'s' if field.npartitions != 1 else ''}) "
          f"kernel={noise.kernel.name} basis={noise.basis} {args.kind} octaves used {used}/{args.octaves} "
          f"bound [{lo:.4f}, {hi:.4f}]")
    return 0


def write_snow_zarr(args, shape, path):
    """``noiselab snow ... -o out.zarr [--chunks TxHxW] [--scheduler ...]``: one period of the opacity, out of core.

    The snow is computed by :func:`noiselab.scale.spectral.chunked_snow` with
    its transpose spilled to a temporary zarr array beside the output (removed
    afterwards, also on failure), so no worker holds more than its chunks; the
    store carries the command's parameters, the seed, the noiselab version and
    the units, with dims ``(t, y, x)`` in frames and pixels.
    """
    from ..io.atomic import scratch_folder
    from ..io.zarr import write_zarr
    from ..snowfall import snow

    if path.suffix.lower() != ".zarr":
        raise ValueError(f"--chunks and --scheduler need .zarr output, got {path.name!r}")
    if args.tile is not None or args.background:
        raise ValueError("--tile and --background are not used with .zarr output (it stores the opacity of one "
                         "period); drop them")
    chunks = _parse_chunks(args.chunks, 3)
    band = None if args.band is None else tuple(args.band)
    path.parent.mkdir(parents=True, exist_ok=True)
    with scratch_folder(path, suffix=".spill.tmp") as spill:   # removed afterwards, also when a signal stops the run
        try:
            alpha = snow(shape, rng=args.seed, c=args.c, band=band, thickness=args.thickness,
                         direction_yx=tuple(args.direction_yx), pan_yx=tuple(args.pan_yx), beta=args.beta,
                         exponent=args.exponent, amplitude_distribution=args.amplitude, dtype=args.dtype,
                         on_alias=args.on_alias, chunks=chunks, spill=spill)
        except ImportError as exc:
            raise ValueError(str(exc)) from None
        T, H, W = shape
        params = {
            "command": "noiselab snow", "shape": [T, H, W], "c": args.c,
            "band": list(band) if band is not None else [W / 32, W / 4], "thickness": args.thickness,
            "direction_yx": list(args.direction_yx), "pan_yx": list(args.pan_yx), "beta": args.beta,
            "exponent": args.exponent, "amplitude": args.amplitude, "on_alias": args.on_alias, "dtype": args.dtype,
        }
        coords = {"t": np.arange(T, dtype=np.float64), "y": np.arange(H, dtype=np.float64),
                  "x": np.arange(W, dtype=np.float64)}
        try:
            write_zarr(path, alpha, dims=("t", "y", "x"), coords=coords, params=params, rng=args.seed,
                       units="opacity in [0, 1]; t in frames (one period, it loops), y and x in pixels",
                       scheduler=args.scheduler, progress=args.progress)
        except (ImportError, FileExistsError) as exc:
            raise ValueError(str(exc)) from None
    chunk_shape = tuple(max(c) for c in alpha.chunks)
    print(f"noiselab snow: wrote {path} shape={alpha.shape} chunks={chunk_shape} opacity of one period "
          f"({T} frames of {W} x {H} px), seed {args.seed}")
    return 0
