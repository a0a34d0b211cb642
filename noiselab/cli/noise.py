"""``noiselab noise``: render lattice noise (1-D curve, 2-D image, 3-D video or volume) to PNG, MP4/GIF or NPY.

Examples::

    noiselab noise --output out/noise.png                                  # 512x512 image, cubic B-spline value noise
    noiselab noise --size 256x256 --octaves 6 --kernel quintic -o out/fbm.png
    noiselab noise --dims 3 --size 48x128x128 --cells 3x6x6 --sum turbulence -o out/turb.mp4
    noiselab noise --dims 3 --size 64 --output out/volume.npy --dtype float32
    noiselab noise --dims 1 --size 2000 --cells 20 --octaves 5 -o out/curve.png
    noiselab noise --dims 3 --size 512 --chunks 128 --octaves 6 -o out/volume.zarr   # bigger than memory
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..io.media import DEFAULT_FPS
from ..scale.commands import add_dask_arguments, parse_axes

NAME = "noise"
HELP = "Render Phillips lattice noise (value or gradient), fractal sums or turbulence to PNG, MP4/GIF or NPY."

_DEFAULT_SIZE = {1: "1024", 2: "512x512", 3: "48x128x128"}


def add_arguments(parser):
    from ..lattice.kernels import kernel_names

    parser.add_argument("-o", "--output", default="out/noise.png",
                        help="output file: .png (1-D plot or 2-D image), .mp4/.gif (3-D video over axis 0), "
                             ".npy (raw array, any dimension), .zarr (chunked store, computed on dask: see --chunks); "
                             "missing folders are created (default: %(default)s)")
    parser.add_argument("--dims", type=int, default=2, choices=(1, 2, 3), help="field dimension (default: 2)")
    parser.add_argument("--size", default=None,
                        help="samples per axis, e.g. 512 or 480x640 or 48x128x128 (frames x height x width); "
                             "default 1024 / 512x512 / 48x128x128")
    parser.add_argument("--cells", default="8",
                        help="lattice cells across the field per axis, e.g. 8 or 2x8x8 (default: %(default)s)")
    parser.add_argument("--kernel", default=None,
                        help=f"smoothing kernel: {', '.join(kernel_names())} (default: cubic for --basis value, "
                             "quintic, Perlin's, for --basis gradient)")
    parser.add_argument("--basis", default="value", choices=("value", "gradient"), help="lattice basis (default: value)")
    parser.add_argument("--octaves", type=int, default=1, help="octaves of the sum (default: 1)")
    parser.add_argument("--sum", dest="kind", default="fractal", choices=("fractal", "turbulence"),
                        help="fractal sum (Eq. 9) or turbulence (Eq. 10) (default: fractal)")
    parser.add_argument("--lacunarity", type=float, default=2.0, help="frequency ratio between octaves (default: 2)")
    parser.add_argument("--gain", type=float, default=0.5, help="amplitude ratio between octaves (default: 0.5)")
    parser.add_argument("--seed", type=int, default=0, help="random seed (default: 0)")
    parser.add_argument("--table-size", type=int, default=None,
                        help="permutation table size (default: 256; with --tileable, larger when the finest "
                             "octave's period, cells x lacunarity**(octaves-1), needs it)")
    parser.add_argument("--alternation", default="table", choices=("table", "lattice"),
                        help="sign alternation of the value tables (default: table)")
    parser.add_argument("--tileable", action="store_true",
                        help="make the field tile exactly, with the tile as its only period (needs a whole "
                             "number of cells per axis and, with octaves, a whole-number lacunarity: octave o "
                             "repeats once per tile)")
    parser.add_argument("--range", dest="value_range", default="bound", choices=("bound", "data"),
                        help="grey mapping for images and videos: the guaranteed bound ([-1, 1] for one octave) "
                             "or the data's min..max (default: bound)")
    parser.add_argument("--dtype", default="float32", choices=("float32", "float64"),
                        help="precision of .npy and .zarr output (default: float32)")
    parser.add_argument("--fps", type=float, default=DEFAULT_FPS,
                        help="frames per second of an MP4/GIF video (default: %(default)g)")
    add_dask_arguments(parser, "with .zarr output: chunk shape, e.g. 64 or 32x64x64, or auto (default: auto)")
    parser.add_argument("--workers", type=int, default=-1,
                        help="threads: a count, or -1 for every core, -2 for all but one (default: -1); "
                             "the output is the same for any count")


def run(args) -> int:
    from ..fractal import fractal_sum, turbulence
    from ..io import write_image, write_video
    from ..lattice import Grid, LatticeNoise

    dims = args.dims
    shape = tuple(parse_axes("--size", args.size or _DEFAULT_SIZE[dims], dims, int))
    if any(s < 1 for s in shape):
        raise ValueError(f"--size entries must be >= 1, got {shape}")
    cells = parse_axes("--cells", args.cells, dims, float)
    if any(not np.isfinite(c) or c <= 0 for c in cells):
        raise ValueError(f"--cells entries must be positive, got {cells}")
    if args.octaves < 1:
        raise ValueError(f"--octaves must be >= 1, got {args.octaves}")
    path = Path(args.output)
    suffix = path.suffix.lower()
    allowed = {1: (".png", ".npy"), 2: (".png", ".npy"), 3: (".mp4", ".gif", ".npy")}[dims] + (".zarr",)
    if suffix not in allowed:
        raise ValueError(f"--output for a {dims}-D field must end in {' or '.join(allowed)}, got {path.name!r}")
    from ..io import prepare_output

    prepare_output(path, directory=suffix == ".zarr")   # fail now, not after computing the field
    period = None
    if args.tileable:
        if any(abs(c - round(c)) > 1e-9 for c in cells):
            raise ValueError(f"--tileable needs a whole number of --cells per axis, got {cells}")
        period = [int(round(c)) for c in cells]
    dtype = np.float32 if (suffix not in (".npy", ".zarr") or args.dtype == "float32") else np.float64
    table_size = 256 if args.table_size is None else args.table_size
    if period is not None and args.table_size is None:
        table_size = _tile_table_size(period, shape, cells, args.octaves, args.lacunarity, args.gain, dtype)
    noise = LatticeNoise(dims, rng=args.seed, kernel=args.kernel, basis=args.basis, table_size=table_size,
                         period=period, alternation=args.alternation)
    grid = Grid(shape, [(0.0, c) for c in cells])
    summer = turbulence if args.kind == "turbulence" else fractal_sum
    if suffix == ".zarr" or args.chunks is not None or args.scheduler is not None:
        from ..scale.commands import write_noise_zarr  # chunked on dask, streamed to zarr
        return write_noise_zarr(args, noise, grid, summer, dtype, path)
    from .._core import resolve_workers

    field, used = summer(noise, grid, args.octaves, lacunarity=args.lacunarity, gain=args.gain,
                         dtype=dtype, return_octaves=True, workers=resolve_workers(args.workers))
    bound = sum(args.gain ** o for o in range(used))
    lo, hi = (0.0 if args.kind == "turbulence" else -bound), bound
    if args.value_range == "data":
        lo, hi = float(field.min()), float(field.max())
        if hi <= lo:
            hi = lo + 1.0
    if suffix == ".npy":
        write_image(path, field) if dims < 3 else write_video(path, field)
    elif dims == 1:
        _plot_curve(path, field, cells[0], lo, hi)
    elif dims == 2:
        write_image(path, field, vmin=lo, vmax=hi)
    else:
        write_video(path, field, fps=args.fps, vmin=lo, vmax=hi)
    tiled = "" if period is None else (f" tileable: period {period} cells, octave o at period cells x "
                                       f"{args.lacunarity:g}**o, table_size {table_size}")
    print(f"noiselab noise: wrote {path} shape={field.shape} kernel={noise.kernel.name} basis={args.basis} "
          f"{args.kind} octaves used {used}/{args.octaves} range [{field.min():.4f}, {field.max():.4f}]{tiled}")
    return 0


def _tile_table_size(period, shape, cells, octaves, lacunarity, gain, dtype):
    """The table size a tileable sum needs: 256, or the finest visible octave's period (the table hash
    repeats every table_size cells, so a longer octave period needs as many entries)."""
    from ..fractal import octaves_used

    if lacunarity != int(lacunarity) or lacunarity < 2:
        return 256  # refused with the lacunarity's own message when the sum is made
    spacing = [c / n if n > 1 else np.nan for c, n in zip(cells, shape)]
    used = octaves_used(octaves, lacunarity=lacunarity, gain=gain, spacing=spacing, dtype=dtype)
    need = max(period) * int(lacunarity) ** (used - 1)
    return max(256, need + need % 2)


def _plot_curve(path, values, cells, lo, hi):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..io import atomic_output

    x = np.arange(values.shape[0]) * (cells / values.shape[0])
    fig, ax = plt.subplots(figsize=(8, 2.5), dpi=100)
    ax.plot(x, values, lw=1.0, color="black")
    ax.set_xlim(0, cells)
    ax.set_ylim(lo, hi)
    ax.set_xlabel("lattice units")
    fig.tight_layout()
    try:
        with atomic_output(path) as tmp:
            fig.savefig(tmp, format="png")
    finally:
        plt.close(fig)
