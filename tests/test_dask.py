"""Chunked lattice noise on dask and zarr output, on a real distributed cluster with worker processes.

One ``LocalCluster`` (2 worker processes, 1 thread each) serves the whole
module; tests that need dask's local threads say ``scheduler="threads"``.
"""
import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import noiselab
from noiselab.fractal import fractal_sum, turbulence
from noiselab.io import read_zarr, write_zarr
from noiselab.lattice import Grid, LatticeNoise
from noiselab.scale import compute

import dask.array as da  # the test extras install noiselab[dask]
import distributed


@pytest.fixture(scope="module")
def client():
    import cloudpickle

    # the workers cannot import this test module: ship its helper functions by value
    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  memory_limit="1GiB") as cluster, distributed.Client(cluster) as c:
        yield c
    cloudpickle.unregister_pickle_by_value(sys.modules[__name__])


# (noise, shape, extent, uneven chunks): 1-4-D, both bases, several kernels, vector output, periods
CASES = {
    "1d-gradient": (dict(dim_in=1, rng=3, basis="gradient"), (257,), [(0, 19)], ((100, 57, 100),)),
    "2d-vector-period-catmullrom": (dict(dim_in=2, dim_out=3, rng=4, kernel="catmull-rom", period=(3, 5)),
                                    (41, 33), [(0, 3), (0, 5)], (7, (1, 32))),
    "3d-quintic-gradient": (dict(dim_in=3, rng=5, kernel="quintic", basis="gradient"),
                            (19, 23, 17), [(0, 2), (-1, 3), (5, 7)], (5, 8, (16, 1))),
    "4d-linear": (dict(dim_in=4, rng=6, kernel="linear"), (6, 7, 5, 9), [(0, 1), (0, 2), (0, 1), (0, 3)],
                  (4, 3, 5, (2, 7))),
    "2d-sparse-grid-scattered-path": (dict(dim_in=2, rng=7), (30, 30), [(0, 200), (0, 200)], ((13, 17), 11)),
}


def _noise(spec):
    spec = dict(spec)
    return LatticeNoise(spec.pop("dim_in"), spec.pop("dim_out", 1), **spec)


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("dtype", ["float32", "float64"])
def test_chunked_grid_is_bit_identical_to_in_memory_on_the_cluster(client, case, dtype):
    spec, shape, extent, chunks = CASES[case]
    noise = _noise(spec)
    lazy = noise.grid(shape, extent, dtype=dtype, chunks=chunks)
    assert isinstance(lazy, da.Array) and lazy.dtype == np.dtype(dtype)
    assert lazy.npartitions > 1 and len({c for axis in lazy.chunks[:len(shape)] for c in axis}) > 1  # uneven
    ref = noise.grid(shape, extent, dtype=dtype)
    got = client.compute(lazy).result()
    assert got.dtype == np.dtype(dtype) and got.shape == ref.shape
    assert np.array_equal(got, ref)


@pytest.mark.parametrize("case", ["1d-gradient", "2d-vector-period-catmullrom", "3d-quintic-gradient", "4d-linear"])
def test_chunked_fractal_sums_and_turbulence_are_bit_identical(client, case):
    spec, shape, extent, chunks = CASES[case]
    noise = _noise(spec)
    grid = Grid(shape, extent)
    # a tileable noise's octave o has period * lacunarity**o cells, which needs a whole lacunarity
    lacunarity = 3.0 if noise.tileable else 2.3
    for summer, kw in ((fractal_sum, dict(octaves=7, dtype="float32")),
                       (turbulence, dict(octaves=5, normalize=True, lacunarity=lacunarity, gain=0.6))):
        ref, used = summer(noise, grid, return_octaves=True, **kw)
        lazy, used_lazy = summer(noise, grid, return_octaves=True, chunks=chunks, **kw)
        assert used_lazy == used and lazy.dtype == ref.dtype
        assert np.array_equal(client.compute(lazy).result(), ref)


def test_threaded_scheduler_auto_chunks_and_a_callable_noise():
    noise = LatticeNoise(3, 2, rng=8)
    grid = Grid((20, 18, 16), [(0, 2)] * 3)
    ref = fractal_sum(noise, grid, 4)
    # "auto" chunks with a small block limit, so the grid really is cut
    import dask

    with dask.config.set({"array.chunk-size": "8KiB"}):
        lazy = fractal_sum(noise, grid, 4, chunks="auto")
    assert lazy.npartitions > 1 and lazy.chunks[-1] == (2,)
    assert np.array_equal(lazy.compute(scheduler="threads"), ref)
    # any pointwise callable, chunked likewise (each chunk evaluates its own points)
    f = lambda p: np.sin(3 * p[..., 0]) * np.cos(2 * p[..., 1]) + p[..., 2]  # noqa: E731
    ref = turbulence(f, grid, 3, normalize=True, dtype="float32")
    assert np.array_equal(turbulence(f, grid, 3, normalize=True, dtype="float32", chunks=(7, 18, 5)).compute(), ref)
    # a callable that returns inf is refused per chunk as in memory, not passed through
    bad = lambda p: np.where(p[..., 0] > 1.5, np.inf, 0.0)  # noqa: E731
    with pytest.raises(ValueError, match="noise returned NaN or inf"):
        fractal_sum(bad, grid, 2)
    with pytest.raises(ValueError, match="noise returned NaN or inf"):
        fractal_sum(bad, grid, 2, chunks=(7, 18, 5)).compute(scheduler="synchronous")


def test_the_lazy_array_does_not_follow_later_changes_to_the_noise():
    noise = LatticeNoise(2, rng=1)
    ref = noise.grid((16, 16), [(0, 2), (0, 2)])
    lazy = noise.grid((16, 16), [(0, 2), (0, 2)], chunks=8)
    noise.values[:] = 0.0
    assert np.array_equal(lazy.compute(scheduler="synchronous"), ref)


def test_bad_chunks_are_refused_with_the_parameter_named():
    noise = LatticeNoise(2, 2, rng=1)
    ext = [(0, 1), (0, 1)]
    with pytest.raises(ValueError, match=r"chunks\[0\] must be >= 1"):
        noise.grid((8, 8), ext, chunks=0)
    with pytest.raises(ValueError, match="one entry per grid axis"):
        noise.grid((8, 8), ext, chunks=(4, 4, 2, 1))
    with pytest.raises(ValueError, match="do not fit the grid shape"):
        noise.grid((8, 8), ext, chunks=((4, 3), 4))
    with pytest.raises(ValueError, match="component axis"):
        noise.grid((8, 8), ext, chunks=(4, 4, 1))
    with pytest.raises(TypeError, match="chunks"):
        noise.grid((8, 8), ext, chunks=True)
    with pytest.raises(ValueError, match="window= and chunks="):
        noise.grid((8, 8), ext, chunks=4, window=[(0, 4), (0, 4)])
    with pytest.raises(ValueError, match="needs x to be a Grid"):
        fractal_sum(noise, np.zeros((5, 2)), 3, chunks=2)
    # the component axis may be named as one whole chunk
    assert noise.grid((8, 8), ext, chunks=(4, 4, -1)).chunks == ((4, 4), (4, 4), (2,))


def test_without_dask_the_error_names_the_extra(monkeypatch, tmp_path, capsys):
    import importlib

    from noiselab._core import deps as _deps

    def absent(name):
        if name.split(".")[0] in ("dask", "zarr", "distributed"):
            raise ModuleNotFoundError(f"No module named {name!r}")
        return importlib.import_module(name)

    # (patched at noiselab's one import seam, not in sys.modules: the cluster's threads share this process)
    monkeypatch.setattr(_deps, "_import", absent)
    noise = LatticeNoise(2, rng=1)
    with pytest.raises(ImportError, match=r"chunks= needs the optional package 'dask'.*pip install 'noiselab\[dask\]'"):
        noise.grid((8, 8), [(0, 1), (0, 1)], chunks=4)
    with pytest.raises(ImportError, match=r"noiselab\[dask\]"):
        fractal_sum(noise, Grid((8, 8), [(0, 1), (0, 1)]), 3, chunks=4)
    with pytest.raises(ImportError, match=r"write_zarr needs .*noiselab\[dask\]"):
        write_zarr(tmp_path / "a.zarr", np.zeros(3))
    from noiselab.cli import main

    assert main(["noise", "--size", "16", "--chunks", "8", "-o", str(tmp_path / "a.zarr")]) == 2
    assert "pip install 'noiselab[dask]'" in capsys.readouterr().err and os.listdir(tmp_path) == []
    # the in-memory path needs none of it
    assert noise.grid((8, 8), [(0, 1), (0, 1)]).shape == (8, 8)


def test_zarr_round_trip_on_the_cluster_keeps_data_attributes_dims_and_coords(client, tmp_path):
    noise = LatticeNoise(3, rng=11, kernel="quintic")
    grid = Grid((24, 20, 18), [(0, 3), (0, 2), (0, 2)])
    lazy = fractal_sum(noise, grid, 5, dtype="float32", chunks=((10, 14), 7, 18))  # uneven: regrouped for zarr
    coords = {"x": np.arange(18) / 9.0}
    out = write_zarr(tmp_path / "vol.zarr", lazy, dims=("z", "y", "x"), coords=coords, units="amplitude",
                     params={"octaves": 5, "kernel": "quintic", "frequency": noise.frequency}, rng=11,
                     attrs={"note": "test"})
    assert out == tmp_path / "vol.zarr" and sorted(os.listdir(tmp_path)) == ["vol.zarr"]
    back = read_zarr(out)
    assert back.dtype == np.float32 and back.chunksize == (14, 7, 18)
    assert np.array_equal(back.compute(), fractal_sum(noise, grid, 5, dtype="float32"))
    xa = read_zarr(out, as_xarray=True)
    assert xa.dims == ("z", "y", "x") and np.array_equal(xa["x"].values, coords["x"])
    attrs = xa.attrs
    assert attrs["noiselab_version"] == noiselab.__version__ and attrs["seed"] == 11
    assert attrs["units"] == "amplitude" and attrs["note"] == "test"
    assert attrs["params"] == {"octaves": 5, "kernel": "quintic", "frequency": [1.0, 1.0, 1.0]}
    # writing again replaces the store atomically; a folder that is not a store is never replaced
    write_zarr(out, np.ones((2, 3), np.float32), dims=("a", "b"))
    assert read_zarr(out).shape == (2, 3)
    (tmp_path / "keep").mkdir()
    with pytest.raises(FileExistsError, match="not a zarr store"):
        write_zarr(tmp_path / "keep", np.zeros(3))
    with pytest.raises(ValueError, match="dims must be 2 distinct names"):
        write_zarr(tmp_path / "b.zarr", np.zeros((2, 2)), dims=("y", "y"))
    with pytest.raises(TypeError, match=r"attrs\['when'\]"):
        write_zarr(tmp_path / "b.zarr", np.zeros(2), attrs={"when": object()})
    assert not (tmp_path / "b.zarr").exists()


def _fail_on_block(block, block_info=None):
    if block_info[0]["chunk-location"] == (1, 1):
        raise ValueError("boom in one chunk")
    return block


def test_a_failed_run_leaves_no_store_under_the_final_name(client, tmp_path):
    lazy = LatticeNoise(2, rng=1).grid((32, 32), [(0, 4), (0, 4)], chunks=8)
    with pytest.raises(ValueError, match="boom in one chunk"):
        write_zarr(tmp_path / "f.zarr", lazy.map_blocks(_fail_on_block, dtype=lazy.dtype))
    assert os.listdir(tmp_path) == []  # neither the store nor its temporary folder


def test_a_killed_run_leaves_only_a_temporary_folder(tmp_path):
    # the writing process itself dies (os._exit) after some chunks were written
    code = textwrap.dedent(f"""
        import os
        from noiselab.io import write_zarr
        from noiselab.lattice import LatticeNoise
        count = [0]
        def die_after_some(block):
            count[0] += 1
            if count[0] == 6:
                os._exit(9)
            return block
        lazy = LatticeNoise(2, rng=1).grid((64, 64), [(0, 4), (0, 4)], chunks=16)
        write_zarr({str(tmp_path / "k.zarr")!r}, lazy.map_blocks(die_after_some, dtype=lazy.dtype),
                   scheduler="synchronous")
    """)
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert proc.returncode == 9, proc.stderr
    left = os.listdir(tmp_path)
    assert "k.zarr" not in left
    assert len(left) == 1 and left[0].startswith(".k.zarr.") and left[0].endswith(".tmp")
    written = [f for _, _, files in os.walk(tmp_path / left[0]) for f in files if f != "zarr.json"]
    assert 0 < len(written) < 16  # it really died half way through


def _kill_worker_once(block, marker, block_info=None):
    if block_info[0]["chunk-location"] == (2, 1, 0) and not os.path.exists(marker):
        with open(marker, "w") as f:
            f.write(str(os.getpid()))
        os._exit(1)  # the worker process dies mid-task; its nanny starts a new one
    return block


def test_a_worker_killed_mid_run_still_completes_a_right_store(client, tmp_path):
    marker = str(tmp_path / "killed")
    noise = LatticeNoise(3, rng=12)
    grid = Grid((32, 24, 16), [(0, 4), (0, 3), (0, 2)])
    lazy = fractal_sum(noise, grid, 3, dtype="float32", chunks=(8, 8, 16))
    killer = lazy.map_blocks(_kill_worker_once, marker, dtype=lazy.dtype)
    out = write_zarr(tmp_path / "w.zarr", killer, dims=("z", "y", "x"))
    killed_pid = int(open(marker).read())
    assert killed_pid not in client.run(os.getpid).values()  # that worker really died
    assert np.array_equal(read_zarr(out).compute(), fractal_sum(noise, grid, 3, dtype="float32"))
    assert sorted(os.listdir(tmp_path)) == ["killed", "w.zarr"]


def test_compute_names_bad_schedulers():
    x = da.ones(4, chunks=2).sum()
    assert compute(x, scheduler="threads") == (4.0,)
    with pytest.raises(ValueError, match="scheduler must be one of"):
        compute(x, scheduler="fast")
    with pytest.raises(TypeError, match="scheduler must be"):
        compute(x, scheduler=3)


def test_cli_writes_zarr_on_the_cluster_and_analyze_reads_it(client, tmp_path, capsys):
    from noiselab.cli import main

    out = tmp_path / "sub" / "v.zarr"
    rc = main(["noise", "--dims", "3", "--size", "20x24x16", "--cells", "2x3x2", "--chunks", "7x24x16",
               "--octaves", "3", "--seed", "5", "--kernel", "quintic", "-o", str(out),
               "--scheduler", client.scheduler.address])  # connects to the running cluster by its address
    assert rc == 0
    assert "chunks=(7, 24, 16) (3 tasks)" in capsys.readouterr().out
    noise = LatticeNoise(3, rng=5, kernel="quintic")
    ref = fractal_sum(noise, Grid((20, 24, 16), [(0, 2), (0, 3), (0, 2)]), 3, dtype="float32")
    xa = read_zarr(out, as_xarray=True)
    assert np.array_equal(xa.values, ref) and xa.dims == ("z", "y", "x")
    assert xa.attrs["params"]["size"] == [20, 24, 16] and xa.attrs["params"]["kernel"] == "quintic"
    assert xa.attrs["seed"] == 5 and np.allclose(xa["y"].values, np.arange(24) / 8)
    assert main(["analyze", str(out), "--as", "volume", "--json", str(tmp_path / "m.json")]) == 0
    m = json.loads((tmp_path / "m.json").read_text())
    assert m["kind"] == "volume" and m["shape"] == [20, 24, 16]
    assert m["mean"] == pytest.approx(float(np.mean(ref, dtype=np.float64)), rel=1e-12)


def test_cli_errors_for_chunks_without_zarr_and_an_unreachable_scheduler(tmp_path, capsys):
    from noiselab.cli import main

    assert main(["noise", "--size", "16", "--chunks", "8", "-o", str(tmp_path / "a.png")]) == 2
    assert "--chunks and --scheduler need .zarr output" in capsys.readouterr().err
    assert main(["noise", "--size", "16", "--chunks", "0", "-o", str(tmp_path / "a.zarr")]) == 2
    assert "--chunks entries must be >= 1" in capsys.readouterr().err
    assert main(["noise", "--size", "16", "--scheduler", "nonsense", "-o", str(tmp_path / "a.zarr")]) == 2
    assert "scheduler must be one of" in capsys.readouterr().err
    assert os.listdir(tmp_path) == []


def _partition(draw, n, st):
    """A random partition of n into positive block sizes."""
    cuts = sorted(draw(st.sets(st.integers(1, max(n - 1, 1)), max_size=min(n - 1, 4))) if n > 1 else [])
    edges = [0] + cuts + [n]
    return tuple(b - a for a, b in zip(edges[:-1], edges[1:]))


def test_any_chunking_is_bit_identical_property():
    from hypothesis import given, settings
    from hypothesis import strategies as st

    @st.composite
    def cases(draw):
        d = draw(st.integers(1, 4))
        shape = tuple(draw(st.integers(1, {1: 40, 2: 14, 3: 9, 4: 6}[d])) for _ in range(d))
        chunks = tuple(_partition(draw, n, st) for n in shape)
        extent = [(draw(st.floats(-50, 50)), draw(st.floats(-50, 50))) for _ in range(d)]
        kernel = draw(st.sampled_from(["box", "linear", "quadratic", "cubic", "catmull-rom", "quintic"]))
        basis = draw(st.sampled_from(["value", "gradient"]))
        return d, shape, chunks, extent, kernel, basis, draw(st.integers(1, 5)), draw(st.booleans())

    @settings(max_examples=30, deadline=None, derandomize=True)
    @given(cases())
    def check(case):
        d, shape, chunks, extent, kernel, basis, octaves, turb = case
        noise = LatticeNoise(d, rng=d, kernel=kernel, basis=basis)
        grid = Grid(shape, extent)
        summer = turbulence if turb else fractal_sum
        lazy = summer(noise, grid, octaves, dtype="float32", chunks=chunks)
        assert lazy.chunks == chunks
        assert np.array_equal(lazy.compute(scheduler="synchronous"), summer(noise, grid, octaves, dtype="float32"))

    check()


def test_progress_bars_go_to_stderr_locally_and_on_the_cluster(client, capsys):
    x = LatticeNoise(2, rng=1).grid((32, 32), [(0, 2), (0, 2)], chunks=8).sum()
    compute(x, scheduler="threads", progress=True)
    err = capsys.readouterr()
    assert "100% Completed" in err.err and err.out == ""
    compute(x, progress=True)  # the active distributed client
    err = capsys.readouterr()
    assert "100% Completed" in err.err and err.out == ""


def test_read_zarr_opens_stores_written_by_other_tools(tmp_path):
    import zarr

    g = zarr.open_group(str(tmp_path / "g.zarr"), mode="w")  # no consolidated metadata, no noiselab attrs
    g.create_array("v", shape=(3, 2), dtype="f4", dimension_names=("y", "x"))[:] = np.arange(6).reshape(3, 2)
    assert np.array_equal(read_zarr(tmp_path / "g.zarr").compute(), np.arange(6).reshape(3, 2))
    assert read_zarr(tmp_path / "g.zarr", as_xarray=True).dims == ("y", "x")
    g.create_array("w", shape=(2,), dtype="f4")
    with pytest.raises(ValueError, match=r"holds arrays \['v', 'w'\]; say which"):
        read_zarr(tmp_path / "g.zarr")
    assert read_zarr(tmp_path / "g.zarr", name="w").shape == (2,)
    a = zarr.open_array(str(tmp_path / "a.zarr"), mode="w", shape=(4,), dtype="i2")
    a[:] = [1, 2, 3, 4]
    assert read_zarr(tmp_path / "a.zarr").sum().compute() == 10
    with pytest.raises(FileNotFoundError, match="no zarr store"):
        read_zarr(tmp_path / "missing.zarr")


@pytest.mark.parametrize("module", ["noiselab._core.deps", "noiselab.scale.run", "noiselab.scale.lattice",
                                    "noiselab.io.zarr", "noiselab.scale.zarr"])
def test_docstring_examples_run(module):
    import doctest
    import importlib

    result = doctest.testmod(importlib.import_module(module), optionflags=doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0
