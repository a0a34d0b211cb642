"""Renamed parameters: the old spelling keeps working for one release, with a DeprecationWarning naming the new one.

noiselab renames a parameter only to make one word mean one thing across the
API (the conventions page lists every word). A user's script that still
passes the old keyword runs unchanged for one release and is told, once per
call site (Python's default warning filter), which spelling to use instead.
"""
from __future__ import annotations

import functools
import inspect
import operator
import warnings

# pytest leaves out of a failure's report the frames whose ``__tracebackhide__`` says so (a callable is asked
# with the exception): an assertion helper's own source says nothing about the caller's failing test, so its
# frames (and these wrappers') are hidden for AssertionError only; any other error keeps its full traceback
HIDE_ASSERTION_FRAMES = operator.methodcaller("errisinstance", AssertionError)

__all__ = ["renamed_parameters", "keyword_only", "array_order", "swap_pair"]

# the release that removes the old spellings (0.2.0 deprecated them; 0.3.0 followed within days, so they
# stay one release longer)
REMOVED_IN = "0.4"


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
            __tracebackhide__ = HIDE_ASSERTION_FRAMES
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


def _fold_extra_positionals(function, n_positional, names, args, kwargs):
    """Move the positional ``args`` past ``n_positional`` into ``kwargs`` under ``names``, in order.

    Returns the remaining positional args and the names moved. Too many
    positional arguments, or one also given by keyword, is the ``TypeError``
    Python itself raises.
    """
    if len(args) <= n_positional:
        return args, ()
    extra = args[n_positional:]
    if len(extra) > len(names):
        raise TypeError(f"{function.__qualname__}() takes {n_positional} positional arguments but "
                        f"{len(args)} were given")
    moved = names[:len(extra)]
    for name, value in zip(moved, extra):
        if name in kwargs:
            raise TypeError(f"{function.__qualname__}() got multiple values for argument {name!r}")
        kwargs[name] = value
    return args[:n_positional], moved


def keyword_only(*names):
    """Decorator: ``names``, now keyword-only, still taken by position for one release with a DeprecationWarning.

    The old positional order of ``names`` follows the last positional
    parameter of the new signature. The wrapped function's signature shows
    them keyword-only.

    Examples
    --------
    >>> import warnings
    >>> @keyword_only("axis")
    ... def period(x, *, axis=-1):
    ...     return axis
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     period([1], 0), period([1], axis=0), caught[0].category.__name__
    (0, 0, 'DeprecationWarning')
    """
    def decorate(function):
        parameters = inspect.signature(function).parameters
        for name in names:
            if name not in parameters or parameters[name].kind is not inspect.Parameter.KEYWORD_ONLY:
                raise TypeError(f"{function.__qualname__} has no keyword-only parameter {name!r}")
        n_positional = sum(p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) for p in parameters.values())

        @functools.wraps(function)
        def wrapper(*args, **kwargs):
            __tracebackhide__ = HIDE_ASSERTION_FRAMES
            args, moved = _fold_extra_positionals(function, n_positional, names, args, kwargs)
            for name in moved:
                warnings.warn(f"{function.__qualname__}(): passing {name} by position is deprecated and will "
                              f"stop working in noiselab {REMOVED_IN}; pass {name}= as a keyword",
                              DeprecationWarning, stacklevel=2)
            return function(*args, **kwargs)

        wrapper.__keyword_only__ = tuple(names)
        return wrapper

    return decorate


def swap_pair(name, value):
    """``value``, a pair, in the other order: ``(x, y)`` <-> ``(y, x)``; a ``TypeError``/``ValueError`` naming ``name``.

    Examples
    --------
    >>> swap_pair("direction_yx", (1.0, 0.0))
    (0.0, 1.0)
    """
    if isinstance(value, (str, bytes, set, frozenset, dict)) or not hasattr(value, "__len__"):
        raise TypeError(f"{name} must be a pair of real numbers in array order (y, x), got {value!r}")
    if len(value) != 2:
        raise ValueError(f"{name} must be a pair in array order (y, x), got {len(value)} entries: {value!r}")
    return (value[1], value[0])


def array_order(*pairs, positional=()):
    """Decorator: ``old=(x, y)`` keywords replaced by ``new=(y, x)`` ones in array order, the old kept for one release.

    ``pairs`` are ``(old, new)`` names. An old keyword still works with a
    ``DeprecationWarning`` that names the new one: its pair is swapped into
    array order, never reinterpreted. ``positional`` names the old keywords
    that an old call could pass by position, in that order, after the new
    signature's positional parameters (they are warned about and swapped the
    same way). Passing an old and its new spelling together is a ``TypeError``.

    Examples
    --------
    >>> import warnings
    >>> @array_order(("velocity", "velocity_yx"))
    ... def speed(*, velocity_yx=(0.0, 0.0)):
    ...     return velocity_yx
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     speed(velocity=(2.0, 1.0)), speed(velocity_yx=(1.0, 2.0)), caught[0].category.__name__
    ((1.0, 2.0), (1.0, 2.0), 'DeprecationWarning')
    """
    old_to_new = dict(pairs)

    def decorate(function):
        parameters = inspect.signature(function).parameters
        for old, new in old_to_new.items():
            if new not in parameters or old in parameters:
                raise TypeError(f"{function.__qualname__} has no parameter {new!r} to replace {old!r} with")
        n_positional = sum(p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) for p in parameters.values())

        @functools.wraps(function)
        def wrapper(*args, **kwargs):
            __tracebackhide__ = HIDE_ASSERTION_FRAMES
            args, _ = _fold_extra_positionals(function, n_positional, positional, args, kwargs)
            for old, new in old_to_new.items():
                if old in kwargs:
                    if new in kwargs:
                        raise TypeError(f"{function.__qualname__}() got both {old}= (deprecated, (x, y) order) and "
                                        f"{new}=; pass {new}= only")
                    warnings.warn(f"{function.__qualname__}(): {old}=(x, y) is deprecated and will be removed in "
                                  f"noiselab {REMOVED_IN}; pass {new}=(y, x) instead (array order, like shapes)",
                                  DeprecationWarning, stacklevel=2)
                    kwargs[new] = swap_pair(old, kwargs.pop(old))
            return function(*args, **kwargs)

        wrapper.__array_order__ = dict(old_to_new)
        return wrapper

    return decorate
