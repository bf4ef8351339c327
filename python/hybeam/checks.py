"""Checks shared by the tools' input files (system files, study files): the closest name to a
misspelt one and the first key of a table that is not one of the known keys."""

import difflib
from collections.abc import Iterable


def did_you_mean(name: str, names: Iterable[str]) -> str:
    """'; did you mean 'x'?' for the closest of `names` (difflib), or ''."""
    close = difflib.get_close_matches(name, list(names), n=1, cutoff=0.6)
    return f"; did you mean {close[0]!r}?" if close else ""


def unknown_key(table: dict, keys: Iterable[str]) -> str | None:
    """The first key of `table` that is not one of `keys`, or None."""
    return next((k for k in table if k not in keys), None)
