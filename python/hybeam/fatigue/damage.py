"""Rainflow counting, S–N curves and Miner damage.

An S–N curve is Basquin's N(Δσ) = C·Δσ^(−m): N cycles of stress range Δσ [Pa] to failure,
exponent m > 0, constant C > 0 [Pa^m]; ranges below an optional cut-off [Pa] do no damage
(`cutoff`, the constant-amplitude fatigue limit of a design code). The damage of a history is
Miner's sum D = Σ nᵢ/N(Δσᵢ) over its rainflow cycles (half cycles counted 0.5); the equivalent
stress range at n_ref cycles is the constant range of the same damage,
Δσ_eq = (Σ nᵢ Δσᵢ^m / n_ref)^(1/m) (over the ranges at or above the cut-off).
"""

from __future__ import annotations

import math
import pathlib
from collections.abc import Iterable, Mapping
from dataclasses import dataclass

import numpy as np


class FatigueError(ValueError):
    """A bad S–N curve, file or column: the message names the field, the value and the fix."""


@dataclass(frozen=True)
class SNCurve:
    """Basquin's N = C·Δσ^(−m) [Δσ in Pa], no damage below `cutoff` [Pa]."""

    m: float
    C: float
    cutoff: float = 0.0

    def cycles_to_failure(self, stress_range: float) -> float:
        """N(Δσ); infinite below the cut-off or at Δσ = 0."""
        if stress_range <= 0.0 or stress_range < self.cutoff:
            return math.inf
        return self.C * stress_range ** (-self.m)


def sn_curve(fields: Mapping[str, object], where: str) -> SNCurve:
    """An S–N curve from its fields `m`, `C` and optionally `cutoff`; `where` names them in an
    error (e.g. "--sn" or "sn.toml [root_weld]")."""
    known = {"m", "C", "cutoff"}
    for key in fields:
        if key not in known:
            raise FatigueError(
                f"{where}: unknown field {key!r}; an S-N curve takes m (exponent), C "
                f"(constant, Pa^m) and optionally cutoff (Pa)"
            )
    values: dict[str, float] = {}
    for key in ("m", "C", "cutoff"):
        if key not in fields:
            if key == "cutoff":
                continue
            raise FatigueError(f"{where}: missing {key}; give e.g. m=3,C=2e12")
        raw = fields[key]
        try:
            x = float(raw)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            raise FatigueError(f"{where}: {key} = {raw!r} is not a number") from None
        if not math.isfinite(x):
            raise FatigueError(f"{where}: {key} = {raw!r} must be finite")
        values[key] = x
    if values["m"] <= 0.0:
        raise FatigueError(
            f"{where}: m = {values['m']:g}: the S-N exponent must be positive "
            f"(N = C * range^-m; steel welds: m = 3)"
        )
    if values["C"] <= 0.0:
        raise FatigueError(
            f"{where}: C = {values['C']:g}: the S-N constant must be positive [Pa^m] "
            f"(e.g. detail category 71 MPa at 2e6 cycles, m = 3: C = 2e6 * 71e6**3 = 7.16e29)"
        )
    if values.get("cutoff", 0.0) < 0.0:
        raise FatigueError(f"{where}: cutoff = {values['cutoff']:g} must be >= 0 [Pa]")
    return SNCurve(values["m"], values["C"], values.get("cutoff", 0.0))


def parse_sn(text: str) -> SNCurve:
    """`m=3,C=7.16e29[,cutoff=5.2e7]` (the command line's --sn)."""
    fields: dict[str, object] = {}
    for part in filter(None, (p.strip() for p in text.split(","))):
        key, eq, value = part.partition("=")
        if not eq:
            raise FatigueError(f"--sn {text!r}: {part!r} is not KEY=VALUE; give e.g. m=3,C=7.16e29")
        fields[key.strip()] = value.strip()
    return sn_curve(fields, f"--sn {text!r}")


def load_sn_file(path: pathlib.Path) -> dict[str, SNCurve]:
    """The S–N curve of each station from a TOML file: a table per station,
    `[root_weld]` with `m`, `C` and optionally `cutoff`."""
    import tomllib

    try:
        table = tomllib.loads(path.read_text())
    except OSError as e:
        raise FatigueError(f"{path}: cannot read it ({e})") from None
    except tomllib.TOMLDecodeError as e:
        raise FatigueError(f"{path}: not valid TOML ({e})") from None
    out = {}
    for station, fields in table.items():
        if not isinstance(fields, dict):
            raise FatigueError(
                f"{path}: {station} = {fields!r}: give a table per station, "
                f"[{station}] with m, C (and cutoff)"
            )
        out[station] = sn_curve(fields, f"{path} [{station}]")
    return out


def cycles(series: Iterable[float]) -> np.ndarray:
    """Rainflow cycles of a stress history [Pa]: rows (range [Pa], count), half cycles 0.5
    (`rainflow.count_cycles`, ASTM E1049-85)."""
    import rainflow

    data = np.asarray(list(series), dtype=float)
    if not np.all(np.isfinite(data)):
        raise FatigueError("the stress history has non-finite values")
    counted = rainflow.count_cycles(data)
    return np.asarray(counted, dtype=float).reshape(-1, 2)


@dataclass(frozen=True)
class Fatigue:
    """The fatigue of one history: its cycles, Miner damage, the equivalent stress range at
    `n_ref` cycles [Pa] and the largest range [Pa]."""

    cycles: np.ndarray
    damage: float
    equivalent_range: float
    n_ref: float
    largest_range: float


def assess(series: Iterable[float], sn: SNCurve, n_ref: float = 2e6) -> Fatigue:
    """Rainflow cycles of `series` [Pa], their Miner damage on `sn` and the equivalent range
    at `n_ref` cycles."""
    if not (n_ref > 0.0 and math.isfinite(n_ref)):
        raise FatigueError(f"--n-ref {n_ref!r}: the reference cycle count must be positive")
    c = cycles(series)
    ranges, counts = (c[:, 0], c[:, 1]) if len(c) else (np.zeros(0), np.zeros(0))
    damaging = ranges >= max(sn.cutoff, np.finfo(float).tiny)
    d = float(np.sum(counts[damaging] * ranges[damaging] ** sn.m) / sn.C)
    eq = float((np.sum(counts[damaging] * ranges[damaging] ** sn.m) / n_ref) ** (1.0 / sn.m))
    largest = float(ranges.max()) if len(ranges) else 0.0
    return Fatigue(c, d, eq, n_ref, largest)
