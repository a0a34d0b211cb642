"""The timing harness (noiselab.lab.measure) with a fake clock, and the benchmark scripts' command lines.

No timing is asserted: every duration below is what a fake clock was told to advance by.
"""
from __future__ import annotations

import datetime
import importlib.util
import os
import sys
from pathlib import Path

import numpy as np
import pytest

from noiselab.lab.measure import (
    Laps,
    Stopwatch,
    Timings,
    header_lines,
    interleaved,
    machine_info,
    markdown_table,
    run_info,
    time_against_floor,
)

ROOT = Path(__file__).resolve().parents[1]


class FakeClock:
    """A clock that only moves when a candidate says how long it took; logs every call."""

    def __init__(self, costs):
        self.t = 0.0
        self.round = -1
        self.log = []
        self.costs = costs  # (name, round) -> seconds, or name -> seconds

    def __call__(self):
        return self.t

    def candidate(self, name):
        def fn(*args):
            self.log.append((name, args))
            c = self.costs.get((name, args[0] if args else None), self.costs.get(name, 1.0))
            self.t += c
        return fn


def _cands(clock, names):
    return {n: clock.candidate(n) for n in names}


def test_rotate_order_and_warmup_calls():
    clock = FakeClock({})
    t = interleaved(_cands(clock, "abc"), repeats=4, warmup=1, timer=clock, collect=False)
    assert t.calls == [(-1, "a"), (-1, "b"), (-1, "c"),
                       (0, "a"), (0, "b"), (0, "c"),
                       (1, "b"), (1, "c"), (1, "a"),
                       (2, "c"), (2, "a"), (2, "b"),
                       (3, "a"), (3, "b"), (3, "c")]
    assert [name for name, _ in clock.log] == [name for _, name in t.calls]
    assert all(len(v) == 4 for v in t.raw.values())


@pytest.mark.parametrize("order, second", [("fixed", ["a", "b", "c"]), ("alternate", ["c", "b", "a"])])
def test_fixed_and_alternate_orders(order, second):
    clock = FakeClock({})
    t = interleaved(_cands(clock, "abc"), repeats=3, warmup=0, order=order, timer=clock, collect=False)
    rounds = [[n for r, n in t.calls if r == k] for k in range(3)]
    assert rounds == [["a", "b", "c"], second, ["a", "b", "c"]]


def test_warmup_excluded_from_every_statistic():
    # the warm-up call (round -1) costs 100 s, every timed call 2 s (case) or 1 s (floor)
    clock = FakeClock({("case", -1): 100.0, ("floor", -1): 100.0, "case": 2.0, "floor": 1.0})
    t = interleaved(_cands(clock, ["floor", "case"]), repeats=5, warmup=2, timer=clock, round_arg=True, collect=False)
    assert list(t.raw["case"]) == [2.0] * 5 and list(t.raw["floor"]) == [1.0] * 5
    assert t["case"] == 2.0 and t.min("case") == 2.0 and t.ratio("case", "floor") == 2.0
    assert sum(1 for r, _ in t.calls if r == -1) == 4  # 2 warm-up rounds x 2 candidates, untimed
    assert [args for name, args in clock.log if name == "case"] == [(-1,), (-1,), (0,), (1,), (2,), (3,), (4,)]


def test_ratio_is_median_of_per_round_ratios_not_ratio_of_medians():
    # the load jumps by 4x from round 2 on, and in round 4 hits the floor but not the case
    floor = [1.0, 1.0, 4.0, 4.0, 4.0]
    case = [2.0, 2.0, 8.0, 8.0, 3.0]
    costs = {**{("floor", r): v for r, v in enumerate(floor)}, **{("case", r): v for r, v in enumerate(case)}}
    clock = FakeClock(costs)
    t = interleaved(_cands(clock, ["floor", "case"]), repeats=5, warmup=0, timer=clock, round_arg=True, collect=False)
    assert np.allclose(t.ratios("case", "floor"), [2, 2, 2, 2, 0.75])
    assert t.ratio("case", "floor") == 2.0
    assert t["case"] / t["floor"] == 0.75  # what a ratio of medians would have said
    assert t.ratio("floor", "case") == 0.5


def test_work_units_give_rates():
    clock = FakeClock({"a": 0.5, "b": 0.25})
    t = interleaved(_cands(clock, "ab"), repeats=5, timer=clock, units=1000, collect=False)
    assert t.rate("a") == 2000.0 and t.rate("b") == 4000.0
    t = interleaved(_cands(clock, "ab"), repeats=5, timer=clock, units={"a": 10}, collect=False)
    assert t.rate("a") == 20.0 and t.rate("b", 100) == 400.0
    with pytest.raises(ValueError, match="work units"):
        t.rate("b")


def test_laps_recorded_per_round():
    clock = FakeClock({})

    def staged(r):
        sw = Stopwatch(timer=clock)
        sw("build", lambda: setattr(clock, "t", clock.t + 1.0 + r))
        sw("fft", lambda: setattr(clock, "t", clock.t + 3.0))
        sw("build", lambda: setattr(clock, "t", clock.t + 1.0))  # laps of one name add up
        return sw.laps

    t = interleaved({"floor": clock.candidate("floor"), "snow": staged}, repeats=5, warmup=1, timer=clock,
                    round_arg=True, collect=False)
    assert list(t.raw["build"]) == [2.0, 3.0, 4.0, 5.0, 6.0]
    assert list(t.raw["fft"]) == [3.0] * 5
    assert list(t.raw["snow"]) == [5.0, 6.0, 7.0, 8.0, 9.0]
    assert t.ratio("fft", "snow") == pytest.approx(3.0 / 7.0)
    assert isinstance(Laps(a=1.0), dict)


def test_bad_arguments_are_refused():
    with pytest.raises(ValueError, match="repeats"):
        interleaved({"a": lambda: None}, repeats=4, min_repeats=5)
    with pytest.raises(ValueError, match="warmup"):
        interleaved({"a": lambda: None}, warmup=-1)
    with pytest.raises(ValueError, match="order"):
        interleaved({"a": lambda: None}, order="random")
    with pytest.raises(ValueError, match="candidates"):
        interleaved({})
    with pytest.raises(ValueError, match="lap"):
        interleaved({"a": lambda: Laps(b=1.0), "b": lambda: None}, repeats=1, warmup=0, collect=False)
    with pytest.raises(TypeError, match="repeats"):
        interleaved({"a": lambda: None}, repeats=5.0)


def test_time_against_floor_runs_floor_first_and_keeps_its_format():
    clock = FakeClock({"floor": 1.0, "x": 3.0, "y": 0.5})
    order = []
    cands = {k: (lambda k=k: (order.append(k), clock.candidate(k)())) for k in ("x", "y")}
    floor = lambda: (order.append("floor"), clock.candidate("floor")())
    r = time_against_floor(cands, floor, repeats=5, warmup=1, timer=clock, collect=False)
    assert order == ["floor", "x", "y"] * 6
    assert r["x"] == {"median_s": 3.0, "ratio": 3.0, "times": [3.0] * 5}
    assert r["y"]["ratio"] == 0.5 and r["floor"] == {"median_s": 1.0, "ratio": 1.0, "times": [1.0] * 5}


def test_run_info_and_header_lines():
    now = datetime.datetime(2026, 1, 2, 3, 4, tzinfo=datetime.UTC)
    info = run_info("python3 benchmarks/bench_x.py --repeats 7", ["numpy", "no-such-dist-xyz"], now=now, load=1.25)
    assert info["date"] == "2026-01-02 03:04 UTC"
    assert info["load"] == 1.25 and info["cores"] == (os.cpu_count() or 1)
    assert info["versions"]["numpy"] == np.__version__
    assert list(info["versions"])[:3] == ["python", "numpy", "numba"]
    assert info["versions"]["no-such-dist-xyz"] == "not installed"
    text = "\n".join(header_lines(info, timing="median of 7 interleaved rounds"))
    for expected in ("- date: 2026-01-02 03:04 UTC", "`python3 benchmarks/bench_x.py --repeats 7`", info["cpu"],
                     f"{info['cores']} cores", "shared with other jobs", "at start 1.2", "no-such-dist-xyz not installed",
                     "- timing: median of 7 interleaved rounds"):
        assert expected in text
    assert "load (1 min) at start" in machine_info()


def test_markdown_table_and_timings_table():
    assert markdown_table(["a", "b"], [[1, "x"]], align="lr") == ["| a | b |", "| --- | ---: |", "| 1 | x |"]
    with pytest.raises(ValueError, match="align"):
        markdown_table(["a", "b"], [], align="l")
    with pytest.raises(ValueError, match="cells"):
        markdown_table(["a", "b"], [[1]])
    t = Timings({"floor": [1.0, 2.0, 1.0], "f": [4.0, 4.0, 2.0]}, units={"f": 8})
    lines = t.table("floor", labels={"f": "my f"})
    assert lines[0] == "| candidate | median s | min s | x floor | pts/s |"
    assert lines[3] == "| my f | 4 | 2 | 2 | 2 |"


# ------------------------------------------------------------------ the benchmark scripts' command lines

SCRIPTS = {
    "bench_snow": (["--quick", "--rounds", "7", "--shape", "8", "64", "64", "--workers", "1", "2", "--no-peer"],
                   {"quick": True, "rounds": 7, "shape": [8, 64, 64], "workers": [1, 2], "no_peer": True}),
    "bench_lattice": (["--repeats", "7", "--quick", "--output", "/tmp/x.md", "--hash-only"],
                      {"repeats": 7, "quick": True, "output": "/tmp/x.md", "hash_only": True}),
    "bench_analysis": (["--quick", "--rounds", "6"], {"quick": True, "rounds": 6}),
    "bench_spectral": (["--rounds", "9", "--quick", "--before", "5a730d9", "--workers", "1", "2", "--output", "o.md",
                        "--exponents"],
                       {"rounds": 9, "quick": True, "before": "5a730d9", "workers": [1, 2], "output": "o.md",
                        "exponents": True}),
    "bench_mesh": (["--count", "300", "--octaves", "3", "--size", "128", "--repeats", "5", "--output", "/tmp/b.md"],
                   {"count": 300, "octaves": 3, "size": 128, "repeats": 5, "output": "/tmp/b.md"}),
    "bench_derivatives": (["--repeats", "9", "--quick"], {"repeats": 9, "quick": True}),
    "bench_contract": (["--repeats", "11"], {"repeats": 11}),
    "bench_dask": (["--quick", "--repeats", "3", "--out", "d.md", "--snow"],
                   {"quick": True, "repeats": 3, "out": "d.md", "snow": True}),
}


@pytest.mark.parametrize("name", sorted(SCRIPTS))
def test_bench_script_imports_and_parses_its_flags(name, monkeypatch):
    import numba  # noqa: F401  (its thread count is fixed before a script's NUMBA_NUM_THREADS default)

    had_product = hasattr(np, "product")
    environ = dict(os.environ)
    monkeypatch.setattr(sys, "path", list(sys.path))
    try:
        spec = importlib.util.spec_from_file_location(f"_bench_under_test_{name}", ROOT / "benchmarks" / f"{name}.py")
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
    finally:
        os.environ.clear()
        os.environ.update(environ)
        if not had_product and hasattr(np, "product"):  # bench_lattice's shim for pyfastnoisesimd
            del np.product
    argv, expected = SCRIPTS[name]
    args = vars(mod.build_parser().parse_args(argv))
    assert {k: args[k] for k in expected} == expected
    with pytest.raises(SystemExit):
        mod.build_parser().parse_args(["--no-such-flag"])
    assert "interleaved(" in (ROOT / "benchmarks" / f"{name}.py").read_text()  # timed by the harness
