"""Renamed parameters: the old spelling is refused with a TypeError that names the new one.

noiselab renames a parameter only to make one word mean one thing across the
API (the conventions page lists every word). 0.2.0 renamed them and kept the
old spellings working, with a DeprecationWarning, through 0.3; since
:data:`REMOVED_IN` an old spelling is an error, but one that says which
spelling to use instead (``snow(seed=1)`` fails with "seed= was removed in
noiselab 0.4; pass rng= instead"), never Python's bare "unexpected keyword
argument" and never a silent reinterpretation (an old ``(x, y)`` pair is not
read as ``(y, x)``).
"""
from __future__ import annotations

import functools
import inspect
import operator

# pytest leaves out of a failure's report the frames whose ``__tracebackhide__`` says so (a callable is asked
# with the exception): an assertion helper's own source says nothing about the caller's failing test, so its
# frames (and these wrappers') are hidden for AssertionError only; any other error keeps its full traceback
HIDE_ASSERTION_FRAMES = operator.methodcaller("errisinstance", AssertionError)

__all__ = ["renamed_parameters", "keyword_only", "array_order", "swap_pair"]

# the release that removed the old spellings (0.2.0 deprecated them, 0.3 kept them with a warning)
REMOVED_IN = "0.4"


def renamed_parameters(**old_to_new):
    """Decorator: refuse each removed ``old=`` keyword with a ``TypeError`` naming ``new=``.

    The wrapped function's signature shows the new names only.

    Examples
    --------
    >>> @renamed_parameters(seed="rng")
    ... def draw(*, rng=None):
    ...     return rng
    >>> draw(rng=3)
    3
    >>> draw(seed=3)
    Traceback (most recent call last):
    ...
    TypeError: draw(): seed= was removed in noiselab 0.4; pass rng= instead
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
                    raise TypeError(f"{function.__qualname__}(): {old}= was removed in noiselab {REMOVED_IN}; "
                                    f"pass {new}= instead")
            return function(*args, **kwargs)

        wrapper.__renamed_parameters__ = dict(old_to_new)
        return wrapper

    return decorate


def _too_many_positionals(function, n_positional, args, hint):
    """A ``TypeError`` if ``args`` go past the ``n_positional`` positional parameters, ending with ``hint``."""
    if len(args) > n_positional:
        raise TypeError(f"{function.__qualname__}() takes {n_positional} positional arguments but {len(args)} "
                        f"were given; {hint}")


def keyword_only(*names):
    """Decorator: ``names``, keyword-only, passed by position is a ``TypeError`` that names them.

    noiselab 0.2.0 made them keyword-only and took them by position with a
    warning until :data:`REMOVED_IN`. The wrapped function's signature shows
    them keyword-only.

    Examples
    --------
    >>> @keyword_only("axis")
    ... def period(x, *, axis=-1):
    ...     return axis
    >>> period([1], axis=0)
    0
    >>> period([1], 0)
    Traceback (most recent call last):
    ...
    TypeError: period() takes 1 positional arguments but 2 were given; pass axis= as a keyword (by position it was removed in noiselab 0.4)
    """
    def decorate(function):
        parameters = inspect.signature(function).parameters
        for name in names:
            if name not in parameters or parameters[name].kind is not inspect.Parameter.KEYWORD_ONLY:
                raise TypeError(f"{function.__qualname__} has no keyword-only parameter {name!r}")
        n_positional = sum(p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) for p in parameters.values())
        hint = (", ".join(f"{name}=" for name in names) + f" as a keyword (by position it was removed in noiselab "
                f"{REMOVED_IN})")

        @functools.wraps(function)
        def wrapper(*args, **kwargs):
            __tracebackhide__ = HIDE_ASSERTION_FRAMES
            _too_many_positionals(function, n_positional, args, "pass " + hint)
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
    """Decorator: removed ``old=(x, y)`` keywords refused with a ``TypeError`` naming ``new=(y, x)``, in array order.

    ``pairs`` are ``(old, new)`` names. ``positional`` names the old keywords
    that an old call could pass by position (after the new signature's
    positional parameters): such a call is refused the same way. Until
    :data:`REMOVED_IN` the old spellings were swapped into array order with a
    ``DeprecationWarning``; an old pair is never read as a new one.

    Examples
    --------
    >>> @array_order(("velocity", "velocity_yx"))
    ... def speed(*, velocity_yx=(0.0, 0.0)):
    ...     return velocity_yx
    >>> speed(velocity_yx=(1.0, 2.0))
    (1.0, 2.0)
    >>> speed(velocity=(2.0, 1.0))
    Traceback (most recent call last):
    ...
    TypeError: speed(): velocity=(x, y) was removed in noiselab 0.4; pass velocity_yx=(y, x) instead (array order, like shapes)
    """
    old_to_new = dict(pairs)

    def decorate(function):
        parameters = inspect.signature(function).parameters
        for old, new in old_to_new.items():
            if new not in parameters or old in parameters:
                raise TypeError(f"{function.__qualname__} has no parameter {new!r} to replace {old!r} with")
        n_positional = sum(p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) for p in parameters.values())
        hint = ("pass " + ", ".join(f"{old_to_new[name]}=(y, x)" if name in old_to_new else f"{name}="
                                    for name in positional)
                + f" as keywords, pairs in array order (by position, in (x, y) order, they were removed in noiselab "
                  f"{REMOVED_IN})")

        @functools.wraps(function)
        def wrapper(*args, **kwargs):
            __tracebackhide__ = HIDE_ASSERTION_FRAMES
            if positional:
                _too_many_positionals(function, n_positional, args, hint)
            for old, new in old_to_new.items():
                if old in kwargs:
                    raise TypeError(f"{function.__qualname__}(): {old}=(x, y) was removed in noiselab {REMOVED_IN}; "
                                    f"pass {new}=(y, x) instead (array order, like shapes)")
            return function(*args, **kwargs)

        wrapper.__array_order__ = dict(old_to_new)
        return wrapper

    return decorate
