"""hybeam-cosim reads SSP 1.0 systems (an .ssp archive or a bare .ssd, docs/coupling.md):

- `hybeam-ssp` writes a system file as an SSD that validates against the SSP 1.0 schema
  (fmpy's XSDs) and reads back into the same system (the FMUs, the scheme's connections in
  order, the start values, the knobs, order, initialization, energy ledger, record, times);
- an .ssp archive holds SystemStructure.ssd and the FMUs in resources/;
- a run from the .ssp equals the run from the TOML bit for bit (the roof boom's FMU, 10 ms);
- a bad SSP input ends in one line naming the element and the fix, exit code 2.

The FMUs of the checks are a modelDescription.xml alone (fakefmu.py)."""

import re
import zipfile

import numpy as np
import pandas as pd
import pytest
from fakefmu import BEAM, CAR, write_fmu
from hybeam.cosim import cli, ssp
from hybeam.cosim.system import SystemFileError, load

SYSTEM = """
[system]
t_end = 0.5
step = 2e-3
order = ["car", "boom"]
initialization = ["boom", "car", "boom"]

[fmus.car]
path = "car.fmu"
parameters = { mass = 1200.0 }
[fmus.boom]
path = "boom.fmu"
parameters = { "tip.length" = 2.5, "visualization.directory" = "out/view" }
knobs = { mass_factor = ["*.density", "*.youngs_modulus"] }

[connections]
mount = [["car.mount.position.y", "boom.root.position.y"],
         ["car.mount.acceleration.y", "boom.root.acceleration.y"]]
reaction = [["boom.root.force.y", "car.beam.root.force.y"]]
spare = [["boom.root.moment.z", "car.beam.root.force.y"]]

[schemes]
naive = { algorithm = "naive", connections = ["mount", "reaction"] }
implicit = { algorithm = "implicit", connections = ["mount", "reaction"] }
other = { algorithm = "naive", connections = ["mount", "spare"] }

[energy]
stored = ["car.energy.total", "boom.energy.kinetic"]
divergence = 1e6

[record]
columns = ["car.body.pitch", "boom.tip.position.y"]
plot = ["boom.tip.position.y"]
"""


@pytest.fixture
def toml(tmp_path):
    write_fmu(tmp_path / "car.fmu", "car", CAR)
    write_fmu(tmp_path / "boom.fmu", "boom", BEAM)
    path = tmp_path / "system.toml"
    path.write_text(SYSTEM)
    return path


def _same(a, b, scheme="implicit"):
    assert a.connections(scheme) == b.connections(scheme)
    for n in a.fmus:
        assert a.fmus[n].path.resolve() == b.fmus[n].path.resolve()
        assert a.fmus[n].parameters == b.fmus[n].parameters
        assert a.fmus[n].knobs == b.fmus[n].knobs
    assert list(a.fmus) == list(b.fmus)
    assert (a.order, a.initialization, a.energy) == (b.order, b.initialization, b.energy)
    assert (a.record, a.plot, a.t_end, a.step) == (b.record, b.plot, b.t_end, b.step)


def test_an_exported_ssd_is_valid_ssp_and_reads_back_into_the_same_system(toml, tmp_path):
    assert cli.export([str(toml), "--out", str(tmp_path / "sub" / "x.ssd")]) == 0
    ssd = tmp_path / "sub" / "x.ssd"
    ssp.validate(ssd)  # the SSP 1.0 schema (fmpy/ssp/schema)
    assert 'source="../car.fmu"' in ssd.read_text()
    system = load(ssd)
    _same(load(toml), system)
    # one configuration: both algorithms on its connections; the other groups stay in TOML
    assert sorted(system.schemes) == ["implicit", "naive"]
    assert system.connections("naive") == load(toml).connections("naive")
    # another scheme's connections
    other = ssp.export(load(toml), "other", tmp_path / "other.ssd")
    assert load(other).connections("naive") == load(toml).connections("other")


def test_an_ssp_archive_holds_the_ssd_and_the_fmus(toml, tmp_path):
    archive = ssp.export(load(toml), "implicit", tmp_path / "x.ssp")
    with zipfile.ZipFile(archive) as z:
        names = set(z.namelist())
        assert names == {"SystemStructure.ssd", "resources/car.fmu", "resources/boom.fmu"}
        assert z.read("resources/boom.fmu") == (tmp_path / "boom.fmu").read_bytes()
    system = load(archive)
    for n in ("car", "boom"):
        assert system.fmus[n].path.read_bytes() == (tmp_path / f"{n}.fmu").read_bytes()
    # --fmu replaces a packed FMU
    assert load(archive, {"boom": str(tmp_path / "boom.fmu")}).fmus["boom"].path == (
        tmp_path / "boom.fmu"
    )


def _ssd(toml, tmp_path, old=None, new=None):
    ssd = ssp.export(load(toml), "implicit", tmp_path / "bad.ssd")
    if old is not None:
        text = ssd.read_text()
        assert old in text, old
        ssd.write_text(text.replace(old, new))
    return ssd


def _error(capsys, argv) -> str:
    with pytest.raises(SystemExit) as e:
        cli.main(argv)
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert "Traceback" not in err and len(err.splitlines()) == 1, err
    assert err.startswith("hybeam-cosim: "), err
    return err


# (what, the SSD's text (old, new), the error's pattern: the element and the fix)
BAD = [
    (
        "a connector kind the schema refuses",
        ('kind="output"', 'kind="outptu"'),
        r"bad\.ssd line \d+.*outptu.*not valid SSP 1\.0",
    ),
    ("not XML", ("</ssd:Connections>", "</ssd:Connection>"), r"line \d+.*not well-formed XML"),
    (
        "a connection to an undeclared connector",
        ('endConnector="root.position.y"', 'endConnector="root.positon.y"'),
        r"<ssd:Connection> 1 \(car\.mount\.position\.y -> boom\.root\.positon\.y\).*declare "
        r'<ssd:Connector name="root\.positon\.y" kind="input"> in <ssd:Component name="boom">',
    ),
    (
        "a connector the FMU does not have",
        ('"root.position.y"', '"root.positon.y"'),
        r"<ssd:Connection> 1 .*boom has no input 'root\.positon\.y'; did you mean "
        r"'root\.position\.y'",
    ),
    (
        "an output as the end",
        (
            'startConnector="mount.position.y" endElement="boom"',
            'startConnector="mount.position.y" endElement="car"',
        ),
        r"<ssd:Connection> 1 .*connect two different components",
    ),
    (
        "a transformation",
        (
            'endConnector="root.position.y"/>',
            'endConnector="root.position.y"><ssc:LinearTransformation factor="2"/>'
            "</ssd:Connection>",
        ),
        r"<ssd:Connection> 1 .*LinearTransformation.*not applied; remove it",
    ),
    (
        "an Integer parameter",
        ('<ssv:Real value="1200.0"/>', '<ssv:Integer value="1200"/>'),
        r'<ssd:Component name="car"> <ssv:Parameter name="mass">.*Real and String parameters',
    ),
    (
        "a parameter the FMU does not have",
        ('name="tip.length"', 'name="tip.lenght"'),
        r'<ssd:Component name="boom"> <ssv:Parameter>.*no Real parameter.*tip\.length',
    ),
    (
        "a misspelt annotation attribute",
        ('<hc:System step="0.002"', '<hc:System stepp="0.002"'),
        r"<hc:System> stepp = '0\.002'.*not an attribute.*'step'",
    ),
    (
        "a ledger term of no component",
        ('stored="car.energy.total', 'stored="cart.energy.total'),
        r"<hc:Energy> stored = 'cart\.energy\.total'.*'cart' is not an FMU",
    ),
    (
        "a recorded variable the FMU does not have",
        ('columns="car.body.pitch', 'columns="car.body.pich'),
        r"<hc:Record> columns = 'car\.body\.pich'.*did you mean 'body\.pitch'",
    ),
    (
        "a missing FMU",
        ('source="boom.fmu"', 'source="nowhere/boom.fmu"'),
        r'<ssd:Component name="boom"> source = .*nowhere/boom\.fmu.*no such file',
    ),
    (
        "a component that is not an FMU",
        (
            'type="application/x-fmu-sharedlibrary" source="boom.fmu"',
            'type="application/x-ssp-package" source="boom.fmu"',
        ),
        r'<ssd:Component name="boom"> type = .*couples FMUs',
    ),
    (
        "a nested system",
        (
            "    </ssd:Elements>",
            '      <ssd:System name="sub"/>\n    </ssd:Elements>',
        ),
        r"nested systems are not read; flatten them",
    ),
    (
        "an order without every component",
        ('order="car boom"', 'order="car"'),
        r"<hc:System> order = 'car'.*list every Component once",
    ),
]


@pytest.mark.parametrize("what, edit, pattern", BAD, ids=[b[0] for b in BAD])
def test_a_bad_ssd_is_one_line_naming_the_element_and_the_fix(
    toml, tmp_path, capsys, what, edit, pattern
):
    ssd = _ssd(toml, tmp_path, *edit)
    err = _error(capsys, [str(ssd), "--out", str(tmp_path / "o")])
    print(err)
    assert re.search(pattern, err), err


def test_an_archive_without_its_ssd_or_fmu_is_named(toml, tmp_path, capsys):
    bare = tmp_path / "empty.ssp"
    with zipfile.ZipFile(bare, "w") as z:
        z.writestr("resources/boom.fmu", b"")
    err = _error(capsys, [str(bare)])
    assert "no SystemStructure.ssd at the archive's root" in err, err
    archive = ssp.export(load(toml), "implicit", tmp_path / "x.ssp")
    with zipfile.ZipFile(archive) as z, zipfile.ZipFile(tmp_path / "y.ssp", "w") as y:
        y.writestr("SystemStructure.ssd", z.read("SystemStructure.ssd"))
    err = _error(capsys, [str(tmp_path / "y.ssp")])
    assert re.search(r'<ssd:Component name="car"> source = .*resources/car\.fmu.*pack', err), err
    with pytest.raises(SystemFileError, match="not an .ssp archive"):
        (tmp_path / "z.ssp").write_text("not a zip")
        load(tmp_path / "z.ssp")


def test_hybeam_ssp_refuses_an_output_that_is_not_ssd_or_ssp(toml, tmp_path, capsys):
    with pytest.raises(SystemExit) as e:
        cli.export([str(toml), "--out", str(tmp_path / "x.xml")])
    assert e.value.code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("hybeam-ssp: --out") and "NAME.ssd" in err, err


def test_a_run_from_the_ssp_equals_the_run_from_the_toml_bit_for_bit(boom_fmu, tmp_path):
    """The roof boom's FMU alone, 10 steps of 1 ms on a still mount, a start value and a knob
    set: the .ssp archive's run writes the TOML run's table, every value bit for bit."""
    toml = tmp_path / "boom.toml"
    toml.write_text(
        f'[system]\nt_end = 0.01\nstep = 1e-3\n[fmus.boom]\npath = "{boom_fmu}"\n'
        'parameters = { "tip.length" = 2.25 }\nknobs = { mass_factor = "*.density" }\n'
        '[energy]\nstored = ["boom.energy.kinetic", "boom.energy.strain", '
        '"boom.energy.potential"]\n[record]\ncolumns = ["boom.tip.position.y", '
        '"boom.root.force.y"]\n'
    )
    assert cli.export([str(toml), "--out", str(tmp_path / "boom.ssp")]) == 0
    tables = []
    for system in (toml, tmp_path / "boom.ssp"):
        out = tmp_path / system.suffix[1:]
        argv = [str(system), "--scheme", "naive", "--set", "boom.mass_factor=3", "--out", str(out)]
        assert cli.main([*argv, "--no-plot"]) == 0
        tables.append(pd.read_parquet(out / "cosim.parquet"))
    assert list(tables[0].columns) == list(tables[1].columns)
    assert len(tables[0]) == 11
    assert np.array_equal(tables[0].to_numpy(), tables[1].to_numpy(), equal_nan=True)
