"""The shared internal base every layer of noiselab builds on (layer 0; imports nothing of noiselab).

- :mod:`.validate`: argument checks that name the parameter and the allowed range, dtypes, memory estimates;
- :mod:`.workers`: scipy.fft's meaning of ``workers`` and the one thread pool;
- :mod:`.deps`: the optional dask extra, imported in one place with an install hint;
- :mod:`.progress`: tqdm progress bars, silent unless asked for or on a terminal;
- :mod:`.contrast`: the Michelson contrast, shared by the snow compositor and the analysers;
- :mod:`.renamed`: renamed parameters, the old spelling refused with a TypeError naming the new one (and pairs
  moved to array order, and parameters made keyword-only);
- :mod:`.conventions`: the conventions table, every parameter word of the public API (data only);
- :mod:`.dispatch`: the registry through which ``chunks=`` reaches the dask layer;
- :mod:`.jitcache`: where numba's compile cache keeps noiselab's kernels, and how to clear a damaged one
  (numba's cache is used as numba documents it: importing noiselab changes nothing in numba).

Internal: any noiselab subpackage may import these names; users should not.
"""
from . import dispatch
from .deps import EXTRA_HINT, require_dask
from .progress import progress
from .renamed import HIDE_ASSERTION_FRAMES, REMOVED_IN, array_order, keyword_only, renamed_parameters, swap_pair
from .validate import (MAX_ELEMENTS, as_array, as_generator, available_memory, check_axes, check_band, check_finite_array,
                       check_int, check_memory, check_real, check_real_array, check_real_sequence,
                       check_real_vector, check_shape, float_dtype, memory_limits)
from .workers import map_blocks, resolve_workers, run_split, thread_pool

__all__ = ["HIDE_ASSERTION_FRAMES", "REMOVED_IN", "dispatch", "EXTRA_HINT", "require_dask", "progress", "MAX_ELEMENTS", "as_array", "as_generator",
           "available_memory", "check_axes", "check_band", "check_finite_array", "check_int", "check_memory", "check_real",
           "check_real_array", "check_real_sequence", "check_real_vector", "check_shape", "float_dtype",
           "memory_limits", "renamed_parameters", "keyword_only", "array_order", "swap_pair", "map_blocks",
           "resolve_workers", "run_split", "thread_pool"]
