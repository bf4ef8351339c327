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

An OSP system structure (`OspSystemStructure.xml`) is read too (`load_osp`): its simulators
and connections (variable groups expanded from the `<modelName>_OspModelDescription.xml` beside
each FMU), one `naive` and one `implicit` scheme on all connections, no energy ledger.
"""

from __future__ import annotations

import pathlib
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

import tomllib


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


def _fail(where: str, value, fix: str):
    raise SystemFileError(f"{where} = {value!r}: {fix}")


def _var(where: str, text, fmus) -> tuple[str, str]:
    if not isinstance(text, str) or "." not in text:
        _fail(where, text, 'write FMU.VARIABLE, e.g. "car.mount.position.x"')
    fmu, var = text.split(".", 1)
    if fmu not in fmus:
        _fail(where, text, f"{fmu!r} is not an FMU of [fmus] ({sorted(fmus)})")
    return fmu, var


def _num(where: str, value, positive=True) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float):
        _fail(where, value, "give a number")
    if positive and not value > 0:
        _fail(where, value, "give a positive number")
    return float(value)


def load(path, fmu_paths: dict[str, str] | None = None) -> System:
    """Reads a system file (TOML, or an OSP system structure `.xml`)."""
    path = pathlib.Path(path)
    if path.suffix.lower() == ".xml":
        return load_osp(path, fmu_paths)
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
    for name, spec in doc.get("fmus", {}).items():
        if not isinstance(spec, dict) or "path" not in spec:
            _fail(f"[fmus.{name}]", spec, 'give at least path = "NAME.fmu"')
        unknown = set(spec) - {"path", "parameters", "knobs"}
        if unknown:
            _fail(f"[fmus.{name}]", sorted(unknown), "keys are path, parameters, knobs")
        p = (fmu_paths or {}).get(name) or base / spec["path"]
        # numbers for Real parameters; a string for a String parameter (e.g. the beam's
        # visualization.directory)
        params = {
            k: v if isinstance(v, str) else _num(f"fmus.{name}.parameters.{k}", v, False)
            for k, v in spec.get("parameters", {}).items()
        }
        knobs = {}
        for k, v in spec.get("knobs", {}).items():
            knobs[k] = [v] if isinstance(v, str) else list(v)
        fmus[name] = FmuSpec(name, pathlib.Path(p), params, knobs)
    if not fmus:
        _fail(f"{path}: [fmus]", {}, 'declare at least one FMU: [fmus.NAME] path = "..."')
    for name in fmu_paths or {}:
        if name not in fmus:
            _fail(f"--fmu {name}", fmu_paths[name], f"no such FMU in [fmus] ({sorted(fmus)})")
    groups = {}
    for g, pairs in doc.get("connections", {}).items():
        conns = []
        for i, pair in enumerate(pairs):
            where = f"connections.{g}[{i}]"
            if not (isinstance(pair, list) and len(pair) == 2):
                _fail(where, pair, 'give ["FMU.OUTPUT", "FMU.INPUT"]')
            s, d = _var(where, pair[0], fmus), _var(where, pair[1], fmus)
            if s[0] == d[0]:
                _fail(where, pair, "connect two different FMUs")
            conns.append(Connection(s[0], s[1], d[0], d[1]))
        groups[g] = conns
    schemes = {}
    for name, s in doc.get(
        "schemes", {"naive": {"algorithm": "naive"}, "implicit": {"algorithm": "implicit"}}
    ).items():
        algo = s.get("algorithm", name)
        if algo not in ALGORITHMS:
            _fail(f"schemes.{name}.algorithm", algo, f"choose one of {list(ALGORITHMS)}")
        gs = s.get("connections", sorted(groups))
        for g in gs:
            if g not in groups:
                _fail(
                    f"schemes.{name}.connections",
                    g,
                    f"not a group of [connections] ({sorted(groups)})",
                )
        schemes[name] = Scheme(name, algo, list(gs))
    sysdoc = doc.get("system", {})
    order = list(sysdoc.get("order", list(fmus)))
    if sorted(order) != sorted(fmus):
        _fail("system.order", order, f"list every FMU of [fmus] once ({sorted(fmus)})")
    init = list(sysdoc.get("initialization", []))
    for n in init:
        if n not in fmus:
            _fail("system.initialization", n, f"not an FMU of [fmus] ({sorted(fmus)})")
    e = doc.get("energy", {})
    energy = Energy(
        stored=[_var("energy.stored", v, fmus) for v in e.get("stored", [])],
        supplied=[_var("energy.supplied", v, fmus) for v in e.get("supplied", [])],
        dissipated=[_var("energy.dissipated", v, fmus) for v in e.get("dissipated", [])],
        divergence=_num("energy.divergence", e.get("divergence", float("inf"))),
    )
    rec = doc.get("record", {})
    record = [_var("record.columns", v, fmus) for v in rec.get("columns", [])]
    plot = [_var("record.plot", v, fmus) for v in rec.get("plot", rec.get("columns", []))]
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


def load_osp(path, fmu_paths: dict[str, str] | None = None) -> System:
    """Reads an OSP system structure: simulators, `VariableConnection`s and
    `VariableGroupConnection`s (direction from the FMUs' causalities)."""
    from fmpy import read_model_description

    path = pathlib.Path(path)
    root = ET.parse(path).getroot()

    def find(el, tag):
        return [c for c in el.iter() if c.tag.split("}")[-1] == tag]

    fmus = {}
    for s in find(root, "Simulator"):
        name = s.get("name")
        p = (fmu_paths or {}).get(name) or path.parent / s.get("source")
        fmus[name] = FmuSpec(name, pathlib.Path(p))
    causality = {
        n: {v.name: v.causality for v in read_model_description(str(f.path)).modelVariables}
        for n, f in fmus.items()
    }
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
    step = [float(e.text) for e in find(root, "BaseStepSize")]
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
