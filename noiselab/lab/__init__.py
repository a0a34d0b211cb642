"""The laboratory: spectral against lattice on the same scenes, speed against error, and the peers.

- :mod:`noiselab.lab.snowgen`: the alternative snow generators,
  :func:`layered_lattice_snow` (depth layers of lattice noise) and
  :func:`particle_snow` (Reeves-style particles).
- :mod:`noiselab.lab.measure`: the one timing harness (:func:`~noiselab.lab.measure.interleaved`
  rounds, medians, per-round ratios, run headers, tables; every ``benchmarks/bench_*.py``
  times through it), peak memory, machine description, scaling fits.
- :mod:`noiselab.lab.experiments`: the experiments, each returning rows of a
  results table.
- :mod:`noiselab.lab.run`: runs them all and writes ``RESULTS.md`` and its
  plots where ``--output`` says (``noiselab bench``); the package writes into no git checkout
  (the published ``benchmarks/RESULTS.md`` is written by the checkout's ``benchmarks/lab_run.py --publish``).
- :mod:`noiselab.lab.figures`: the report's figures, drawn from a run's tables
  (or its ``results.json``: ``benchmarks/lab_run.py --replot`` redraws them without measuring).
"""
from .snowgen import layer_plan, lattice_peak, layered_lattice_snow, particle_snow

__all__ = ["layered_lattice_snow", "particle_snow", "layer_plan", "lattice_peak"]
