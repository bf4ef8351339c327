"""Study files of `hybeam-sweep`: one FMU, the parameters to vary, constant inputs, what to keep.

    [study]
    fmu = "../../out/boom.fmu"          # relative to the study file
    stop_time = 1.0                     # s
    step = 1e-3                         # communication step [s]
    decimate = 10                       # keep every 10th point of the time series (default 1)

    [parameters]                        # a full grid of every list's values
    "tip.length" = [1.5, 2.0, 2.5]      # an FMU parameter ...
    "*.density" = [7850.0, 15700.0]     # ... or a glob: every matching parameter gets the value

    [inputs]                            # constant inputs from t = 0 on, set after the
    "tip.force.y" = -100.0              # initialization: a step on the initial state

    [outputs]
    series = ["tip.position.y", "root.moment.z"]
    # a summary per name: KIND(variable), KIND one of max, min, peak (max |x|), range
    # (max - min), rms, mean, final
    summaries = { tip_drop = "range(tip.position.y)", peak_root_moment = "peak(root.moment.z)" }

A variant is one point of the grid; its id is a hash of its content (the FMU's bytes, the
parameter values, inputs, times and outputs), so a rerun recognises what it has done. Errors
name the field, the value and the fix.
"""

import hashlib
import itertools
import json
import pathlib
import re
from dataclasses import dataclass, field

import tomllib

SUMMARY_KINDS = ("max", "min", "peak", "range", "rms", "mean", "final")


class StudyError(ValueError):
    """A study file that cannot be run, with the field, the value and the fix."""


@dataclass
class Study:
    """A parsed study file."""

    path: pathlib.Path
    fmu: pathlib.Path
    stop_time: float
    step: float
    decimate: int
    parameters: dict[str, list[float]]
    inputs: dict[str, float] = field(default_factory=dict)
    series: list[str] = field(default_factory=list)
    summaries: dict[str, tuple[str, str]] = field(default_factory=dict)

    def variants(self) -> list[dict[str, float]]:
        """Every point of the parameter grid, in file order (the last parameter fastest)."""
        names = list(self.parameters)
        return [
            dict(zip(names, values, strict=True))
            for values in itertools.product(*(self.parameters[n] for n in names))
        ]

    def fmu_digest(self) -> str:
        """SHA-256 of the FMU's bytes."""
        return hashlib.sha256(self.fmu.read_bytes()).hexdigest()

    def variant_id(self, variant: dict[str, float], fmu_digest: str) -> str:
        """The content hash of one variant's run (16 hex digits)."""
        content = {
            "fmu": fmu_digest,
            "parameters": variant,
            "inputs": self.inputs,
            "times": [self.stop_time, self.step, self.decimate],
            "series": self.series,
            "summaries": self.summaries,
        }
        text = json.dumps(content, sort_keys=True, default=float)
        return hashlib.sha256(text.encode()).hexdigest()[:16]


def _fail(where: str, value, fix: str):
    raise StudyError(f"{where} = {value!r}: {fix}")


def _number(where: str, x) -> float:
    if isinstance(x, bool) or not isinstance(x, int | float):
        _fail(where, x, "must be a number")
    return float(x)


def load(path) -> Study:
    """Reads and checks a study file (see the module's docstring)."""
    path = pathlib.Path(path)
    try:
        doc = tomllib.loads(path.read_text())
    except (OSError, tomllib.TOMLDecodeError) as e:
        raise StudyError(f"{path}: {e}") from None
    unknown = set(doc) - {"study", "parameters", "inputs", "outputs"}
    if unknown:
        _fail("tables", sorted(unknown), "the tables are study, parameters, inputs, outputs")
    st = doc.get("study", {})
    if "fmu" not in st:
        _fail("[study] fmu", None, "give the FMU's path, relative to the study file")
    fmu = (path.parent / st["fmu"]).resolve()
    if not fmu.is_file():
        _fail("[study] fmu", st["fmu"], f"no such file ({fmu}); build it first (fmu-build)")
    stop = _number("[study] stop_time", st.get("stop_time"))
    step = _number("[study] step", st.get("step"))
    if not (step > 0 and stop > 0):
        _fail("[study] stop_time, step", (stop, step), "both must be > 0")
    n = stop / step
    if abs(n - round(n)) > 1e-9 * n:
        _fail("[study] stop_time", stop, f"must be a whole number of steps of {step}")
    decimate = st.get("decimate", 1)
    if not isinstance(decimate, int) or decimate < 1:
        _fail("[study] decimate", decimate, "must be an integer >= 1")
    params = {}
    for name, values in doc.get("parameters", {}).items():
        where = f"[parameters] {name!r}"
        if not isinstance(values, list) or not values:
            _fail(where, values, "give a non-empty list of values")
        params[name] = [_number(where, v) for v in values]
    if not params:
        _fail("[parameters]", {}, "vary at least one parameter")
    inputs = {k: _number(f"[inputs] {k!r}", v) for k, v in doc.get("inputs", {}).items()}
    out = doc.get("outputs", {})
    series = out.get("series", [])
    if not isinstance(series, list) or not all(isinstance(s, str) for s in series):
        _fail("[outputs] series", series, "give a list of output names")
    summaries = {}
    for key, text in out.get("summaries", {}).items():
        m = re.fullmatch(r"\s*(\w+)\s*\(\s*([^()\s]+)\s*\)\s*", str(text))
        if not m or m.group(1) not in SUMMARY_KINDS:
            _fail(
                f"[outputs] summaries.{key}",
                text,
                f"write KIND(variable) with KIND one of {', '.join(SUMMARY_KINDS)}",
            )
        summaries[key] = (m.group(1), m.group(2))
    return Study(path, fmu, stop, step, decimate, params, inputs, series, summaries)
