"""hybeam-sweep's study checks and its chunked, resumable runs, without running an FMU: the
FMU is a modelDescription.xml alone (fakefmu.py) and, where variants run, `run_chunk` is
replaced by a stand-in that answers from the parameter values (docs/sweeps.md).

- a grid over the maximum is refused up front with its count and how to raise the maximum;
  the variants are generated lazily (a 10^9 grid's first points at once);
- results are written per chunk: an interrupted sweep keeps what ran and a rerun runs only
  the rest;
- the study is checked against the FMU's variables (names, causality) and every number is
  finite before anything runs; each error names the field, the value and the fix, and the CLI
  exits non-zero with one line (no traceback).
"""

import itertools
import math
import time

import numpy as np
import pandas as pd
import pytest
from fakefmu import BEAM, write_fmu
from hybeam.sweep import cli, sweep
from hybeam.sweep import run as run_module
from hybeam.sweep.study import StudyError, load


@pytest.fixture
def fmu(tmp_path):
    return write_fmu(tmp_path / "beam.fmu", "beam", BEAM)


def _write(tmp_path, fmu, study="", parameters=None, inputs="", outputs=None, name="s.toml"):
    parameters = parameters or '"tip.length" = [1.5, 2.0, 2.5]\n"*.density" = [7850.0, 15700.0]'
    outputs = outputs or (
        'series = ["tip.position.y"]\nsummaries = { drop = "range(tip.position.y)" }'
    )
    text = (
        f'[study]\nfmu = "{fmu}"\nstop_time = 0.01\nstep = 1e-3\n{study}\n'
        f"[parameters]\n{parameters}\n[inputs]\n{inputs}\n[outputs]\n{outputs}\n"
    )
    p = tmp_path / name
    p.write_text(text)
    return p


def _cli_error(capsys, argv) -> str:
    """The one-line error of `hybeam-sweep ARGV`: SystemExit non-zero, no traceback."""
    with pytest.raises(SystemExit) as e:
        cli.main(argv)
    assert e.value.code not in (0, None)
    err = capsys.readouterr().err.strip()
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    return err


# --- T1: the grid's size, lazy variants, results per chunk and resume -------------------------


def test_a_grid_over_the_maximum_is_refused_up_front_with_its_count(tmp_path, fmu):
    values = "[" + ", ".join(str(1.0 + k) for k in range(1000)) + "]"
    params = f'"tip.length" = {values}\n"tip.density" = {values}\n"root.density" = {values}'
    path = _write(tmp_path, fmu, parameters=params)
    t0 = time.perf_counter()
    with pytest.raises(StudyError, match=r"1000000000 variants.*max_variants"):
        load(path)
    assert time.perf_counter() - t0 < 2.0
    # the limit is a key of [study] ...
    small = _write(tmp_path, fmu, study="max_variants = 4", name="small.toml")
    with pytest.raises(StudyError, match=r"\[study\] .*6 variants.*max_variants = 4"):
        load(small)
    assert load(_write(tmp_path, fmu, study="max_variants = 6", name="six.toml")).count() == 6


def test_the_cli_refuses_a_grid_over_max_variants(tmp_path, fmu, capsys):
    """--max-variants: the limit as an option, refused before anything runs."""
    path = _write(tmp_path, fmu)
    err = _cli_error(
        capsys, ["run", str(path), "--out", str(tmp_path / "o"), "--max-variants", "4"]
    )
    assert "6 variants" in err and "--max-variants" in err, err
    assert not (tmp_path / "o" / "variants.parquet").exists()


def test_the_variants_of_a_huge_grid_are_generated_lazily(tmp_path, fmu):
    values = "[" + ", ".join(str(1.0 + k) for k in range(1000)) + "]"
    params = f'"tip.length" = {values}\n"tip.density" = {values}\n"root.density" = {values}'
    study = load(_write(tmp_path, fmu, parameters=params), max_variants=10**9)
    t0 = time.perf_counter()
    first = list(itertools.islice(study.variants(), 3))
    assert time.perf_counter() - t0 < 0.5
    assert study.count() == 10**9
    assert first[2] == {"tip.length": 1.0, "tip.density": 1.0, "root.density": 3.0}


def _stand_in(calls: list, stop_after: int | None = None):
    """A `run_chunk` answering each variant from its values (drop = the tip length), counting
    the variants run; raises KeyboardInterrupt on chunk `stop_after` (0-based)."""

    def run_chunk(data, digest, study, chunk):
        if stop_after is not None and len(calls) == stop_after:
            raise KeyboardInterrupt
        calls.append([vid for vid, _ in chunk])
        out = []
        for vid, v in chunk:
            t = np.array([0.0, study.stop_time])
            x = np.array([0.0, v["tip.length"]])
            out.append(
                (
                    vid,
                    {
                        "status": "ok",
                        "message": "",
                        "summaries": {"drop": v["tip.length"] * v["*.density"]},
                        "time": t,
                        "series": {"tip.position.y": x},
                        "wall_s": 0.0,
                    },
                )
            )
        return out

    return run_chunk


def test_an_interrupted_sweep_keeps_its_chunks_and_a_rerun_runs_only_the_rest(
    tmp_path, fmu, monkeypatch
):
    path = _write(tmp_path, fmu)  # 3 x 2 = 6 variants
    calls = []
    monkeypatch.setattr(run_module, "run_chunk", _stand_in(calls, stop_after=2))
    with pytest.raises(KeyboardInterrupt):
        sweep.run(path, tmp_path / "out", serial=True, quiet=True)
    kept = sum(len(c) for c in calls)
    assert 1 <= kept < 6
    assert list((tmp_path / "out" / "chunks").glob("*.parquet")), "no chunk written"
    again = []
    monkeypatch.setattr(run_module, "run_chunk", _stand_in(again))
    v = sweep.run(path, tmp_path / "out", serial=True, quiet=True)
    assert sum(len(c) for c in again) == 6 - kept
    # every variant in grid order, as one uninterrupted run gives them
    whole = []
    monkeypatch.setattr(run_module, "run_chunk", _stand_in(whole))
    ref = sweep.run(path, tmp_path / "whole", serial=True, quiet=True)
    assert sum(len(c) for c in whole) == 6
    pd.testing.assert_frame_equal(v.drop(columns="wall_s"), ref.drop(columns="wall_s"))
    assert list(v["tip.length"]) == [1.5, 1.5, 2.0, 2.0, 2.5, 2.5]
    s1 = pd.read_parquet(tmp_path / "out" / "series.parquet")
    s2 = pd.read_parquet(tmp_path / "whole" / "series.parquet")
    pd.testing.assert_frame_equal(s1, s2)
    # a third run runs nothing
    none = []
    monkeypatch.setattr(run_module, "run_chunk", _stand_in(none))
    sweep.run(path, tmp_path / "out", serial=True, quiet=True)
    assert none == []


def test_a_sweep_whose_variants_all_fail_still_writes_its_tables_and_plot(
    tmp_path, fmu, monkeypatch
):
    def refuse(data, digest, study, chunk):
        return [
            (vid, {"status": "failed", "message": "refused", "wall_s": 0.0}) for vid, _ in chunk
        ]

    monkeypatch.setattr(run_module, "run_chunk", refuse)
    v = sweep.run(_write(tmp_path, fmu), tmp_path / "out", serial=True, quiet=True)
    assert (v["status"] == "failed").all() and v["drop"].isna().all()
    assert (tmp_path / "out" / "sweep.png").exists()


# --- T2: the study checked against the FMU, finite numbers, known keys ------------------------

BAD = [
    # (what, study, parameters, inputs, outputs, the error's pattern)
    ("misspelt parameter", "", '"tip.lenght" = [1.0]', "", None, r"'tip.lenght'.*tip\.length"),
    ("an input as parameter", "", '"tip.force.y" = [1.0]', "", None, r"'tip.force.y'.*input"),
    ("unknown input", "", None, '"tip.force.z" = 1.0', None, r"\[inputs\] 'tip.force.z'.*force\.y"),
    ("an output as input", "", None, '"tip.position.y" = 1.0', None, r"'tip.position.y'.*output"),
    (
        "unknown series",
        "",
        None,
        "",
        'series = ["tip.positon.y"]',
        r"\[outputs\] series.*'tip.positon.y'.*tip\.position\.y",
    ),
    (
        "unknown summary variable",
        "",
        None,
        "",
        'summaries = { drop = "range(tip.y)" }',
        r"\[outputs\] summaries\.drop.*tip\.y",
    ),
    ("NaN parameter value", "", '"tip.length" = [nan]', "", None, r"'tip.length'.*nan.*finite"),
    ("NaN input", "", None, '"tip.force.y" = nan', None, r"'tip.force.y'.*nan.*finite"),
    (
        "infinite frequency",
        "",
        None,
        '"root.position.y" = { sine = { amplitude = 0.01, frequency = inf } }',
        None,
        r"sine\.frequency.*inf.*finite",
    ),
    ("infinite step", "step = inf", None, "", None, r"\[study\] step.*inf.*finite"),
    ("infinite stop time", "stop_time = inf", None, "", None, r"\[study\] stop_time.*inf"),
    ("unknown study key", "stoptime = 2.0", None, "", None, r"\[study\] stoptime.*stop_time"),
    (
        "unknown outputs key",
        "",
        None,
        "",
        'series = ["tip.position.y"]\nsummary = { a = "max(tip.position.y)" }',
        r"\[outputs\] summary.*summaries",
    ),
    (
        "a summary named like a column",
        "",
        None,
        "",
        'summaries = { status = "max(tip.position.y)" }',
        r"summaries\.status.*another name",
    ),
    (
        "unknown key of an input",
        "",
        None,
        '"tip.force.y" = { sine = { amplitude = 1.0, frequency = 1.0 }, phase = 3 }',
        None,
        r"\[inputs\] 'tip.force.y'.*phase",
    ),
    ("decimate true", "decimate = true", None, "", None, r"\[study\] decimate.*True.*integer"),
    (
        "two parameters setting one",
        "",
        '"*.density" = [1.0]\n"tip.density" = [2.0]',
        "",
        None,
        r"'tip.density'.*'\*\.density'",
    ),
]


@pytest.mark.parametrize(
    "what, study, params, inputs, outputs, pattern", BAD, ids=[b[0] for b in BAD]
)
def test_a_bad_study_is_refused_naming_the_field_the_value_and_the_fix(
    tmp_path, fmu, capsys, what, study, params, inputs, outputs, pattern
):
    text = _write(tmp_path, fmu, "", params, inputs, outputs).read_text()
    if study:
        # replace the key when the study sets one of the defaults, else add it
        key = study.split("=")[0].strip()
        lines = [ln for ln in text.splitlines() if not ln.startswith(key + " =")]
        lines.insert(1, study)
        text = "\n".join(lines) + "\n"
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(StudyError, match=pattern):
        load(path)
    err = _cli_error(capsys, ["run", str(path), "--out", str(tmp_path / "o"), "--serial"])
    assert err.startswith("hybeam-sweep: "), err
    assert not (tmp_path / "o" / "variants.parquet").exists()


def test_a_file_that_is_no_fmu_is_refused(tmp_path, capsys):
    fake = tmp_path / "beam.fmu"
    fake.write_text("not a zip")
    path = _write(tmp_path, fake)
    with pytest.raises(StudyError, match=r"\[study\] fmu = .*beam\.fmu.*not an FMU"):
        load(path)
    _cli_error(capsys, ["run", str(path), "--out", str(tmp_path / "o")])


def test_plot_of_a_directory_without_a_sweep_is_one_line(tmp_path, capsys):
    err = _cli_error(capsys, ["plot", str(tmp_path / "nothing")])
    assert "hybeam-sweep run" in err, err


def test_the_values_of_the_study_stay_numbers(tmp_path, fmu):
    """A good study still loads: finite values, known names, its count the grid's."""
    s = load(_write(tmp_path, fmu, inputs='"tip.force.y" = -200.0'))
    assert s.count() == 6 and all(math.isfinite(x) for x in s.parameters["tip.length"])
