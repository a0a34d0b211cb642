"""Computing dask collections on the scheduler the user chose, with progress on long runs."""
from __future__ import annotations

import contextlib
import sys
import time

from .._core import require_dask

__all__ = ["compute", "LOCAL_SCHEDULERS"]

#: dask's single-machine schedulers, by name
LOCAL_SCHEDULERS = ("threads", "processes", "synchronous", "sync", "single-threaded")


def _is_address(scheduler):
    return isinstance(scheduler, str) and scheduler not in LOCAL_SCHEDULERS and ":" in scheduler


def _active_client():
    """The active ``distributed.Client``, or None (without importing distributed if nobody did)."""
    if "distributed" not in sys.modules:
        return None
    import distributed

    try:
        return distributed.default_client()
    except ValueError:
        return None


def _on_client(client, objs, progress):
    futures = client.compute(list(objs))
    if progress:
        import distributed

        # distributed's text bar writes to stdout; keep stdout for results
        with contextlib.redirect_stdout(sys.stderr):
            distributed.progress(futures)
        print(file=sys.stderr)
    try:
        return tuple(client.gather(futures))
    except BaseException:
        # gather raises at the first failed task while others may still be running (and, for a store, still
        # writing chunks into the caller's temporary folder, re-creating it after the caller cleans up): cancel
        # what has not started and wait until none of this graph's tasks is running any more, then re-raise
        client.cancel(futures)
        _wait_idle(client, objs)
        raise


def _wait_idle(client, objs, timeout=60.0):
    keys = set()
    for obj in objs:
        keys.update(str(k) for k in obj.__dask_graph__().keys())
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            running = {str(k) for ks in client.processing().values() for k in ks}
        except Exception:  # the cluster went away: nothing of ours can still run there
            return
        if not running & keys:
            return
        time.sleep(0.05)


def compute(*objs, scheduler=None, progress=None):
    """Compute dask collections (or delayed values) and return their results as a tuple.

    Parameters
    ----------
    *objs : dask collections
        What to compute (e.g. the delayed store that :func:`noiselab.scale.zarr.write_dask_zarr` builds
        for :func:`noiselab.io.write_zarr`).
    scheduler : None, str or distributed.Client, optional
        ``None``: the active ``distributed.Client`` if there is one, else dask's
        default (threads). ``"threads"``, ``"processes"``, ``"synchronous"``:
        dask's local schedulers. An address such as ``"tcp://10.0.0.1:8786"``:
        connect to that running ``dask.distributed`` scheduler for this
        computation. A ``Client``: use it.
    progress : bool, optional
        Show a progress bar on stderr (dask's ``ProgressBar`` locally,
        ``distributed.progress`` on a cluster). Default: only when stderr is a
        terminal.

    Returns
    -------
    tuple
        One result per object.

    Examples
    --------
    >>> import dask.array as da
    >>> compute(da.ones(4, chunks=2).sum(), scheduler="synchronous")
    (np.float64(4.0),)
    """
    require_dask("compute")
    import dask

    if progress is None:
        progress = sys.stderr.isatty()
    if scheduler is None:
        client = _active_client()
        if client is not None:
            return _on_client(client, objs, progress)
    elif _is_address(scheduler):
        require_dask("scheduler=ADDRESS", "distributed")
        import distributed

        try:
            client = distributed.Client(scheduler, timeout="10s", set_as_default=False)
        except OSError as exc:
            raise ValueError(f"scheduler: cannot connect to the dask scheduler at {scheduler!r}: {exc}") from None
        with client:
            return _on_client(client, objs, progress)
    elif not isinstance(scheduler, str):
        if "distributed" in sys.modules and isinstance(scheduler, sys.modules["distributed"].Client):
            return _on_client(scheduler, objs, progress)
        raise TypeError(f"scheduler must be None, a scheduler name, an address or a distributed.Client, "
                        f"got {type(scheduler).__name__}")
    elif scheduler not in LOCAL_SCHEDULERS:
        raise ValueError(f"scheduler must be one of {LOCAL_SCHEDULERS} or a dask.distributed address "
                         f"such as 'tcp://host:8786', got {scheduler!r}")
    if progress:
        from dask.diagnostics import ProgressBar

        with ProgressBar(out=sys.stderr):
            return dask.compute(*objs, scheduler=scheduler)
    return dask.compute(*objs, scheduler=scheduler)


def _worker_events_plugin():
    """A ``distributed`` scheduler plugin counting the workers that join and leave (internal: tests, benchmarks).

    Registered on a running cluster, every join is a worker started after it
    (a nanny's restart is one leave and one join); read the counts with
    :func:`_worker_events` through ``client.run_on_scheduler``.
    """
    from distributed.diagnostics.plugin import SchedulerPlugin

    class WorkerEvents(SchedulerPlugin):
        name = "noiselab-worker-events"

        def __init__(self):
            self.joined, self.left = 0, 0

        def add_worker(self, scheduler=None, worker=None, **kw):
            self.joined += 1

        def remove_worker(self, scheduler=None, worker=None, **kw):
            self.left += 1

    return WorkerEvents()


def _worker_events(dask_scheduler=None):
    """``(joined, left)`` counted by :func:`_worker_events_plugin` (run with ``client.run_on_scheduler``)."""
    p = dask_scheduler.plugins["noiselab-worker-events"]
    return p.joined, p.left
