"""Plotting is optional (the `plot` extra: `pip install "hybeam-tools[plot]"`): matplotlib is
imported only when a figure is drawn, and a figure asked for without it says which extra to
install."""

from __future__ import annotations

from typing import Any

EXTRA = "pip install 'hybeam-tools[plot]' (matplotlib)"


class PlotUnavailable(RuntimeError):
    """A figure was asked for and matplotlib is not installed."""


def available() -> bool:
    """Whether matplotlib can be imported."""
    try:
        import matplotlib  # noqa: F401
    except ImportError:
        return False
    return True


def pyplot(what: str) -> Any:
    """matplotlib.pyplot on the Agg backend, or PlotUnavailable naming `what` (the figure) and
    the extra to install."""
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise PlotUnavailable(f"{what} needs matplotlib: {EXTRA}") from None
    return plt
