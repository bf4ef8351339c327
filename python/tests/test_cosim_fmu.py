"""hybeam-cosim on the roof boom's FMU alone (10 steps of 1 ms, on a still mount in its static
equilibrium): a value the FMU refuses ends in one line carrying the FMU's own message (its
logger callback), not fmpy's "fmi2SetReal failed with status 3"; the FMU's warnings are
printed; and a run in which no energy is exchanged says that its stability is not judged
instead of calling it NOT stable."""

import json

import pytest
from hybeam.cosim import cli


@pytest.fixture
def system(tmp_path, boom_fmu):
    path = tmp_path / "boom.toml"
    path.write_text(
        f'[system]\nt_end = 0.01\nstep = 1e-3\n[fmus.boom]\npath = "{boom_fmu}"\n'
        '[energy]\nstored = ["boom.energy.kinetic", "boom.energy.strain", '
        '"boom.energy.potential"]\n[record]\ncolumns = ["boom.tip.position.y"]\n'
    )
    return path


def _run(system, tmp_path, *options):
    return cli.main([str(system), "--scheme", "naive", "--out", str(tmp_path / "o"), *options])


def test_a_value_the_fmu_refuses_is_one_line_with_the_fmus_message(system, tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        _run(system, tmp_path, "--set", "boom.tip.inner_diameter=0.06")
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    print(err)
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert "tip.inner_diameter" in err and "must be in [0, diameter = 0.05)" in err, err
    assert "failed with status" not in err


def test_the_fmus_warnings_are_printed(system, tmp_path, capsys):
    """visualization.directory under a regular file: the FMU cannot write its ParaView series
    and says so with fmi2Warning (docs/fmu-variables.md); the run goes on."""
    (tmp_path / "a_file").write_text("")
    view = tmp_path / "a_file" / "view"
    code = _run(system, tmp_path, "--set", f"boom.visualization.directory={view}")
    err = capsys.readouterr().err
    print(err)
    assert "warning from boom" in err and "Not a directory" in err, err
    assert err.count("warning from boom") == 1
    assert code == 0


def test_a_run_that_exchanges_no_energy_is_not_judged(system, tmp_path, capsys):
    code = _run(system, tmp_path)
    captured = capsys.readouterr()
    record = json.loads(captured.out.strip().splitlines()[-1])
    print(captured.err)
    assert "stability not judged" in captured.err and "NOT stable" not in captured.err
    assert record["stable"] is None and record["steps"] == 10
    assert code == 0


def test_hybeam_cosim_study_runs_on_the_library(system, tmp_path, capsys):
    """`hybeam-cosim-study` (cli.study) on `hybeam.cosim.stability` and `hybeam.cosim.run`: a
    stability map of two cells and an order study, each writing its tables."""
    out = tmp_path / "map"
    argv = ["map", str(system), "--scheme", "naive", "--steps", "1e-3,2e-3"]
    argv += ["--grid", "boom.tip.density=7850", "--t-end", "0.01", "--jobs", "1", "--out", str(out)]
    assert cli.study(argv) == 0
    rows = (out.with_suffix(".csv")).read_text().splitlines()
    assert len(rows) == 3 and out.with_suffix(".svg").exists()
    assert "Stability map: `map " in out.with_suffix(".md").read_text()
    argv = ["order", str(system), "--scheme", "naive", "--steps", "2e-3,1e-3"]
    argv += ["--reference", "5e-4", "--columns", "boom.tip.position.y", "--t-end", "0.01"]
    assert cli.study([*argv, "--jobs", "1", "--out", str(tmp_path / "order")]) == 0
    assert "| 2 |" in (tmp_path / "order.md").read_text()
    assert '{"orders"' in capsys.readouterr().out
