"""Chunked spectral noise and snow on dask (pencil-decomposed inverse FFTs), on a real LocalCluster.

One ``LocalCluster`` (2 worker processes, 1 thread each, 352 MiB of memory
each: a worker process with noiselab, numba, scipy and distributed loaded
already takes about 240 MiB) serves the module. The chunked results are
compared with the in-memory ones computed in the test process: snow is
bit-identical; spectral noise is bit-identical where the spectrum is pruned
and otherwise at most 9.5e-7 apart on fields of largest value ~4.3 (under 2
float32 ulp of it; in memory the unpruned field is one ``irfftn`` call).
"""
import signal
import sys

import numpy as np
import pytest

from noiselab.io import read_zarr, write_zarr
from noiselab.scale.run import _worker_events, _worker_events_plugin
from noiselab.snowfall import snow
from noiselab.spectral import spectral_noise

import dask.array as da  # the test extras install noiselab[dask]
import distributed

LIMIT = 352 << 20  # bytes per worker


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  memory_limit=LIMIT) as cluster, distributed.Client(cluster) as c:
        yield c


def _close(got, ref):
    """Equal to float32 rounding of the field's scale: at most 2 ulp of its largest value apart."""
    tol = 2 * np.finfo(np.float32).eps * float(np.max(np.abs(ref)))
    return float(np.max(np.abs(got - ref))) <= tol


BIG = (48, 1024, 2048)  # 384 MiB of float32, more than a worker's 352 MiB limit


@pytest.fixture(scope="module")
def big_snow():
    return snow(BIG, rng=9)


# (shape, kwargs, chunks): odd and even sizes, bands touching Nyquist, every normalisation, dc, 1-3-D
NOISE = {
    "2d-odd-band": ((41, 37), dict(band=(2, 12)), (16, (20, 17))),
    "2d-even-band-at-nyquist": ((48, 40), dict(band=(4, 20), normalize="sample"), (13, 40)),
    "2d-full-dc": ((30, 32), dict(dc=True, band=(0, 16), exponent=2.0), (7, 9)),
    "3d-odd-full": ((17, 19, 15), dict(exponent=1.5), (5, 19, 15)),
    "3d-even-band-at-nyquist": ((16, 20, 24), dict(band=(2, 12), amplitude_distribution="uniform"), (6, 7, 24)),
    "3d-sample-float64": ((12, 14, 18), dict(band=(1, 6), normalize="sample", dtype="float64"), (12, 5, 9)),
    "1d": ((257,), dict(exponent=1.0, dc=True), (100,)),
}


@pytest.mark.parametrize("case", sorted(NOISE))
def test_chunked_spectral_noise_equals_in_memory(client, case, tmp_path):
    shape, kw, chunks = NOISE[case]
    ref = spectral_noise(shape, rng=11, **kw)
    lazy = spectral_noise(shape, rng=11, chunks=chunks, **kw)
    assert isinstance(lazy, da.Array) and lazy.dtype == ref.dtype and lazy.shape == ref.shape
    assert lazy.npartitions > 1
    got = client.compute(lazy).result()
    assert _close(got, ref)
    # through zarr arrays on disk: the same values
    spilled = spectral_noise(shape, rng=11, chunks=chunks, spill=tmp_path, **kw)
    assert np.array_equal(client.compute(spilled).result(), got)


# (shape, kwargs, chunks): odd and even sizes, a band touching Nyquist, a pan (sheared tent), T = 1
SNOW = {
    "even": ((8, 48, 64), dict(), (3, 20, 64)),
    "odd": ((9, 47, 63), dict(), (4, 13, 20)),
    "band-at-nyquist": ((6, 32, 40), dict(band=(4, 20), c=0.5), (6, 11, 13)),
    "pan": ((9, 40, 36), dict(pan_yx=(-0.3, 0.4), direction_yx=(1.0, 0.3)), (5, 40, 7)),
    "still-T1": ((1, 40, 41), dict(amplitude_distribution="rayleigh"), (1, 16, 16)),
    "float64-thick": ((10, 32, 32), dict(dtype="float64", thickness=0.5), (4, 32, 32)),
}


@pytest.mark.parametrize("case", sorted(SNOW))
@pytest.mark.parametrize("spill", [False, True])
def test_chunked_snow_equals_in_memory(client, case, spill, tmp_path):
    shape, kw, chunks = SNOW[case]
    ref = snow(shape, rng=5, **kw)
    lazy = snow(shape, rng=5, chunks=chunks, spill=tmp_path if spill else None, **kw)
    assert isinstance(lazy, da.Array) and lazy.dtype == ref.dtype and lazy.npartitions > 1
    got = client.compute(lazy).result()
    assert _close(got, ref) and float(got.min()) == 0.0 and float(got.max()) == 1.0
    raw_ref = snow(shape, rng=5, rescale=False, **kw)
    raw = snow(shape, rng=5, chunks=chunks, rescale=False, spill=tmp_path if spill else None, **kw)
    assert _close(client.compute(raw).result(), raw_ref)


def test_a_snow_video_bigger_than_a_workers_memory_is_written_and_right(client, big_snow, tmp_path):
    shape = BIG  # 384 MiB of float32, more than a worker's 352 MiB limit
    assert np.prod(shape) * 4 > LIMIT
    workers = set(client.scheduler_info()["workers"])
    lazy = snow(shape, rng=9, chunks=(8, 128, 2048), spill=tmp_path / "spill")
    write_zarr(tmp_path / "big.zarr", lazy, dims=("t", "y", "x"), rng=9)
    # no worker was restarted for memory (a restarted worker comes back under a new address)
    assert set(client.scheduler_info()["workers"]) == workers
    ref = big_snow  # snow(shape, rng=9) in memory
    stored = read_zarr(tmp_path / "big.zarr")  # lazy, chunk by chunk
    for t0 in range(0, shape[0], 8):
        assert np.array_equal(np.asarray(stored[t0:t0 + 8]), ref[t0:t0 + 8])


def test_auto_chunked_snow_written_by_memory_limited_workers_restarts_none(client, tmp_path):
    """Chunked snow within the workers' memory at the suite's scale: the full-size run (512 MiB by 2 workers of 600 MiB, about 350 MiB above a
    worker's ~250 MiB of imports) is in benchmarks/bench_dask.md; here 128 MiB by this module's 2 workers of
    352 MiB (about 110 MiB above the imports): the video is about the same multiple of a worker's headroom."""
    client.register_plugin(_worker_events_plugin())
    shape = (32, 1024, 1024)  # 128 MiB of float32
    lazy = snow(shape, rng=2, chunks="auto", spill=tmp_path / "spill")  # as `noiselab snow -o x.zarr` does
    assert max(lazy.chunks[-1]) == shape[-1] and lazy.npartitions > 2  # whole rows: the x-pass makes them
    write_zarr(tmp_path / "v.zarr", lazy, dims=("t", "y", "x"), rng=2)
    assert client.run_on_scheduler(_worker_events) == (0, 0)  # no worker restarted or lost
    stored = read_zarr(tmp_path / "v.zarr")
    ref = snow(shape, rng=2)
    assert np.array_equal(np.asarray(stored[:4]), ref[:4]) and np.array_equal(np.asarray(stored[-4:]), ref[-4:])


def test_cli_writes_snow_zarr_on_the_cluster(client, tmp_path, capsys):
    from noiselab.cli import main

    out = tmp_path / "snow.zarr"
    assert main(["snow", "--frames", "6", "--width", "40", "--height", "32", "--seed", "4", "--pan", "0.2", "0",
                 "-o", str(out), "--chunks", "3x16x40", "--scheduler", client.scheduler.address]) == 0
    assert "wrote" in capsys.readouterr().out
    x = read_zarr(out, as_xarray=True)
    assert x.dims == ("t", "y", "x")
    attrs = x.attrs["noiselab"] if "noiselab" in x.attrs else x.attrs
    text = repr(attrs)
    assert "noiselab snow" in text and "seed" in text
    ref = snow((6, 32, 40), rng=4, pan_yx=(0.0, 0.2))
    assert _close(np.asarray(x.values), ref)
    assert [p.name for p in tmp_path.iterdir()] == ["snow.zarr"]  # the spill folder is gone


def test_bad_chunked_arguments_name_the_parameter(tmp_path):
    with pytest.raises(ValueError, match="spill= .* pass chunks="):
        snow((4, 16, 16), rng=0, spill=tmp_path)
    with pytest.raises(ValueError, match="spill= .* pass chunks="):
        spectral_noise((16, 16), rng=0, spill=tmp_path)
    with pytest.raises(ValueError, match=r"chunks\[0\] must be >= 1"):
        snow((4, 16, 16), rng=0, chunks=(0, 16, 16))
    with pytest.raises(ValueError, match="one entry per grid axis"):
        spectral_noise((16, 16), rng=0, chunks=(4, 4, 4))


def test_docstring_examples_run():
    import doctest

    import noiselab.scale.spectral as mod

    assert doctest.testmod(mod).failed == 0


@pytest.mark.parametrize("hold", [True, False])
def test_chunked_snow_one_pass_or_two_gives_the_in_memory_bits(client, hold, monkeypatch):
    # the raw field waits in memory for its extremes when it fits (one FFT pass), else the FFT runs twice:
    # either way the in-memory video's bits; the graph holds the second pass's slabs only when it needs them
    from noiselab.scale import spectral as S

    monkeypatch.setattr(S, "_hold_raw", lambda nbytes: hold)
    # the in-memory route, whatever the workers' memory reads when the suite runs beside other jobs (which route a
    # cluster's memory allows is tested apart): the graph's shape on that route is the subject here
    monkeypatch.setattr(S, "_route", lambda spill, task, shared: spill)
    shape, kw, chunks = SNOW["odd"]
    lazy = snow(shape, rng=7, chunks=chunks, **kw)
    names = {k[0] if isinstance(k, tuple) else k for k in dict(lazy.__dask_graph__())}
    assert any(n.startswith("snow-b-ty-") for n in names) == (not hold)
    assert sum(n.startswith("snow-raw-x-") for n in names) == (1 if hold else 0)
    got = client.compute(lazy).result()
    assert np.array_equal(got, snow(shape, rng=7, **kw))


def test_hold_raw_counts_the_workers_memory(client):
    from noiselab.scale.spectral import _hold_raw

    total = 2 * LIMIT  # this module's cluster
    assert _hold_raw(total // 4) and not _hold_raw(total // 4 + 1)


def test_chunks_no_worker_can_hold_are_a_clear_error_before_any_graph(client):
    # one output chunk of 64 x 2048 x 2048 (1 GiB, assembled and copied by the writer), past a 352 MiB worker
    with pytest.raises(MemoryError, match=r"snow\(64, 2048, 2048\).* needs at least \d+ MiB per worker .*output chunk"
                                          r".* 352 MiB"):
        snow((64, 2048, 2048), rng=0, chunks=(64, 2048, 2048))
    with pytest.raises(MemoryError, match=r"spectral_noise\(8192, 8192\).* MiB per worker .* memory_limit"):
        spectral_noise((8192, 8192), rng=0, chunks=(8192, 8192))
    # chunks a worker can hold build their graph as before
    assert snow((64, 2048, 2048), rng=0, chunks=(8, 256, 2048)).npartitions == 64


def test_a_worker_past_its_pause_point_is_a_clear_error_before_any_graph():
    # an in-process worker (no nanny: nothing restarts it) whose memory limit puts this process past the point
    # where distributed pauses it: it would take no task, and the computation would wait for ever
    import time

    import psutil

    ballast = np.ones(32 << 20, np.uint8)  # held (and touched): this process stays above the limit's 80 %
    rss = psutil.Process().memory_info().rss
    lim = int(rss / 2)
    with distributed.LocalCluster(n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None,
                                  memory_limit=lim) as cluster, \
            distributed.Client(cluster, set_as_default=False) as c, c.as_current():
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:  # the scheduler hears of the pause at the worker's next heartbeat
            w, = c.scheduler_info()["workers"].values()
            if w.get("status") == "paused":
                break
            time.sleep(0.1)
        assert w.get("status") == "paused"
        limit = f"{lim / 2**20:.0f} MiB"
        with pytest.raises(MemoryError, match=rf"snow\(8, 64, 64\) .*needs at least [\d.]+ MiB per worker \(.*\), "
                                              rf"and the cluster's workers have at most 0.0 MiB before distributed "
                                              rf"pauses them \(worker .* of its {limit} memory limit, paused at "
                                              rf"[\d.]+ MiB \(80%\), paused now\).*memory_limit of at least"):
            snow((8, 64, 64), rng=0, chunks=(4, 32, 64))
        with pytest.raises(MemoryError, match=r"spectral_noise\(64, 64\).* per worker .* paused now"):
            spectral_noise((64, 64), rng=0, chunks=(32, 64))
    assert ballast[-1] == 1


@pytest.fixture
def fresh_client():
    """A cluster of its own (2 worker processes, 1 thread, 352 MiB each), the workers' join and leave counted.

    Its own for each test, not one for the module: the workers keep memory
    that an earlier write left them, and on one cluster shared by these
    tests the second 384 MiB write paused a worker for good (no progress in
    400 s, 2026-11-27, load average 8-11 on 2 cores): a shared cluster tests
    that residue, not the route.
    """
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  memory_limit=LIMIT) as cluster, distributed.Client(cluster) as c:
        c.register_plugin(_worker_events_plugin())
        # a worker that pauses for memory and never resumes would hang the suite: fail the test instead
        previous = signal.signal(signal.SIGALRM, _no_progress)
        signal.alarm(NO_PROGRESS_S)
        try:
            yield c
        finally:
            signal.alarm(0)
            signal.signal(signal.SIGALRM, previous)


NO_PROGRESS_S = 400  # about 4x the slowest case measured on a loaded 2-core machine


def _no_progress(signum, frame):
    raise TimeoutError(f"the cluster did not finish in {NO_PROGRESS_S} s: a worker paused for memory and never resumed")


@pytest.mark.parametrize("chunks", [(48, 256, 512), (8, 1024, 256), (16, 128, 2048)])
def test_user_chunks_without_spill_lose_no_worker(fresh_client, big_snow, chunks, tmp_path):
    # the chunks any dask user would pass and no spill=: the in-memory rechunk would hold the transposed spectrum
    # across 2 workers short of room, so the route spills by itself, into a folder owned by the graph
    import gc

    import dask

    client = fresh_client
    assert np.prod(BIG) * 4 > LIMIT
    workers = {a: w["id"] for a, w in client.scheduler_info()["workers"].items()}
    with dask.config.set({"temporary-directory": str(tmp_path / "dask")}):
        (tmp_path / "dask").mkdir()
        lazy = snow(BIG, rng=9, chunks=chunks)
        assert lazy.chunks == da.core.normalize_chunks(chunks, BIG)  # the caller's chunks, whatever the route
        assert any(str(k[0] if isinstance(k, tuple) else k).startswith("spill-write-")
                   for k in dict(lazy.__dask_graph__()))
        assert len(list((tmp_path / "dask").iterdir())) == 1  # the scratch folder, while the graph lives
        write_zarr(tmp_path / "v.zarr", lazy, dims=("t", "y", "x"), rng=9)
        del lazy
        gc.collect()
        assert list((tmp_path / "dask").iterdir()) == []  # removed with the graph
    # no worker joined or left: the same addresses and ids, and no event counted by the scheduler plugin
    assert {a: w["id"] for a, w in client.scheduler_info()["workers"].items()} == workers
    assert client.run_on_scheduler(_worker_events) == (0, 0)
    stored = read_zarr(tmp_path / "v.zarr")
    assert np.array_equal(np.asarray(stored[:4]), big_snow[:4])
    assert np.array_equal(np.asarray(stored[-3:, 500:700]), big_snow[-3:, 500:700])


def test_spectral_noise_with_user_chunks_without_spill_loses_no_worker(fresh_client, tmp_path):
    shape = (24, 1024, 2048)  # 192 MiB of float32; its half spectrum and the leading-axes transpose 385 MiB more
    client = fresh_client
    workers = set(client.scheduler_info()["workers"])
    lazy = spectral_noise(shape, rng=4, chunks=(24, 256, 512))
    assert any(str(k[0] if isinstance(k, tuple) else k).startswith("spill-write-") for k in dict(lazy.__dask_graph__()))
    write_zarr(tmp_path / "n.zarr", lazy, dims=("t", "y", "x"), rng=4)
    assert set(client.scheduler_info()["workers"]) == workers
    assert client.run_on_scheduler(_worker_events) == (0, 0)
    ref = spectral_noise(shape, rng=4)[:3]
    # the full band is not pruned: the pencil FFT's rounding against one irfftn, 2.2 float32 ulp of the largest
    # value on this 1024 x 2048 field (the same bits as the in-memory-rechunk route, checked by hand)
    tol = 4 * np.finfo(np.float32).eps * float(np.max(np.abs(ref)))
    assert float(np.max(np.abs(np.asarray(read_zarr(tmp_path / "n.zarr")[:3]) - ref))) <= tol


def test_the_route_spills_only_when_the_rechunk_would_not_fit(fresh_client):
    # on this cluster (2 workers of 352 MiB, paused at 80 %): a small video keeps dask's rechunk, a large one spills
    from noiselab.scale.spectral import _budget

    budget, n = _budget()
    assert n == 2 and 0 < budget <= 0.8 * LIMIT - (240 << 20)

    def spills(x):
        keys = dict(x.__dask_graph__())
        return any(str(k[0] if isinstance(k, tuple) else k).startswith("spill-write-") for k in keys)

    assert not spills(snow((8, 64, 64), rng=0, chunks=(4, 32, 64)))
    assert spills(snow((32, 1024, 1024), rng=0, chunks=(8, 256, 1024)))
    assert not spills(spectral_noise((32, 32, 32), rng=0, chunks=(8, 32, 32)))
    assert spills(spectral_noise((16, 1024, 1024), rng=0, chunks=(8, 256, 1024)))
