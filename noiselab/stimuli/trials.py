"""The seeds of an experiment's trials: distinct, recorded, and the same on every run."""
from __future__ import annotations

import numbers

import numpy as np

from .._core import as_generator, check_int

__all__ = ["trial_seeds"]

MAX_TRIALS = 1_000_000


def trial_seeds(trials, *, rng=None) -> list[int]:
    """One seed per trial, derived from the experiment's ``rng``: distinct, and the same on every run.

    For an int ``rng`` (the experiment's seed), trial ``i`` gets
    ``numpy.random.SeedSequence(rng).spawn(trials)[i].generate_state(1)[0]``:
    numpy's derivation of independent streams, cut to one 32-bit word so that
    it can be written in a manifest and passed back as ``rng=`` (or
    ``noiselab stimulus --seed``) to make that trial alone. Two trials whose
    words coincide (about one run in ``2**33 / trials**2``) are told apart
    deterministically: the later one takes the next word of its own stream
    (``generate_state(2)[1]``, and so on). These are the
    seeds ``noiselab stimulus --seed S --trials N`` writes in its manifest.
    Trial ``i``'s seed does not depend on ``trials`` for ``i < trials``
    (a longer run extends a shorter one). A ``Generator`` ``rng`` draws the
    experiment's seed from its stream (one draw); ``None`` takes fresh
    entropy (not repeatable: record the seeds returned).

    Parameters
    ----------
    trials : int
        How many trials, 1 to 1 000 000.
    rng : int, numpy.random.Generator or None
        The experiment's seed (see above).

    Returns
    -------
    list of int
        ``trials`` distinct seeds in ``[0, 2**32)``.

    Raises
    ------
    ValueError
        ``trials`` out of range, or a negative seed.

    Examples
    --------
    >>> seeds = trial_seeds(4, rng=2026)
    >>> len(seeds), len(set(seeds))
    (4, 4)
    >>> seeds == trial_seeds(4, rng=2026), seeds[:2] == trial_seeds(2, rng=2026)
    (True, True)
    """
    trials = check_int("trials", trials, lo=1, hi=MAX_TRIALS)
    if isinstance(rng, numbers.Integral) and not isinstance(rng, (bool, np.bool_)):
        as_generator(rng)   # (a negative seed or a bool: the error SPEC 7 gives)
        entropy = int(rng)
    else:
        entropy = int(as_generator(rng).integers(0, 2**63))
    children = np.random.SeedSequence(entropy).spawn(trials)
    seeds = [int(child.generate_state(1)[0]) for child in children]
    if len(set(seeds)) != trials:
        taken = set()
        for i, child in enumerate(children):
            words = 1
            while seeds[i] in taken:   # (a 32-bit coincidence: the next word of this trial's own stream)
                words += 1
                seeds[i] = int(child.generate_state(words)[-1])
            taken.add(seeds[i])
    return seeds
