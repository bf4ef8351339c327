"""hybeam-cosim's tables: cosim.parquet holds cosim.csv's table, every value bit for bit."""

import csv

import numpy as np
import pandas as pd
from hybeam.cosim.master import Result
from hybeam.cosim.run import write


def test_the_parquet_table_equals_the_csv_table(tmp_path):
    rng = np.random.default_rng(7)
    res = Result(["time", "a.x", "b.y", "energy_residual"])
    res.rows = [
        [k * 1e-3, *rng.normal(size=2), float("nan") if k == 0 else 1e-9 * k] for k in range(50)
    ]
    write(res, tmp_path, "test", ["a.x"])
    table = pd.read_parquet(tmp_path / "cosim.parquet")
    assert list(table.columns) == res.columns
    assert np.array_equal(table.to_numpy(), np.array(res.rows), equal_nan=True)
    with open(tmp_path / "cosim.csv") as fh:
        rows = list(csv.reader(fh))[1:]
    assert np.array_equal(np.array(rows, dtype=float), table.to_numpy(), equal_nan=True)
