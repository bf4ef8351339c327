"""SSP 1.0 systems (System Structure and Parameterization, the format Dymola, OMSimulator,
Simcenter and libcosim read): `load_ssp` reads an `.ssp` archive (a zip holding
`SystemStructure.ssd` and the FMUs, `resources/NAME.fmu`) or a bare `.ssd` into the `System`
a TOML system file gives; `export` writes a TOML system's scheme as either (`hybeam-ssp`).

The SSD (read by fmpy's `fmpy.ssp.ssd.read_ssd`, validated against the SSP 1.0 schema fmpy
ships) carries the FMUs (`<Component>`s: name, source), their connections (`<Connection>`s
from an output `<Connector>` to an input one), their start values (`<ParameterBindings>` with
an inline `<ssv:ParameterSet>` of Real and String parameters) and the stop time
(`<DefaultExperiment stopTime>`). What SSP 1.0 cannot say is an annotation of type
`org.hybeam.cosim` (other tools skip it):

```xml
<ssd:System name="vehicle"> ...
  <ssd:Annotations>
    <ssc:Annotation type="org.hybeam.cosim">
      <hc:System xmlns:hc="urn:hybeam:ssp:cosim" step="0.001" order="car boom"
                 initialization="boom car boom">
        <hc:Energy stored="car.energy.total boom.energy.kinetic" supplied="car.energy.road_work"
                   dissipated="car.energy.dissipated" divergence="1000000.0"/>
        <hc:Record columns="car.body.pitch boom.tip.position.y" plot="car.body.pitch"/>
      </hc:System>
    </ssc:Annotation>
  </ssd:Annotations>
</ssd:System>
<ssd:Component name="boom" ...> ...
  <ssd:Annotations>
    <ssc:Annotation type="org.hybeam.cosim">
      <hc:Knobs xmlns:hc="urn:hybeam:ssp:cosim">
        <hc:Knob name="mass_factor" parameters="*.density *.youngs_modulus"/>
      </hc:Knobs>
    </ssc:Annotation>
  </ssd:Annotations>
</ssd:Component>
```

The SSD's connections are one configuration: the system gets the schemes `naive` and
`implicit`, both on all of them (`--scheme`); connection groups and the other schemes of a
system file (the vehicle's interface-mass and partner-model schemes, whose connections feed
inputs the plain ones feed too) stay in TOML. Not supported (each refused with one line
naming the element and the fix): nested `<System>`s, signal dictionaries, connections to the
system's own connectors, connection and parameter transformations, parameter mappings,
Integer, Boolean, Enumeration and Binary parameters, components other than FMUs.
"""

from __future__ import annotations

import atexit
import io
import math
import os
import pathlib
import shutil
import tempfile
import zipfile
from collections.abc import Iterable
from typing import Any
from xml.sax.saxutils import quoteattr

from .system import (
    Connection,
    Energy,
    FmuSpec,
    Scheme,
    System,
    _fail,
    _num,
    _var,
    one_source,
)

NS = {
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
    "hc": "urn:hybeam:ssp:cosim",
}
#: the type of hybeam-cosim's annotations
ANNOTATION = "org.hybeam.cosim"
FMU_TYPE = "application/x-fmu-sharedlibrary"
#: the SSD of an .ssp archive
SSD = "SystemStructure.ssd"
#: the one connection group of an SSP system (the schemes `naive` and `implicit` run on it)
GROUP = "ssd"


def _ssd_bytes(path: pathlib.Path) -> tuple[bytes, zipfile.ZipFile | None]:
    """The SSD's text, and the archive when `path` is an .ssp."""
    if not path.is_file():
        _fail(str(path), str(path), "no such file; give an .ssp archive or an .ssd file")
    if path.suffix.lower() == ".ssd":
        return path.read_bytes(), None
    try:
        zf = zipfile.ZipFile(path)
    except (OSError, zipfile.BadZipFile) as e:
        _fail(str(path), str(path), f"not an .ssp archive ({e}); give a zip with {SSD}")
    if SSD not in zf.namelist():
        zf.close()
        _fail(
            str(path),
            sorted(zf.namelist())[:5],
            f"no {SSD} at the archive's root; put the system structure there",
        )
    return zf.read(SSD), zf


def validate(path: str | pathlib.Path) -> None:
    """Validates an .ssd file or an .ssp archive's SSD against the SSP 1.0 schema (fmpy's
    `validate_tree` and XSDs), or SystemFileError with the first error's line."""
    path = pathlib.Path(path)
    data, zf = _ssd_bytes(path)
    if zf is not None:
        zf.close()
    _root(path, data)


def _root(path: pathlib.Path, data: bytes) -> Any:
    """The SSD's parsed and schema-validated root element (lxml)."""
    from fmpy.ssp.ssd import validate_tree
    from lxml import etree

    try:
        root = etree.fromstring(data)
    except etree.XMLSyntaxError as e:
        _fail(f"{path} line {e.lineno}", e.msg, "not well-formed XML; fix the SSD's syntax")
    try:
        validate_tree(root, "SystemStructureDescription.xsd")
    except Exception as e:
        lines = str(e).splitlines()
        first = lines[1] if len(lines) > 1 else lines[0] if lines else type(e).__name__
        where, _, msg = first.partition("): ")
        line = where.split("(line ")[-1].split(",")[0] if "(line " in where else "?"
        _fail(
            f"{path} line {line}",
            msg.strip() or first,
            "not valid SSP 1.0 (SystemStructureDescription.xsd, fmpy/ssp/schema); fix the "
            "element the schema names",
        )
    return root


def _annotation(el: Any, tag: str) -> Any:
    """The `hc:TAG` element of `el`'s org.hybeam.cosim annotation, or None."""
    for a in el.findall("ssd:Annotations/ssc:Annotation", NS):
        if a.get("type") == ANNOTATION:
            found = a.find(f"hc:{tag}", NS)
            if found is None:
                inner = [c.tag for c in a]
                _fail(
                    f"<ssc:Annotation type={ANNOTATION!r}> of <{_name(el)}>",
                    inner,
                    f"give one <hc:{tag} xmlns:hc={NS['hc']!r}> (docs/coupling.md)",
                )
            return found
    return None


def _name(el: Any) -> str:
    tag = el.tag.split("}")[-1]
    return f'ssd:{tag} name="{el.get("name")}"'


def _attrs(where: str, el: Any, keys: Iterable[str]) -> dict[str, str]:
    known = list(keys)
    for k in el.attrib:
        if k not in known:
            _fail(f"{where} {k}", el.get(k), f"not an attribute of it (the attributes: {known})")
    return dict(el.attrib)


def _words(text: str | None) -> list[str]:
    return (text or "").split()


def _extract(zf: zipfile.ZipFile, entry: str) -> pathlib.Path:
    """An archive's FMU, extracted to a folder removed at exit."""
    tmp = pathlib.Path(tempfile.mkdtemp(prefix="hybeam-ssp-"))
    atexit.register(shutil.rmtree, tmp, True)
    target = tmp / pathlib.PurePosixPath(entry).name
    with zf.open(entry) as src, open(target, "wb") as dst:
        shutil.copyfileobj(src, dst)
    return target


def load_ssp(path: str | pathlib.Path, fmu_paths: dict[str, str] | None = None) -> System:
    """Reads an SSP 1.0 system (an .ssp archive or a bare .ssd) into a `System` (see the
    module's docstring); `fmu_paths`: FMU paths by component name instead of the sources."""
    from fmpy.ssp.ssd import Component, read_ssd

    path = pathlib.Path(path)
    data, zf = _ssd_bytes(path)
    try:
        root = _root(path, data)
        # fmpy's object model of the SSD (validated above), read from an archive
        if zf is None:
            mem = io.BytesIO()
            with zipfile.ZipFile(mem, "w") as z:
                z.writestr(SSD, data)
            ssd = read_ssd(mem, validate=False)
        else:
            ssd = read_ssd(str(path), validate=False)
        return _system(path, root, ssd, zf, fmu_paths or {}, Component)
    finally:
        if zf is not None:
            zf.close()


def _system(
    path: pathlib.Path,
    root: Any,
    ssd: Any,
    zf: zipfile.ZipFile | None,
    fmu_paths: dict[str, str],
    component: Any,
) -> System:
    sys_el = root.find("ssd:System", NS)
    sysname = f'<ssd:System name="{sys_el.get("name")}">'
    if sys_el.find("ssd:Elements/ssd:System", NS) is not None:
        _fail(f"{sysname} <ssd:System>", "nested", "nested systems are not read; flatten them")
    if sys_el.find("ssd:Elements/ssd:SignalDictionaryReference", NS) is not None:
        _fail(f"{sysname} <ssd:SignalDictionaryReference>", "...", "connect components directly")
    if ssd.system.parameterBindings:
        _fail(f"{sysname} <ssd:ParameterBindings>", "...", "bind parameters on the components")
    labels: dict[str, str] = {}
    fmus: dict[str, FmuSpec] = {}
    connectors: dict[str, dict[str, str]] = {}
    comp_els = {c.get("name"): c for c in sys_el.findall("ssd:Elements/ssd:Component", NS)}
    for comp in ssd.system.elements:
        if not isinstance(comp, component):
            continue
        name = comp.name
        where = f'<ssd:Component name="{name}">'
        if comp.type not in (None, FMU_TYPE):
            _fail(f"{where} type", comp.type, f"hybeam-cosim couples FMUs; give type={FMU_TYPE!r}")
        labels[f"fmus.{name}.path"] = f"{where} source"
        labels[f"fmus.{name}.parameters"] = f"{where} <ssv:Parameter>"
        if name in fmu_paths:
            fmu = pathlib.Path(fmu_paths[name])
        elif zf is not None:
            entry = comp.source.removeprefix("./")
            if entry not in zf.namelist():
                _fail(
                    f"{where} source",
                    comp.source,
                    f"no such entry in {path.name}; pack the FMU as resources/{name}.fmu "
                    "(hybeam-ssp SYSTEM.toml --out NAME.ssp) or pass --fmu "
                    f"{name}=PATH",
                )
            fmu = _extract(zf, entry)
        else:
            src = comp.source.removeprefix("file:")
            fmu = path.parent / src
        params: dict[str, float | str] = {}
        for b in comp.parameterBindings:
            if b.source is not None or b.parameterMapping or (b.prefix or ""):
                what = "source" if b.source is not None else "a mapping or prefix"
                _fail(
                    f"{where} <ssd:ParameterBinding>",
                    b.source or b.prefix or "ParameterMapping",
                    f"{what} is not read; give the values inline "
                    "(<ssd:ParameterValues><ssv:ParameterSet>)",
                )
            for pset in b.parameterValues:
                for p in pset.parameters:
                    pwhere = f'{where} <ssv:Parameter name="{p.name}">'
                    if p.type == "Real":
                        params[p.name] = _num(pwhere, float(p.value), positive=False)
                    elif p.type == "String":
                        params[p.name] = p.value
                    else:
                        _fail(
                            pwhere,
                            p.type,
                            "hybeam-cosim sets Real and String parameters; give <ssv:Real> or "
                            "<ssv:String>",
                        )
        knobs: dict[str, list[str]] = {}
        kn = _annotation(comp_els[name], "Knobs")
        if kn is not None:
            for k in kn.findall("hc:Knob", NS):
                kw = f"{where} <hc:Knob>"
                a = _attrs(kw, k, ("name", "parameters"))
                if not a.get("name") or not _words(a.get("parameters")):
                    _fail(kw, a, 'give name="KNOB" parameters="*.density ..."')
                knobs[a["name"]] = _words(a["parameters"])
        fmus[name] = FmuSpec(name, fmu, params, knobs)
        connectors[name] = {c.name: c.kind for c in comp.connectors}
    if not fmus:
        _fail(f"{sysname} <ssd:Elements>", [], "add a <ssd:Component> per FMU")
    for name in fmu_paths:
        if name not in fmus:
            _fail(f"--fmu {name}", fmu_paths[name], f"no such Component in {path.name}")
    conns: list[Connection] = []
    conn_els = sys_el.findall("ssd:Connections/ssd:Connection", NS)
    for i, c in enumerate(ssd.system.connections):
        text = f"{c.startElement}.{c.startConnector} -> {c.endElement}.{c.endConnector}"
        where = f"<ssd:Connection> {i + 1} ({text})"
        labels[f"connections.{GROUP}[{i}]"] = where
        if c.startElement is None or c.endElement is None:
            _fail(where, text, "connect a component's output to another's input (both Elements)")
        kinds = [x.tag.split("}")[-1] for x in conn_els[i]]
        transforms = [k for k in kinds if k.endswith("Transformation")]
        if transforms or hasattr(c, "linearTransformation"):
            what = transforms[0] if transforms else "LinearTransformation"
            _fail(where, what, "transformations are not applied; remove it")
        if c.startElement == c.endElement:
            _fail(where, text, "connect two different components")
        for el, conn, kind in (
            (c.startElement, c.startConnector, "output"),
            (c.endElement, c.endConnector, "input"),
        ):
            if el not in connectors:
                _fail(where, el, f"no such Component ({sorted(connectors)})")
            if connectors[el].get(conn) != kind:
                got = connectors[el].get(conn)
                fix = (
                    f'declare <ssd:Connector name="{conn}" kind="{kind}"> in <ssd:Component '
                    f'name="{el}">'
                    if got is None
                    else f"connect from an output to an input (it is {got!r})"
                )
                _fail(where, f"{el}.{conn}", fix)
        conns.append(Connection(c.startElement, c.startConnector, c.endElement, c.endConnector))
    one_source(GROUP, [(labels[f"connections.{GROUP}[{i}]"], c) for i, c in enumerate(conns)])
    t_end = 1.0
    exp = root.find("ssd:DefaultExperiment", NS)
    if exp is not None:
        if float(exp.get("startTime", 0.0)) != 0.0:
            _fail("<ssd:DefaultExperiment> startTime", exp.get("startTime"), "start at 0")
        if exp.get("stopTime") is not None:
            t_end = _num("<ssd:DefaultExperiment> stopTime", float(exp.get("stopTime")))
    step, order, init = 1e-3, list(fmus), []
    energy, record, plot = Energy(), [], []
    ann = _annotation(sys_el, "System")
    if ann is not None:
        aw = f"{sysname} <hc:System>"
        a = _attrs(aw, ann, ("step", "order", "initialization"))
        if "step" in a:
            step = _num(f"{aw} step", _float(f"{aw} step", a["step"]))
        order = _words(a.get("order")) or order
        if sorted(order) != sorted(fmus):
            _fail(f"{aw} order", a.get("order"), f"list every Component once ({sorted(fmus)})")
        init = _words(a.get("initialization"))
        for n in init:
            if n not in fmus:
                _fail(f"{aw} initialization", n, f"not a Component ({sorted(fmus)})")
        for child in ann:
            tag = child.tag.split("}")[-1]
            if tag not in ("Energy", "Record") or not child.tag.startswith(f"{{{NS['hc']}}}"):
                _fail(f"{aw} <{tag}>", child.tag, "the children are <hc:Energy>, <hc:Record>")
        e = ann.find("hc:Energy", NS)
        if e is not None:
            ew = f"{aw} <hc:Energy>"
            ea = _attrs(ew, e, ("stored", "supplied", "dissipated", "divergence"))
            energy = Energy(
                stored=[_var(f"{ew} stored", v, fmus) for v in _words(ea.get("stored"))],
                supplied=[_var(f"{ew} supplied", v, fmus) for v in _words(ea.get("supplied"))],
                dissipated=[
                    _var(f"{ew} dissipated", v, fmus) for v in _words(ea.get("dissipated"))
                ],
                divergence=_num(
                    f"{ew} divergence",
                    _float(f"{ew} divergence", ea.get("divergence", "inf")),
                    finite=False,
                ),
            )
            for k in ("stored", "supplied", "dissipated"):
                labels[f"energy.{k}"] = f"{ew} {k}"
        r = ann.find("hc:Record", NS)
        if r is not None:
            rw = f"{aw} <hc:Record>"
            ra = _attrs(rw, r, ("columns", "plot"))
            record = [_var(f"{rw} columns", v, fmus) for v in _words(ra.get("columns"))]
            plot = [
                _var(f"{rw} plot", v, fmus) for v in _words(ra.get("plot", ra.get("columns", "")))
            ]
            labels["record.columns"] = f"{rw} columns"
            labels["record.plot"] = f"{rw} plot"
    return System(
        path,
        fmus,
        {GROUP: conns},
        {
            "naive": Scheme("naive", "naive", [GROUP]),
            "implicit": Scheme("implicit", "implicit", [GROUP]),
        },
        order,
        init,
        energy,
        record,
        plot,
        t_end,
        step,
        labels,
    )


def _float(where: str, text: str | None) -> float:
    try:
        return float(text)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        _fail(where, text, "give a number")


def _xs(x: float) -> str:
    """A float as xs:double text that reads back to the same float."""
    if math.isnan(x):
        return "NaN"
    if math.isinf(x):
        return "INF" if x > 0 else "-INF"
    return repr(float(x))


def _names(where: str, pairs: list[tuple[str, str]]) -> str:
    names = [f"{f}.{v}" for f, v in pairs]
    for n in names:
        if n.split() != [n]:
            _fail(where, n, "a name with white space cannot be listed in the SSD annotation")
    return " ".join(names)


def ssd_text(system: System, scheme: str, sources: dict[str, str], name: str) -> str:
    """The SSD of `system`'s `scheme` (its connections, in order), the FMUs at `sources`
    (URIs by FMU name), the system named `name`."""
    conns = system.connections(scheme)
    ports: dict[str, dict[str, str]] = {n: {} for n in system.fmus}
    for c in conns:
        ports[c.src].setdefault(c.src_var, "output")
        ports[c.dst].setdefault(c.dst_var, "input")
    q = quoteattr
    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f"<!-- {system.path.name}, scheme {scheme}: written by hybeam-ssp (python/hybeam/cosim/"
        "ssp.py); hybeam-cosim runs it like the system file (docs/coupling.md) -->",
        f'<ssd:SystemStructureDescription xmlns:ssc="{NS["ssc"]}"',
        f'    xmlns:ssd="{NS["ssd"]}"',
        f'    xmlns:ssv="{NS["ssv"]}"',
        f'    xmlns:hc="{NS["hc"]}" version="1.0" name={q(name)}>',
        f"  <ssd:System name={q(name)}>",
        "    <ssd:Elements>",
    ]
    for n, f in system.fmus.items():
        out.append(f"      <ssd:Component name={q(n)} type={q(FMU_TYPE)} source={q(sources[n])}>")
        if ports[n]:
            out.append("        <ssd:Connectors>")
            for var, kind in ports[n].items():
                out.append(
                    f"          <ssd:Connector name={q(var)} kind={q(kind)}><ssc:Real/>"
                    "</ssd:Connector>"
                )
            out.append("        </ssd:Connectors>")
        if f.parameters:
            out += [
                "        <ssd:ParameterBindings>",
                "          <ssd:ParameterBinding>",
                "            <ssd:ParameterValues>",
                f'              <ssv:ParameterSet version="1.0" name={q(n)}>',
                "                <ssv:Parameters>",
            ]
            for k, v in f.parameters.items():
                value = (
                    f"<ssv:String value={q(v)}/>"
                    if isinstance(v, str)
                    else f"<ssv:Real value={q(_xs(v))}/>"
                )
                out.append(f"                  <ssv:Parameter name={q(k)}>{value}</ssv:Parameter>")
            out += [
                "                </ssv:Parameters>",
                "              </ssv:ParameterSet>",
                "            </ssd:ParameterValues>",
                "          </ssd:ParameterBinding>",
                "        </ssd:ParameterBindings>",
            ]
        if f.knobs:
            out += [
                "        <ssd:Annotations>",
                f"          <ssc:Annotation type={q(ANNOTATION)}>",
                "            <hc:Knobs>",
            ]
            for k, pats in f.knobs.items():
                for p in pats:
                    if p.split() != [p]:
                        _fail(f"fmus.{n}.knobs.{k}", p, "give patterns without white space")
                out.append(f"              <hc:Knob name={q(k)} parameters={q(' '.join(pats))}/>")
            out += [
                "            </hc:Knobs>",
                "          </ssc:Annotation>",
                "        </ssd:Annotations>",
            ]
        out.append("      </ssd:Component>")
    out.append("    </ssd:Elements>")
    if conns:  # the schema wants at least one <ssd:Connection> in <ssd:Connections>
        out.append("    <ssd:Connections>")
        for c in conns:
            out.append(
                f"      <ssd:Connection startElement={q(c.src)} startConnector={q(c.src_var)} "
                f"endElement={q(c.dst)} endConnector={q(c.dst_var)}/>"
            )
        out.append("    </ssd:Connections>")
    e = system.energy
    init = f" initialization={q(' '.join(system.initialization))}" if system.initialization else ""
    out += [
        "    <ssd:Annotations>",
        f"      <ssc:Annotation type={q(ANNOTATION)}>",
        f"        <hc:System step={q(_xs(system.step))} order={q(' '.join(system.order))}{init}>",
    ]
    if e.declared or e.supplied or e.dissipated or math.isfinite(e.divergence):
        out.append(
            f"          <hc:Energy stored={q(_names('energy.stored', e.stored))} "
            f"supplied={q(_names('energy.supplied', e.supplied))} "
            f"dissipated={q(_names('energy.dissipated', e.dissipated))} "
            f"divergence={q(_xs(e.divergence))}/>"
        )
    if system.record or system.plot:
        out.append(
            f"          <hc:Record columns={q(_names('record.columns', system.record))} "
            f"plot={q(_names('record.plot', system.plot))}/>"
        )
    out += [
        "        </hc:System>",
        "      </ssc:Annotation>",
        "    </ssd:Annotations>",
        "  </ssd:System>",
        f'  <ssd:DefaultExperiment startTime="0.0" stopTime={q(_xs(system.t_end))}/>',
        "</ssd:SystemStructureDescription>",
        "",
    ]
    return "\n".join(out)


def _system_name(system: System) -> str:
    stem = system.path.stem
    return system.path.resolve().parent.name if stem == "system" else stem


def export(system: System, scheme: str, out: pathlib.Path, name: str | None = None) -> pathlib.Path:
    """Writes `system`'s `scheme` as SSP 1.0: `out` a bare .ssd (the FMUs by their paths
    relative to it) or an .ssp archive (SystemStructure.ssd and the FMUs as
    resources/NAME.fmu; they must exist). Validated against the schema; `out`."""
    out = pathlib.Path(out)
    name = name or _system_name(system)
    system.scheme(scheme)
    kind = out.suffix.lower()
    if kind == ".ssd":
        base = out.resolve().parent
        sources = {
            n: pathlib.Path(os.path.relpath(f.path.resolve(), base)).as_posix()
            for n, f in system.fmus.items()
        }
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(ssd_text(system, scheme, sources, name))
    elif kind == ".ssp":
        for n, f in system.fmus.items():
            if not f.path.is_file():
                _fail(
                    f"fmus.{n}.path", str(f.path), f"no such file; build it or pass --fmu {n}=PATH"
                )
        sources = {n: f"resources/{n}.fmu" for n in system.fmus}
        out.parent.mkdir(parents=True, exist_ok=True)
        tmp = out.with_name(out.name + ".part")
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as z:
            z.writestr(SSD, ssd_text(system, scheme, sources, name))
            for n, f in system.fmus.items():
                z.write(f.path, sources[n])
        os.replace(tmp, out)
    else:
        _fail("--out", str(out), "give NAME.ssd (a bare SSD) or NAME.ssp (an archive)")
    validate(out)
    return out
