"""Python values to what the C++ core reads: overrides as (key, YAML text, origin) and a dict
scenario as plain YAML types."""
import json
import os
from collections.abc import Mapping

import numpy as np


def plain(value):
    """The value with NumPy scalars and arrays, tuples and paths as YAML's plain types."""
    if isinstance(value, Mapping):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return value


def override_texts(overrides):
    """``{key.path: value}`` as ``--set key.path=value`` takes them: a str is YAML text as on the
    command line (``"[0, 1]"`` is a list), any other value is written as YAML (JSON's subset)."""
    if overrides is None:
        return []
    if not isinstance(overrides, Mapping):
        raise TypeError("overrides: expected a dict {key.path: value}, got %s" % type(overrides).__name__)
    texts = []
    for key, value in overrides.items():
        value = plain(value)
        text = value if isinstance(value, str) else json.dumps(value)
        texts.append((str(key), text, "overrides[%r]" % str(key)))
    return texts
