"""``noiselab mesh``: displace a mesh (a file or a built-in shape) by lattice noise; write it and render it."""
from __future__ import annotations

from pathlib import Path

from ..io.media import DEFAULT_FPS

NAME = "mesh"
HELP = "displace a mesh or built-in shape along its normals by noise (Eq. 11); write PLY/OBJ/STL/GLB, render PNG/MP4/GIF"

SHAPES = ("sphere", "squashed", "plane", "ant", "airplane", "nut")


def add_arguments(parser):
    src = parser.add_argument_group("input")
    g = src.add_mutually_exclusive_group()
    g.add_argument("--input", "-i", metavar="FILE", help="mesh file to displace (PLY, OBJ, STL, GLB, OFF ...)")
    g.add_argument("--shape", choices=SHAPES, default=None,
                   help="built-in shape (default sphere): unit icosphere, sphere squashed by --squash "
                        "(figure 19), a flat 2 x 2 sheet (a Monge surface once displaced), or one of pyvista's "
                        "bundled models scaled to size 2")
    src.add_argument("--subdivisions", type=int, default=None,
                     help="icosphere level for sphere/squashed, or samples per side for plane "
                          "(default: the coarsest the noise needs)")
    src.add_argument("--squash", type=float, default=0.05, help="vertical squash of 'squashed' (default 0.05 = 5%%)")
    src.add_argument("--normalize", type=float, default=None, metavar="SIZE",
                     help="centre an input file's mesh and scale its largest extent to SIZE")
    f = parser.add_argument_group("field")
    f.add_argument("--field", choices=("noise", "fractal", "turbulence"), default="noise",
                   help="plain noise, fractal sum (Eq. 9) or turbulence (Eq. 10); default noise")
    f.add_argument("--octaves", type=int, default=None, help="octaves of the sum (default 1 for noise, 4 otherwise)")
    f.add_argument("--amplitude", "-a", type=float, default=0.1, help="displacement scale in mesh units (default 0.1)")
    f.add_argument("--frequency", "-f", type=float, default=2.0, help="noise cycles per mesh unit (default 2)")
    f.add_argument("--phase", type=float, default=0.0, help="offset added to the noise input (default 0)")
    f.add_argument("--lacunarity", type=float, default=2.0, help="frequency ratio between octaves (default 2)")
    f.add_argument("--gain", type=float, default=0.5, help="amplitude ratio between octaves (default 1/2)")
    f.add_argument("--seed", type=int, default=0, help="seed of the lattice noise's tables (default 0)")
    f.add_argument("--kernel", default="cubic",
                   help="lattice smoothing kernel: box, linear, quadratic, cubic (default), catmull-rom, quintic")
    f.add_argument("--basis", choices=("value", "gradient"), default="value",
                   help="Phillips' value noise (default) or Perlin's gradient noise")
    f.add_argument("--time", type=float, default=None, help="time coordinate: use 4-D noise (x, y, z, t)")
    f.add_argument("--direction", choices=("normal", "vector"), default="normal",
                   help="move vertices along their normals (Eq. 11, default) or by a 3-component noise vector")
    r = parser.add_argument_group("resolution")
    r.add_argument("--resolution", choices=("auto", "warn", "raise", "ignore"), default="auto",
                   help="mesh too coarse for the highest octave: refine to what it needs (auto, default), "
                        "warn, fail, or ignore")
    r.add_argument("--samples-per-period", type=float, default=4.0,
                   help="samples per period of the highest octave the mesh must have (default 4)")
    o = parser.add_argument_group("output")
    o.add_argument("--output", "-o", metavar="FILE", help="displaced mesh (.ply, .obj, .stl, .glb, .off)")
    o.add_argument("--render", metavar="FILE", help="render: image (.png/.jpg) or animation (.mp4/.gif)")
    o.add_argument("--animate", choices=("turntable", "boil"), default="turntable",
                   help="animation for a video --render: camera turntable or boiling shape (4-D noise over time)")
    o.add_argument("--frames", type=int, default=48, help="animation frames (default 48)")
    o.add_argument("--fps", type=float, default=DEFAULT_FPS,
                   help="frames per second of a video --render (default %(default)g)")
    o.add_argument("--duration", type=float, default=2.0, help="noise time spanned by a 'boil' animation (default 2)")
    o.add_argument("--size", type=int, default=512, help="rendered image size in pixels (square, default 512)")
    o.add_argument("--view", default="iso", help="camera view: iso, xy, xz, yz (default iso)")
    o.add_argument("--style", choices=("surface", "wireframe", "points"), default="surface",
                   help="shaded surface (default) or wire frame, as in the paper's figures")
    o.add_argument("--color-by", choices=("none", "displacement"), default="none",
                   help="colour the render by the displacement (viridis) instead of a flat colour")


def _lattice(dim, args):
    try:
        from ..lattice import LatticeNoise
    except ImportError as exc:  # pragma: no cover - the lattice package is part of noiselab
        raise ValueError(f"the lattice noise is not available: {exc}") from None
    dim_out = 3 if args.direction == "vector" else 1
    return LatticeNoise(dim, dim_out, rng=args.seed, kernel=args.kernel, basis=args.basis)


def _load(args):
    import numpy as np

    from .. import geometry as geo
    from ..io import read_mesh

    if args.input:
        mesh = read_mesh(args.input)
        return geo.normalize(mesh, args.normalize) if args.normalize is not None else mesh
    shape = args.shape or "sphere"
    if shape in ("sphere", "squashed"):
        if args.subdivisions is not None:
            base = geo.sphere(args.subdivisions)
        else:
            base = geo.sphere_for_noise(args._max_frequency, samples_per_period=args.samples_per_period)
        if shape == "squashed":
            from .._core import check_real

            squash = check_real("--squash", args.squash, lo=0.0, hi=1.0, hi_open=True)
            base.apply_scale([1.0, 1.0, 1.0 - squash])
        return base
    if shape == "plane":
        from .._core import check_int

        if args.subdivisions is not None:
            n = check_int("--subdivisions", args.subdivisions, lo=2, hi=20_000)
        else:   # longest edge, the cells' diagonal sqrt(2) * 2 / (n - 1), <= 1 / (samples_per_period * max_frequency)
            n = max(2, int(np.ceil(2.0 * np.sqrt(2.0) * args.samples_per_period * args._max_frequency)) + 1)
            if n > 4096:
                raise ValueError(f"a plane fine enough for {args._max_frequency:g} cycles/unit needs {n} x {n} "
                                 "vertices; lower the frequency or octaves, or give --subdivisions")
        return geo.plane(n)
    return geo.load_model(shape)


def run(args) -> int:
    import numpy as np

    from .. import geometry as geo
    from .._core import check_int, check_real
    from ..io import MESH_SUFFIXES, write_mesh

    if not args.output and not args.render:
        raise ValueError("nothing to do: give --output FILE (mesh) and/or --render FILE (image or video)")
    if args.output and Path(args.output).suffix.lower() not in MESH_SUFFIXES:
        raise ValueError(f"--output must end in one of {', '.join(MESH_SUFFIXES)}, got {args.output!r}")
    video = args.render and Path(args.render).suffix.lower() in (".mp4", ".gif")
    if args.render and not video and Path(args.render).suffix.lower() not in (".png", ".jpg", ".jpeg", ".tif", ".tiff"):
        raise ValueError(f"--render must end in .png, .jpg, .tif (image) or .mp4, .gif (animation), got {args.render!r}")
    boil = bool(video and args.animate == "boil")
    from ..io import prepare_output

    for out in (args.output, args.render):   # fail now, not after displacing and rendering
        if out:
            prepare_output(out)
    octaves = check_int("--octaves", args.octaves if args.octaves is not None else (1 if args.field == "noise" else 4),
                        lo=1, hi=64)
    if args.field == "noise" and octaves != 1:
        raise ValueError(f"--field noise is a single octave; use --field fractal for --octaves {octaves}")
    frequency = check_real("--frequency", args.frequency, lo=0.0)
    lacunarity = check_real("--lacunarity", args.lacunarity, lo=1.0, lo_open=True)
    frames = check_int("--frames", args.frames, lo=1, hi=100_000)
    duration = check_real("--duration", args.duration)
    args._max_frequency = frequency * lacunarity ** (octaves - 1)

    mesh = _load(args)
    on_alias = "warn" if args.resolution == "auto" else args.resolution
    if args.resolution == "auto":
        report = geo.resolution_report(mesh, args._max_frequency, samples_per_period=args.samples_per_period)
        if not report.ok:
            print(f"noiselab mesh: {report.message()}; subdividing")
            mesh = geo.subdivide_for_noise(mesh, args._max_frequency, samples_per_period=args.samples_per_period)
    use_time = boil or args.time is not None
    field = _lattice(4 if use_time else 3, args)
    kind = "fractal" if args.field == "noise" else args.field
    common = dict(amplitude=args.amplitude, frequency=frequency, phase=args.phase, octaves=octaves, kind=kind,
                  lacunarity=lacunarity, gain=args.gain, samples_per_period=args.samples_per_period,
                  on_alias=on_alias, direction=args.direction)
    t0 = 0.0 if args.time is None else args.time
    displaced = geo.displace(mesh, field, time=t0 if use_time else None, **common)
    s = displaced.vertex_attributes["displacement"]
    print(f"noiselab mesh: {len(displaced.vertices):,} vertices, {len(displaced.faces):,} faces; "
          f"displacement in [{s.min():.4g}, {s.max():.4g}] (mean |s| {np.abs(s).mean():.4g}); "
          f"watertight: {displaced.is_watertight}")
    if args.output:
        write_mesh(args.output, displaced)
        print(f"noiselab mesh: wrote {args.output}")
    if args.render:
        scalars = "displacement" if args.color_by == "displacement" else None
        clim = (-abs(args.amplitude), abs(args.amplitude)) if scalars else None
        size = check_int("--size", args.size, lo=16, hi=8192)
        if not video:
            geo.render_mesh(displaced, args.render, size=size, view=args.view, scalars=scalars, clim=clim,
                            style=args.style)
        elif boil:
            times = t0 + np.arange(frames) * (duration / frames)
            seq = geo.displace_frames(mesh, field, times, **common)
            geo.render_sequence(seq, args.render, fps=args.fps, size=size, view=args.view, scalars=scalars, clim=clim)
        else:
            geo.render_turntable(displaced, args.render, frames=frames, fps=args.fps, size=size, view=args.view,
                                 scalars=scalars, clim=clim, style=args.style)
        print(f"noiselab mesh: wrote {args.render}")
    return 0
