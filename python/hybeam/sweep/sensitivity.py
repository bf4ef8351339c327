"""The ranking of a sampled study: how strongly each parameter drives each summary."""

from __future__ import annotations

import pandas as pd


def sensitivity(
    variants: pd.DataFrame, parameters: list[str], summaries: list[str]
) -> pd.DataFrame:
    """The sampled study's ranking: per summary, each parameter's Spearman rank correlation
    with it over the variants that ran (scipy.stats.spearmanr), strongest |rho| first."""
    from scipy.stats import spearmanr

    ok = variants[variants["status"] == "ok"]
    rows = []
    for s in summaries:
        for p in parameters:
            rho = spearmanr(ok[p], ok[s]).statistic if len(ok) > 2 else float("nan")
            rows.append({"summary": s, "parameter": p, "spearman_rho": float(rho)})
    table = pd.DataFrame(rows)
    table["rank"] = (
        table.groupby("summary")["spearman_rho"]
        .transform(lambda r: r.abs().rank(ascending=False, method="first"))
        .astype(int)
    )
    return table.sort_values(["summary", "rank"], ignore_index=True)
