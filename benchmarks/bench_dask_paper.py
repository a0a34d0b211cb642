"""Paper sketch: the chunked spectral paths on 4 to 16 workers (graph size, all-to-all volume, memory per worker).

Run from the repository root::

    python3 benchmarks/bench_dask_paper.py              # replaces its section of benchmarks/bench_dask.md
    python3 benchmarks/bench_dask_paper.py --no-write

This machine has 2 cores, so nothing here runs on 4 to 16 workers. What is
counted, not estimated: the task graph of ``snow(..., chunks=)`` and
``spectral_noise(..., chunks=)`` built here (``len`` of the graph, dask's
rechunk tasks included; nothing is computed) and the bytes each all-to-all
transpose moves (the nbytes of the array that is rechunked). What is
estimated on paper: the memory per worker, from two terms:

- the largest task's arrays (the bound ``scale.spectral._check_worker_memory``
  checks before building the graph) plus 250 MiB of imports per worker
  process (numba, scipy, distributed; measured in ``bench_dask_memory.py``);
- for dask's in-memory rechunk, the worst case when every piece of a
  transpose is in memory at once, spread evenly: all-to-all bytes / workers
  (the spilled path, ``spill=``, writes the pieces to zarr instead: 0 here).
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from noiselab.lab.measure import header_lines, run_info  # noqa: E402

MARK = "<!-- paper sketch: python3 benchmarks/bench_dask_paper.py -->"
END = "<!-- end of paper sketch -->"
WORKERS = (4, 8, 16)
IMPORTS_MIB = 250


def _case(name, lazy, a2a_bytes, largest_bytes, out_bytes):
    return dict(name=name, tasks=len(lazy.__dask_graph__()), a2a=a2a_bytes, largest=largest_bytes, out=out_bytes,
                chunk=tuple(max(c) for c in lazy.chunks))


def cases():
    """Build the graphs (not computed) and count; the all-to-all bytes from the transposed arrays' sizes."""
    from noiselab.scale import spectral as S
    from noiselab.snowfall import snow
    from noiselab.spectral import spectral_noise

    out = []
    for shape, chunks in (((128, 1024, 1024), (128, 256, 256)), ((128, 1024, 1024), (16, 512, 1024)),
                          ((512, 2048, 2048), (16, 512, 2048))):
        T, H, W = shape
        V = T * H * W * 4
        K = W // 4 + 1  # the default band's kx columns (up to W/4 cycles/frame): what the transpose moves
        stage = T * H * K * 8                        # complex64 t/y slabs, kx within the band
        ct, cy = chunks[0], chunks[1]
        largest = max(T * H * 8, ct * cy * (K * 8 + 2 * W * 4))  # one kx column's slab or one x-pass chunk
        keep = S._hold_raw
        for hold in (True, False):
            S._hold_raw = lambda nbytes, hold=hold: hold
            try:
                lazy = snow(shape, rng=0, chunks=chunks)
            finally:
                S._hold_raw = keep
            passes = 1 if hold else 2
            label = "one FFT pass (raw held)" if hold else "two FFT passes"
            out.append(_case(f"snow{shape}, chunks {chunks}, {label}", lazy, passes * stage,
                             largest + (V if hold else 0), V))
    for shape, chunks in (((512, 512, 512), (64, 512, 512)), ((1024, 1024, 1024), (32, 1024, 1024))):
        n = shape[-1]
        K = n // 2 + 1
        lead = int(np.prod(shape[:-1]))
        spec = lead * K * 8
        V = int(np.prod(shape)) * 4
        lazy = spectral_noise(shape, rng=0, chunks=chunks)
        largest = max(16 << 20, int(np.prod(chunks[:-1])) * (K * 8 + n * 4))
        out.append(_case(f"spectral_noise{shape}, chunks {chunks}", lazy, 2 * spec, largest, V))
    return out


def report(rows):
    mib = 2 ** 20
    L = ["| case | output MiB | tasks | all-to-all MiB (x output) | largest task MiB | "
         + " | ".join(f"per worker, {w} workers: in-memory rechunk / spill= (MiB)" for w in WORKERS) + " |",
         "|" + " --- |" * (5 + len(WORKERS))]
    for r in rows:
        held = "raw held" in r["name"]
        task = (r["largest"] - (r["out"] if held else 0)) / mib
        cells = []
        for w in WORKERS:
            raw = r["out"] / w / mib if held else 0.0  # the raw field waiting for its extremes, spread
            mem_rechunk = IMPORTS_MIB + task + raw + r["a2a"] / w / mib
            # spill= keeps the two-pass structure (t/y once into zarr, the x-pass twice): no raw field held
            cells.append(f"{mem_rechunk:.0f} / " + ("-" if held else f"{IMPORTS_MIB + task:.0f}"))
        L.append(f"| {r['name']} | {r['out'] / mib:.0f} | {r['tasks']:,} | {r['a2a'] / mib:.0f} "
                 f"({r['a2a'] / r['out']:.2f}) | {task:.0f} | " + " | ".join(cells) + " |")
    return L


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-write", action="store_true")
    ap.add_argument("--out", default=str(ROOT / "benchmarks" / "bench_dask.md"))
    a = ap.parse_args(argv)
    info = run_info("python3 benchmarks/bench_dask_paper.py", ["dask", "noiselab"])
    rows = cases()
    L = [MARK, "", "# Paper sketch: 4 to 16 workers", "", *header_lines(info), "",
         "Counted here: the task graph (`len` of the lazy array's graph, dask's rechunk tasks included; nothing "
         "computed). Estimated: the all-to-all volume (the bytes of each transposed array: snow's `(T, H, K)` "
         "complex64 t/y stage, K the band's kx columns, once or twice; spectral noise's half spectrum, twice) and "
         f"the memory per worker = {IMPORTS_MIB} MiB of imports + the largest task's arrays + (one-pass snow) its "
         "share of the raw field waiting for the extremes + (in-memory rechunk, worst case) its share of the "
         "all-to-all; with `spill=` the all-to-all goes through zarr and only the task term stays (`spill=` runs "
         "the two-pass structure: '-' in the one-pass rows). For reference, 2 workers of 600 MiB writing the "
         "first case's two-pass graph come to 250 + 320 + 514 / 2 = 827 MiB per worker by this estimate, past "
         "their limit: dask's in-memory rechunk is expected to lose workers there. The graph "
         "does not depend on the number of workers; memory per worker falls as 1 / workers only through the "
         "shared terms.", "", *report(rows), "",
         "As functions of the output volume V (float32 bytes) and W workers: snow's all-to-all is "
         "`8 T H K` bytes = 2 V K / W_x, about V/2 for the default band (K = W_x/4 + 1 columns of a W_x-wide "
         "frame), once with the raw field held, twice without; spectral noise's is 2 x (V/n) (n/2 + 1) x 2 = "
         "about 2V. Tasks grow as (kx slabs) x (output chunks) through the rechunk. Memory per worker with the "
         "in-memory rechunk: imports + largest task + (all-to-all + held raw) / W, so a worker's memory limit must "
         "exceed about 250 MiB + task + V (0.5 to 2) / W; with `spill=` it is imports + task, whatever V and W.",
         "", END]
    text = "\n".join(L)
    print(text)
    if not a.no_write:
        md = Path(a.out)
        cur = md.read_text() if md.exists() else ""
        if MARK in cur and END in cur:
            cur = cur[:cur.index(MARK)] + text + cur[cur.index(END) + len(END):]
        else:
            snow_mark = "<!-- snow sections: python3 benchmarks/bench_dask.py --snow -->"
            at = cur.index(snow_mark) if snow_mark in cur else len(cur)
            cur = cur[:at].rstrip("\n") + "\n\n" + text + "\n\n" + cur[at:]
        md.write_text(cur)


if __name__ == "__main__":
    main()
