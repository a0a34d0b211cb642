"""What every test shares: its random inputs depend on its own name, never on the tests that ran before it.

Several test modules draw inputs from a module-level ``RNG`` (a
``numpy.random.Generator``). Drawn in file order, a test's inputs depended on
which tests ran before it, so a random order (pytest-randomly) or ``-n 2``
gave each test other inputs in every run, and a failure could not be
repeated alone. Here each test gets ``RNG`` seeded from its node id: the same
inputs alone, in any order and in any worker.
"""
import zlib

import numpy as np
import pytest


@pytest.fixture(autouse=True)
def _rng_from_the_test_name(request, monkeypatch):
    module = getattr(request, "module", None)
    if isinstance(getattr(module, "RNG", None), np.random.Generator):
        monkeypatch.setattr(module, "RNG", np.random.default_rng(zlib.crc32(request.node.nodeid.encode())))
