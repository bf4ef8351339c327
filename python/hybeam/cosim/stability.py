"""Studies of a coupled system: the stability map and the order of convergence.

    hybeam-cosim-study map SYSTEM --scheme naive --scheme implicit \\
        --steps 1e-4,2.5e-4,5e-4,1e-3,2e-3,5e-3,1e-2,2e-2 \\
        --grid boom.mass_factor=1,10,20,50,100 --t-end 2 --out docs/report/coupling_map
    hybeam-cosim-study order SYSTEM --scheme implicit --steps 2e-2,1e-2,5e-3,2e-3,1e-3 \\
        --reference 1e-4 --columns car.body.pitch,boom.tip.position.y --out ...

`map` runs every (scheme, step, grid value) cell through `hybeam.cosim.master.run` in
parallel processes (`--jobs`, default 2) and writes CELLS.csv (one row per cell: the run's JSON
summary), CELLS.md (a table per scheme) and CELLS.svg (green: stable, red: not; the energy
residual as a fraction of its scale in each cell). A cell is stable when no step is refused,
the implicit iterations converge, and the largest energy residual stays below 1 % of its scale.

`order` runs one scheme at each step and at a fine reference step, and prints (and writes
as .md) the largest difference of each column from the reference over the reference's points
that every run shares, with the observed order between neighbouring steps.
"""

from __future__ import annotations

import csv
import json
import math
import pathlib
import sys
from concurrent.futures import ProcessPoolExecutor

import numpy as np

from ..plotting import pyplot
from .master import Result
from .run import simulate
from .system import load


def _word(stable: bool | None) -> str:
    """The verdict of a run (`Result.stable`: True, False, or None when not judged)."""
    return {True: "stable", None: "not judged"}.get(stable, "NOT stable")


def _cell(args: tuple) -> Result:
    path, fmus, scheme, step, t_end, sets = args
    return simulate(load(path, fmus), scheme, step, t_end, sets)


def _summary(args: tuple) -> dict:
    res = _cell(args[:-1])
    out = res.summary(args[2], args[3])
    out["set"] = " ".join(args[5])
    out["grid"] = args[6]
    return out


def floats(text: str) -> list[float]:
    """Comma-separated numbers ("1e-3,2e-3") as floats."""
    return [float(x) for x in text.split(",") if x]


def stability_map(
    system: str | pathlib.Path,
    schemes: list[str],
    steps: list[float],
    grid: str,
    out: str | pathlib.Path,
    t_end: float = 2.0,
    sets: list[str] | None = None,
    fmus: dict[str, str] | None = None,
    jobs: int = 2,
    command: str = "",
) -> list[dict]:
    """Runs every (scheme, step, grid value) cell (`grid`: "FMU.KEY=V1,V2,..."; `sets`:
    `--set` items for every cell) in `jobs` processes and writes OUT.csv, OUT.md and OUT.svg
    (see the module's docstring; `command`: the command line the .md quotes). The cells'
    summaries."""
    key, _, values = grid.partition("=")
    grid_values = floats(values)
    sets = list(sets or [])
    fmus = dict(fmus or {})
    cells = [
        (system, fmus, s, h, t_end, [f"{key}={g}"] + sets, g)
        for s in schemes
        for g in grid_values
        for h in steps
    ]
    # the longest cells (fine steps) first, to balance the processes
    order = sorted(range(len(cells)), key=lambda i: cells[i][3])
    rows: list[dict] = [{} for _ in cells]
    with ProcessPoolExecutor(max_workers=jobs) as ex:
        futs = {i: ex.submit(_summary, cells[i]) for i in order}
        for n, i in enumerate(order):
            rows[i] = futs[i].result()
            r = rows[i]
            print(
                f"[{n + 1}/{len(cells)}] {r['scheme']} h = {r['step']:g} {r['set']}: "
                f"{_word(r['stable'])} residual "
                f"{r['energy_residual']} of {r['energy_scale']} ({r['wall_s']:.1f} s, "
                f"{r['iterations']:.2f} it/step) {r['message']}",
                file=sys.stderr,
            )
    out = pathlib.Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    with open(out.with_suffix(".csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    md = [f"Stability map: `{command}`", ""]
    for s in schemes:
        md += [
            f"**{s}** — energy residual / scale (✗: not stable; wall time per cell "
            f"relative to the naive cell where both ran)",
            "",
            "| " + key + " \\ h [ms] | " + " | ".join(f"{1e3 * h:g}" for h in steps) + " |",
            "|---" * (len(steps) + 1) + "|",
        ]
        for g in grid_values:
            texts = [_text(_find(rows, s, h, g), rows, g, h) for h in steps]
            md.append(f"| {g:g} | " + " | ".join(texts) + " |")
        md.append("")
    out.with_suffix(".md").write_text("\n".join(md))
    _figure(rows, schemes, steps, grid_values, key, out.with_suffix(".svg"))
    print("\n".join(md))
    return rows


def _find(rows, scheme, h, g):
    return next(r for r in rows if r["scheme"] == scheme and r["step"] == h and r["grid"] == g)


def _text(r, rows, g, h):
    if r["energy_residual"] is None or not r["energy_scale"]:
        frac = "-"
    else:
        frac = f"{r['energy_residual'] / r['energy_scale']:.1e}"
    mark = {True: "", None: "? "}.get(r["stable"], "✗ ")
    naive = [x for x in rows if x["scheme"] == "naive" and x["step"] == h and x["grid"] == g]
    cost = ""
    if r["scheme"] != "naive" and naive and naive[0]["steps"] == r["steps"]:
        cost = f" ({r['wall_s'] / max(naive[0]['wall_s'], 1e-9):.1f}×)"
    return f"{mark}{frac}{cost}"


def _figure(rows, schemes, steps, grid, key, path):
    plt = pyplot(f"{path.name} (the stability map's figure)")

    fig, axes = plt.subplots(1, len(schemes), figsize=(4.2 * len(schemes), 3.4), squeeze=False)
    for ax, s in zip(axes[0], schemes, strict=True):
        for i, g in enumerate(grid):
            for j, h in enumerate(steps):
                r = _find(rows, s, h, g)
                ok = r["stable"]
                ax.add_patch(
                    plt.Rectangle((j, i), 1, 1, color="#7fc97f" if ok else "#f0027f", alpha=0.8)
                )
                if r["energy_residual"] is not None and r["energy_scale"]:
                    f = r["energy_residual"] / r["energy_scale"]
                    txt = f"{f:.0e}" if math.isfinite(f) else "inf"
                else:
                    txt = "refused"
                ax.text(j + 0.5, i + 0.5, txt, ha="center", va="center", fontsize=6)
        ax.set_xlim(0, len(steps))
        ax.set_ylim(0, len(grid))
        ax.set_xticks(np.arange(len(steps)) + 0.5, [f"{1e3 * h:g}" for h in steps], fontsize=7)
        ax.set_yticks(np.arange(len(grid)) + 0.5, [f"{g:g}" for g in grid], fontsize=7)
        ax.set_xlabel("communication step [ms]")
        ax.set_ylabel(key)
        ax.set_title(s)
    fig.suptitle(
        "green: stable (energy residual < 1 % of its scale, no step refused); "
        "cells: residual / scale",
        fontsize=8,
    )
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def order(
    system: str | pathlib.Path,
    scheme: str,
    steps: list[float],
    reference: float,
    columns: list[str],
    out: str | pathlib.Path | None = None,
    t_end: float = 2.0,
    sets: list[str] | None = None,
    fmus: dict[str, str] | None = None,
    jobs: int = 2,
    command: str = "",
) -> list[tuple[str, float]]:
    """Runs `scheme` at each of `steps` and at `reference`, prints (and writes as OUT.md) the
    largest difference of each of `columns` from the reference run, with the observed order
    between neighbouring steps; the orders, (column, order) pairs."""
    sets = list(sets or [])
    fmus = dict(fmus or {})
    cols = columns
    runs = [(system, fmus, scheme, h, t_end, sets) for h in [reference] + steps]
    with ProcessPoolExecutor(max_workers=jobs) as ex:
        results = list(ex.map(_cell, runs))
    ref = results[0]
    if ref.stable is False:
        raise SystemExit(f"the reference run is not stable: {ref.message}")
    rt = ref.table()
    coarse = max(steps)
    stride = int(round(coarse / reference))
    md = [
        f"Order of convergence: `{command}`; largest difference from the "
        f"reference (h = {reference:g} s) at every {coarse:g} s",
        "",
        "| h [ms] | " + " | ".join(cols) + " | stable | wall [s] |",
        "|---" * (len(cols) + 3) + "|",
    ]
    prev: tuple[list[float], float] | None = None
    orders: list[tuple[str, float]] = []
    for h, r in zip(steps, results[1:], strict=True):
        t = r.table()
        k = int(round(coarse / h))
        errs = []
        for c in cols:
            got = t[::k, r.columns.index(c)]
            want = rt[::stride, ref.columns.index(c)]
            n = min(len(got), len(want))
            errs.append(float(np.max(np.abs(got[:n] - want[:n]))))
        cells = []
        for i, e in enumerate(errs):
            o = ""
            if prev is not None and e > 0 and prev[0][i] > 0:
                p = math.log(prev[0][i] / e) / math.log(prev[1] / h)
                o = f" ({p:.2f})"
                orders.append((cols[i], p))
            cells.append(f"{e:.3e}{o}")
        prev = (errs, h)
        md.append(f"| {1e3 * h:g} | " + " | ".join(cells) + f" | {r.stable} | {r.wall_s:.1f} |")
    text = "\n".join(md)
    if out:
        pathlib.Path(out).parent.mkdir(parents=True, exist_ok=True)
        pathlib.Path(out).with_suffix(".md").write_text(text + "\n")
    print(text)
    print(json.dumps({"orders": orders}))
    return orders
