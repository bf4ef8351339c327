"""DIR/sweep.png, the figure of a sweep (`hybeam-sweep plot DIR`; optional: the `plot`
extra)."""

from __future__ import annotations

import json
import pathlib

from ..plotting import pyplot
from .study import StudyError


def plot(out: str | pathlib.Path) -> pathlib.Path:
    """DIR/sweep.png: each summary against each swept parameter (one point per variant that
    ran); its path. Needs the `plot` extra (`plotting.PlotUnavailable` without it)."""
    import pandas as pd

    out = pathlib.Path(out)
    if not (out / "variants.parquet").exists() or not (out / "study.json").exists():
        raise StudyError(
            f"{out}: no sweep there (variants.parquet, study.json); run "
            f"hybeam-sweep run STUDY.toml --out {out} first"
        )
    v = pd.read_parquet(out / "variants.parquet")
    meta = json.loads((out / "study.json").read_text())
    params, sums = meta["parameters"], meta["summaries"]
    if not sums:
        raise StudyError(f"{out}: the study has no [outputs] summaries to plot; add some")
    ok = v[v["status"] == "ok"] if "status" in v else v.iloc[:0]
    plt = pyplot(f"{out / 'sweep.png'} (the sweep's figure)")
    fig, axes = plt.subplots(
        len(sums), len(params), figsize=(3.2 * len(params), 2.6 * len(sums)), squeeze=False
    )
    for i, s in enumerate(sums):
        for j, p in enumerate(params):
            ax = axes[i][j]
            if p in ok and s in ok:
                ax.plot(ok[p], ok[s], "o", ms=4)
            ax.set_xlabel(p)
            ax.set_ylabel(s)
            ax.grid(alpha=0.3)
    fig.suptitle(f"{meta['study']}: {len(ok)} of {len(v)} variants ran")
    fig.tight_layout()
    fig.savefig(out / "sweep.png", dpi=110)
    plt.close(fig)
    return out / "sweep.png"
