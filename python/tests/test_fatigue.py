"""hybeam-fatigue (issue 40 item 3) against independent references: the rainflow count of the
ASTM E1049-85 example history (§5.4.4, Fig. 6: ranges 3, 4, 6, 8, 9 with 0.5, 1.5, 0.5, 1.0,
0.5 cycles), Miner's damage of a constant-amplitude history n (2a)^m / C and its equivalent
range 2a, the cut-off, the command line on a run's CSV and on a sweep's series, and the bad
inputs named."""

import json
import math

import numpy as np
import pandas as pd
import pytest
from hybeam.fatigue import cli
from hybeam.fatigue.damage import FatigueError, SNCurve, assess, cycles, parse_sn


def test_astm_e1049_example_history():
    c = cycles([-2, 1, -3, 5, -1, 3, -4, 4, -2])
    assert c.tolist() == [[3, 0.5], [4, 1.5], [6, 0.5], [8, 1.0], [9, 0.5]]


def _constant(a: float, n: int, mean: float = 0.0) -> list[float]:
    """n full cycles of range 2a about `mean`, peaks and troughs only."""
    return [mean + a * (1 if k % 2 == 0 else -1) for k in range(2 * n + 1)]


def test_miner_damage_of_constant_amplitude_is_n_over_cycles_to_failure():
    sn = SNCurve(m=3.0, C=2e6 * 71e6**3)
    a, n = 40e6, 1000
    r = assess(_constant(a, n, mean=15e6), sn)
    exact = n / sn.cycles_to_failure(2 * a)
    assert math.isclose(r.damage, exact, rel_tol=1e-12), (r.damage, exact)
    assert math.isclose(r.largest_range, 2 * a, rel_tol=1e-15)
    # the equivalent range at n cycles is the range itself
    assert math.isclose(assess(_constant(a, n), sn, n_ref=n).equivalent_range, 2 * a, rel_tol=1e-12)
    # below the cut-off: no damage
    assert assess(_constant(a, n), SNCurve(3.0, sn.C, cutoff=2 * a * 1.01)).damage == 0.0


def test_cli_on_a_run_csv_and_on_a_sweep(tmp_path, capsys):
    t = np.linspace(0.0, 1.0, 2001)
    stress = 20e6 + 30e6 * np.sin(2 * np.pi * 10 * t)
    csv = tmp_path / "run.csv"
    pd.DataFrame({"time": t, "station.root_weld.stress": stress}).to_csv(csv, index=False)
    out = tmp_path / "r.json"
    code = cli.main(
        [str(csv), "--station", "root_weld", "--sn", "m=3,C=7.16e29", "--json", str(out)]
    )
    assert code == 0, capsys.readouterr().err
    got = json.loads(out.read_text())["run"]
    want = assess(stress, SNCurve(3.0, 7.16e29))
    assert math.isclose(got["damage"], want.damage, rel_tol=1e-12)
    # ten sine cycles from the mean (peaks sampled exactly): 9.5 cycles of range 60 MPa and
    # the first rise and the last fall, half cycles of 30 MPa
    exact = (9.5 * 60e6**3 + 2 * 0.5 * 30e6**3) / 7.16e29
    assert math.isclose(got["damage"], exact, rel_tol=1e-9), (got["damage"], exact)
    # a study: one damage per variant, the second twice the amplitude (8× the damage)
    series = pd.concat(
        [
            pd.DataFrame({"variant": v, "time": t, "station.root_weld.stress": k * stress})
            for v, k in (("v0", 1.0), ("v1", 2.0))
        ]
    )
    study = tmp_path / "study"
    study.mkdir()
    series.to_parquet(study / "series.parquet", index=False)
    sn = tmp_path / "sn.toml"
    sn.write_text("[root_weld]\nm = 3\nC = 7.16e29\n")
    assert (
        cli.main([str(study), "--station", "root_weld", "--sn-file", str(sn), "--json", str(out)])
        == 0
    )
    per = json.loads(out.read_text())
    assert math.isclose(per["v1"]["damage"], 8 * per["v0"]["damage"], rel_tol=1e-12)


@pytest.mark.parametrize(
    ("sn", "message"),
    [
        ("m=-3,C=1e12", r"m = -3: the S-N exponent must be positive"),
        ("m=3,C=0", r"C = 0: the S-N constant must be positive"),
        ("m=3", r"missing C"),
        ("m=3,C=1e12,k=2", r"unknown field 'k'"),
        ("m=3,C=abc", r"C = 'abc' is not a number"),
        ("m=3;C=1", r"m = '3;C=1' is not a number"),
        ("m=3,C", r"'C' is not KEY=VALUE"),
    ],
)
def test_bad_curves_are_named(sn, message):
    with pytest.raises(FatigueError, match=message):
        parse_sn(sn)


def test_cli_names_missing_columns_and_bad_files(tmp_path, capsys):
    csv = tmp_path / "run.csv"
    pd.DataFrame({"time": [0.0, 1.0], "tip.position.y": [0.0, 1.0]}).to_csv(csv, index=False)
    assert cli.main([str(csv), "--station", "root_weld", "--sn", "m=3,C=1e12"]) == 2
    assert "no column 'station.root_weld.stress'" in capsys.readouterr().err
    sn = tmp_path / "sn.toml"
    sn.write_text("[root_weld]\nm = -3\nC = 1e12\n")
    assert cli.main([str(csv), "--station", "root_weld", "--sn-file", str(sn)]) == 2
    err = capsys.readouterr().err
    assert "[root_weld]: m = -3" in err and "must be positive" in err
    assert cli.main([str(csv), "--station", "root_weld"]) == 2
    assert "give the S-N curve once" in capsys.readouterr().err


def test_cli_names_unreadable_files_and_text_columns(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_bytes(b"\xff\xfe\x00garbage")
    assert cli.main([str(bad), "--station", "w", "--sn", "m=3,C=1e12"]) == 2
    assert "cannot read it as a table" in capsys.readouterr().err
    text = tmp_path / "text.csv"
    pd.DataFrame({"station.w.stress": ["a", "b"]}).to_csv(text, index=False)
    assert cli.main([str(text), "--station", "w", "--sn", "m=3,C=1e12"]) == 2
    assert "is not numeric" in capsys.readouterr().err
