"""Run every laboratory experiment and write ``RESULTS.md`` with its plots.

One command runs it all; a run writes to ``out/bench/`` under the current
folder (or ``--output DIR``), from an installed noiselab anywhere. The package
never writes into a git checkout: the published ``benchmarks/RESULTS.md`` is
written by the checkout's own script, ``python benchmarks/lab_run.py --publish``::

    noiselab bench                  # -> out/bench/RESULTS.md
    noiselab bench --quick --output /tmp/lab   # CI-size smoke run

The peers run in their own environment (an interpreter with them installed,
``--peers-python``; ``benchmarks/.venv-peers/bin/python`` in a checkout) in a
subprocess (:mod:`noiselab.lab.peers`); without one the peer section says so.
"""
from __future__ import annotations

import json
import math
import os
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from .experiments import (CAPABILITIES, Config, flake_scaling, pareto_sweeps, scaling_fits, snow_experiment,
                          snow_scaling, texture_experiment, texture_scaling)
from .figures import write_figures
from .measure import fit_exponent, machine_info
from .hashes import hash_experiment, hash_section
from .quality import quality_experiment, quality_section

__all__ = ["run_all", "md_table", "default_output"]


def default_output(quick=False) -> Path:
    """Where an ordinary run writes: ``out/bench`` (``out/bench-quick`` for ``--quick``) under the current folder."""
    return Path("out") / ("bench-quick" if quick else "bench")


def peers_missing_reason(peers_python=None):
    """Why the peers cannot run with the interpreter ``peers_python`` (a string), or None when it exists."""
    if peers_python is None:
        return ("no peer interpreter given (--peers-python: an environment with the peers installed, "
                "benchmarks/.venv-peers/bin/python in a checkout after `bash benchmarks/setup_peers.sh`)")
    if not Path(peers_python).exists():
        return f"peer interpreter missing ({peers_python}): run `bash benchmarks/setup_peers.sh`"
    return None


def _fmt(v):
    if v is None:
        return "-"
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    if isinstance(v, (int, np.integer)):
        return f"{int(v):,}"
    if isinstance(v, (float, np.floating)):
        v = float(v)
        if math.isnan(v):
            return "-"
        if math.isinf(v):
            return "inf"
        a = abs(v)
        if a == 0:
            return "0"
        if a >= 1e5 or a < 1e-3:
            return f"{v:.2e}"
        if a >= 100:
            return f"{v:.0f}"
        if a >= 10:
            return f"{v:.1f}"
        return f"{v:.3f}"
    if isinstance(v, (list, tuple)):
        return "(" + ", ".join(_fmt(x) for x in v) + ")"
    return str(v).replace("|", "/")


def md_table(rows, cols):
    """A Markdown table of ``rows`` (dicts); ``cols`` is a list of (key, header).

    Examples
    --------
    >>> print(md_table([{"a": 1, "b": 0.5}], [("a", "A"), ("b", "B")]))
    | A | B |
    | --- | --- |
    | 1 | 0.500 |
    """
    lines = ["| " + " | ".join(h for _, h in cols) + " |", "| " + " | ".join("---" for _ in cols) + " |"]
    for r in rows:
        lines.append("| " + " | ".join(_fmt(r.get(k)) for k, _ in cols) + " |")
    return "\n".join(lines)


# ----------------------------------------------------------------------------- peers

def run_peers(n, frames, repeats, timeout=900, peers_python=None):
    """Run :mod:`noiselab.lab.peers` with the peers' interpreter; returns (info, rows) or (None, reason)."""
    reason = peers_missing_reason(peers_python)
    if reason:
        return None, reason
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "peers.json"
        # the peers' interpreter imports this very noiselab (the one running), whichever folder holds it
        package_parent = str(Path(__file__).resolve().parents[2])
        env = dict(os.environ, PYTHONPATH=package_parent + os.pathsep + os.environ.get("PYTHONPATH", ""))
        cmd = [str(peers_python), "-m", "noiselab.lab.peers", "--n", str(n), "--frames", str(frames),
               "--repeats", str(repeats), "--json", str(out)]
        try:
            proc = subprocess.run(cmd, cwd=tmp, env=env, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return None, f"peer run timed out after {timeout} s"
        if proc.returncode != 0 or not out.exists():
            tail = (proc.stderr or proc.stdout).strip().splitlines()[-3:]
            return None, "peer run failed: " + " / ".join(tail)
        data = json.loads(out.read_text())
    return data["info"], data["rows"]


# ----------------------------------------------------------------------------- report

def _strip(rows):
    return [{k: v for k, v in r.items() if not k.startswith("_")} for r in rows]


def run_all(*, quick=False, output=None, peers=True, peers_python=None, log=print, command=None):
    """Run the experiments and write ``RESULTS.md``, ``results.json`` and the plots.

    Parameters
    ----------
    quick : bool
        CI-size run (seconds, tiny sizes); the numbers are not meaningful.
    output : path, optional
        Folder for ``RESULTS.md``; plots and JSON go to ``output/results/``.
        Default :func:`default_output` (``out/bench``).
    peers : bool
        Also run the peers (with ``peers_python``).
    peers_python : path, optional
        The interpreter of an environment with the peers installed; without
        it the peer section is skipped and says why.
    command : str, optional
        The command named in the report's header as the one that regenerates
        it (default: the ``noiselab bench`` command of this run).

    Returns
    -------
    dict with the tables (``texture``, ``snow``, ``scaling``, ``fits``, ``flakes``,
    ``sweeps``, ``peers``), ``info``, the written ``path`` and ``skipped``
    (section -> reason).
    """
    cfg = Config.quick_config() if quick else Config.full()
    out_dir = Path(output) if output is not None else default_output(quick)
    res_dir = out_dir / "results"
    res_dir.mkdir(parents=True, exist_ok=True)
    t_start = time.perf_counter()
    info = machine_info()
    results = {"info": info, "config": cfg.__dict__}
    steps = [("texture", lambda: texture_experiment(cfg)), ("texture_scaling", lambda: texture_scaling(cfg)),
             ("snow", lambda: snow_experiment(cfg)),
             ("scaling", lambda: snow_scaling(cfg)), ("flakes", lambda: flake_scaling(cfg)),
             ("sweeps", lambda: pareto_sweeps(cfg)), ("quality", lambda: quality_experiment(cfg)),
             ("hashes", lambda: hash_experiment(cfg))]
    for name, fn in steps:
        t0 = time.perf_counter()
        results[name] = fn()
        log(f"lab: {name} done in {time.perf_counter() - t0:.1f} s")
    results["fits"] = scaling_fits(results["scaling"])
    results["texture_fits"] = scaling_fits(results["texture_scaling"])
    fr = results["flakes"]
    results["flake_exponent"] = fit_exponent([r["flakes"] for r in fr], [r["time_s"] for r in fr])
    if peers:
        t0 = time.perf_counter()
        n = 128 if quick else 512
        pinfo, prows = run_peers(n, 8 if quick else 32, cfg.repeats, peers_python=peers_python)
        results["peer_info"], results["peers"] = pinfo, prows
        status = f"{len(prows)} cases" if isinstance(prows, list) else f"NOT RUN: {prows}"
        log(f"lab: peers done in {time.perf_counter() - t0:.1f} s ({status})")
    else:
        results["peer_info"], results["peers"] = None, "peers not run (--no-peers)"
    skipped = {}
    if not isinstance(results["peers"], list):
        skipped["4. the peers"] = results["peers"]
    for section, why in skipped.items():
        log(f"lab: SKIPPED section {section}: {why}")
    results["skipped"] = skipped
    results["elapsed_s"] = time.perf_counter() - t_start
    write_figures(results, res_dir)     # redrawn from results.json alone by `benchmarks/lab_run.py --replot`
    from ..io import atomic_output

    with atomic_output(res_dir / "results.json") as tmp:
        Path(tmp).write_text(json.dumps(_json_ready(results), indent=1, default=str))
    md = render_markdown(results, quick=quick, command=command)
    path = out_dir / "RESULTS.md"
    with atomic_output(path) as tmp:
        Path(tmp).write_text(md)
    results["path"] = path
    log(f"lab: wrote {path} ({results['elapsed_s']:.0f} s)")
    return results


def _json_ready(obj):
    if isinstance(obj, dict):
        return {str(k): _json_ready(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_json_ready(v) for v in obj]
    if isinstance(obj, (np.floating, np.integer)):
        return obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return str(obj)
    return obj


def _winner(rows, key, best="min"):
    rs = [r for r in rows if r.get(key) is not None and np.isfinite(r[key])]
    if not rs:
        return None
    return (min if best == "min" else max)(rs, key=lambda r: r[key])


def render_markdown(res, *, quick=False, command=None):
    info = res["info"]
    cmd = command or ("python3 -m noiselab bench --quick" if quick else "python3 -m noiselab bench")
    L = []
    L.append("# noiselab laboratory results\n")
    # the version that made this report, on a line of its own (tests/test_gabor_lab.py reads it)
    L.append(f"Made by noiselab {info.get('noiselab', 'unknown')}.\n")
    for section, why in res.get("skipped", {}).items():
        L.append(f"> **Section {section} skipped in this run:** {why}\n")
    if quick:
        L.append("> **Quick run** (CI sizes): the numbers only show that the pipeline works.\n")
    L.append(f"Regenerate with `{cmd}`; this run took {res['elapsed_s']:.0f} s. "
             "Every number below was measured in that one run, on this machine:\n")
    L.append(md_table([info], [(k, k) for k in info]) + "\n")
    pi = res.get("peer_info")
    if pi:
        L.append("Peer environment (`benchmarks/.venv-peers`, Python " + pi["python"] + "): " +
                 ", ".join(f"{k} {v}" for k, v in pi["versions"].items()) + ".\n")
    L.append(_headline(res))
    L.append("**How to read the times.** Each case is timed in the same process as its floor, in interleaved "
             "rounds (floor, case, floor, case, ...), median of "
             f"{res['config']['repeats']} rounds after one warm-up; `x floor` is the median of the per-round ratios "
             "to the floor: a bare `scipy.fft.irfftn` producing the same float32 output (spectral work) or "
             "allocating and writing a float64 array of the output size (lattice work). Other helpers ran their own "
             "benchmarks on this shared 2-core machine at the same time, so absolute seconds drift by tens of per "
             "cent between rounds; the ratios side by side are what hold. Peak memory is the `tracemalloc` peak of "
             "one call (every numpy allocation; not the FFT library's or numba's own scratch).\n")

    # --- texture
    L.append("## 1. Same scene: 1/f textures, spectral against lattice\n")
    L.append("Scene: amplitude spectrum `f**-(d/2)` (equal energy per octave) from f0 = "
             f"{res['config']['texture_f0']:g} cycles/frame to Nyquist. Spectral: `spectral_noise(exponent=d/2, "
             "band=(f0, N/2))`. Lattice: `fractal_sum` of `LatticeNoise` (each kernel; value and gradient basis), "
             "lacunarity 2, gain 1 (equal amplitude per octave = equal energy per octave), base density "
             "`f0 / lattice_peak(kernel)` cells per frame, octaves up to the sampling Nyquist. Figures from "
             "`noiselab.analysis` on the standardised field: slope error = `spectral_slope` over (2 f0, N/4) minus "
             "the target -d/2; octave ripple = `octave_energy(f0, N/2).db_range` (0 dB is ideal); anisotropy = "
             "`anisotropy` (0 isotropic; in 3-D the mean over the three central slices); band leakage = power "
             "outside (f0, N/2); range = (max - min) / sd.\n")
    tcols = [("scene", "scene"), ("method", "method"), ("slope_error", "slope err"), ("octave_ripple_db", "ripple dB"),
             ("anisotropy", "aniso"), ("band_leakage", "leakage"), ("range_sd", "range/sd"), ("time_s", "time s"),
             ("x_fft_floor", "x FFT floor"), ("x_write_floor", "x write floor"), ("points_per_s", "points/s"),
             ("peak_mib", "peak MiB")]
    L.append(md_table(res["texture"], tcols) + "\n")
    for dim in (2, 3):
        rs = [r for r in res["texture"] if r["dim"] == dim]
        lat = [r for r in rs if r["family"] == "lattice"]
        sp = next(r for r in rs if r["family"] == "spectral")
        if not lat:
            continue
        bs = min(lat, key=lambda r: abs(r["slope_error"]))
        ba = min(lat, key=lambda r: r["anisotropy"])
        bl = min(lat, key=lambda r: r["band_leakage"])
        br = min(lat, key=lambda r: r["octave_ripple_db"])
        fl = min(lat, key=lambda r: r["time_s"])
        L.append(f"- {dim}-D: spectral: slope error {sp['slope_error']:+.3f}, ripple {sp['octave_ripple_db']:.2f} dB, "
                 f"anisotropy {sp['anisotropy']:.3f}, leakage {sp['band_leakage']:.1e}, {sp['x_fft_floor']:.1f}x the "
                 f"FFT floor. Best lattice on each figure: slope {bs['method']} ({bs['slope_error']:+.3f}); ripple "
                 f"{br['method']} ({br['octave_ripple_db']:.2f} dB); anisotropy {ba['method']} ({ba['anisotropy']:.3f}, "
                 f"{ba['anisotropy'] / max(sp['anisotropy'], 1e-9):.0f}x the spectral field's); leakage {bl['method']} "
                 f"({bl['band_leakage']:.3f}); time {fl['method']} ({fl['time_s'] / sp['time_s']:.2f}x the spectral "
                 "time). No lattice sum matches the spectral field on all figures at once.")
        gb = next((r for r in rs if r["family"] == "gabor"), None)
        if gb:
            L.append(f"  Sparse Gabor (octave layers): slope error {gb['slope_error']:+.3f}, ripple "
                     f"{gb['octave_ripple_db']:.2f} dB, anisotropy {gb['anisotropy']:.3f}, leakage "
                     f"{gb['band_leakage']:.3f}, {gb['time_s'] / sp['time_s']:.1f}x the spectral time: the spectrum "
                     "of the spectral field within its lobes' blur, evaluated point by point like the lattice.")
    L.append("\nScaling of 2-D textures with the image size (N x N):\n")
    L.append(md_table(res["texture_scaling"], [("method", "method"), ("size", "N"), ("time_s", "time s"),
                                               ("x_fft_floor", "x FFT floor"), ("peak_mib", "peak MiB")]) + "\n")
    L.append(md_table(res["texture_fits"], [("method", "method"), ("time_exponent", "time k (time ~ pixels**k)"),
                                            ("time_exponent_nlogn", "k of time / log2(pixels)"),
                                            ("time_exponent_top", "k, two largest sizes"),
                                            ("memory_exponent", "memory k")]) + "\n")
    L.append("\n![texture spectra](results/texture_spectra.png)\n")
    L.append("What each can do that the other cannot:\n")
    L.append(md_table([{"c": c, "s": s, "l": l, "g": g} for c, s, l, g in CAPABILITIES],
                      [("c", "capability"), ("s", "spectral (IFFT)"), ("l", "lattice"), ("g", "sparse Gabor")]) + "\n")

    # --- snow
    L.append("## 2. Same scene: falling snow, tent IFFT against layered lattice against particles against sparse "
             "Gabor\n")
    srow = res["snow"][0]
    L.append(f"Scene: {srow['scene']}, straight down. Tent energy = `tent_energy(video, c, band)` (fraction of "
             "the power within one temporal-frequency cell of the tent); parallax error = RMS relative deviation of "
             "`speed_profile` band speeds (two bands per octave) from the law `c N / (2 pi f)`; loop seam = "
             "`loop_seam` (1 = a seamless loop); mean alpha = average opacity (coverage).\n")
    L.append(md_table(res["snow"], [("method", "method"), ("tent_energy", "tent energy"),
                                    ("parallax_rms_error", "parallax err"), ("loop_seam", "loop seam"),
                                    ("mean_alpha", "mean alpha"), ("time_s", "time s"),
                                    ("x_fft_floor", "x FFT floor"), ("peak_mib", "peak MiB (traced)"),
                                    ("rss_peak_mib", "peak RSS MiB"), ("output_mib", "output MiB")]) + "\n")
    L.append("Peak RSS: resident-set high-water mark of one call above the process's baseline, in a fresh "
             "subprocess after a warm-up call (sees the FFT library's and numba's scratch too).\n")
    L.append("![speed per band](results/snow_parallax.png)\n")
    L.append("Scaling with the frame size (" + str(res["config"]["scaling_frames"]) + " frames; W x W frames):\n")
    L.append(md_table(res["scaling"], [("method", "method"), ("size", "W"), ("voxels", "voxels"),
                                       ("time_s", "time s"), ("x_fft_floor", "x FFT floor"),
                                       ("peak_mib", "peak MiB")]) + "\n")
    L.append("Fitted exponents (time ~ voxels**k over all sizes; `k (N log N)` fits time / log2(voxels), 1.0 for a "
             "clean N log N law; the two largest sizes alone show the asymptotic law once fixed per-call costs "
             "(numba dispatch, per-frame grid set-up, thread start) stop counting):\n")
    L.append(md_table(res["fits"], [("method", "method"), ("time_exponent", "time k"),
                                    ("time_exponent_nlogn", "time k (N log N)"),
                                    ("time_exponent_top", "time k, two largest sizes"),
                                    ("memory_exponent", "memory k")]) + "\n")
    fs = res["config"]["flake_shape"]
    L.append(f"Particles as the flake count grows ({'x'.join(map(str, fs))}; time exponent "
             f"{res['flake_exponent']:.2f} against flakes):\n")
    L.append(md_table(res["flakes"], [("flakes", "flakes"), ("time_s", "time s"), ("x_fft_floor", "x FFT floor"),
                                      ("x_tent_snow", "x tent snow"), ("peak_mib", "peak MiB"),
                                      ("mean_alpha", "mean alpha")]) + "\n")
    L.append("![scaling](results/snow_scaling.png)\n")
    L.append(_snow_verdict(res))

    # --- pareto
    L.append("## 3. Speed against error\n")
    L.append("Each sweep: time (median) against an error a user could see, log-log; the knee is the cheapest "
             "setting whose error is at or below the stated threshold (red star in the plot).\n")
    for s in res["sweeps"]:
        extra = [k for k in ("parallax_error", "tent_energy", "slope_error", "anisotropy", "octave_ripple_db", "peak_mib")
                 if k in s["points"][0]]
        cols = [("setting", "setting"), ("time_s", "time s"), ("x_floor", "x floor"), ("error", "error")] + \
               [(k, k) for k in extra]
        L.append(f"### {s['name']}\n")
        L.append(f"Error: {s['error']}; threshold {s['threshold']:.3g}. **Knee: {s['knee'] or 'none below threshold'}**."
                 + (f" {s['note']}." if s.get("note") else "") + "\n")
        L.append(md_table(s["points"], cols) + "\n")
    L.append("![pareto](results/pareto.png)\n")

    # --- peers
    L.append("## 4. The peers, side by side in one run\n")
    pr = res["peers"]
    if not isinstance(pr, list):
        L.append(f"Not measured: {pr}\n")
    else:
        L.append("Run in the peer environment (`PYTHONPATH=. benchmarks/.venv-peers/bin/python -m noiselab.lab.peers`), "
                 "one process, all cases interleaved with their floor. Quality figures use the same analysers: for "
                 "the 1/f images the target slope is -1; for six octaves of gain 1/2 it is -2; the one-octave "
                 "lattice slope has no target (shown for the spectrum's shape). A peer that failed is listed with "
                 "its error.\n")
        for g in dict.fromkeys(r["group"] for r in pr):
            rs = [r for r in pr if r["group"] == g]
            L.append(f"### {g}\n")
            ok = [r for r in rs if r["status"] == "ok"]
            if ok and "best_velocity" in ok[0]:
                cols = [("case", "case"), ("time_s", "time s"), ("x_floor", "x floor"), ("points_per_s", "points/s"),
                        ("peak_mib", "peak MiB"), ("best_velocity", "best velocity (vx, vy)"),
                        ("motion_energy_v(0,1)", "energy on plane v=(0,1)"), ("loop_seam", "loop seam")]
            else:
                cols = [("case", "case"), ("dtype", "dtype"), ("time_s", "time s"), ("x_floor", "x floor"),
                        ("points_per_s", "points/s"), ("peak_mib", "peak MiB"), ("slope", "slope"),
                        ("anisotropy", "aniso"), ("octave_ripple_db", "ripple dB"), ("outside_band", "outside fit band"),
                        ("axis_excess", "axis excess"), ("mean_spread", "mean spread"), ("min", "min"), ("max", "max")]
            L.append(md_table(ok, cols) + "\n")
            for r in rs:
                if r["status"] != "ok":
                    L.append(f"- **{r['case']}: failed** - `{r['error']}`")
            L.append("")
        L.append("![peers](results/peers.png)\n")
    L.append(quality_section(res))
    if "hashes" in res:
        L.append(hash_section(res["hashes"]))
    L.append("## Notes\n")
    L.append("- Other benchmark reports: [bench_snow.md](bench_snow.md) (snow against its floor, MotionClouds), "
             "[bench_lattice.md](bench_lattice.md) (lattice peers, precision), [bench_mesh.md](bench_mesh.md).")
    L.append("- Raw numbers of this run: [results/results.json](results/results.json).")
    L.append("- pyfftw is measured when installed (it is not a dependency; the FFT sweep says when it was absent).")
    L.append("- Worker counts above 1 (scipy.fft workers, numba's parallel particle splatting) compete with the other "
             "helpers' benchmarks for the machine's 2 cores, so their gains here are a floor, not a promise.")
    return "\n".join(L) + "\n"


def _headline(res):
    """The key figures of this run, computed from the tables below."""
    H = ["## Headline (this run)\n"]
    snow = {r["method"].split(" (")[0]: r for r in res["snow"]}
    t, lay, par = snow["tent IFFT"], snow["layered lattice"], snow["particles"]
    scene = res["snow"][0]["scene"]
    H.append(f"- {scene[0].upper() + scene[1:]}: tent IFFT {t['x_fft_floor']:.2f}x a bare inverse FFT, "
             f"{t['peak_mib']:.1f} MiB, tent energy {t['tent_energy']:.3f}, parallax error "
             f"{t['parallax_rms_error']:.3f}, loop seam {t['loop_seam']:.2f}; layered lattice "
             f"{lay['time_s'] / t['time_s']:.1f}x its time, tent energy {lay['tent_energy']:.3f}, parallax "
             f"{lay['parallax_rms_error']:.3f}, seam {lay['loop_seam']:.2f}; particles {par['time_s'] / t['time_s']:.1f}x, "
             f"tent energy {par['tent_energy']:.3f}, parallax {par['parallax_rms_error']:.3f}, seam {par['loop_seam']:.2f}.")
    gs = next((r for k, r in snow.items() if k.startswith("sparse Gabor")), None)
    if gs:
        H.append(f"- The same snow by sparse Gabor kernels (no period, any window): {gs['time_s'] / t['time_s']:.1f}x "
                 f"the tent IFFT's time, tent energy {gs['tent_energy']:.3f}, parallax {gs['parallax_rms_error']:.3f}, "
                 f"seam {gs['loop_seam']:.2f} (it does not loop: it never repeats).")
    for dim in (2, 3):
        rs = [r for r in res["texture"] if r["dim"] == dim]
        if not rs:
            continue
        sp = next(r for r in rs if r["family"] == "spectral")
        lat = [r for r in rs if r["family"] == "lattice"]
        gb = next((r for r in rs if r["family"] == "gabor"), None)
        if gb:
            H.append(f"- 1/f texture {dim}-D, sparse Gabor: slope error {gb['slope_error']:+.3f}, anisotropy "
                     f"{gb['anisotropy']:.3f}, leakage {gb['band_leakage']:.3f}, {gb['time_s'] / sp['time_s']:.1f}x "
                     "the spectral field's time.")
        H.append(f"- 1/f texture {dim}-D ({sp['n']}^{dim}): spectral slope error {sp['slope_error']:+.3f}, "
                 f"anisotropy {sp['anisotropy']:.3f}, leakage {sp['band_leakage']:.0e}; lattice sums: slope error "
                 f"{min(r['slope_error'] for r in lat):+.3f}..{max(r['slope_error'] for r in lat):+.3f}, anisotropy "
                 f"{min(r['anisotropy'] for r in lat):.3f}..{max(r['anisotropy'] for r in lat):.3f}, leakage "
                 f"{min(r['band_leakage'] for r in lat):.3f}..{max(r['band_leakage'] for r in lat):.3f}; time "
                 f"{min(r['time_s'] for r in lat) / sp['time_s']:.2f}..{max(r['time_s'] for r in lat) / sp['time_s']:.2f}x "
                 "the spectral field's.")
    pr = res.get("peers")
    if isinstance(pr, list):
        mc = next((r for r in pr if r["case"] == "MotionClouds" and r["status"] == "ok"), None)
        ns = next((r for r in pr if r["case"] == "noiselab snow" and r["status"] == "ok"), None)
        if mc and ns:
            H.append(f"- Spectral video against MotionClouds ({mc['group'].split()[-1]}): noiselab snow "
                     f"{ns['x_floor']:.2f}x the FFT floor and {ns['peak_mib']:.1f} MiB; MotionClouds "
                     f"{mc['x_floor']:.1f}x and {mc['peak_mib']:.1f} MiB.")
        for g in dict.fromkeys(r["group"] for r in pr if r["group"].startswith("lattice")):
            ok = [r for r in pr if r["group"] == g and r["status"] == "ok"]
            ours = [r for r in ok if r["case"].startswith("noiselab")]
            peers = [r for r in ok if not r["case"].startswith("noiselab")]
            if ours and peers:
                bp = max(peers, key=lambda r: r["points_per_s"])
                mine = "; ".join(f"{r['case']} {r['points_per_s']:.2e} points/s "
                                 f"({r['points_per_s'] / bp['points_per_s']:.2f}x)" for r in ours)
                H.append(f"- {g}: fastest peer {bp['case']} {bp['points_per_s']:.2e} points/s; {mine}.")
    knees = "; ".join(f"{s['name']}: {s['knee'] or 'none'}" for s in res["sweeps"])
    H.append(f"- Knees (cheapest setting under the visibility threshold): {knees}.\n")
    return "\n".join(H)


def _snow_verdict(res):
    """Which method is best on each figure of this run (computed, not asserted)."""
    rows = res["snow"]
    short = {r["method"]: r["method"].split(" (")[0] for r in rows}
    figures = [("tent energy", "tent_energy", max), ("parallax error", "parallax_rms_error", min),
               ("loop seam (closest to 1)", "_seam_dist", min), ("time", "time_s", min), ("peak memory", "peak_mib", min)]
    for r in rows:
        r["_seam_dist"] = abs(r["loop_seam"] - 1.0)
    lines = ["**Where each method wins (this run).** Best on each figure: " +
             "; ".join(f"{label}: {short[best(rows, key=lambda r: r[k])['method']]}" for label, k, best in figures)
             + ".\n"]
    tent = next(r for r in rows if r["method"].startswith("tent"))
    lay = next(r for r in rows if r["method"].startswith("layered"))
    par = next(r for r in rows if r["method"].startswith("particles"))
    big = [r for r in res["scaling"] if r["size"] == max(x["size"] for x in res["scaling"])]
    t_big = {r["method"].split(" (")[0]: r["time_s"] for r in big}
    lines.append(f"- Tent IFFT: the only exact loop (seam {tent['loop_seam']:.2f}); energy on the tent "
                 f"{tent['tent_energy']:.3f} at {tent['x_fft_floor']:.1f}x the FFT floor. Its limits: it renders the "
                 "whole video at once (memory grows with T x H x W) and one period of it (longer videos tile or loop).")
    lines.append(f"- Layered lattice: tent energy {lay['tent_energy']:.3f}, parallax error "
                 f"{lay['parallax_rms_error']:.3f} (each layer is one rigid speed; its ~1-octave spectrum blends "
                 f"neighbouring speeds), loop seam {lay['loop_seam']:.2f} (no loop), {lay['time_s'] / tent['time_s']:.1f}x "
                 f"the tent's time here and {t_big.get('layered lattice', float('nan')) / t_big['tent IFFT']:.1f}x at "
                 f"{max(x['size'] for x in res['scaling'])} px. Its reason to exist: every frame is independent "
                 "(`start=` renders any piece bit-identically), so a video of any length streams in pieces of bounded "
                 "memory, and the noise can be evaluated at any point, not only on a grid.")
    fr = res["flakes"]
    cheaper = [r["flakes"] for r in fr if r["x_tent_snow"] < 1.0]
    cross = (f"in the flake sweep particles beat the tent IFFT's time up to {max(cheaper):,} flakes per "
             f"{'x'.join(map(str, res['config']['flake_shape']))} (mean alpha "
             f"{next(r['mean_alpha'] for r in fr if r['flakes'] == max(cheaper)):.2f})") if cheaper else \
        "in the flake sweep particles never beat the tent IFFT's time"
    blur = next((r for r in rows if r["method"].startswith("particles, motion")), None)
    if blur is not None:
        cross += (f"; motion blur (each flake averaged over the shutter) changes tent energy to "
                  f"{blur['tent_energy']:.3f} and parallax error to {blur['parallax_rms_error']:.3f} at "
                  f"{blur['time_s'] / par['time_s']:.1f}x the unblurred time")
        if abs(blur["tent_energy"] - par["tent_energy"]) < 0.1:
            cross += ": the particles' shortfall is their broadband spatial spectrum, not temporal aliasing"
    lines.append(f"- Particles: tent energy {par['tent_energy']:.3f}, parallax error {par['parallax_rms_error']:.3f} "
                 "(a disc's spectrum is broadband, so every band mixes flake speeds), loop seam "
                 f"{par['loop_seam']:.2f}, {par['time_s'] / tent['time_s']:.1f}x the tent's time at the default "
                 f"density ({t_big.get('particles', float('nan')) / t_big['tent IFFT']:.1f}x at "
                 f"{max(x['size'] for x in res['scaling'])} px). Cost grows with flakes x frames x flake area "
                 f"(exponent {res['flake_exponent']:.2f} against flakes), not with the band; {cross}. It wins for sparse scenes, "
                 "hard-edged flakes and anything per-flake (landing, collisions, lighting), which no spectral method "
                 "expresses.\n")
    for r in rows:
        r.pop("_seam_dist", None)
    return "\n".join(lines)
