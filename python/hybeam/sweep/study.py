"""Study files of `hybeam-sweep`: one FMU, the parameters to vary, constant inputs, what to keep.

    [study]
    fmu = "../../out/boom.fmu"          # relative to the study file
    stop_time = 1.0                     # s
    step = 1e-3                         # communication step [s]
    decimate = 10                       # keep every 10th point of the time series (default 1)
    max_variants = 100000               # the largest grid run (default 100000; --max-variants)

    [parameters]                        # a full grid of every list's values
    "tip.length" = [1.5, 2.0, 2.5]      # an FMU parameter ...
    "*.density" = [7850.0, 15700.0]     # ... or a glob: every matching parameter gets the value

or, with `scene` instead of `fmu`, scene values that change the model's structure, prefixed
`scene:` (a dotted path into the scene file; a segment by index or name): an FMU is built per
distinct structure (`cargo fmu-build`, linux64, from the source tree) and cached by the scene's
content in the output directory:

    [study]
    scene = "../../scenes/boom.toml"
    [parameters]
    "scene:segments.tip.elements" = [4, 8, 16]
    "scene:segments.root.kind" = ["modal", "ancf"]

or, instead of a grid, a sample of ranges (scipy.stats.qmc, scaled to the ranges):

    [study]
    sample = { method = "sobol", n = 16, seed = 1 }   # or "lhs" (Latin hypercube)
    [parameters]
    "tip.length" = { range = [1.5, 2.5] }

    [inputs]                            # inputs from t = 0 on, set after the initialization
    "tip.force.y" = -100.0              # a constant: a step on the initial state
    "tip.force.x" = { csv = "load.csv", column = "fx" }   # a time series (columns time, fx),
                                        # linear between its rows, held beyond them; a list
                                        # of files is a dimension of the grid, "input:tip.force.x"
    "root.position.y" = { sine = { amplitude = 0.01, frequency = 2.0, phase = 0.0 } }
                                        # added to the input's start value (m, Hz, deg)

The inputs are set at every communication point (a mount's position, velocity and
acceleration are three inputs: give them consistently, or the FMU re-anchors the beam).

    [outputs]
    series = ["tip.position.y", "root.moment.z"]
    # a summary per name: KIND(variable), KIND one of max, min, peak (max |x|), range
    # (max - min), rms, mean, final, frequency (the dominant one [Hz], from the signal's
    # mean-crossings), settling (the last time [s] outside 2 % of the change from the final
    # value)
    summaries = { tip_drop = "range(tip.position.y)", peak_root_moment = "peak(root.moment.z)" }

A variant is one point of the grid; its id is a hash of its content (the FMU's bytes, the
parameter values, inputs, times and outputs), so a rerun recognises what it has done. The grid's
size is known before any variant is made (`Study.count`): a study over `max_variants` is refused
with its count; the variants themselves are generated lazily (`Study.variants`).

The study is checked against the FMU's modelDescription.xml before anything runs (`check`): every
parameter (name or glob) must match Real parameters, every input be a Real input, every series
and summary a Real variable; every number must be finite and every key known. Errors name the
field, the value and the fix.
"""

import fnmatch
import hashlib
import itertools
import json
import math
import pathlib
import re
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any, NoReturn

import numpy as np
import tomllib

from hybeam.checks import did_you_mean, unknown_key

SUMMARY_KINDS = ("max", "min", "peak", "range", "rms", "mean", "final", "frequency", "settling")
#: the prefix of a parameter that is a value of the scene file
SCENE = "scene:"
#: the largest grid (or sample) a study runs unless it raises the limit ([study] max_variants,
#: `hybeam-sweep run --max-variants`): 1e5 variants of a second each are a day on 2 cores
MAX_VARIANTS = 100_000
#: the most communication steps of one variant (its series are held in memory while it runs)
MAX_STEPS = 10_000_000
#: the keys of each table of a study file
STUDY_KEYS = ("fmu", "scene", "stop_time", "step", "decimate", "sample", "max_variants")
OUTPUT_KEYS = ("series", "summaries")
#: the columns of the variants table besides the parameters and summaries
COLUMNS = ("variant", "status", "message", "wall_s")


class StudyError(ValueError):
    """A study file that cannot be run, with the field, the value and the fix."""


@dataclass
class Study:
    """A parsed study file."""

    path: pathlib.Path
    #: the FMU, or None for a study of a scene (an FMU per structure: `scene`)
    fmu: pathlib.Path | None
    stop_time: float
    step: float
    decimate: int
    parameters: dict[str, list[float]]
    inputs: dict[str, "Signal"] = field(default_factory=dict)
    series: list[str] = field(default_factory=list)
    summaries: dict[str, tuple[str, str]] = field(default_factory=dict)
    #: (method, n, seed) of a sampled study (then `parameters` holds [low, high] ranges)
    sample: tuple[str, int, int] | None = None
    #: the scene file of a study that builds its FMUs
    scene: pathlib.Path | None = None
    #: the largest number of variants the study runs ([study] max_variants, --max-variants)
    max_variants: int = MAX_VARIANTS

    def count(self) -> int:
        """The number of variants (the grid's size or the sample's), without making them."""
        if self.sample is not None:
            return self.sample[1]
        return math.prod(len(v) for v in self.parameters.values())

    def variants(self) -> Iterator[dict[str, float]]:
        """Every point of the parameter grid, in file order (the last parameter fastest), or
        the sample's points in the order drawn: made one at a time (itertools.product)."""
        names = list(self.parameters)
        if self.sample is None:
            for values in itertools.product(*(self.parameters[n] for n in names)):
                yield dict(zip(names, values, strict=True))
            return
        from scipy.stats import qmc

        method, n, seed = self.sample
        d = len(names)
        engine = qmc.Sobol(d, seed=seed) if method == "sobol" else qmc.LatinHypercube(d, seed=seed)
        lo = [self.parameters[k][0] for k in names]
        hi = [self.parameters[k][1] for k in names]
        points = qmc.scale(engine.random(n), lo, hi)
        for row in points:
            yield {k: float(x) for k, x in zip(names, row, strict=True)}

    def fmu_parameters(self) -> dict[str, list]:
        """The parameters set through the FMU (not `scene:` or `input:` ones)."""
        return {k: v for k, v in self.parameters.items() if not k.startswith((SCENE, INPUT))}

    def fmu_bytes(self) -> tuple[bytes, str]:
        """The FMU's bytes and their SHA-256."""
        if self.fmu is None:
            raise StudyError("a scene study's FMU is built per structure (hybeam.sweep.build)")
        data = self.fmu.read_bytes()
        return data, hashlib.sha256(data).hexdigest()

    def fmu_digest(self) -> str:
        """SHA-256 of the FMU's bytes."""
        return self.fmu_bytes()[1]

    def variant_id(self, variant: dict[str, float], fmu_digest: str) -> str:
        """The content hash of one variant's run (16 hex digits)."""
        content = {
            "fmu": fmu_digest,
            "parameters": variant,
            "inputs": {k: v.content() for k, v in self.inputs.items()},
            "times": [self.stop_time, self.step, self.decimate],
            "sample": self.sample,
            "series": self.series,
            "summaries": self.summaries,
        }
        text = json.dumps(content, sort_keys=True, default=float)
        return hashlib.sha256(text.encode()).hexdigest()[:16]


@dataclass
class Signal:
    """An input over time: a constant, a table (linear, held beyond its ends; one per variant
    when the study sweeps CSV files) or a sine added to the input's start value."""

    constant: float | None = None
    #: (times, values) per CSV file name
    tables: dict[str, tuple[list[float], list[float]]] | None = None
    sine: tuple[float, float, float] | None = None  # amplitude, frequency [Hz], phase [deg]
    #: the value as the study file gives it (for error messages)
    described: object = field(default=None, compare=False)

    def at(self, t: float, start: float, table: str | None = None) -> float:
        """The value at time `t` [s] of an input whose start value is `start` (`table`: the
        variant's CSV file, when there are several)."""
        if self.constant is not None:
            return self.constant
        if self.sine is not None:
            a, f, phase = self.sine
            return start + a * math.sin(2 * math.pi * f * t + math.radians(phase))
        tables = self.tables or {}
        times, values = tables[table] if table else next(iter(tables.values()))
        return float(np.interp(t, times, values))

    def content(self) -> list:
        return [self.constant, self.tables, self.sine]


#: the prefix of the parameter that picks a swept input's CSV file
INPUT = "input:"


def _table(where: str, base: pathlib.Path, name: str, column) -> tuple[list, list]:
    csv = base / str(name)
    try:
        table = np.genfromtxt(csv, delimiter=",", names=True)
    except OSError:
        _fail(f"{where}.csv", name, f"no such file ({csv})")
    names = table.dtype.names or ()
    if "time" not in names or column not in names:
        _fail(where, name, f"{csv} needs a 'time' column and the column named (has {names})")
    t, x = np.atleast_1d(table["time"]).astype(float), np.atleast_1d(table[column]).astype(float)
    if len(t) < 1 or np.any(np.diff(t) <= 0) or not np.all(np.isfinite(x)):
        _fail(where, name, "the times must increase and the values be finite")
    return t.tolist(), x.tolist()


def _signal(where: str, spec, base: pathlib.Path) -> Signal:
    if not isinstance(spec, dict):
        return Signal(constant=_number(where, spec))
    kinds = [k for k in ("csv", "sine") if k in spec]
    allowed = {"csv": {"csv", "column"}, "sine": {"sine"}}.get(kinds[0] if kinds else "", set())
    extra = sorted(set(spec) - allowed)
    if len(kinds) == 1 and extra:
        _fail(where, spec, f"unknown key {extra[0]!r}; {_HOW_INPUT}")
    if "csv" in spec:
        files = spec["csv"] if isinstance(spec["csv"], list) else [spec["csv"]]
        if not files:
            _fail(f"{where}.csv", files, "give a file, or a list of files to sweep")
        column = spec.get("column")
        return Signal(tables={str(f): _table(where, base, f, column) for f in files})
    if "sine" in spec and isinstance(spec["sine"], dict):
        sn = spec["sine"]
        extra = sorted(set(sn) - {"amplitude", "frequency", "phase"})
        if extra:
            _fail(
                f"{where}.sine",
                sn,
                f"unknown key {extra[0]!r}; the keys are amplitude, frequency [Hz] and phase [deg]",
            )
        amp = _number(f"{where}.sine.amplitude", sn.get("amplitude"))
        freq = _number(f"{where}.sine.frequency", sn.get("frequency"))
        phase = _number(f"{where}.sine.phase", sn.get("phase", 0.0))
        return Signal(sine=(amp, freq, phase))
    _fail(where, spec, _HOW_INPUT)


_HOW_INPUT = (
    "give a number, { csv = FILE, column = NAME } or "
    "{ sine = { amplitude = A, frequency = F, phase = DEG } }"
)


def _fail(where: str, value: object, fix: str) -> NoReturn:
    raise StudyError(f"{where} = {value!r}: {fix}")


def _number(where: str, x) -> float:
    if isinstance(x, bool) or not isinstance(x, int | float):
        _fail(where, x, "must be a number")
    if not math.isfinite(x):
        _fail(where, x, "must be a finite number")
    return float(x)


_like = did_you_mean


def _known(where: str, table, keys) -> None:
    """Refuses a key of `table` (a study file's table) that is not one of `keys`."""
    if (k := unknown_key(table, keys)) is not None:
        _fail(
            f"{where} {k}",
            table[k],
            f"not a key of {where}{_like(k, keys)} (the keys: {', '.join(keys)})",
        )


def model_description(where: str, path: pathlib.Path, written: str | None = None) -> Any:
    """The FMU's model description (fmpy), or StudyError naming `where` when `path` is not an
    FMI 2.0 co-simulation FMU."""
    from fmpy import read_model_description

    try:
        md = read_model_description(str(path))
    except Exception as e:  # a zip without the XML, not a zip, an invalid XML, ...
        text = " ".join(str(e).split())[:200]
        _fail(
            where,
            written if written is not None else str(path),
            f"not an FMU ({type(e).__name__}: {text}); give the path of an FMI 2.0 "
            "co-simulation FMU (e.g. cargo fmu-build scenes/boom.toml --out out)",
        )
    if md.fmiVersion != "2.0" or md.coSimulation is None:
        _fail(
            where,
            written if written is not None else str(path),
            f"an FMI {md.fmiVersion} FMU without co-simulation; give an FMI 2.0 co-simulation FMU",
        )
    return md


def check(study: Study, md: Any, fmu_name: str) -> None:
    """Checks the study's FMU parameters, inputs and outputs against the FMU's variables (its
    model description `md`): names, causality and type. Raises StudyError naming the field,
    the value and the fix."""
    variables = {v.name: v for v in md.modelVariables}
    params = [n for n, v in variables.items() if v.causality == "parameter" and v.type == "Real"]
    inputs = [n for n, v in variables.items() if v.causality == "input" and v.type == "Real"]
    reals = [n for n, v in variables.items() if v.type == "Real"]

    def what(n):
        v = variables[n]
        return f"a {v.type} {v.causality} of {fmu_name}"

    set_by: dict[str, str] = {}
    for p, values in study.fmu_parameters().items():
        where = f"[parameters] {p!r}"
        hits = [n for n in variables if fnmatch.fnmatchcase(n, p)]
        names = [n for n in hits if n in params]
        if not names:
            if hits:
                fix = f"{hits[0]!r} is {what(hits[0])}, not a Real parameter" + (
                    "; give it in [inputs]" if hits[0] in inputs else ""
                )
            else:
                fix = (
                    f"matches no parameter of {fmu_name}{_like(p, params)} (write a parameter's "
                    "name, docs/fmu-variables.md, or a glob such as '*.density')"
                )
            _fail(where, values, fix)
        for n in names:
            if n in set_by:
                _fail(
                    where,
                    values,
                    f"sets {n!r}, which {set_by[n]!r} sets too; give each parameter one entry",
                )
            set_by[n] = p
    for name in study.inputs:
        if name not in inputs:
            fix = (
                f"{name!r} is {what(name)}, not an input; give one of its Real inputs"
                if name in variables
                else f"no input of {fmu_name} by that name{_like(name, inputs)}"
            )
            _fail(f"[inputs] {name!r}", study.inputs[name].described, fix)
    for name in study.series:
        if name not in reals:
            _fail(
                "[outputs] series",
                study.series,
                f"{name!r} is no Real variable of {fmu_name}{_like(name, reals)}",
            )
    for key, (kind, name) in study.summaries.items():
        if name not in reals:
            _fail(
                f"[outputs] summaries.{key}",
                f"{kind}({name})",
                f"{name!r} is no Real variable of {fmu_name}{_like(name, reals)}",
            )


def _section(where: str, value) -> dict:
    if not isinstance(value, dict):
        _fail(where, value, f"must be a table ({where} with KEY = VALUE lines)")
    return value


def load(
    path: str | pathlib.Path, max_variants: int | None = None, check_fmu: bool = True
) -> Study:
    """Reads and checks a study file (see the module's docstring); `max_variants` overrides
    the file's limit (`--max-variants`); `check_fmu`: the FMU study's names against its
    modelDescription.xml (a scene study's FMUs are checked as they are built)."""
    path = pathlib.Path(path)
    try:
        doc = tomllib.loads(path.read_text())
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
        raise StudyError(f"{path}: {e}; give a study file (TOML, docs/sweeps.md)") from None
    unknown = set(doc) - {"study", "parameters", "inputs", "outputs"}
    if unknown:
        _fail("tables", sorted(unknown), "the tables are study, parameters, inputs, outputs")
    st = _section("[study]", doc.get("study", {}))
    _known("[study]", st, STUDY_KEYS)
    if ("fmu" in st) == ("scene" in st):
        _fail("[study] fmu, scene", None, "give one: the FMU's or the scene's path")
    key = "fmu" if "fmu" in st else "scene"
    if not isinstance(st[key], str):
        _fail(f"[study] {key}", st[key], "give a path (relative to the study file)")
    source = (path.parent / st[key]).resolve()
    if not source.is_file():
        _fail(f"[study] {key}", st[key], f"no such file ({source})")
    fmu, scene = (source, None) if key == "fmu" else (None, source)
    stop = _number("[study] stop_time", st.get("stop_time"))
    step = _number("[study] step", st.get("step"))
    if not (step > 0 and stop > 0):
        _fail("[study] stop_time, step", (stop, step), "both must be > 0")
    n = stop / step
    if abs(n - round(n)) > 1e-9 * n:
        _fail("[study] stop_time", stop, f"must be a whole number of steps of {step}")
    if round(n) > MAX_STEPS:
        _fail(
            "[study] stop_time, step",
            (stop, step),
            f"{round(n)} steps per variant, over {MAX_STEPS}; a shorter stop_time or a larger step",
        )
    decimate = st.get("decimate", 1)
    if isinstance(decimate, bool) or not isinstance(decimate, int) or decimate < 1:
        _fail("[study] decimate", decimate, "must be an integer >= 1")
    limit_where = "--max-variants" if max_variants is not None else "[study] max_variants"
    limit = max_variants if max_variants is not None else st.get("max_variants", MAX_VARIANTS)
    if isinstance(limit, bool) or not isinstance(limit, int) or limit < 1:
        _fail(limit_where, limit, "must be an integer >= 1")
    sample = st.get("sample")
    if sample is not None:
        if not isinstance(sample, dict) or sample.get("method") not in ("sobol", "lhs"):
            _fail("[study] sample", sample, 'write { method = "sobol" or "lhs", n = N, seed = S }')
        _known("[study] sample", sample, ("method", "n", "seed"))
        count, seed = sample.get("n"), sample.get("seed", 0)
        if (
            isinstance(count, bool)
            or not isinstance(count, int)
            or count < 2
            or isinstance(seed, bool)
            or not isinstance(seed, int)
        ):
            _fail("[study] sample", sample, "n must be an integer >= 2 and seed an integer")
        sample = (sample["method"], count, seed)
    params: dict[str, list] = {}
    for name, values in _section("[parameters]", doc.get("parameters", {})).items():
        where = f"[parameters] {name!r}"
        if sample is not None:
            r = values.get("range") if isinstance(values, dict) else None
            if not (isinstance(r, list) and len(r) == 2) or len(values) != 1:
                _fail(where, values, "a sampled study gives each parameter { range = [low, high] }")
            lo, hi = (_number(where, x) for x in r)
            if not lo < hi:
                _fail(where, values, "the range must have low < high")
            params[name] = [lo, hi]
            continue
        if not isinstance(values, list) or not values:
            _fail(where, values, "give a non-empty list of values (or [study] sample and ranges)")
        if name.startswith(SCENE):
            if scene is None:
                _fail(where, values, "a scene: parameter needs [study] scene, not fmu")
            params[name] = list(values)
            continue
        params[name] = [_number(where, v) for v in values]
    inputs = {}
    for k, v in _section("[inputs]", doc.get("inputs", {})).items():
        inputs[k] = _signal(f"[inputs] {k!r}", v, path.parent)
        inputs[k].described = v
    for k, sig in inputs.items():
        # several CSV files of one input: a swept dimension of the grid, `input:<name>`
        if sig.tables and len(sig.tables) > 1:
            if sample is not None:
                _fail(f"[inputs] {k!r}.csv", list(sig.tables), "a sampled study takes one file")
            params[INPUT + k] = list(sig.tables)
    if not params:
        _fail("[parameters]", {}, "vary at least one parameter (or an input's CSV files)")
    out = _section("[outputs]", doc.get("outputs", {}))
    _known("[outputs]", out, OUTPUT_KEYS)
    series = out.get("series", [])
    if not isinstance(series, list) or not all(isinstance(s, str) for s in series):
        _fail("[outputs] series", series, "give a list of output names")
    summaries = {}
    for key, text in _section("[outputs] summaries", out.get("summaries", {})).items():
        m = re.fullmatch(r"\s*(\w+)\s*\(\s*([^()\s]+)\s*\)\s*", str(text))
        if not m or m.group(1) not in SUMMARY_KINDS:
            _fail(
                f"[outputs] summaries.{key}",
                text,
                f"write KIND(variable) with KIND one of {', '.join(SUMMARY_KINDS)}",
            )
        if key in COLUMNS or key in params:
            _fail(
                f"[outputs] summaries.{key}",
                text,
                f"{key!r} is a column of the variants "
                "table already (a parameter's or one of " + ", ".join(COLUMNS) + "); give the "
                "summary another name",
            )
        summaries[key] = (m.group(1), m.group(2))
    study = Study(path, fmu, stop, step, decimate, params, inputs, series, summaries, sample, scene)
    study.max_variants = limit
    count = study.count()
    if count > limit:
        dims = " x ".join(str(len(v)) for v in params.values()) if sample is None else "sample n"
        raise StudyError(
            f"{limit_where} = {limit}: the study has {count} variants ({dims}), more than "
            f"max_variants = {limit}; give fewer values, or raise the limit ([study] "
            f"max_variants = {count} or --max-variants {count})"
        )
    if fmu is not None and check_fmu:
        check(study, model_description("[study] fmu", fmu, st["fmu"]), fmu.name)
    return study
