"""hybeam-cosim's bad inputs: each refused before any FMU is instantiated with one line naming
the field, the value and the fix, and a non-zero exit (no traceback). The FMUs are a
modelDescription.xml alone (fakefmu.py): what is checked is the system file, the options and
the FMUs' variables (names, causality), not a run. And a run with nothing in its energy ledger
says that its stability is not judged, instead of calling it not stable."""

import pytest
from fakefmu import BEAM, CAR, write_fmu
from hybeam.cosim import cli
from hybeam.cosim.master import run
from hybeam.cosim.system import SystemFileError, load

SYSTEM = """
[system]
t_end = 0.5
step = 1e-3
order = ["car", "boom"]

[fmus.car]
path = "car.fmu"
[fmus.boom]
path = "boom.fmu"
knobs = { mass_factor = "*.density" }

[connections]
mount = [["car.mount.position.y", "boom.root.position.y"]]
reaction = [["boom.root.force.y", "car.beam.root.force.y"]]

[schemes]
naive = { algorithm = "naive", connections = ["mount", "reaction"] }

[energy]
stored = ["car.energy.total", "boom.energy.kinetic"]

[record]
columns = ["car.body.pitch", "boom.tip.position.y"]
"""


@pytest.fixture
def system(tmp_path):
    write_fmu(tmp_path / "car.fmu", "car", CAR)
    write_fmu(tmp_path / "boom.fmu", "boom", BEAM)
    path = tmp_path / "system.toml"
    path.write_text(SYSTEM)
    return path


def _error(capsys, argv) -> str:
    with pytest.raises(SystemExit) as e:
        cli.main(argv)
    assert e.value.code not in (0, None)
    err = capsys.readouterr().err.strip()
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    assert err.startswith("hybeam-cosim: "), err
    return err


# (what, a replacement in the system file (old, new) or None, options, the error's pattern)
BAD = [
    (
        "misspelt input",
        ('"boom.root.position.y"]]', '"boom.root.positon.y"]]'),
        [],
        r"connections\.mount\[0\].*'root.positon.y'.*root\.position\.y",
    ),
    (
        "misspelt output",
        ('"car.mount.position.y",', '"car.mount.pos.y",'),
        [],
        r"connections\.mount\[0\].*'mount.pos.y'",
    ),
    (
        "an input as the source",
        (
            '["boom.root.force.y", "car.beam.root.force.y"]',
            '["car.beam.root.force.y", "boom.tip.force.y"]',
        ),
        [],
        r"connections\.reaction\[0\].*beam\.root\.force\.y.*input, not an output",
    ),
    (
        "misspelt record column",
        ('"car.body.pitch", "boom', '"car.body.pich", "boom'),
        [],
        r"record\.columns.*'body.pich'.*body\.pitch",
    ),
    (
        "misspelt energy term",
        ('"boom.energy.kinetic"]', '"boom.energy.kinetc"]'),
        [],
        r"energy\.stored.*'energy.kinetc'",
    ),
    (
        "misspelt parameter of the file",
        ("knobs = {", 'parameters = { "tip.lenght" = 2.0 }\nknobs = {'),
        [],
        r"fmus\.boom\.parameters.*'tip.lenght'.*tip\.length",
    ),
    (
        "two connections into one input",
        (
            'reaction = [["boom.root.force.y", "car.beam.root.force.y"]]',
            'reaction = [["boom.root.force.y", "car.beam.root.force.y"], '
            '["boom.root.moment.z", "car.beam.root.force.y"]]',
        ),
        [],
        r"car\.beam\.root\.force\.y.*boom\.root\.force\.y.*boom\.root\.moment\.z",
    ),
    ("t_end = inf", ("t_end = 0.5", "t_end = inf"), [], r"system\.t_end = inf.*finite"),
    ("step = nan", ("step = 1e-3", "step = nan"), [], r"system\.step = nan.*finite"),
    ("path not a string", ('path = "car.fmu"', "path = 5"), [], r"fmus\.car\.path = 5"),
    (
        "connections of a group not a list",
        ('mount = [["car.mount.position.y", "boom.root.position.y"]]', "mount = 5"),
        [],
        r"connections\.mount = 5.*list",
    ),
    (
        "knobs not a table",
        ('knobs = { mass_factor = "*.density" }', "knobs = 5"),
        [],
        r"fmus\.boom\.knobs = 5",
    ),
    (
        "a scheme not a table",
        ('naive = { algorithm = "naive", connections = ["mount", "reaction"] }', 'naive = "naive"'),
        [],
        r"schemes\.naive = 'naive'.*algorithm",
    ),
    (
        "record columns a string",
        ('columns = ["car.body.pitch", "boom.tip.position.y"]', 'columns = "car.body.pitch"'),
        [],
        r"record\.columns = 'car.body.pitch'.*list",
    ),
    (
        "order a string",
        ('order = ["car", "boom"]', 'order = "car"'),
        [],
        r"system\.order = 'car'.*list",
    ),
    (
        "unknown key of [system]",
        ("t_end = 0.5", "t_end = 0.5\ntend = 1.0"),
        [],
        r"system\.tend.*t_end",
    ),
    (
        "parameters not a table",
        ("knobs = {", "parameters = [1]\nknobs = {"),
        [],
        r"fmus\.boom\.parameters = \[1\]",
    ),
    (
        "mass_factor nan",
        None,
        ["--set", "boom.mass_factor=nan"],
        r"boom\.mass_factor=nan.*positive",
    ),
    (
        "mass_factor inf",
        None,
        ["--set", "boom.mass_factor=inf"],
        r"boom\.mass_factor=inf.*positive",
    ),
    ("mass_factor 0", None, ["--set", "boom.mass_factor=0"], r"boom\.mass_factor=0.*positive"),
    ("mass_factor -1", None, ["--set", "boom.mass_factor=-1"], r"boom\.mass_factor=-1.*positive"),
    ("parameter nan", None, ["--set", "boom.tip.length=nan"], r"boom\.tip\.length=nan.*finite"),
    (
        "--set without =",
        None,
        ["--set", "boom.mass_factor"],
        r"--set 'boom.mass_factor'.*FMU\.NAME=VALUE",
    ),
    ("--set unknown", None, ["--set", "boom.tip.lenght=2"], r"tip\.lenght.*tip\.length"),
    ("--fmu without =", None, ["--fmu", "boom.fmu"], r"--fmu 'boom.fmu'.*NAME=PATH"),
    ("--max-iterations 0", None, ["--max-iterations", "0"], r"--max-iterations = 0.*>= 1"),
    ("--rtol -1", None, ["--rtol", "-1"], r"--rtol = -1.*positive"),
    ("--rtol nan", None, ["--rtol", "nan"], r"--rtol = nan.*positive"),
    ("--t-end 0", None, ["--t-end", "0"], r"--t-end = 0.*positive"),
    ("--step 0", None, ["--step", "0"], r"--step = 0.*positive"),
    ("--step inf", None, ["--step", "inf"], r"--step = inf.*finite"),
    ("--step -1", None, ["--step", "-1"], r"--step = -1.*positive"),
    ("--t-end inf", None, ["--t-end", "inf"], r"--t-end = inf.*finite"),
    ("--step over --t-end", None, ["--step", "1.0"], r"--step = 1.*--t-end"),
    ("--t-end not a multiple", None, ["--t-end", "0.0105"], r"--t-end.*multiple.*--step"),
    ("unknown scheme", None, ["--scheme", "fast"], r"--scheme 'fast'.*naive"),
]


@pytest.mark.parametrize("what, edit, options, pattern", BAD, ids=[b[0] for b in BAD])
def test_a_bad_input_is_one_line_naming_the_field_and_the_fix(
    tmp_path, system, capsys, what, edit, options, pattern
):
    if edit:
        text = system.read_text()
        assert edit[0] in text, edit
        system.write_text(text.replace(edit[0], edit[1], 1))
    argv = [str(system), "--scheme", "naive", "--out", str(tmp_path / "out"), *options]
    err = _error(capsys, argv)
    import re

    assert re.search(pattern, err), err
    assert not (tmp_path / "out" / "cosim.csv").exists()


def test_a_file_that_is_no_fmu_is_refused(tmp_path, system, capsys):
    (tmp_path / "boom.fmu").write_text("not a zip")
    err = _error(capsys, [str(system), "--scheme", "naive"])
    assert "fmus.boom.path" in err and "not an FMU" in err and "--fmu boom=PATH" in err, err
    other = tmp_path / "other.txt"
    other.write_text("no")
    err = _error(capsys, [str(system), "--scheme", "naive", "--fmu", f"boom={other}"])
    assert "not an FMU" in err, err


def test_a_missing_fmu_or_system_file_is_one_line(tmp_path, system, capsys):
    (tmp_path / "car.fmu").unlink()
    err = _error(capsys, [str(system), "--scheme", "naive"])
    assert "fmus.car.path" in err and "no such file" in err, err
    _error(capsys, [str(tmp_path / "none.toml")])


def test_two_connections_into_one_input_are_refused_by_load(tmp_path, system):
    text = system.read_text().replace(
        'mount = [["car.mount.position.y", "boom.root.position.y"]]',
        'mount = [["car.mount.position.y", "boom.root.position.y"], '
        '["car.mount.acceleration.y", "boom.root.position.y"]]',
    )
    system.write_text(text)
    with pytest.raises(SystemFileError, match=r"boom\.root\.position\.y.*fed by two"):
        load(system)


def test_a_run_without_energy_exchanged_is_not_judged(tmp_path):
    """Two oscillators at rest in their static equilibrium: the ledger's terms stay zero, so
    there is nothing to measure a residual against; the run says so instead of calling itself
    not stable."""
    from test_master import subsystems
    from test_master import system as oscillators

    res = run(oscillators(True), "naive", subsystems(1.0, x1=0.0, x2=0.0), 2e-3, 0.02)
    assert res.stable is None, res.message
    assert "not judged" in res.verdict and "--t-end" in res.verdict, res.verdict
    assert res.summary("naive", 2e-3)["stable"] is None
    # a run that exchanges energy is judged as before
    moving = run(oscillators(True), "implicit", subsystems(1.0), 2e-3, 0.2)
    assert moving.stable is True and moving.verdict == "stable"
