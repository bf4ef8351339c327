"""The system file: which FMUs, how they are connected, by which schemes, and the energy ledger.

A system file (TOML; `examples/vehicle/system.toml` is the worked example):

```toml
[system]
t_end = 2.0                        # s, default stop time (--t-end)
step = 1e-3                        # s, default communication step (--step)
order = ["car", "boom"]            # the implicit scheme steps the FMUs in this order
initialization = ["boom", "car", "boom"]   # who leaves initialization mode when (see below)

[fmus.car]
path = "../../out/car.fmu"         # relative to this file; --fmu car=PATH overrides
[fmus.boom]
path = "../../out/boom.fmu"
parameters = { "solver.tolerance" = 1e-11 }   # start values set in initialization mode
knobs = { mass_factor = "*.density" }         # --set boom.mass_factor=F scales these by F

[connections]                      # named groups of [output, input] pairs "fmu.variable"
mount = [["car.mount.position.x", "boom.root.position.x"], ...]
reaction = [["boom.root.force.x", "car.beam.root.force.x"], ...]

[schemes]                          # a scheme: an algorithm on a set of connection groups
naive = { algorithm = "naive", connections = ["mount", "reaction"] }
implicit = { algorithm = "implicit", connections = ["mount", "reaction"] }

[energy]                           # the coupled energy balance, zero for the exact solution:
                                   # ΔΣ E_stored − Σ W_supplied + Σ D
stored = ["car.energy.total", "boom.energy.kinetic"]   # Σ ΔE_stored
supplied = ["car.energy.road_work", "car.energy.drive_work"]  # − Σ W_supplied (since start)
dissipated = ["car.energy.dissipated"]                 # + Σ D (outputs, since start)
divergence = 1e6                   # J: a residual beyond this stops the run as diverged

[record]
columns = ["car.body.pitch", "boom.tip.position.y"]  # written per communication point
plot = ["car.body.pitch", "boom.tip.position.y"]
```

Initialization: every FMU enters initialization mode with its parameters; then, in the listed
order, each FMU gets its inputs from the current outputs of their sources and leaves
initialization mode (an FMU listed again is reset and initialized anew: the vehicle example
starts the beam on the car's pose, the car on the beam's static reaction, and the beam again on
the car's settled pose). FMUs not listed leave in the order of `[fmus]`.

Checks: every key known, every table and list of its shape, every time and number finite,
an input fed by one connection per scheme; before any FMU is instantiated (`check`), every
variable the file names is one of its FMU's (a connection from a Real output to a Real input,
the recorded and ledger terms Real variables, the parameters parameters). Each error names the
field, the value and the fix (`SystemFileError`).

An OSP system structure (`OspSystemStructure.xml`) is read too (`load_osp`): its simulators
and connections (variable groups expanded from the `<modelName>_OspModelDescription.xml` beside
each FMU), one `naive` and one `implicit` scheme on all connections, no energy ledger.
"""

from __future__ import annotations

import fnmatch
import math
import pathlib
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from typing import Any, NoReturn

import tomllib

from hybeam.checks import did_you_mean, unknown_key


class SystemFileError(ValueError):
    """A bad system file: the message names the field, the value and the fix."""


@dataclass(frozen=True)
class Connection:
    """An output of one FMU feeding an input of another."""

    src: str
    src_var: str
    dst: str
    dst_var: str

    def __str__(self):
        return f"{self.src}.{self.src_var} -> {self.dst}.{self.dst_var}"


@dataclass
class FmuSpec:
    name: str
    path: pathlib.Path
    parameters: dict[str, float | str] = field(default_factory=dict)
    knobs: dict[str, list[str]] = field(default_factory=dict)


@dataclass
class Scheme:
    name: str
    algorithm: str
    groups: list[str]


@dataclass
class Energy:
    stored: list[tuple[str, str]] = field(default_factory=list)
    supplied: list[tuple[str, str]] = field(default_factory=list)
    dissipated: list[tuple[str, str]] = field(default_factory=list)
    divergence: float = float("inf")

    @property
    def declared(self) -> bool:
        return bool(self.stored)


@dataclass
class System:
    path: pathlib.Path
    fmus: dict[str, FmuSpec]
    groups: dict[str, list[Connection]]
    schemes: dict[str, Scheme]
    order: list[str]
    initialization: list[str]
    energy: Energy
    record: list[tuple[str, str]]
    plot: list[tuple[str, str]]
    t_end: float = 1.0
    step: float = 1e-3
    #: the names of a source other than TOML for the fields the checks name (an SSP's
    #: elements: "fmus.car.path" -> "<Component name="car"> source"), see `label`
    labels: dict[str, str] = field(default_factory=dict)

    def label(self, where: str) -> str:
        """The field `where` (TOML's name: "connections.mount[0]") as the file names it."""
        return self.labels.get(where, where)

    def connections(self, scheme: str) -> list[Connection]:
        s = self.scheme(scheme)
        return [c for g in s.groups for c in self.groups[g]]

    def scheme(self, name: str) -> Scheme:
        if name not in self.schemes:
            raise SystemFileError(
                f"--scheme {name!r}: {self.path} has no such scheme; "
                f"choose one of {sorted(self.schemes)}"
            )
        return self.schemes[name]


ALGORITHMS = ("naive", "implicit")


def _fail(where: str, value: object, fix: str) -> NoReturn:
    raise SystemFileError(f"{where} = {value!r}: {fix}")


_like = did_you_mean


def _table(where: str, value) -> dict:
    if not isinstance(value, dict):
        _fail(where, value, f"must be a table ([{where}] or {where} = {{ KEY = VALUE, ... }})")
    return value


def _list(where: str, value, example: str) -> list:
    if not isinstance(value, list):
        _fail(where, value, f"give a list, e.g. {example}")
    return value


def _keys(where: str, table: dict, keys) -> None:
    if (k := unknown_key(table, keys)) is not None:
        _fail(
            f"{where}.{k}",
            table[k],
            f"not a key of {where}{_like(k, keys)} (the keys: {', '.join(keys)})",
        )


def _names(where: str, value, fmus, example='"car.body.pitch"') -> list[tuple[str, str]]:
    return [_var(where, v, fmus) for v in _list(where, value, f"[{example}]")]


def _var(where: str, text, fmus) -> tuple[str, str]:
    if not isinstance(text, str) or "." not in text:
        _fail(where, text, 'write FMU.VARIABLE, e.g. "car.mount.position.x"')
    fmu, var = text.split(".", 1)
    if fmu not in fmus:
        _fail(where, text, f"{fmu!r} is not an FMU of [fmus] ({sorted(fmus)})")
    return fmu, var


def _num(where: str, value, positive=True, finite=True) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        _fail(where, value, "give a number")
    if math.isnan(value) or (finite and math.isinf(value)):
        _fail(where, value, "give a finite number")
    if positive and not value > 0:
        _fail(where, value, "give a positive number")
    return float(value)


def one_source(name: str, conns: list[tuple[str, Connection]]) -> None:
    """Refuses an input fed by two of `conns` ((where, connection) pairs of scheme `name`)."""
    fed: dict[tuple[str, str], tuple[str, Connection]] = {}
    for where, c in conns:
        key = (c.dst, c.dst_var)
        if key in fed:
            w0, c0 = fed[key]
            _fail(
                f"schemes.{name}",
                f"{c.dst}.{c.dst_var}",
                f"the input is fed by two connections, {c0.src}.{c0.src_var} ({w0}) and "
                f"{c.src}.{c.src_var} ({where}); give each input one source in a scheme",
            )
        fed[key] = (where, c)


def load(path: str | pathlib.Path, fmu_paths: dict[str, str] | None = None) -> System:
    """Reads a system file (TOML; an SSP 1.0 `.ssp` archive or bare `.ssd`, see `ssp.py`;
    or an OSP system structure `.xml`). `fmu_paths`: FMU paths by name (`--fmu NAME=PATH`)
    instead of the file's."""
    path = pathlib.Path(path)
    fmu_paths = fmu_paths or {}
    if path.suffix.lower() == ".xml":
        return load_osp(path, fmu_paths)
    if path.suffix.lower() in (".ssp", ".ssd"):
        from .ssp import load_ssp

        return load_ssp(path, fmu_paths)
    try:
        doc = tomllib.loads(path.read_text())
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise SystemFileError(f"{path}: {e}") from None
    known = {"system", "fmus", "connections", "schemes", "energy", "record"}
    for key in doc:
        if key not in known:
            _fail(f"{path}: [{key}]", "...", f"not a section; the sections are {sorted(known)}")
    base = path.parent
    fmus = {}
    for name, spec in _table("fmus", doc.get("fmus", {})).items():
        if not isinstance(spec, dict) or "path" not in spec:
            _fail(f"[fmus.{name}]", spec, 'give at least path = "NAME.fmu"')
        unknown = set(spec) - {"path", "parameters", "knobs"}
        if unknown:
            _fail(f"[fmus.{name}]", sorted(unknown), "keys are path, parameters, knobs")
        if not isinstance(spec["path"], str):
            _fail(f"fmus.{name}.path", spec["path"], 'give the FMU\'s path, e.g. "../out/car.fmu"')
        p = (fmu_paths or {}).get(name) or base / spec["path"]
        # numbers for Real parameters; a string for a String parameter (e.g. the beam's
        # visualization.directory)
        params = {
            k: v if isinstance(v, str) else _num(f"fmus.{name}.parameters.{k}", v, False)
            for k, v in _table(f"fmus.{name}.parameters", spec.get("parameters", {})).items()
        }
        knobs = {}
        for k, v in _table(f"fmus.{name}.knobs", spec.get("knobs", {})).items():
            knobs[k] = (
                [v]
                if isinstance(v, str)
                else _list(
                    f"fmus.{name}.knobs.{k}", v, '"*.density" or ["*.density", "*.youngs_modulus"]'
                )
            )
            if not all(isinstance(x, str) for x in knobs[k]):
                _fail(f"fmus.{name}.knobs.{k}", v, 'give parameter names or globs, "*.density"')
        fmus[name] = FmuSpec(name, pathlib.Path(p), params, knobs)
    if not fmus:
        _fail(f"{path}: [fmus]", {}, 'declare at least one FMU: [fmus.NAME] path = "..."')
    for name in fmu_paths or {}:
        if name not in fmus:
            _fail(f"--fmu {name}", fmu_paths[name], f"no such FMU in [fmus] ({sorted(fmus)})")
    groups = {}
    where_of: dict[Connection, str] = {}
    for g, pairs in _table("connections", doc.get("connections", {})).items():
        conns = []
        example = '[["car.mount.position.y", "boom.root.position.y"]]'
        for i, pair in enumerate(_list(f"connections.{g}", pairs, example)):
            where = f"connections.{g}[{i}]"
            if not (isinstance(pair, list) and len(pair) == 2):
                _fail(where, pair, 'give ["FMU.OUTPUT", "FMU.INPUT"]')
            s, d = _var(where, pair[0], fmus), _var(where, pair[1], fmus)
            if s[0] == d[0]:
                _fail(where, pair, "connect two different FMUs")
            c = Connection(s[0], s[1], d[0], d[1])
            conns.append(c)
            where_of.setdefault(c, where)
        groups[g] = conns
    schemes = {}
    for name, s in _table(
        "schemes",
        doc.get(
            "schemes", {"naive": {"algorithm": "naive"}, "implicit": {"algorithm": "implicit"}}
        ),
    ).items():
        if not isinstance(s, dict):
            _fail(
                f"schemes.{name}",
                s,
                '{ algorithm = "naive" or "implicit", connections = ["GROUP", ...] }',
            )
        _keys(f"schemes.{name}", s, ("algorithm", "connections"))
        algo = s.get("algorithm", name)
        if algo not in ALGORITHMS:
            _fail(f"schemes.{name}.algorithm", algo, f"choose one of {list(ALGORITHMS)}")
        gs = _list(f"schemes.{name}.connections", s.get("connections", sorted(groups)), '["mount"]')
        for g in gs:
            if g not in groups:
                _fail(
                    f"schemes.{name}.connections",
                    g,
                    f"not a group of [connections] ({sorted(groups)})",
                )
        one_source(name, [(where_of[c], c) for g in gs for c in groups[g]])
        schemes[name] = Scheme(name, algo, list(gs))
    sysdoc = _table("system", doc.get("system", {}))
    _keys("system", sysdoc, ("t_end", "step", "order", "initialization"))
    order = _list("system.order", sysdoc.get("order", list(fmus)), str(list(fmus)))
    if sorted(map(str, order)) != sorted(fmus):
        _fail("system.order", order, f"list every FMU of [fmus] once ({sorted(fmus)})")
    init = _list("system.initialization", sysdoc.get("initialization", []), str(list(fmus)))
    for n in init:
        if n not in fmus:
            _fail("system.initialization", n, f"not an FMU of [fmus] ({sorted(fmus)})")
    ledger = _table("energy", doc.get("energy", {}))
    _keys("energy", ledger, ("stored", "supplied", "dissipated", "divergence"))
    energy = Energy(
        stored=_names("energy.stored", ledger.get("stored", []), fmus),
        supplied=_names("energy.supplied", ledger.get("supplied", []), fmus),
        dissipated=_names("energy.dissipated", ledger.get("dissipated", []), fmus),
        divergence=_num("energy.divergence", ledger.get("divergence", float("inf")), finite=False),
    )
    rec = _table("record", doc.get("record", {}))
    _keys("record", rec, ("columns", "plot"))
    record = _names("record.columns", rec.get("columns", []), fmus)
    plot = _names("record.plot", rec.get("plot", rec.get("columns", [])), fmus)
    return System(
        path,
        fmus,
        groups,
        schemes,
        order,
        init,
        energy,
        record,
        plot,
        _num("system.t_end", sysdoc.get("t_end", 1.0)),
        _num("system.step", sysdoc.get("step", 1e-3)),
    )


class Variables:
    """An FMU's variables by name, from its modelDescription.xml (what `check` and `--set`
    need before the FMU is instantiated)."""

    def __init__(self, md: Any) -> None:
        self.md = md
        self.vars = {v.name: v for v in md.modelVariables}

    def match(self, pattern: str) -> list[str]:
        """Variable names matching a glob pattern (`*.density`)."""
        return [n for n in self.vars if fnmatch.fnmatchcase(n, pattern)]

    def parameters(self, pattern: str) -> list[str]:
        """The parameters among `match(pattern)`."""
        return [n for n in self.match(pattern) if self.vars[n].causality == "parameter"]

    def names(self, causality: str | None = None, kind: str | None = "Real") -> list[str]:
        return [
            n
            for n, v in self.vars.items()
            if (causality is None or v.causality == causality) and (kind is None or v.type == kind)
        ]


def model_description(where: str, path: pathlib.Path, fix: str) -> Any:
    """The FMI 2.0 co-simulation FMU's model description (fmpy), or SystemFileError."""
    from fmpy import read_model_description

    if not pathlib.Path(path).is_file():
        _fail(where, str(path), f"no such file; {fix}")
    try:
        md = read_model_description(str(path))
    except Exception as e:  # not a zip, no or an invalid modelDescription.xml, ...
        text = " ".join(str(e).split())[:200]
        _fail(where, str(path), f"not an FMU ({type(e).__name__}: {text}); {fix}")
    if md.fmiVersion != "2.0" or md.coSimulation is None:
        _fail(where, str(path), f"not an FMI 2.0 co-simulation FMU (FMI {md.fmiVersion}); {fix}")
    return md


def variables(system: System) -> dict[str, Variables]:
    """The variables of each FMU of `system` (its modelDescription.xml), or SystemFileError
    for a missing file or one that is not an FMI 2.0 co-simulation FMU."""
    return {
        n: Variables(
            model_description(
                system.label(f"fmus.{n}.path"),
                f.path,
                f"build it or pass --fmu {n}=PATH (an FMI 2.0 co-simulation FMU)",
            )
        )
        for n, f in system.fmus.items()
    }


def check(system: System, models: dict[str, Variables]) -> None:
    """Checks every variable `system` names against its FMU's (`models`): connections from a
    Real output to a Real input, recorded and ledger terms Real variables, the parameters of
    [fmus] parameters (Real for a number, String for a text)."""

    def var(where, value, fmu, name, causality=None):
        m = models[fmu]
        v = m.vars.get(name)
        if v is None or v.type != "Real":
            pool = m.names(causality)
            what = f"{causality} " if causality else "Real variable "
            _fail(system.label(where), value, f"{fmu} has no {what}{name!r}{_like(name, pool)}")
        if causality and v.causality != causality:
            _fail(
                system.label(where),
                value,
                f"{fmu}.{name} is an {v.causality}, not an {causality}; connect "
                '["FMU.OUTPUT", "FMU.INPUT"]',
            )

    for g, conns in system.groups.items():
        for i, c in enumerate(conns):
            where, value = f"connections.{g}[{i}]", [f"{c.src}.{c.src_var}", f"{c.dst}.{c.dst_var}"]
            var(where, value, c.src, c.src_var, "output")
            var(where, value, c.dst, c.dst_var, "input")
    e = system.energy
    for where, terms in [
        ("energy.stored", e.stored),
        ("energy.supplied", e.supplied),
        ("energy.dissipated", e.dissipated),
        ("record.columns", system.record),
        ("record.plot", system.plot),
    ]:
        for fmu, name in terms:
            var(where, f"{fmu}.{name}", fmu, name)
    for n, spec in system.fmus.items():
        m = models[n]
        for k, given in spec.parameters.items():
            v = m.vars.get(k)
            kind = "String" if isinstance(given, str) else "Real"
            if v is None or v.causality != "parameter" or v.type != kind:
                _fail(
                    system.label(f"fmus.{n}.parameters"),
                    {k: given},
                    f"{n} has no {kind} parameter {k!r}{_like(k, m.names('parameter', kind))}",
                )


def _float(where: str, text) -> float:
    try:
        return float(text)
    except (TypeError, ValueError):
        _fail(where, text, "give a number")


def _osp_groups(fmu_path: pathlib.Path) -> dict[str, list[str]]:
    """Variable groups of an FMU from `<modelName>_OspModelDescription.xml` beside it: group
    name → variable names in order (nested groups flattened)."""
    from fmpy import read_model_description

    model = read_model_description(str(fmu_path)).modelName
    candidates = [
        fmu_path.parent / f"{model}_OspModelDescription.xml",
        fmu_path.with_name(f"{fmu_path.stem}_OspModelDescription.xml"),
    ]
    for c in candidates:
        if c.exists():
            root = ET.parse(c).getroot()
            break
    else:
        raise SystemFileError(
            f"{fmu_path}: no OSP model description beside it "
            f"({candidates[0].name}); VariableGroupConnection needs it"
        )
    groups: dict[str, list[str]] = {}

    def walk(el, owners):
        tag = el.tag.split("}")[-1]
        name = el.get("name")
        if tag == "Variable":
            name = el.get("ref") or name
            for o in owners:
                groups.setdefault(o, []).append(name)
            return
        if tag != "OspModelDescription" and name and tag != "VariableGroups":
            owners = owners + [name]
        for child in el:
            walk(child, owners)

    walk(root, [])
    return groups


def load_osp(path: str | pathlib.Path, fmu_paths: dict[str, str] | None = None) -> System:
    """Reads an OSP system structure: simulators, `VariableConnection`s and
    `VariableGroupConnection`s (direction from the FMUs' causalities)."""
    path = pathlib.Path(path)
    fmu_paths = fmu_paths or {}
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        raise SystemFileError(f"{path}: {e}; give an OSP system structure (XML)") from None

    def find(el, tag):
        return [c for c in el.iter() if c.tag.split("}")[-1] == tag]

    fmus = {}
    for s in find(root, "Simulator"):
        name = s.get("name")
        p = (fmu_paths or {}).get(name) or path.parent / str(s.get("source"))
        fmus[name] = FmuSpec(name, pathlib.Path(p))
    for name in fmu_paths or {}:
        if name not in fmus:
            _fail(
                f"--fmu {name}",
                fmu_paths[name],
                f"no such Simulator in {path.name} ({sorted(fmus)})",
            )
    models = {
        n: model_description(f"Simulator {n} source", f.path, f"pass --fmu {n}=PATH")
        for n, f in fmus.items()
    }
    causality = {n: {v.name: v.causality for v in md.modelVariables} for n, md in models.items()}
    conns = []

    def pair(a, b, where):
        (sa, va), (sb, vb) = a, b
        ca, cb = causality[sa].get(va), causality[sb].get(vb)
        if ca == "output" and cb == "input":
            conns.append(Connection(sa, va, sb, vb))
        elif cb == "output" and ca == "input":
            conns.append(Connection(sb, vb, sa, va))
        else:
            _fail(where, f"{sa}.{va} ({ca}) - {sb}.{vb} ({cb})", "join an output and an input")

    for c in find(root, "VariableConnection"):
        vs = [(v.get("simulator"), v.get("name")) for v in find(c, "Variable")]
        if len(vs) != 2 or any(s not in fmus for s, _ in vs):
            _fail("VariableConnection", vs, "give two <Variable simulator= name=> of Simulators")
        pair(vs[0], vs[1], "VariableConnection")
    cache = {}
    for c in find(root, "VariableGroupConnection"):
        gs = [(g.get("simulator"), g.get("name")) for g in find(c, "VariableGroup")]
        names = []
        for sim, g in gs:
            if sim not in cache:
                cache[sim] = _osp_groups(fmus[sim].path)
            if g not in cache[sim]:
                _fail("VariableGroupConnection", f"{sim}.{g}", "no such variable group")
            names.append(cache[sim][g])
        if len(names[0]) != len(names[1]):
            _fail("VariableGroupConnection", gs, "the groups differ in size")
        for a, b in zip(names[0], names[1], strict=True):
            pair((gs[0][0], a), (gs[1][0], b), f"VariableGroupConnection {gs}")
    one_source("naive", [("VariableConnection", c) for c in conns])
    step = [
        _num("BaseStepSize", _float("BaseStepSize", e.text)) for e in find(root, "BaseStepSize")
    ]
    return System(
        path,
        fmus,
        {"all": conns},
        {
            "naive": Scheme("naive", "naive", ["all"]),
            "implicit": Scheme("implicit", "implicit", ["all"]),
        },
        list(fmus),
        [],
        Energy(),
        [],
        [],
        1.0,
        step[0] if step else 1e-3,
    )
