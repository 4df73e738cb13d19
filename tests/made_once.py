"""A deterministic computation the tests repeat, made once a run: :func:`made_once`.

Used by tests/test_fit_accel.py (the synthetic recordings), tests/test_tensor_fit.py (a throw's
fit, also where ``pool_throws`` makes it: its ``flown_once`` fixture, which tests/test_tensor_device.py
uses too) and tests/test_fit_pool.py (a recording's search for flights), whose tests ask for the
same results with the same arguments.
"""

from __future__ import annotations

import copy
import functools
import hashlib
import inspect
import pickle
from collections.abc import Callable
from typing import Any


def made_once(function: Callable[..., Any]) -> Callable[..., Any]:
    """``function`` with its results kept: the key is the pickled arguments, the defaults filled in
    (so a call that spells a default out and one that leaves it are one); each call gets a deep copy,
    so a test that changes what it got changes nothing for the next. For functions whose result
    follows from their arguments alone (seeded generators, fits).

    Examples
    --------
    >>> from made_once import made_once
    >>> calls = []
    >>> def square(x, scale=1.0):
    ...     calls.append(x)
    ...     return [scale * x * x]
    >>> once = made_once(square)
    >>> once(3.0), once(3.0, scale=1.0), once(3.0, 2.0), len(calls)
    ([9.0], [9.0], [18.0], 2)
    """
    signature = inspect.signature(function)
    kept: dict[bytes, Any] = {}

    @functools.wraps(function)
    def once(*args: Any, **kwargs: Any) -> Any:
        bound = signature.bind(*args, **kwargs)
        bound.apply_defaults()
        key = hashlib.sha256(pickle.dumps(tuple(bound.arguments.items()))).digest()
        if key not in kept:
            kept[key] = function(*args, **kwargs)
        return copy.deepcopy(kept[key])

    return once
