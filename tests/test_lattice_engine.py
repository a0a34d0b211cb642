"""The lattice engine's own guarantees: read-only tables shared by every path, points in either layout, the
kernels as plain Python, and numba's cache following every edit of the engine's source."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from noiselab import LatticeNoise, fractal_sum
from noiselab.lattice import Grid

RNG = np.random.default_rng(33)
HERE = Path(__file__).resolve().parent.parent


# ----------------------------------------------------------------- tables
@pytest.mark.parametrize("hash_", ["table", "integer"])
def test_permutations_and_keys_are_read_only_for_good(hash_):
    noise = LatticeNoise(2, 2, rng=1, hash=hash_)
    for table in (noise.perms, noise.keys):
        assert not table.flags.writeable
        with pytest.raises(ValueError, match="read-only"):
            table[...] = table[..., ::-1]
        with pytest.raises(ValueError):
            table.setflags(write=True)   # not a flag one can set back: the buffer itself is immutable
    with pytest.raises(ValueError, match="read-only"):
        noise.perms[0, :2] = noise.perms[0, 1::-1]


def test_points_and_grids_read_one_table():
    # a changed table once made points (a copy taken at construction) and grids (the live table) disagree by
    # 0.56 on a 16^2 grid; now the table cannot change, and a changed value table reaches both paths alike
    noise = LatticeNoise(2, rng=2, kernel="quintic")
    shape, ext = (16, 16), [(0, 4), (0, 4)]
    with pytest.raises(ValueError):
        noise.perms[0] = noise.perms[0][::-1]
    noise.values[:] = noise.values[:, ::-1].copy()
    grid = noise.grid(shape, ext)
    np.testing.assert_allclose(noise(noise.grid_points(shape, ext)), grid, rtol=0, atol=1e-12)
    assert np.abs(grid - LatticeNoise(2, rng=2, kernel="quintic").grid(shape, ext)).max() > 0.1


# ----------------------------------------------------------------- layout
@pytest.mark.parametrize("hash_", ["table", "integer"])
def test_points_in_rows_or_columns_give_the_same_bits(hash_):
    noise = LatticeNoise(3, 2, rng=4, hash=hash_, kernel="quintic", basis="gradient")
    rows = RNG.uniform(-20, 20, (3000, 3))
    cols = np.ascontiguousarray(rows.T)           # structure of arrays, (3, N)
    want = noise(rows)
    np.testing.assert_array_equal(noise(cols, axis=0), want)
    np.testing.assert_array_equal(noise(cols, axis=-2, workers=3), want)
    np.testing.assert_array_equal(noise(cols.astype(np.float32), axis=0), noise(rows.astype(np.float32)))
    np.testing.assert_array_equal(noise.evaluate(cols, octaves=3, axis=0), noise.evaluate(rows, octaves=3))
    for a, b in zip(noise.evaluate_jacobian(cols, axis=0), noise.evaluate_jacobian(rows)):
        np.testing.assert_array_equal(a, b)
    # N == d is the ambiguous case: the keyword decides, nothing is guessed
    square = RNG.uniform(-5, 5, (3, 3))
    np.testing.assert_array_equal(noise(square, axis=0), noise(square.T))
    assert not np.array_equal(noise(square, axis=0), noise(square))
    # leading axes keep their order: (d, a, b) -> (a, b)
    block = RNG.uniform(-5, 5, (3, 4, 5))
    np.testing.assert_array_equal(noise(block, axis=0), noise(np.moveaxis(block, 0, -1)))
    with pytest.raises(ValueError, match="axis 0"):
        noise(rows, axis=0)
    with pytest.raises(ValueError, match="axis must be"):
        noise(rows, axis=2)


# ----------------------------------------------------------------- the folded tables
@pytest.mark.parametrize("kw", [{}, {"basis": "gradient"}, {"kernel": "catmull-rom", "dim_out": 2},
                                {"alternation": "lattice"}, {"table_size": 20, "kernel": "quadratic"},
                                {"basis": "gradient", "table_size": 30}])
def test_folded_tables_give_the_per_point_kernels_bits(kw, monkeypatch):
    # many 3-D points read the folded tables (pair_tables), few the permutation itself, and either through the
    # block kernel (_jit.table_block_kernel) or the per-point kernel: the same bits
    from noiselab.lattice import points_path

    noise = LatticeNoise(3, rng=2, **kw)
    pts = RNG.uniform(-300, 300, (3000, 3))
    pts[::7] += 1e13   # past 2**52: the exact reduction
    results = []
    for least, split in ((1 << 40, False), (0, False), (0, True), (1 << 40, True)):
        monkeypatch.setattr(points_path, "PAIRS_MIN", least)
        monkeypatch.setattr(points_path, "TABLE_SPLIT", split)
        results.append([noise.evaluate(pts, octaves=3), noise.evaluate(pts, octaves=2, absval=True),
                        noise(pts[:300].T, axis=0)])
    for other in results[1:]:
        for a, b in zip(results[0], other):
            np.testing.assert_array_equal(a, b)
            np.testing.assert_array_equal(np.signbit(a), np.signbit(b))
    # and a changed value table reaches the folded tables (they are built from the live tables at each call)
    noise.values[:] = -noise.values
    noise.gradients[:] = -noise.gradients
    np.testing.assert_array_equal(noise.evaluate(pts, octaves=3), -results[1][0])



@pytest.mark.parametrize("basis", ["value", "gradient"])
def test_the_integer_hash_never_takes_the_table_kernels(basis, monkeypatch):
    # with its vectorised kernel off, integer-hash 3-D points run the general integer kernel (the same bits),
    # never a table-hash kernel that would read its keys as permutations
    from noiselab.lattice import points_path

    noise = LatticeNoise(3, rng=2, hash="integer", basis=basis)
    pts = RNG.uniform(-50, 50, (2000, 3))
    results = []
    for dims in (3, 0):
        monkeypatch.setattr(points_path, "INT_FAST_DIM", dims)
        monkeypatch.setattr(points_path, "PAIRS_MIN", 0)
        results.append(noise.evaluate(pts, octaves=2))
    np.testing.assert_array_equal(results[0], results[1])

@pytest.mark.parametrize("dim", [1, 2, 3])
def test_the_integer_block_kernel_gives_the_other_kernels_bits(dim, monkeypatch):
    # 1-3-D integer-hash values without a period run block by block (_jit.int_block_kernel: rows or columns read
    # in place, every lattice index reduced modulo 2**32 in float64, no exact fallback); the vectorised kernel
    # (INT_BLOCK off) and the general one (INT_FAST_DIM 0) give the same bits, huge coordinates included
    from noiselab.lattice import points_path

    x = RNG.uniform(-300, 300, (3000, dim))
    x[::7] += 1e13     # past 2**52: no fractional bits
    x[::11] *= 1e18    # past 2**63: the exact reduction in the other kernels
    x[::13] *= -1e250
    x[::17] = np.round(x[::17])   # exact lattice points
    x32 = RNG.uniform(-300, 300, (3000, dim)).astype(np.float32)
    x32[::19] *= np.float32(1e30)
    cases = [({}, 3), ({"kernel": "quintic"}, 1), ({"basis": "gradient", "kernel": "quintic"}, 2)]
    results = []
    for block, fast in ((True, 3), (False, 3), (True, 0)):
        monkeypatch.setattr(points_path, "INT_BLOCK", block)
        monkeypatch.setattr(points_path, "INT_FAST_DIM", fast)
        got = []
        for kw, octaves in cases:
            noise = LatticeNoise(dim, 2, rng=3, hash="integer", **kw)
            got += [noise.evaluate(x, octaves=octaves), noise.evaluate(x, octaves=2, absval=True),
                    noise.evaluate(x32, octaves=octaves, dtype=np.float64), noise(x32)]
        results.append(got)
    for other in results[1:]:
        for a, b in zip(results[0], other):
            assert a.dtype == b.dtype
            np.testing.assert_array_equal(a, b)
            np.testing.assert_array_equal(np.signbit(a), np.signbit(b))
    # the block kernel reads columns and strided rows (copied) to the same bits, on any number of threads
    monkeypatch.setattr(points_path, "INT_BLOCK", True)
    monkeypatch.setattr(points_path, "INT_FAST_DIM", 3)
    for (kw, octaves), i in zip(cases, range(0, 12, 4)):
        noise = LatticeNoise(dim, 2, rng=3, hash="integer", **kw)
        cols, cols32 = np.ascontiguousarray(x.T), np.ascontiguousarray(x32.T)
        np.testing.assert_array_equal(noise.evaluate(cols, octaves=octaves, axis=0, workers=2), results[0][i])
        np.testing.assert_array_equal(noise.evaluate(x, octaves=2, absval=True, workers=3), results[0][i + 1])
        np.testing.assert_array_equal(noise(cols32, axis=0, workers=2), results[0][i + 3])
        np.testing.assert_array_equal(noise(x[::2]), noise(np.ascontiguousarray(x[::2])))
    assert np.ptp(results[0][0]) > 0.5   # not vacuous: the noise varies over these points


# ----------------------------------------------------------------- plain Python
_CASE = """
import sys
import numpy as np
import noiselab as nl
from noiselab.lattice import Grid
x = np.random.default_rng(1).uniform(-9, 9, (40, 3))
out = []
for h in ("table", "integer"):
    for kw in ({}, {"basis": "gradient", "kernel": "catmull-rom"}, {"period": (3, 4, 5), "kernel": "quintic"}):
        n3 = nl.LatticeNoise(3, 2, rng=3, hash=h, **kw)
        out += [n3.evaluate(x, octaves=2), n3(x.T, axis=0), n3(np.float32(1e13) * x.astype(np.float32).T, axis=0)]
        out += list(n3.evaluate_jacobian(x, octaves=2, absval=True))
        kw2 = dict(kw, period=(3, 4)) if "period" in kw else kw
        n2g = nl.LatticeNoise(2, rng=3, hash=h, **kw2)
        out += [nl.fractal_sum(n2g, Grid((9, 7), ((0, 3), (-1, 2))), 3), n2g.grid((6, 5), [(0, 2), (0, 2)],
                                                                                  dtype=np.float32)]
        out += [nl.LatticeNoise(3, rng=3, hash=h).grid((5, 4, 3), [(0, 2), (0, 2), (0, 1)])]
        out += list(n2g.evaluate_grid_jacobian((6, 5), [(0, 2), (0, 2)], octaves=2))
    out += [nl.LatticeNoise(5, rng=3, hash=h, kernel="linear")(x[:, :1].repeat(5, axis=1))]
    # the fused grid kernel's shared variant (3 taps) with turbulence, and the separable passes of a 4-D grid
    out += [nl.turbulence(nl.LatticeNoise(3, rng=3, hash=h, kernel="quadratic", basis="gradient"),
                          Grid((4, 5, 3), ((0, 2), (0, 2), (0, 1))), 2)]
    out += [nl.LatticeNoise(4, rng=3, hash=h).grid((3, 4, 3, 2), [(0, 2)] * 4)]
for d in (1, 2, 3):   # the integer hash's 2-tap kernel
    for b in ("value", "gradient"):
        out += [nl.LatticeNoise(d, 2, rng=3, hash="integer", kernel="quintic", basis=b).evaluate(x[:, :d], octaves=2)]
far = x + 1e12 * (np.arange(40) % 5 == 0)[:, None]
for d in (1, 2, 3):   # the float32 arithmetic's kernels (2-tap and block), rows and columns, near 0 and at 1e12
    for k, b in (("quintic", "value"), ("quintic", "gradient"), ("catmull-rom", "value"), ("catmull-rom", "gradient")):
        n = nl.LatticeNoise(d, 2, rng=3, hash="integer", kernel=k, basis=b)
        out += [n.evaluate(far[:, :d], octaves=2, arithmetic="float32"),
                n.evaluate(np.ascontiguousarray(far[:, :d].T), axis=0, octaves=2, absval=True, arithmetic="float32")]
x32 = np.random.default_rng(2).uniform(-40, 40, (600, 3)).astype(np.float32)
x32[300, 1] = np.float32(3e9)   # float32 points: the float32 index, but for the second block (the float64 index)
for d in (1, 2, 3):
    for k, b in (("quintic", "value"), ("quintic", "gradient"), ("catmull-rom", "value"), ("linear", "gradient")):
        n = nl.LatticeNoise(d, 2, rng=3, hash="integer", kernel=k, basis=b)
        out += [n.evaluate(x32[:, :d], octaves=2, arithmetic="float32"),
                n.evaluate(np.ascontiguousarray(x32[:, :d].T), axis=0, absval=True, arithmetic="float32")]
from noiselab.lattice import points_path
for least in (0, 1 << 40):   # 3-D table-hash values over the folded tables, and without them
    points_path.PAIRS_MIN = least
    for kw in ({}, {"basis": "gradient"}, {"alternation": "lattice", "table_size": 20}):
        out += [nl.LatticeNoise(3, 2, rng=5, **kw).evaluate(x, octaves=2)]
np.savez(sys.argv[1], *out)
"""


def test_every_kernel_runs_as_plain_python_with_the_same_bits(tmp_path):
    # NUMBA_DISABLE_JIT=1 runs every kernel's Python source: points (both hashes, with and without a period,
    # Jacobians, both layouts, the folded 3-D tables, the float32 arithmetic with either index), 2-D and 3-D
    # grids by the separable passes and the grid Jacobians
    results = []
    for flag in ("0", "1"):
        env = dict(os.environ, NUMBA_DISABLE_JIT=flag, PYTHONPATH=str(HERE))
        subprocess.run([sys.executable, "-c", _CASE, str(tmp_path / f"jit{flag}.npz")], env=env, check=True,
                       cwd=tmp_path, timeout=900)
        data = np.load(tmp_path / f"jit{flag}.npz")
        results.append([data[k] for k in sorted(data.files, key=lambda s: int(s.split("_")[1]))])
    assert len(results[0]) == len(results[1]) > 40
    for compiled, plain in zip(*results):
        assert compiled.dtype == plain.dtype and compiled.shape == plain.shape
        np.testing.assert_array_equal(compiled, plain)
        np.testing.assert_array_equal(np.signbit(compiled), np.signbit(plain))


# ----------------------------------------------------------------- the compile cache
_EVAL = """
import numpy as np
from noiselab import LatticeNoise
x = np.random.default_rng(0).uniform(-9, 9, (200, 3))
print(repr(float(LatticeNoise(3, rng=1)(x).sum())))
"""


def _engine_source(package):
    """The module whose helpers the point kernels call (today's engine, or the tree before it)."""
    return package / "noiselab" / "lattice" / "_jit.py"


def test_an_edit_of_the_engine_reaches_a_warm_cache(tmp_path):
    # the kernels are cached by numba against their source file: an edit of a helper they call (here the
    # index reduction: every lattice index one cell over) must show in the next process, same cache folder
    package = tmp_path / "install"
    shutil.copytree(HERE / "noiselab", package / "noiselab", ignore=shutil.ignore_patterns("__pycache__"))
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"), PYTHONPATH=str(package))

    def run():
        proc = subprocess.run([sys.executable, "-c", _EVAL], env=env, cwd=tmp_path, capture_output=True,
                              text=True, timeout=600)
        assert proc.returncode == 0, proc.stderr
        return float(proc.stdout.split()[-1])

    before = run()
    assert run() == before   # warm, same source: the same values
    source = _engine_source(package)
    text = source.read_text()
    old = "        i = np.int64(fi) - left\n"
    assert text.count(old) == 1
    source.write_text(text.replace(old, "        i = np.int64(fi) - left + 1  # edited\n"))
    shifted = LatticeNoise(3, rng=1, phase=1.0)(np.random.default_rng(0).uniform(-9, 9, (200, 3))).sum()
    after = run()
    assert after != before
    assert after == pytest.approx(float(shifted), abs=1e-9)   # the edit's effect: the lattice moved one cell


@pytest.mark.parametrize("hash_", ["table", "integer"])
def test_the_scattered_grid_octaves_give_the_same_bits_in_blocks_of_rows(hash_, monkeypatch):
    # octaves sparser than the grid run through the points path; in blocks of rows or one row per call
    from noiselab.fractal import fractal_sum, turbulence
    from noiselab.lattice import Grid, grid_path

    noise = LatticeNoise(2, 2, rng=4, hash=hash_)   # cubic: 4 taps, the finer octaves are sparse
    grid = Grid((60, 50), ((0.0, 64.0), (0.5, 70.0)))
    results = []
    for block in (1, 1000, 1 << 16):
        monkeypatch.setattr(grid_path, "SCATTERED_BLOCK", block)
        results.append([fractal_sum(noise, grid, 5), turbulence(noise, grid, 4), noise.jacobian_grid((30, 20),
                                                                                                     [(0, 90), (0, 77)])])
    for other in results[1:]:
        for a, b in zip(results[0], other):
            np.testing.assert_array_equal(a, b)
            np.testing.assert_array_equal(np.signbit(a), np.signbit(b))


@pytest.mark.parametrize("hash_", ["table", "integer"])
def test_one_dimensional_grids_are_the_points_path_bit_for_bit(hash_):
    # a 1-D grid takes the points path (the separable passes' rows would be one sample each): the values,
    # octave sums, tiled sums and derivatives of the grid's own points, to the last bit
    from noiselab.fractal import turbulence

    shape, ext = (701,), [(-3.3, 57.1)]
    for kw in ({}, {"kernel": "quintic", "basis": "gradient"}):
        noise = LatticeNoise(1, 2, rng=5, hash=hash_, **kw)
        pts = noise.grid_points(shape, ext)
        for octaves in (1, 7):
            np.testing.assert_array_equal(noise.evaluate_grid(shape, ext, octaves=octaves),
                                          noise.evaluate(pts, octaves=octaves))
        # (3 octaves: every one is seen by the grid's 11.6 samples a unit, which a grid's sum would otherwise drop)
        np.testing.assert_array_equal(turbulence(noise, Grid(shape, ext), 3), turbulence(noise, pts, 3))
        np.testing.assert_array_equal(noise.jacobian_grid(shape, ext), noise.jacobian(pts))
        np.testing.assert_array_equal(noise.grid(shape, ext, dtype=np.float32), noise(pts).astype(np.float32))
    tiled = LatticeNoise(1, rng=5, hash=hash_, period=8)   # each octave its own period: one points call each
    grid = Grid((400,), [(0.0, 8.0)])
    sums = fractal_sum(tiled, grid, 5), fractal_sum(tiled, tiled.grid_points(grid.shape, grid.extent), 5)
    np.testing.assert_array_equal(*sums)
    np.testing.assert_allclose(fractal_sum(tiled, Grid((400,), [(8.0, 16.0)]), 5), sums[0], atol=1e-12)  # one tile on


@pytest.mark.parametrize("hash_", ["table", "integer"])
def test_float32_grids_with_sparse_octaves_are_the_float64_sum_rounded_once(hash_):
    # octaves sparser than the grid are added one group at a time; their sum is kept in float64 and rounded
    # once, as the other paths round theirs (summed in float32 it was 1 ulp off at a third of the samples)
    noise = LatticeNoise(2, rng=6, hash=hash_)
    shape, ext = (96, 80), [(0.0, 64.0), (3.0, 70.0)]
    for octaves in (3, 6):
        want = noise.evaluate_grid(shape, ext, octaves=octaves).astype(np.float32)
        np.testing.assert_array_equal(noise.evaluate_grid(shape, ext, octaves=octaves, dtype=np.float32), want)


@pytest.mark.parametrize("dim", [1, 2, 3])
def test_float32_points_read_in_place_give_the_bits_of_their_float64_copy(dim):
    # the integer hash's vectorised kernel reads float32 points without a float64 copy; widening is exact,
    # so the values are those of the float64 points, in either layout, at any worker count
    x = RNG.uniform(-300, 300, (3000, dim)).astype(np.float32)
    x[::97] *= np.float32(1e13)   # past the fast split: the exact reduction
    for kw in ({}, {"basis": "gradient", "kernel": "quintic"}, {"period": 7}):
        noise = LatticeNoise(dim, 2, rng=3, hash="integer", **kw)
        want = noise.evaluate(x.astype(np.float64), octaves=3)
        got = noise.evaluate(x, octaves=3, dtype=np.float64)
        np.testing.assert_array_equal(got, want)
        np.testing.assert_array_equal(np.signbit(got), np.signbit(want))
        np.testing.assert_array_equal(noise(np.ascontiguousarray(x.T), axis=0, workers=2), noise(x))
        assert noise(x).dtype == np.float32
    # one compiled specialisation of each block kernel reads both dtypes (a float32 call after a float64 one
    # compiled it again: 1.3-2.2 s)
    from noiselab.lattice import _jit

    assert len(_jit.int_block_kernel(dim, 4, False).signatures) == 1
    assert len(_jit.int_two_taps_kernel(dim, True).signatures) == 1


def test_integer_hash_prefix_compiles_once():
    # a separable grid's integer-hash prefix starts from the component's key (read-only) and goes on from each
    # axis's result (writable); a read-only array is another numba type, so the key is passed as a writable
    # copy: one compiled specialisation, not two
    from noiselab.lattice import _jit

    noise = LatticeNoise(4, rng=2, hash="integer")
    grid = noise.grid((3, 4, 2, 2), [(0, 2)] * 4)
    np.testing.assert_allclose(grid.ravel(), noise(noise.grid_points((3, 4, 2, 2), [(0, 2)] * 4)).ravel(),
                               atol=1e-12)
    assert len(_jit.block_prefix.signatures) == 1
