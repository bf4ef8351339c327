"""Plotting is the `plot` extra (python/pyproject.toml): without matplotlib the tools run and
write their tables, and a figure asked for says which extra to install (one line, no
traceback). matplotlib is hidden by a None entry in sys.modules (its import then fails)."""

import sys

import pandas as pd
import pytest
from fakefmu import BEAM, write_fmu
from hybeam import plotting
from hybeam.cosim import cli as cosim_cli
from hybeam.sweep import cli as sweep_cli
from hybeam.sweep import run as run_module
from hybeam.sweep import sweep
from test_sweep_checks import _stand_in, _write


@pytest.fixture
def no_matplotlib(monkeypatch):
    for name in [m for m in sys.modules if m == "matplotlib" or m.startswith("matplotlib.")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "matplotlib", None)
    assert not plotting.available()


@pytest.fixture
def system(tmp_path, boom_fmu):
    path = tmp_path / "boom.toml"
    path.write_text(
        f'[system]\nt_end = 0.01\nstep = 1e-3\n[fmus.boom]\npath = "{boom_fmu}"\n'
        '[record]\ncolumns = ["boom.tip.position.y"]\n'
    )
    return path


def test_hybeam_cosim_without_matplotlib_names_the_extra_before_running(
    system, tmp_path, capsys, no_matplotlib
):
    out = tmp_path / "o"
    with pytest.raises(SystemExit) as e:
        cosim_cli.main([str(system), "--scheme", "naive", "--out", str(out)])
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert "pip install 'hybeam-tools[plot]'" in err and "--no-plot" in err, err
    assert not out.exists()  # refused before the run


def test_hybeam_cosim_no_plot_without_matplotlib_writes_the_tables(system, tmp_path, no_matplotlib):
    out = tmp_path / "o"
    argv = [str(system), "--scheme", "naive", "--out", str(out), "--no-plot"]
    assert cosim_cli.main(argv) == 0
    assert len(pd.read_parquet(out / "cosim.parquet")) == 11
    assert (out / "cosim.csv").exists() and not (out / "cosim.png").exists()


def test_a_sweep_without_matplotlib_writes_its_tables_and_says_how_to_plot(
    tmp_path, monkeypatch, capsys, no_matplotlib
):
    fmu = write_fmu(tmp_path / "beam.fmu", "beam", BEAM)
    monkeypatch.setattr(run_module, "run_chunk", _stand_in([]))
    out = tmp_path / "out"
    v = sweep.run(_write(tmp_path, fmu), out, serial=True, quiet=True)
    assert len(v) == 6 and (out / "variants.parquet").exists()
    assert not (out / "sweep.png").exists()
    err = capsys.readouterr().err
    assert "pip install 'hybeam-tools[plot]'" in err and f"hybeam-sweep plot {out}" in err, err
    with pytest.raises(SystemExit) as e:
        sweep_cli.main(["plot", str(out)])
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "pip install 'hybeam-tools[plot]'" in err, err
