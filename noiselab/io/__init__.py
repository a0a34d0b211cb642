"""Reading and writing images, videos, arrays and meshes, always atomically.

A file noiselab writes appears complete or not at all: data goes to a
temporary file beside the target and is renamed into place only when the
writer finished without error.
"""
from .atomic import atomic_output
from .media import (
    read_image,
    read_video,
    to_uint8,
    write_image,
    write_video,
    VIDEO_SUFFIXES,
    IMAGE_SUFFIXES,
)
from .mesh import MESH_SUFFIXES, read_mesh, write_mesh
from .zarr import read_zarr, write_zarr  # zarr and dask are imported on use (the noiselab[dask] extra)

__all__ = [
    "atomic_output",
    "read_image",
    "read_video",
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
