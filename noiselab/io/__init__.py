"""Reading and writing images, videos, arrays and meshes, always atomically.

A file noiselab writes appears complete or not at all: data goes to a
temporary file beside the target and is renamed into place only when the
writer finished without error. A file that cannot be read raises
``InputError`` (a ``ValueError``), one that cannot be written ``OutputError``
(an ``OSError``), each naming the file and the cause in one line.
"""
from .atomic import atomic_output, exchange_paths, prepare_output
from .errors import InputError, OutputError
from .media import (
    DEFAULT_FPS,
    IMAGE_SUFFIXES,
    VIDEO_SUFFIXES,
    iter_video,
    load_npy,
    read_image,
    read_video,
    to_uint8,
    write_image,
    write_video,
)
from .mesh import MESH_SUFFIXES, read_mesh, write_mesh
from .zarr import read_zarr, write_zarr  # zarr and dask are imported on use (the noiselab[dask] extra)

__all__ = [
    "atomic_output",
    "prepare_output",
    "exchange_paths",
    "InputError",
    "OutputError",
    "DEFAULT_FPS",
    "read_image",
    "read_video",
    "iter_video",
    "load_npy",
    "to_uint8",
    "write_image",
    "write_video",
    "VIDEO_SUFFIXES",
    "IMAGE_SUFFIXES",
    "MESH_SUFFIXES",
    "read_mesh",
    "write_mesh",
    "read_zarr",
    "write_zarr",
]
