"""Displacement of meshes along their normals (Phillips 2004, Eq. 11), and the resolution it needs.

``p' = p + amplitude * s(frequency * p + phase) * n_p``: every vertex moves
along its (area-weighted) vertex normal by a scale ``s`` taken from a field of
its position (and, optionally, of time: a 4-D input gives a boiling or
undulating shape).

A mesh samples the field only at its vertices, so a mesh whose edges are long
compared with the field's finest period aliases: the displacement between
vertices is made up by the triangles, not by the noise. :func:`resolution_report`
measures samples per period (counting the highest octave), and
:func:`subdivide_for_noise` refines a mesh to what the field needs, no further.
"""
from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np

from .._core import REMOVED_IN, check_finite_array, check_int, check_memory, check_real, check_real_vector, renamed_parameters
from ._kernels import face_pass, unit_rows
from ._mesh import AliasingWarning, as_trimesh  # noqa: F401  (defined in the leaf module _mesh; re-exported here)
from .fields import evaluate_field, field_max_frequency, octave_field

__all__ = [
    "AliasingWarning",
    "ResolutionReport",
    "displace",
    "displace_frames",
    "vertex_normals",
    "resolution_report",
    "subdivide_for_noise",
    "as_trimesh",
]


def _face_geometry(vertices, faces):
    """Per-face corner differences and cross products, shared by the normals, volume and edge lengths."""
    a, b, c = vertices[faces[:, 0]], vertices[faces[:, 1]], vertices[faces[:, 2]]
    ab, bc, ca = b - a, c - b, a - c
    return a, ab, bc, ca, np.cross(ab, -ca)


def _area_weighted_normals(cross, faces, n):
    idx = faces.ravel()
    normals = np.empty((n, 3))
    for axis in range(3):
        normals[:, axis] = np.bincount(idx, weights=np.repeat(cross[:, axis], 3), minlength=n)
    length = np.sqrt(np.einsum("ij,ij->i", normals, normals))
    tiny = length <= 1e-300
    length[tiny] = 1.0
    normals /= length[:, None]
    normals[tiny] = 0.0
    return normals


def _edge_lengths(ab, bc, ca):
    """Lengths of every face's three edges (an interior edge appears once per face: twice)."""
    return np.sqrt(np.concatenate([np.einsum("ij,ij->i", e, e) for e in (ab, bc, ca)]))


def _closed_and_consistent(faces, n):
    """True when every directed edge a->b has its reverse b->a: a closed surface wound consistently.

    Exactly the condition under which the signed volume tells inside from
    outside. One sort of 3F int64 keys (trimesh's ``is_watertight`` hashes
    rows instead and is several times slower on large meshes).
    """
    src = faces.ravel()
    dst = np.roll(faces, -1, axis=1).ravel()
    n = np.int64(n)
    forward = np.sort(src * n + dst)
    backward = np.sort(dst * n + src)
    return bool(np.array_equal(forward, backward))


def _weld_groups(vertices):
    """Group vertices that sit at exactly the same position: ``(group of each vertex, count)`` or None.

    Meshes split vertices at UV or crease seams (OBJ, glTF) and STL stores a
    triangle soup: copies of one point that must move together, or the
    displaced surface cracks open along the seam. One argsort of a scalar key
    (not a sort of rows) finds them.
    """
    if len(vertices) < 2:
        return None
    key = vertices @ np.array([1.0, 0.7548776662466927, 0.5698402909980532])
    order = np.argsort(key)
    sorted_key = key[order]
    # equal positions have equal keys: compare rows only where neighbouring keys tie (the common
    # case, a mesh without copies, stops here)
    tie = np.flatnonzero(sorted_key[1:] == sorted_key[:-1])
    if tie.size == 0:
        return None
    same = np.zeros(len(vertices) - 1, dtype=bool)
    same[tie] = np.all(vertices[order[tie + 1]] == vertices[order[tie]], axis=1)
    if not same.any():
        return None
    sorted_groups = np.concatenate([[0], np.cumsum(~same)])
    groups = np.empty(len(vertices), dtype=np.int64)
    groups[order] = sorted_groups
    return groups, int(sorted_groups[-1]) + 1


def _normals(vertices, faces, stride, weld):
    """Unit area-weighted normals (welded across coincident vertices), signed volume, longest edge,
    sampled edge lengths, and the faces re-indexed by weld group (for the closed-surface test)."""
    sums, volume, longest, lengths = face_pass(vertices, faces, stride)
    welded_faces = faces
    if weld:
        found = _weld_groups(vertices)
        if found is not None:
            groups, count = found
            total = np.empty((count, 3))
            for axis in range(3):
                total[:, axis] = np.bincount(groups, weights=sums[:, axis], minlength=count)
            sums = total[groups]
            welded_faces = groups[faces]
    return unit_rows(sums), volume, longest, lengths, welded_faces


def vertex_normals(mesh, *, weld=False) -> np.ndarray:
    """Area-weighted unit vertex normals, float64 ``(n_vertices, 3)``.

    Each face adds its cross product ``(b - a) x (c - a)`` (twice its area
    times its unit normal) to its three vertices; the sums are normalised.
    Zero-area faces add nothing. A vertex that no face references, or whose
    faces cancel (zero sum), gets a zero normal and therefore no displacement.
    ``weld=True`` gives vertices at exactly the same position (copies split
    at a seam) their common normal.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    weld : bool, default False
        Give coincident vertices their common normal.

    Returns
    -------
    ndarray (n_vertices, 3) of float64
        Unit normals (zero where undefined).

    Examples
    --------
    >>> import trimesh
    >>> n = vertex_normals(trimesh.creation.box())
    >>> bool(abs(n[0] @ n[0] - 1) < 1e-12)
    True
    """
    mesh = as_trimesh(mesh)
    v, f = _arrays(mesh)
    return _normals(v, f, 0, weld)[0]


def _arrays(mesh):
    v = np.ascontiguousarray(mesh.vertices, dtype=np.float64)
    f = np.ascontiguousarray(mesh.faces, dtype=np.int64)
    if f.size and (f.min() < 0 or f.max() >= len(v)):
        raise ValueError(f"mesh faces index vertices outside [0, {len(v) - 1}]")
    return v, f


@dataclasses.dataclass(frozen=True)
class ResolutionReport:
    """How finely a mesh samples a field of a given highest frequency.

    ``samples_per_period`` is the period of the highest frequency divided by
    the longest edge (the worst place on the mesh); ``median_samples_per_period``
    uses the median edge (over the faces' edges, so shared edges count twice;
    on meshes of more than 2**18 faces, over the edges of evenly strided faces). ``target_edge`` is the longest edge that gives
    ``required`` samples per period, and ``subdivisions`` the number of
    midpoint subdivisions (each halves every edge) that reach it.
    """

    max_frequency: float
    max_edge: float
    median_edge: float
    samples_per_period: float
    median_samples_per_period: float
    required: float
    target_edge: float
    subdivisions: int
    ok: bool

    def message(self) -> str:
        if self.ok:
            return (f"mesh resolution ok: {self.samples_per_period:.1f} samples per period at the "
                    f"highest frequency {self.max_frequency:g} cycles/unit (>= {self.required:g} needed)")
        return (f"mesh too coarse for the field: its longest edge {self.max_edge:.4g} gives "
                f"{self.samples_per_period:.2f} samples per period at the highest frequency "
                f"{self.max_frequency:g} cycles/unit ({self.median_samples_per_period:.2f} at the median edge); "
                f">= {self.required:g} are needed, i.e. edges <= {self.target_edge:.4g}. "
                f"subdivide_for_noise(...) refines it, splitting only the edges longer than that "
                f"(or {self.subdivisions} uniform midpoint subdivision(s), {4 ** self.subdivisions}x the faces)")


def _highest_frequency(field, frequency, octaves, lacunarity):
    freq = np.max(np.abs(np.atleast_1d(np.asarray(frequency, dtype=float))))
    return float(freq * field_max_frequency(field) * lacunarity ** (octaves - 1))


def resolution_report(mesh, max_frequency, *, samples_per_period=4.0) -> ResolutionReport:
    """Measure whether ``mesh`` samples a field of highest frequency ``max_frequency`` without aliasing.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    max_frequency : float in (0, 1e300]
        Highest frequency of the displacement, in cycles per unit of the
        mesh's coordinates: ``frequency * lacunarity**(octaves - 1)`` for an
        octave sum of a unit-frequency lattice noise.
    samples_per_period : float
        Samples per period required (default 4: a period drawn by four edges).

    Returns
    -------
    ResolutionReport
        Every field finite.

    Examples
    --------
    >>> import trimesh
    >>> r = resolution_report(trimesh.creation.icosphere(2), 4.0)
    >>> r.ok, r.subdivisions
    (False, 3)
    """
    mesh = as_trimesh(mesh)
    # > 0: a field of frequency 0 is constant, any mesh samples it (its samples per period would be inf)
    max_frequency = check_real("max_frequency (cycles/unit)", max_frequency, lo=1e-300, hi=1e300)
    required = check_real("samples_per_period", samples_per_period, lo=1.0, hi=1e6)
    v, f = _arrays(mesh)
    return _report(*face_pass(v, f, _stride(len(f)))[2:], max_frequency, required)


# The median edge is taken over the edges of every k-th face, at most about 2**18 faces (exact below that):
# it is informative only, and sorting millions of edges would cost more than the whole face pass.
_MEDIAN_FACES = 1 << 18


def _stride(n_faces):
    return max(1, -(-n_faces // _MEDIAN_FACES))


def _report(max_edge, lengths, max_frequency, required):
    if not math.isfinite(max_edge):
        # a squared edge length past 1.8e308: coordinates beyond about 1e154 apart
        raise ValueError("mesh edge lengths overflow float64 (its vertex coordinates are too large: an edge "
                         "longer than about 1e154 has a squared length past 1.8e308); scale the mesh so that its "
                         "coordinates stay within +-1e150")
    lengths = lengths[lengths > 0]
    if max_edge <= 0 or lengths.size == 0:
        raise ValueError("mesh has only zero-length edges; its resolution is undefined")
    max_edge = float(max_edge)
    median_edge = float(np.median(lengths))
    if max_frequency == 0:
        return ResolutionReport(0.0, max_edge, median_edge, math.inf, math.inf, required, math.inf, 0, True)
    period = 1.0 / max_frequency
    spp = period / max_edge
    target = period / required
    # logs apart: max_edge / target overflows for frequencies near float64's limit
    subdivisions = max(0, math.ceil(math.log2(max_edge) - math.log2(target) - 1e-12))
    return ResolutionReport(max_frequency, max_edge, median_edge, spp, period / median_edge,
                            required, target, subdivisions, spp >= required)


def _split_long_edges(vertices, faces, target, max_passes=40):
    """Conforming adaptive refinement: split every edge longer than ``target`` at its midpoint until none is.

    A split edge is shared by both its faces, so there are no T-junctions: a
    face with 1, 2 or 3 split edges becomes 2, 3 or 4 triangles (same
    winding). Edges already short enough are never split, so a mesh with a few
    long edges is refined only where it needs it.
    """
    import trimesh

    v = np.asarray(vertices, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64)
    for _ in range(max_passes):
        edges = np.sort(np.stack([f, np.roll(f, -1, axis=1)], axis=2).reshape(-1, 2), axis=1)
        unique, inverse = np.unique(edges, axis=0, return_inverse=True)
        inverse = inverse.reshape(-1, 3)          # face k's edge j joins f[k, j] and f[k, (j + 1) % 3]
        length = np.linalg.norm(v[unique[:, 0]] - v[unique[:, 1]], axis=1)
        long_edge = length > target
        if not long_edge.any():
            break
        mid_index = np.full(len(unique), -1, dtype=np.int64)
        mid_index[long_edge] = len(v) + np.arange(int(long_edge.sum()))
        v = np.concatenate([v, 0.5 * (v[unique[long_edge, 0]] + v[unique[long_edge, 1]])])
        split = long_edge[inverse]
        count = split.sum(axis=1)
        # roll each face so that its pattern is canonical: one split -> edge 0; two -> edges 0 and 1
        roll = np.zeros(len(f), dtype=np.int64)
        one, two = count == 1, count == 2
        roll[one] = np.argmax(split[one], axis=1)
        roll[two] = (np.argmin(split[two], axis=1) + 1) % 3
        cols = (np.arange(3)[None, :] + roll[:, None]) % 3
        rows = np.arange(len(f))[:, None]
        fr = f[rows, cols]
        mids = mid_index[inverse[rows, cols]]
        a, b, c = fr[:, 0], fr[:, 1], fr[:, 2]
        mab, mbc, mca = mids[:, 0], mids[:, 1], mids[:, 2]
        out = [f[count == 0]]
        k = one
        out += [np.stack([a[k], mab[k], c[k]], 1), np.stack([mab[k], b[k], c[k]], 1)]
        k = two
        out += [np.stack([mab[k], b[k], mbc[k]], 1), np.stack([a[k], mab[k], c[k]], 1),
                np.stack([mab[k], mbc[k], c[k]], 1)]
        k = count == 3
        out += [np.stack([a[k], mab[k], mca[k]], 1), np.stack([mab[k], b[k], mbc[k]], 1),
                np.stack([mca[k], mbc[k], c[k]], 1), np.stack([mab[k], mbc[k], mca[k]], 1)]
        f = np.concatenate(out)
    return trimesh.Trimesh(v, f, process=False, validate=False)


def subdivide_for_noise(mesh, max_frequency, *, samples_per_period=4.0, method="adaptive", max_faces=50_000_000):
    """Subdivide ``mesh`` to the resolution a field of highest frequency ``max_frequency`` needs, no further.

    The target is a longest edge of ``1 / (samples_per_period * max_frequency)``.
    ``method="adaptive"`` (default) splits only the edges longer than that, at
    their midpoints, pass after pass, and re-triangulates each face around its
    split edges (conforming: no T-junctions, watertightness kept, the surface
    unchanged): a mesh whose edges are mostly fine is refined only where it is
    coarse. ``method="midpoint"`` splits every triangle into four, the fewest
    times that reach the target (regular triangles, but uniform: 4x the faces
    per level everywhere). ``method="loop"`` uses Loop subdivision the same
    number of times (smooths, so it changes the shape of a coarse mesh).
    A mesh that already has the resolution is returned as a copy. The face
    count is checked against ``max_faces`` and memory before subdividing.
    The refined mesh carries geometry only (colours and texture coordinates
    are not interpolated onto the new vertices).

    Parameters
    ----------
    mesh : trimesh.Trimesh
    max_frequency : float
        The field's highest frequency in cycles per unit.
    samples_per_period : float, default 4
        Samples wanted per period of ``max_frequency``.
    method : {"adaptive", "midpoint", "loop"}, default "adaptive"
    max_faces : int, default 50_000_000
        The most faces the result may have.

    Returns
    -------
    trimesh.Trimesh
        A new mesh (a copy when nothing needed splitting).

    Raises
    ------
    ValueError
        For an unknown method, or a result past ``max_faces``.
    MemoryError
        When the refined mesh would not fit.

    Examples
    --------
    >>> import trimesh
    >>> fine = subdivide_for_noise(trimesh.creation.icosphere(1), 2.0)
    >>> resolution_report(fine, 2.0).ok, fine.is_watertight
    (True, True)
    """
    import trimesh

    mesh = as_trimesh(mesh)
    if method not in ("midpoint", "loop", "adaptive"):
        raise ValueError(f"method must be 'adaptive', 'midpoint' or 'loop', got {method!r}")
    max_faces = check_int("max_faces", max_faces, lo=1)
    if check_real("max_frequency (cycles/unit)", max_frequency, lo=0.0, hi=1e300) == 0:
        check_real("samples_per_period", samples_per_period, lo=1.0, hi=1e6)
        return mesh.copy()  # a constant field: any mesh samples it
    report = resolution_report(mesh, max_frequency, samples_per_period=samples_per_period)
    if report.ok:
        return mesh.copy()
    faces = len(mesh.faces) * 4 ** report.subdivisions
    if method == "adaptive":
        # estimate from the edges that must be split: an edge of length L ends as ~L/target pieces
        lengths = np.asarray(mesh.edges_unique_length)
        with np.errstate(over="ignore"):
            pieces = np.maximum(1.0, 2.0 ** np.ceil(np.log2(np.maximum(lengths / report.target_edge, 1.0))))
            ratio = min(float(np.mean(pieces ** 2)) * 1.5, 4.0 ** min(report.subdivisions, 500))
        faces = int(len(mesh.faces) * ratio) if math.isfinite(ratio) else faces
    if faces > max_faces:
        # past 1e15 the count is a power of ten (the uniform estimate 4**subdivisions can have thousands of digits)
        count = f"{faces:,}" if faces < 10 ** 15 else f"10^{int((faces.bit_length() - 1) * math.log10(2))}"
        raise ValueError(
            f"reaching {report.required:g} samples per period at {report.max_frequency:g} cycles/unit needs "
            f"about {count} faces (longest edge {report.max_edge:.3g}), more than max_faces={max_faces:,}; "
            "lower the frequency or the octaves, or raise max_faces"
        )
    check_memory(faces * 3 * 8 * 6, "subdividing the mesh")
    v = np.asarray(mesh.vertices, dtype=np.float64)
    f = np.asarray(mesh.faces, dtype=np.int64)
    if method == "adaptive":
        return _split_long_edges(v, f, report.target_edge)
    if method == "loop":
        v, f = trimesh.remesh.subdivide_loop(v, f, iterations=report.subdivisions)
    else:
        for _ in range(report.subdivisions):
            v, f = trimesh.remesh.subdivide(v, f)
    return trimesh.Trimesh(v, f, process=False)


def _check_resolution(max_edge, lengths, field, frequency, octaves, lacunarity, samples_per_period, on_alias):
    if on_alias == "ignore":
        return None
    report = _report(max_edge, lengths, _highest_frequency(field, frequency, octaves, lacunarity),
                     check_real("samples_per_period", samples_per_period, lo=1.0, hi=1e6))
    if not report.ok:
        if on_alias == "raise":
            raise ValueError(report.message())
        warnings.warn(report.message(), AliasingWarning, stacklevel=3)
    return report


def _as_vector(name, value, size):
    return check_real_vector(name, value, size)


def _outward(normals, volume, faces):
    # Outward whatever the winding: a closed, consistently wound mesh that is
    # inside out has a negative signed volume (only then is the sign defined).
    if volume < 0 and _closed_and_consistent(faces, int(faces.max()) + 1):
        return -normals
    return normals


@renamed_parameters(on_aliasing="on_alias")
def displace(mesh, field, amplitude=1.0, frequency=1.0, phase=0.0, time=None, *, octaves=1, kind="fractal",
             lacunarity=2.0, gain=0.5, normals=None, weld=True, direction="normal", samples_per_period=4.0,
             on_alias="warn", chunk_size=1 << 20):
    """Displace every vertex of ``mesh`` along its normal by a field of its position (Eq. 11).

    ``p' = p + amplitude * s(frequency * p + phase [, time]) * n_p`` where
    ``s`` is ``field`` or, with ``octaves > 1`` or ``kind="turbulence"``, its
    fractal sum (Eq. 9) or turbulence (Eq. 10). Returns a new mesh; the input
    is never modified.

    Parameters
    ----------
    mesh : trimesh.Trimesh or pyvista.PolyData
        Any triangle mesh: watertight or not, with zero-area faces or
        unreferenced vertices (those get a zero normal and stay put). A mesh
        without faces (a point cloud) is an error.
    field : callable
        Points ``(n, 3)`` (``(n, 4)`` when ``time`` is given) -> values ``(n,)``:
        a ``noiselab.LatticeNoise(3)``, a fractal sum, a :func:`sampled_field`...
    amplitude : float
        Scale of the displacement, in the mesh's units.
    frequency : float or (3,) array
        Multiplies the position before the field sees it (per axis if a vector).
    phase : float or (3,) array
        Added after the frequency: moves the noise without changing it.
    time : float, optional
        A 4th input coordinate: step it for a boiling or undulating shape.
    octaves, kind, lacunarity, gain
        Octave sum applied to ``field`` (see :func:`octave_field`).
    normals : (n, 3) array, optional
        Displacement directions; default :func:`vertex_normals` (area-weighted),
        flipped to point outwards for a closed, consistently wound mesh of
        negative signed volume (an inside-out mesh).
    direction : {"normal", "vector"}
        ``"normal"`` (default) is Eq. 11. ``"vector"`` moves each vertex by
        ``amplitude`` times a 3-component field instead (``LatticeNoise(3, 3)``):
        displacement that is not restricted to the normal, as the paper
        allows ("typically (but not necessarily) along the normal").
    weld : bool
        Give vertices at exactly the same position (split at UV or crease
        seams, or an unmerged STL soup) one common normal, so that the
        displaced surface does not crack open along seams (default True).
    samples_per_period, on_alias
        Resolution check: "warn" (:class:`AliasingWarning`), "raise" or
        "ignore" when the longest edge gives fewer than ``samples_per_period``
        samples per period of the highest octave.

    Returns
    -------
    trimesh.Trimesh
        The displaced mesh (same faces, process=False). Its
        ``vertex_attributes["displacement"]`` holds the signed distance each
        vertex moved (``amplitude * s``; for ``direction="vector"``, the
        displacement's component along the normal).

    Raises
    ------
    ValueError
        For a mesh without faces, a field that does not take 3-D points, a
        non-finite amplitude, frequency or phase, or (``on_alias="raise"``)
        a mesh too coarse for the field's highest frequency.

    Examples
    --------
    >>> import numpy as np, trimesh
    >>> sphere = trimesh.creation.icosphere(3)
    >>> bumpy = displace(sphere, lambda p: np.sin(p[:, 0]), amplitude=0.1)
    >>> r = np.linalg.norm(bumpy.vertices, axis=1)
    >>> bool(0.9 <= r.min() and r.max() <= 1.1)
    True
    """
    import trimesh

    mesh = as_trimesh(mesh)
    amplitude = check_real("amplitude", amplitude)
    freq = _as_vector("frequency", frequency, 3)
    if np.any(freq < 0):
        raise ValueError(f"frequency must be >= 0 (on every axis), got {freq.tolist()}")
    phase_v = _as_vector("phase", phase, 3)
    if time is not None:
        time = check_real("time", time)
    if on_alias not in ("warn", "raise", "ignore"):
        raise ValueError(f"on_alias must be 'warn', 'raise' or 'ignore', got {on_alias!r}")
    if direction not in ("normal", "vector"):
        raise ValueError(f"direction must be 'normal' (Eq. 11) or 'vector' (3-component field), got {direction!r}")
    source = octave_field(field, octaves, kind, lacunarity=lacunarity, gain=gain)
    vertices, faces = _arrays(mesh)
    # peak: normals, points, field output and new vertices (n x 3 float64 each), 3 edge lengths per face
    check_memory(len(vertices) * 8 * 3 * 5 + len(faces) * 8 * 4, "displacing the mesh")
    unit, volume, max_edge, lengths, welded = _normals(
        vertices, faces, 0 if on_alias == "ignore" else _stride(len(faces)), weld and normals is None)
    if normals is None:
        n = _outward(unit, volume, welded)
    else:
        n = check_finite_array("normals", normals).astype(np.float64)
        if n.shape != vertices.shape:
            raise ValueError(f"normals must have shape {vertices.shape}, got {n.shape}")
    if on_alias != "ignore":
        _check_resolution(max_edge, lengths, field, freq, octaves if kind != "noise" else 1,
                          check_real("lacunarity", lacunarity), samples_per_period, on_alias)
    del lengths
    points = vertices * freq + phase_v
    if time is not None:
        points = np.concatenate([points, np.full((len(points), 1), time)], axis=1)
    if direction == "vector":
        vec = amplitude * evaluate_field(source, points, components=3, chunk_size=chunk_size)
        new_vertices = vertices + vec
        s = np.einsum("ij,ij->i", vec, n)          # the normal component, for colouring
    else:
        s = evaluate_field(source, points, components=1, chunk_size=chunk_size)
        s *= amplitude
        new_vertices = vertices + s[:, None] * n
    out = trimesh.Trimesh(new_vertices, faces.copy(), process=False, validate=False)
    if mesh.visual.defined:
        # vertices and faces keep their order, so colours and texture coordinates still fit
        out.visual = mesh.visual.copy()
    out.vertex_attributes["displacement"] = s
    return out


def displace_frames(mesh, field, times, amplitude=1.0, frequency=1.0, phase=0.0, **kwargs):
    """Yield :func:`displace` of ``mesh`` at each time in ``times``: a boiling or undulating shape.

    ``field`` takes 4-D points (x, y, z, t). The normals and the resolution
    check are computed once. Extra keyword arguments go to :func:`displace`.

    Parameters
    ----------
    mesh : trimesh.Trimesh
    field : callable
        Takes 4-D points ``(x, y, z, t)``.
    times : sequence of float
    amplitude, frequency, phase
        As for :func:`displace`.
    **kwargs
        Further arguments of :func:`displace`.

    Yields
    ------
    trimesh.Trimesh
        The displaced mesh at each time.

    Examples
    --------
    >>> import numpy as np, trimesh
    >>> f = lambda p: np.sin(p[:, 0] + p[:, 3])
    >>> frames = list(displace_frames(trimesh.creation.icosphere(3), f, [0.0, 1.0], amplitude=0.1))
    >>> len(frames)
    2
    """
    mesh = as_trimesh(mesh)
    times = np.atleast_1d(check_finite_array("times", times).astype(np.float64))
    if times.ndim != 1:
        raise ValueError(f"times must be a 1-D sequence, got shape {times.shape}")
    normals = kwargs.pop("normals", None)
    if normals is None:
        v, f = _arrays(mesh)
        unit, volume, _, _, welded = _normals(v, f, 0, kwargs.get("weld", True))
        normals = _outward(unit, volume, welded)
    if "on_aliasing" in kwargs:   # the old spelling, refused like displace's own
        raise TypeError(f"displace_frames(): on_aliasing= was removed in noiselab {REMOVED_IN}; pass on_alias= instead")
    on_alias = kwargs.pop("on_alias", "warn")
    for i, t in enumerate(times):
        yield displace(mesh, field, amplitude, frequency, phase, float(t), normals=normals,
                       on_alias=on_alias if i == 0 else "ignore", **kwargs)
