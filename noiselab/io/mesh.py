"""Mesh files through trimesh: PLY, OBJ, STL, GLB (and OFF), written atomically."""
from __future__ import annotations

from pathlib import Path

from .atomic import atomic_output, prepare_output
from .errors import InputError, cause, input_error

MESH_SUFFIXES = (".ply", ".obj", ".stl", ".glb", ".off")


def _suffix(path):
    suffix = Path(path).suffix.lower()
    if suffix not in MESH_SUFFIXES:
        raise ValueError(f"mesh path must end in one of {', '.join(MESH_SUFFIXES)}, got {Path(path).name!r}")
    return suffix


def write_mesh(path, mesh, *, make_parents=True) -> Path:
    """Write a ``trimesh.Trimesh`` to PLY (binary), OBJ, STL (binary), GLB or OFF; the file appears only when complete.

    Vertex colours are kept by PLY, OBJ and GLB (STL and OFF have none). PLY
    also keeps per-vertex attributes such as ``displacement``.
    ``make_parents`` creates missing parent folders.

    Parameters
    ----------
    path : str or Path
        Its suffix picks the format: ``.ply``, ``.obj``, ``.stl``, ``.glb`` or ``.off``.
    mesh : trimesh.Trimesh
    make_parents : bool, default True
        Create missing parent folders.

    Returns
    -------
    Path
        The written file.

    Raises
    ------
    ValueError
        For an unknown suffix or a mesh without faces.
    noiselab.io.OutputError
        When the file cannot be written (an ``OSError``).

    Examples
    --------
    >>> import trimesh, tempfile, os
    >>> p = write_mesh(os.path.join(tempfile.mkdtemp(), "a", "box.ply"), trimesh.creation.box())
    >>> len(read_mesh(p).faces)
    12
    """
    import trimesh

    path = Path(path)
    suffix = _suffix(path)
    if not isinstance(mesh, trimesh.Trimesh):
        raise TypeError(f"mesh must be a trimesh.Trimesh, got {type(mesh).__name__}")
    if len(mesh.faces) == 0:
        raise ValueError("mesh has no faces: nothing to write as a surface mesh")
    prepare_output(path, make_parents=make_parents, probe=False)
    kwargs = {"include_attributes": True} if suffix == ".ply" else {}
    data = mesh.export(file_type=suffix[1:], **kwargs)
    if isinstance(data, str):
        data = data.encode("utf-8")
    with atomic_output(path) as tmp:
        Path(tmp).write_bytes(data)
    return path


def read_mesh(path):
    """Read a mesh file (any format trimesh reads) as one ``trimesh.Trimesh`` (a scene's meshes are joined).

    A file holding no faces (a point cloud) is a ``ValueError``.

    Parameters
    ----------
    path : str or Path
        PLY, OBJ, STL, GLB, OFF or any format trimesh reads.

    Returns
    -------
    trimesh.Trimesh

    Raises
    ------
    FileNotFoundError
        For a missing file.
    noiselab.io.InputError
        For a file that cannot be decoded or holds no faces (a ``ValueError``).

    Examples
    --------
    >>> import trimesh, tempfile, os
    >>> p = write_mesh(os.path.join(tempfile.mkdtemp(), "box.stl"), trimesh.creation.box())
    >>> len(read_mesh(p).vertices)          # STL's triangle soup is merged again
    8
    """
    import trimesh

    from .media import _check_readable

    path = Path(path)
    _check_readable(path, "mesh file")
    try:
        loaded = trimesh.load(path, force="mesh", process=False)
    except MemoryError:
        raise
    except Exception as exc:   # trimesh's loaders raise many kinds on a file they cannot parse
        if isinstance(exc, OSError):
            raise input_error(path, exc) from None
        raise InputError(path, f"not a mesh trimesh can read: {cause(exc)}") from None
    if not isinstance(loaded, trimesh.Trimesh) or len(loaded.faces) == 0:
        raise InputError(path, "it holds no triangle faces (a point cloud?): a surface mesh is needed")
    if path.suffix.lower() == ".stl":
        # STL stores a triangle soup: join the corners it repeats so the mesh is connected again
        loaded.merge_vertices()
    return loaded
