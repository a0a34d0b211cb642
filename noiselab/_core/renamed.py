"""Renamed parameters: the old spelling keeps working for one release, with a DeprecationWarning naming the new one.

noiselab renames a parameter only to make one word mean one thing across the
API (the conventions page lists every word). A user's script that still
passes the old keyword runs unchanged for one release and is told, once per
call site (Python's default warning filter), which spelling to use instead.
"""
from __future__ import annotations

import functools
import inspect
import warnings

__all__ = ["renamed_parameters"]

# the release that removes the old spellings
REMOVED_IN = "0.3"


def renamed_parameters(**old_to_new):
    """Decorator: accept each ``old=`` keyword as ``new=`` with a ``DeprecationWarning``.

    Passing both spellings is a ``TypeError`` (as Python does for a keyword
    given twice). The wrapped function's signature shows the new names only.

    Examples
    --------
    >>> import warnings
    >>> @renamed_parameters(seed="rng")
    ... def draw(*, rng=None):
    ...     return rng
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     draw(seed=3), caught[0].category.__name__
    (3, 'DeprecationWarning')
    """
    def decorate(function):
        parameters = inspect.signature(function).parameters
        for old, new in old_to_new.items():
            if new not in parameters:
                raise TypeError(f"{function.__qualname__} has no parameter {new!r} to rename {old!r} to")

        @functools.wraps(function)
        def wrapper(*args, **kwargs):
            for old, new in old_to_new.items():
                if old in kwargs:
                    if new in kwargs:
                        raise TypeError(f"{function.__qualname__}() got both {old}= (deprecated) and {new}=; "
                                        f"pass {new}= only")
                    warnings.warn(f"{function.__qualname__}(): {old}= is deprecated and will be removed in "
                                  f"noiselab {REMOVED_IN}; pass {new}= instead", DeprecationWarning, stacklevel=2)
                    kwargs[new] = kwargs.pop(old)
            return function(*args, **kwargs)

        wrapper.__renamed_parameters__ = dict(old_to_new)
        return wrapper

    return decorate
