"""Peer comparison of hybeam with Exudyn 1.13.6 (issue 23, "Ten times Exudyn").

Runs the planar Sohn & Yoo Case 1 rod, its spatial twin (with a sideways tip force) and the
damped stepped rod of Case 3 in both codes over a grid of elements x time steps, measures each
run's tip error against one shared converged reference and its run time, and writes the CSV of
all runs, the ratio tables, one work-precision SVG per problem and docs/performance.md.
The large-deformation suite (issue 42: the soft rod clamped, pinned and ball-jointed in 3D)
runs the same way on its own grid and writes docs/report/peers_large_* and docs/peers-large.md.

Start it through benches/peers/run.sh (builds hybeam, creates the Exudyn venv); see README.md.
"""

from __future__ import annotations

import argparse
import csv
import math
import os
import platform
import re
import shlex
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]
EXUDYN_VERSION = "1.13.6"

# The rod of Sohn & Yoo, Case 1 (the values of scenes/case1*.toml).
YOUNG = 2.1e11  # Pa
DENSITY = 7850.0  # kg/m^3
DIAMETER = 2e-3  # m
LENGTH = 0.4  # m
GRAVITY = 9.81  # m/s^2
AREA = math.pi * DIAMETER**2 / 4.0
INERTIA = math.pi * DIAMETER**4 / 64.0
WEIGHT = DENSITY * AREA * LENGTH * GRAVITY
TIP_FORCE = 3.0 / 8.0 * WEIGHT  # spatial problem: along +y at the free end
RHO_INF = 0.9  # generalized-alpha spectral radius, as the hybeam scenes
OUTPUT_STEP = 1e-3  # s, the grid on which the tip is compared
TOLERANCES = (1e-4, 3e-5, 1e-5)  # m
# Exudyn's Newton: error measured on the increments (residualMode 1, like hybeam's tolerance on
# increments), this tolerance for both relativeTolerance and absoluteTolerance. Its default
# (residual-based, relative 1e-8) stalls near 1e-7 at 32 elements and h = 5e-5 s (round-off of
# the axial stiffness) and the step adaptivity then stops at the minimum step; see README.md.
EXUDYN_NEWTON_TOL = 1e-10
# hybeam's Newton tolerance in the grid runs (`solver.tolerance`: the largest increment of a
# coordinate relative to its scale, the rod's length for positions): Exudyn's, so that both
# codes stop their iterations at the same tolerance on the increments. The scenes' own 1e-11
# (`--hybeam-tolerance scene`) takes hybeam 14 % more Newton iterations and 65 % more
# factorizations at the same error (angle element, 16 el., h 5e-4; README.md). The shared
# reference keeps the scene's.
HYBEAM_NEWTON_TOL = EXUDYN_NEWTON_TOL


@dataclass(frozen=True)
class Section:
    """A straight piece of round rod (root to tip), as a segment of the hybeam scenes."""

    length: float  # m
    diameter: float  # m
    damping_time: float = 0.0  # Kelvin-Voigt tau_d [s]: sigma = E (eps + tau_d eps')
    young: float = YOUNG  # Pa
    density: float = DENSITY  # kg/m^3

    @property
    def area(self) -> float:
        return math.pi * self.diameter**2 / 4.0

    @property
    def inertia(self) -> float:
        return math.pi * self.diameter**4 / 64.0

    @property
    def weight(self) -> float:
        return self.density * self.area * self.length * GRAVITY


CASE1_ROD = (Section(LENGTH, DIAMETER),)
# Sohn & Yoo, Case 3 (scenes/case3*.toml): 0.2 m of d = 2 mm, then 0.4 m of d = 1 mm, both damped.
CASE3_ROD = (Section(0.2, 2e-3, 7e-4), Section(0.4, 1e-3, 7e-4))
# The soft polymer rod of scenes/soft_rod.toml (d = 5 mm, L = 0.5 m, E = 50 MPa, rho = 1100,
# gamma = q L^3 / EI = 17.3): the large-deformation problems (issue 42).
SOFT_ROD = (Section(0.5, 5e-3, young=5e7, density=1100.0),)
# whip3d: a constant sideways tip force, 3/8 of the rod's weight as the spatial Case 1 problem.
SOFT_TIP_FORCE = 3.0 / 8.0 * SOFT_ROD[0].weight


def shares(rod: tuple[Section, ...]) -> tuple[float, ...]:
    """Each section's share of the rod's length."""
    total = sum(s.length for s in rod)
    return tuple(s.length / total for s in rod)


def split_elements(n: int, parts: tuple[float, ...]) -> list[int]:
    """n elements split by length shares: every part but the last max(1, round(n * share)),
    the last the rest (Case 3, n = 8: 3 + 5)."""
    counts = [max(1, round(n * share)) for share in parts[:-1]]
    counts.append(n - sum(counts))
    if counts[-1] < 1:
        raise ValueError(f"{n} elements cannot be split over {len(parts)} segments")
    return counts


@dataclass(frozen=True)
class Family:
    """One model of a problem in one code."""

    code: str  # "hybeam" or "exudyn"
    name: str  # label in the tables and figures
    scene: str = ""  # hybeam scene file
    elements_key: str = ""  # hybeam --set key of the ANCF element count
    sets: tuple[str, ...] = ()  # further hybeam --set overrides
    element_fraction: float = 1.0  # share of the rod meshed with ANCF elements
    # A rod of several segments (replaces elements_key and element_fraction): per segment, root to
    # tip, the hybeam --set key of its ANCF element count ("" for a modal segment) and its share
    # of the length; a grid point's n elements are split by split_elements.
    segments: tuple[tuple[str, float], ...] = ()
    # A modal family: the hybeam --set key of its mode count, which the grid's n sets
    # (Family.modes); its runs have no ANCF elements.
    modes_key: str = ""
    # Grid steps below this are not run (the ESDIRK families: five solves per step, and at the
    # grid's finest steps their error is already the mesh's).
    min_step: float = 0.0
    # A family on a feature this hybeam may not have yet (the --set key, e.g.
    # "segments.0.degree"): a run refused for an unknown scene field marks the whole family
    # "not available" (recorded, not fatal) instead of "failed".
    pending: str = ""
    # A family whose solver picks its steps: its grid axis is these error tolerances (passed as
    # --set solver.error_tolerance=X) instead of the grid's steps, at solver.max_step =
    # fixed_step.
    error_tolerances: tuple[float, ...] = ()
    fixed_step: float = 0.0
    # Grid points of a larger n (the grid's, not the family's elements) are not run (0: no
    # cap): the higher-degree families, whose error beyond is the time integrator's.
    max_grid_n: int = 0

    def modes(self, n: int) -> int:
        """Modes of a modal family for a grid point of n elements: round(12 n / 32) in 1..=12
        (n = 4, 8, 16, 32: 2, 3, 6, 12 modes); 0 for the other families."""
        return min(12, max(1, round(12 * n / 32))) if self.modes_key else 0

    def segment_elements(self, n: int) -> list[tuple[str, int]]:
        """(--set key, ANCF elements) of each ANCF segment for a grid point of n elements over
        the whole rod."""
        if self.modes_key:
            return []
        if not self.segments:
            return [(self.elements_key, max(1, round(n * self.element_fraction)))]
        counts = split_elements(n, tuple(share for _, share in self.segments))
        return [(key, k) for (key, _), k in zip(self.segments, counts, strict=True) if key]

    def elements(self, n: int) -> int:
        """ANCF elements of this family for a grid point of n elements over the whole rod."""
        return sum(k for _, k in self.segment_elements(n))


@dataclass(frozen=True)
class Grid:
    elements: tuple[int, ...]
    steps: tuple[float, ...]
    t_end: float
    ref_elements: int
    ref_step: float
    repeats: int


FULL = Grid((4, 8, 16, 32), (1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2.5e-5), 2.0, 64, 1e-5, 3)
QUICK = Grid((4, 8), (1e-3, 2e-4), 0.5, 32, 5e-5, 1)
# The large-deformation problems (soft rod): mostly mesh-limited (soft_rod, 1 s: 16 el. 1.8e-3 m,
# 32 el. 5e-5 m, 64 el. 1.5e-6 m at h = 1e-4 s, ESDIRK4), generalized-alpha's step error at 64
# el. about 1e-5 m at h = 1e-4 s (whip3d: 5e-6 m at 2.5e-5 s); steps above the 1 ms output step
# run as 1 ms (README.md, "Large deformation").
LARGE_GRID = Grid(
    (8, 12, 16, 24, 32, 48, 64), (1e-3, 5e-4, 2e-4, 1e-4, 5e-5, 2.5e-5), 1.0, 128, 1e-5, 3
)
LARGE_QUICK = Grid((8, 16), (1e-3, 2e-4), 0.3, 32, 5e-5, 1)
LARGE_TOLERANCES = (1e-3, 1e-4, 1e-5)  # m

# The root kinds: hybeam's `root` (the Exudyn root node's coordinate constraints follow it).
ROOTS = ("clamped", "pinned", "ball")


@dataclass
class Problem:
    name: str
    spatial: bool
    families: list[Family]
    reference: Family  # the family whose finest run is the shared reference
    peer_check: Family  # the other code's run at the reference's mesh and step
    rod: tuple[Section, ...] = CASE1_ROD  # the Exudyn model's sections
    note: str = ""  # how the grid's n maps onto the families' meshes, for the doc
    description: str = ""  # the problem, for the doc (the small suite's: README.md)
    # hybeam's `root` (given as --set root=... unless "clamped", the scenes' own): "clamped"
    # (position and slope direction held), "pinned" (planar: position held) or "ball" (spatial:
    # position held). Exudyn holds the root node's position and, clamped, its slope.
    root: str = "clamped"
    # Clamped: Exudyn holds the root slope's direction only, as hybeam's clamp does (its length,
    # the root's stretch, free), instead of the whole slope (the small problems' clamp).
    clamp_direction_only: bool = False
    tip_force: tuple[float, float, float] | None = None  # Exudyn's dead tip force [N], world
    tolerances: tuple[float, ...] = TOLERANCES  # m: the rows of the ratio tables
    suite: str = "small"  # "small" (docs/performance.md) or "large" (docs/peers-large.md)
    full: Grid = FULL
    quick: Grid = QUICK

    def __post_init__(self) -> None:
        if self.root not in ROOTS:
            raise ValueError(f"{self.name}: root {self.root!r} not in {ROOTS}")

    def exudyn_root(self) -> list[bool]:
        """fixedConstraintsNode0 of GenerateBeamElementsAlongLine: the root node's held
        coordinates, planar [x, y, x', y'], spatial [x, y, z, x', y', z'] (the rod along x)."""
        dims = 3 if self.spatial else 2
        if self.root != "clamped":
            return [True] * dims + [False] * dims
        return [True] * dims + [not self.clamp_direction_only] + [True] * (dims - 1)

    def grid(self, quick: bool) -> Grid:
        return self.quick if quick else self.full


def _tip_force_set(force: float = TIP_FORCE) -> str:
    """hybeam's --set of a tip force `force` [N] along +y."""
    return f"tip.force=[0.0, {force!r}, 0.0]"


EXUDYN_PLANAR = Family("exudyn", "Exudyn ObjectANCFCable2D")
EXUDYN_SPATIAL = Family("exudyn", "Exudyn ObjectANCFCable")
HYBEAM_PLANAR = Family("hybeam", "hybeam all-ANCF", "scenes/case1_ancf.toml", "segments.0.elements")
HYBEAM_CASE3 = Family(
    "hybeam",
    "hybeam all-ANCF",
    "scenes/case3_ancf.toml",
    segments=tuple(
        zip(("segments.0.elements", "segments.1.elements"), shares(CASE3_ROD), strict=True)
    ),
)
HYBEAM_CABLE3D = Family(
    "hybeam",
    "hybeam 3D cable (torsion = false)",
    "scenes/case1_3d_ancf.toml",
    "segments.0.elements",
    ("torsion=false", _tip_force_set()),
)

ESDIRK = ("solver.method=esdirk4",)  # hybeam's order-4 ESDIRK instead of generalized-alpha
ESDIRK_MIN_STEP = 1e-4


def esdirk(fam: Family) -> Family:
    """The family integrated by hybeam's ESDIRK4 (`solver.method = "esdirk4"`), at steps from
    ESDIRK_MIN_STEP up."""
    return replace(
        fam, name=f"{fam.name}, ESDIRK4", sets=fam.sets + ESDIRK, min_step=ESDIRK_MIN_STEP
    )


HYBEAM_HYBRID = Family(
    "hybeam",
    "hybeam hybrid modal+ANCF",
    "scenes/case1.toml",
    "segments.1.elements",
    ("segments.0.modes=2",),
    element_fraction=0.375,
)
HYBEAM_HYBRID3D = Family(
    "hybeam",
    "hybeam hybrid modal+cable",
    "scenes/case1_3d.toml",
    "segments.1.elements",
    ("torsion=false", "segments.0.modes=2", _tip_force_set()),
    element_fraction=0.375,
)


HYBEAM_MODAL = Family(
    "hybeam", "hybeam all-modal", "scenes/case1_modal.toml", modes_key="segments.0.modes"
)
HYBEAM_TORSION = Family(
    "hybeam",
    "hybeam 3D torsion element",
    "scenes/case1_3d_ancf.toml",
    "segments.0.elements",
    (_tip_force_set(),),
)
HYBEAM_ANGLE = Family(
    "hybeam",
    "hybeam 3D angle element",
    "scenes/case1_3d_ancf.toml",
    "segments.0.elements",
    ('torsion_element="angle"', _tip_force_set()),
)
HYBEAM_MODAL3D = Family(
    "hybeam",
    "hybeam all-modal",
    "scenes/case1_3d_modal.toml",
    sets=(_tip_force_set(),),
    modes_key="segments.0.modes",
)
HYBEAM_HYBRID_CASE3 = Family(
    "hybeam",
    "hybeam hybrid modal+ANCF",
    "scenes/case3.toml",
    segments=tuple(zip(("", "segments.1.elements"), shares(CASE3_ROD), strict=True)),
)
HYBEAM_MODAL_CASE3 = Family(
    "hybeam", "hybeam all-modal", "scenes/case3_modal.toml", modes_key="segments.1.modes"
)

PROBLEMS = {
    "planar": Problem(
        "planar",
        False,
        [
            HYBEAM_PLANAR,
            EXUDYN_PLANAR,
            HYBEAM_HYBRID,
            HYBEAM_MODAL,
            esdirk(HYBEAM_PLANAR),
            esdirk(HYBEAM_HYBRID),
            esdirk(HYBEAM_MODAL),
        ],
        HYBEAM_PLANAR,
        EXUDYN_PLANAR,
        note="the hybrid (2 modes on its modal half) meshes its ANCF half with round(3 n / 8) "
        "elements: 2, 3, 6, 12; the all-modal rod (one "
        "modal segment, scenes/case1_modal.toml) gets round(12 n / 32) modes: 2, 3, 6, 12",
    ),
    "spatial": Problem(
        "spatial",
        True,
        [
            HYBEAM_CABLE3D,
            EXUDYN_SPATIAL,
            HYBEAM_TORSION,
            HYBEAM_ANGLE,
            HYBEAM_HYBRID3D,
            HYBEAM_MODAL3D,
            esdirk(HYBEAM_CABLE3D),
            esdirk(HYBEAM_TORSION),
            esdirk(HYBEAM_ANGLE),
            esdirk(HYBEAM_HYBRID3D),
            esdirk(HYBEAM_MODAL3D),
        ],
        HYBEAM_CABLE3D,
        EXUDYN_SPATIAL,
        tip_force=(0.0, TIP_FORCE, 0.0),
        note="the ANCF families mesh the whole rod with the grid's elements; the hybrid (2 modes "
        "per plane) meshes its ANCF half (3D cable) with round(3 n / 8): 2, 3, 6, 12; the "
        "all-modal rod (scenes/case1_3d_modal.toml) gets round(12 n / 32) modes per bending "
        "plane: 2, 3, 6, 12",
    ),
    "case3": Problem(
        "case3",
        False,
        [
            HYBEAM_CASE3,
            EXUDYN_PLANAR,
            HYBEAM_HYBRID_CASE3,
            HYBEAM_MODAL_CASE3,
            esdirk(HYBEAM_CASE3),
            esdirk(HYBEAM_HYBRID_CASE3),
            esdirk(HYBEAM_MODAL_CASE3),
        ],
        HYBEAM_CASE3,
        EXUDYN_PLANAR,
        CASE3_ROD,
        note="n is split by length: the thick 0.2 m segment gets max(1, round(n/3)) elements, the "
        "thin 0.4 m one the rest (all-ANCF and Exudyn: n = 8 is 3 + 5, n = 64 is 21 + 43); the "
        "hybrid's modal thick segment has none, its ANCF thin segment the rest (n = 8: 5); the "
        "all-modal rod (scenes/case3_modal.toml: the thick segment with 4 modes + 2 interface "
        "shapes, the thin one modal too) gets round(12 n / 32) modes on its thin segment: 2, 3, "
        "6, 12",
    ),
}

# ------------------------------------------------------------ large deformation (issue 42)

# Pending hybeam features (README.md, "Pending families"): a family using one is run, and
# reported "not available" while the binary refuses its scene key.
ERROR_TOLERANCES = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7)  # solver.error_tolerance of ESDIRK4
ERROR_CONTROLLED_MAX_STEP = 1e-2  # s: the error-controlled ESDIRK4's solver.max_step


# The higher-degree families mesh the rod with as many coordinates as the cubic family at the
# grid's n: an element of degree p adds p - 3 bubble points (2 coordinates each planar, 3 in
# space; docs/elements.md) to the cubic element's node (2 points), so n cubic elements have the
# unknowns of 2n / (p - 1) elements of degree p (n/2 quintic, n/3 of degree 7), up to
# DEGREE_MAX_GRID.
DEGREE_MAX_GRID = 48  # the grid's largest n for those families (24 quintic elements, 16 of
# degree 7; docs/elements.md: 16 quintic elements are within 1e-6 m of the converged soft rod)


def degree(fam: Family, p: int) -> Family:
    """The family with ANCF elements of degree p (`segments.0.degree = p`; docs/elements.md) at
    the unknowns of the grid's n cubic elements: round(2 n / (p - 1)) of them, up to
    DEGREE_MAX_GRID."""
    return replace(
        fam,
        name=f"{fam.name} degree {p}",
        sets=fam.sets + (f"segments.0.degree={p}",),
        element_fraction=fam.element_fraction * 2.0 / (p - 1),
        pending="segments.<i>.degree",
        max_grid_n=DEGREE_MAX_GRID,
    )


def error_controlled(fam: Family) -> Family:
    """The family integrated by ESDIRK4 with its own step control (`solver.error_tolerance`;
    pending): its grid axis is ERROR_TOLERANCES, at solver.max_step =
    ERROR_CONTROLLED_MAX_STEP."""
    return replace(
        fam,
        name=f"{fam.name}, ESDIRK4 error-controlled",
        sets=fam.sets + ESDIRK,
        pending="solver.error_tolerance",
        error_tolerances=ERROR_TOLERANCES,
        fixed_step=ERROR_CONTROLLED_MAX_STEP,
    )


def large_families(fam: Family, peer: Family) -> list[Family]:
    """A large-deformation problem's families: hybeam's ANCF family and its ESDIRK4 twin, the
    Exudyn peer, the elements of degree 5 and 7 and their ESDIRK4 twins, the error-controlled
    ESDIRK4 (cubic and degree 5)."""
    return [
        fam,
        peer,
        esdirk(fam),
        degree(fam, 5),
        esdirk(degree(fam, 5)),
        degree(fam, 7),
        esdirk(degree(fam, 7)),
        error_controlled(fam),
        error_controlled(degree(fam, 5)),
    ]


SOFT_PLANAR = Family("hybeam", "hybeam all-ANCF", "scenes/soft_rod.toml", "segments.0.elements")
SOFT_CABLE3D = Family(
    "hybeam",
    "hybeam 3D cable (torsion = false)",
    "benches/peers/soft_rod_3d.toml",
    "segments.0.elements",
    ("torsion=false", _tip_force_set(SOFT_TIP_FORCE)),
)
LARGE_NOTE = (
    "the cubic families (and Exudyn) mesh the whole rod with the grid's n elements, the "
    "families of degree p with round(2n / (p - 1)) elements of that degree (the same number of "
    "coordinates: n/2 quintic, n/3 of degree 7), up to n = 48"
)
LARGE = dict(
    rod=SOFT_ROD, tolerances=LARGE_TOLERANCES, suite="large", full=LARGE_GRID, quick=LARGE_QUICK
)

PROBLEMS |= {
    "soft_rod": Problem(
        "soft_rod",
        False,
        large_families(SOFT_PLANAR, EXUDYN_PLANAR),
        SOFT_PLANAR,
        EXUDYN_PLANAR,
        note=LARGE_NOTE,
        clamp_direction_only=True,
        **LARGE,
    ),
    "pendulum": Problem(
        "pendulum",
        False,
        large_families(SOFT_PLANAR, EXUDYN_PLANAR),
        SOFT_PLANAR,
        EXUDYN_PLANAR,
        note=LARGE_NOTE,
        root="pinned",
        **LARGE,
    ),
    "whip3d": Problem(
        "whip3d",
        True,
        large_families(SOFT_CABLE3D, EXUDYN_SPATIAL),
        SOFT_CABLE3D,
        EXUDYN_SPATIAL,
        note=LARGE_NOTE,
        root="ball",
        tip_force=(0.0, SOFT_TIP_FORCE, 0.0),
        **LARGE,
    ),
}
SUITES = {
    suite: [name for name, prob in PROBLEMS.items() if prob.suite == suite]
    for suite in ("small", "large")
}


@dataclass
class Run:
    """One grid point of one family: its tip series (first repeat) and its times."""

    problem: str
    family: Family
    elements: int
    step: float
    modes: int = 0  # modal families: the mode count (Family.modes)
    times_s: list[float] = field(default_factory=list)
    status: str = "ok"
    error_m: float = math.nan
    error_tolerance: float | None = None  # an error-controlled family's solver.error_tolerance
    t: np.ndarray | None = None
    tip: np.ndarray | None = None

    @property
    def time_s(self) -> float:
        return statistics.median(self.times_s) if self.times_s else math.nan


# ----------------------------------------------------------------------------------- hybeam


def run_hybeam(
    binary: Path,
    fam: Family,
    n: int,
    h: float,
    t_end: float,
    spatial: bool,
    tolerance: float | None = None,
    root: str = "clamped",
    error_tolerance: float | None = None,
) -> tuple[float, np.ndarray, np.ndarray]:
    """Runs the hybeam CLI for a grid point of n elements, at the Newton tolerance
    `tolerance` (None: the scene's), with the root `root` (a --set unless "clamped", the
    scenes' own) and the ESDIRK4 step control's `error_tolerance` (None: fixed steps); returns
    (its reported wall time, sample times, tip positions). A refused run raises
    RuntimeError with hybeam's message."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "tip.csv"
        sets = [
            *(f"{key}={k}" for key, k in fam.segment_elements(n)),
            *([f"{fam.modes_key}={fam.modes(n)}"] if fam.modes_key else []),
            f"solver.max_step={h!r}",
            f"simulation.t_end={t_end!r}",
            f"simulation.output_step={OUTPUT_STEP!r}",
            *([f"solver.tolerance={tolerance!r}"] if tolerance is not None else []),
            *fam.sets,
            *([f'root="{root}"'] if root != "clamped" else []),
            *([f"solver.error_tolerance={error_tolerance!r}"] if error_tolerance else []),
        ]
        cmd = [str(binary), "run", str(ROOT / fam.scene), "--out", str(out), "--quiet"]
        for s in sets:
            cmd += ["--set", s]
        proc = subprocess.run(cmd, capture_output=True, text=True)
        if proc.returncode != 0:
            raise RuntimeError(f"{shlex.join(cmd)}: {proc.stderr.strip()}")
        m = re.search(r"wall ([0-9.eE+-]+) s", proc.stdout)
        if not m:
            raise RuntimeError(f"no 'wall X s' in hybeam's output: {proc.stdout!r}")
        with out.open() as f:
            header = f.readline().strip().split(",")
        axes = ("x", "y", "z") if spatial else ("x", "y")
        cols = [header.index(f"tip.position.{a}") for a in axes]
        data = np.loadtxt(out, delimiter=",", skiprows=1, usecols=[0, *cols], ndmin=2)
    return float(m.group(1)), data[:, 0], data[:, 1:]


# ----------------------------------------------------------------------------------- Exudyn


def exudyn_settings(t_end: float, h: float):
    """Exudyn's simulation settings of every peer run: index-3 generalized-alpha at RHO_INF and
    the fixed step h, Newton on the increments at EXUDYN_NEWTON_TOL, sparse LU, the tip sampled
    every OUTPUT_STEP, no files and no console output."""
    import exudyn as exu

    settings = exu.SimulationSettings()
    ti = settings.timeIntegration
    ti.endTime = t_end
    ti.numberOfSteps = int(round(t_end / h))
    ti.verboseMode = 0
    ti.newton.residualMode = 1
    ti.newton.relativeTolerance = EXUDYN_NEWTON_TOL
    ti.newton.absoluteTolerance = EXUDYN_NEWTON_TOL
    ga = ti.generalizedAlpha
    ga.spectralRadius = RHO_INF
    ga.useIndex2Constraints = False
    ga.useNewmark = False
    ga.computeInitialAccelerations = True
    settings.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = OUTPUT_STEP
    settings.show.computationTime = False
    settings.show.statistics = False
    settings.show.globalTimers = False
    return settings


def run_exudyn(
    n: int, h: float, t_end: float, prob: Problem
) -> tuple[float, np.ndarray, np.ndarray]:
    """Builds the problem's rod from ANCF cable elements in Exudyn (n elements split over its
    sections by length, consecutive sections sharing their junction's node; the root node held
    by Problem.exudyn_root, the tip force if any) and solves it with index-3 generalized-alpha at
    the fixed step h; returns (time of exu.SolveDynamic, sample times, tip positions)."""
    import exudyn as exu
    from exudyn.beams import GenerateBeamElementsAlongLine
    from exudyn.itemInterface import (
        Force,
        MarkerNodePosition,
        ObjectANCFCable,
        ObjectANCFCable2D,
        SensorNode,
    )

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    spatial, rod = prob.spatial, prob.rod
    cable = ObjectANCFCable if spatial else ObjectANCFCable2D
    gravity = [0.0, 0.0, -GRAVITY] if spatial else [0.0, -GRAVITY, 0.0]
    clamp = prob.exudyn_root()  # the root node's held coordinates
    x0, tip_node = 0.0, None
    for sec, k in zip(rod, split_elements(n, shares(rod)), strict=True):
        ea, ei = sec.young * sec.area, sec.young * sec.inertia
        damping = {}
        if sec.damping_time > 0.0:
            # Kelvin-Voigt sigma = E (eps + tau_d eps') on the axial strain and the curvature.
            # ObjectANCFCable2D adds axialDamping * eps' to the axial force EA eps and
            # bendingDamping * K' to the bending moment EI K, with eps' = r'.r_t'/|r'| and K'
            # the exact rate of K = (r' x r'')/|r'|^2 (CObjectANCFCable2D.cpp; the docstrings give
            # the virtual work int eps' d(eps) dx without the factor; Exudyn's user-function
            # example: m = EI (K - K0) + bendingDamping K'), hence EA tau_d and EI tau_d.
            damping = {
                "axialDamping": ea * sec.damping_time,
                "bendingDamping": ei * sec.damping_time,
            }
        template = cable(
            massPerLength=sec.density * sec.area,
            bendingStiffness=ei,
            axialStiffness=ea,
            **damping,
        )
        x1 = x0 + sec.length
        beam = GenerateBeamElementsAlongLine(
            mbs,
            [x0, 0.0, 0.0],
            [x1, 0.0, 0.0],
            k,
            template,
            gravity,
            clamp if tip_node is None else None,
            nodeNumberStart=tip_node,  # the previous section's last node: shared at the junction
        )
        x0, tip_node = x1, beam["nodes"][-1]
    if prob.tip_force is not None:
        marker = mbs.AddMarker(MarkerNodePosition(nodeNumber=tip_node))
        force = list(prob.tip_force) if spatial else [*prob.tip_force[:2], 0.0]
        mbs.AddLoad(Force(markerNumber=marker, loadVector=force))
    sensor = mbs.AddSensor(
        SensorNode(
            nodeNumber=tip_node,
            outputVariableType=exu.OutputVariableType.Position,
            storeInternal=True,
            writeToFile=False,
        )
    )
    mbs.Assemble()

    settings = exudyn_settings(t_end, h)

    start = time.perf_counter()
    ok = exu.SolveDynamic(mbs, settings)
    elapsed = time.perf_counter() - start
    if ok is False:
        raise RuntimeError(f"Exudyn SolveDynamic failed (n={n}, h={h})")
    data = np.asarray(mbs.GetSensorStoredData(sensor))
    dims = 3 if spatial else 2
    return elapsed, data[:, 0], data[:, 1 : 1 + dims]


# ------------------------------------------------------------------------------- the runs


def solve(
    binary: Path,
    prob: Problem,
    fam: Family,
    n: int,
    h: float,
    t_end: float,
    tolerance: float | None = None,
    error_tolerance: float | None = None,
):
    """One run of either code; `tolerance` is hybeam's Newton tolerance (None: the scene's),
    `error_tolerance` an error-controlled hybeam family's."""
    if fam.code == "hybeam":
        return run_hybeam(
            binary, fam, n, h, t_end, prob.spatial, tolerance, prob.root, error_tolerance
        )
    return run_exudyn(n, h, t_end, prob)


def on_grid(t: np.ndarray, tip: np.ndarray, t_end: float) -> np.ndarray:
    """The tip on the output grid 0, 1 ms, ..., t_end (exact where the samples lie on it)."""
    grid = np.arange(round(t_end / OUTPUT_STEP) + 1) * OUTPUT_STEP
    if len(t) == len(grid) and np.allclose(t, grid, rtol=0.0, atol=1e-9):
        return tip
    return np.column_stack([np.interp(grid, t, tip[:, k]) for k in range(tip.shape[1])])


def max_distance(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.max(np.linalg.norm(a - b, axis=1)))


def motion(tip: np.ndarray) -> tuple[float, float]:
    """How large a run's motion is: the tip's largest distance from its start [m] and the
    largest angle of the root-to-tip chord (the root at the origin) from its start [deg]."""
    disp = float(np.max(np.linalg.norm(tip - tip[0], axis=1)))
    cos = tip @ tip[0] / (np.linalg.norm(tip, axis=1) * np.linalg.norm(tip[0]))
    return disp, float(np.degrees(np.max(np.arccos(np.clip(cos, -1.0, 1.0)))))


def reference(binary: Path, prob: Problem, grid: Grid, cache: Path, log) -> dict:
    """The shared reference (the finest run of prob.reference) and the peer code's run at the
    same mesh and step; cached in `cache` (keyed by their settings)."""
    key = (
        f"{prob.name} n={grid.ref_elements} h={grid.ref_step!r} t_end={grid.t_end!r} "
        f"exudyn_tol={EXUDYN_NEWTON_TOL!r} v2"
    )
    if cache.exists():
        z = np.load(cache, allow_pickle=False)
        if str(z["key"]) == key:
            log(f"[{prob.name}] reference from cache {cache}")
            return {k: z[k] for k in z.files}
    out = {"key": np.array(key)}
    fine = (grid.ref_elements, grid.ref_step)
    half = (grid.ref_elements // 2, 2.0 * grid.ref_step)  # for the reference's own error
    for label, fam, (n, h) in (
        ("ref", prob.reference, fine),
        ("peer", prob.peer_check, fine),
        ("half", prob.reference, half),
    ):
        log(f"[{prob.name}] fine run {fam.name}: n={n}, h={h:g} ...")
        wall, t, tip = solve(binary, prob, fam, n, h, grid.t_end)
        out[label] = on_grid(t, tip, grid.t_end)
        out[label + "_time"] = np.array(wall)
        log(f"[{prob.name}]   done in {wall:.2f} s")
    cache.parent.mkdir(parents=True, exist_ok=True)
    np.savez(cache, **out)
    return out


NOT_AVAILABLE = "not available"


def unknown_key(err: Exception) -> bool:
    """Whether hybeam refused the run for a scene field it does not know (a pending feature)."""
    return "unknown field" in str(err)


def sweep(
    binary: Path,
    prob: Problem,
    grid: Grid,
    ref: np.ndarray,
    log,
    tolerance: float | None,
) -> list[Run]:
    """Every family at every grid point, the codes alternating, hybeam at the Newton tolerance
    `tolerance` (None: the scenes'); median of grid.repeats. The error-controlled families run
    their error tolerances at each grid point's elements after the steps. A pending family
    whose key this hybeam refuses is marked "not available" at every point, after one try."""
    stepped = [f for f in prob.families if not f.error_tolerances]
    controlled = [f for f in prob.families if f.error_tolerances]
    runs = {
        (fam, n, h): Run(prob.name, fam, fam.elements(n), h, fam.modes(n))
        for n in grid.elements
        for h in grid.steps
        for fam in stepped
    }
    runs |= {
        (fam, n, tol): Run(
            prob.name, fam, fam.elements(n), fam.fixed_step, fam.modes(n), error_tolerance=tol
        )
        for n in grid.elements
        for fam in controlled
        for tol in fam.error_tolerances
    }
    missing: dict[Family, str] = {}  # pending families this hybeam does not have

    def attempt(run: Run, fam: Family, n: int, rep: int) -> None:
        h, tol = run.step, run.error_tolerance
        if fam in missing:
            run.status = missing[fam]
        if h < fam.min_step:
            run.status = f"not run: h below the family's min_step {fam.min_step:g}"
        if fam.max_grid_n and n > fam.max_grid_n:
            run.status = f"not run: grid n above the family's max_grid_n {fam.max_grid_n}"
        if run.status != "ok":
            return
        try:
            wall, t, tip = solve(binary, prob, fam, n, h, grid.t_end, tolerance, tol)
        except Exception as e:  # a failed run is recorded, not fatal
            if fam.pending and unknown_key(e):
                missing[fam] = f"{NOT_AVAILABLE}: this hybeam has no {fam.pending}"
                run.status = missing[fam]
                why = re.search(r"unknown field `[^`]*`", str(e))
                log(f"[{prob.name}] {fam.name}: {run.status} (hybeam: {why and why.group(0)})")
                return
            run.status = f"failed: {e}".replace("\n", " ")[:300]
            log(f"[{prob.name}] {fam.name} n={run.elements} h={h:g}: {run.status}")
            return
        run.times_s.append(wall)
        if rep == 0:
            run.error_m = max_distance(on_grid(t, tip, grid.t_end), ref)

    for rep in range(grid.repeats):
        order = stepped if rep % 2 == 0 else stepped[::-1]
        for n in grid.elements:
            for h in grid.steps:
                for fam in order:
                    attempt(runs[(fam, n, h)], fam, n, rep)
                log(
                    f"[{prob.name}] repeat {rep + 1}/{grid.repeats} n={n} h={h:g}: "
                    + ", ".join(
                        f"{f.name} {runs[(f, n, h)].time_s:.3g} s "
                        f"err {runs[(f, n, h)].error_m:.2e} m"
                        for f in stepped
                        if f not in missing
                    )
                )
            for fam in controlled:
                for tol in fam.error_tolerances:
                    attempt(runs[(fam, n, tol)], fam, n, rep)
                if fam not in missing:
                    log(
                        f"[{prob.name}] repeat {rep + 1}/{grid.repeats} n={n} {fam.name}: "
                        + ", ".join(
                            f"tol {tol:g} {runs[(fam, n, tol)].time_s:.3g} s "
                            f"err {runs[(fam, n, tol)].error_m:.2e} m"
                            for tol in fam.error_tolerances
                        )
                    )
    return list(runs.values())


# ---------------------------------------------------------------------------------- output


def write_csv(path: Path, runs: list[Run], repeats: int) -> None:
    with path.open("w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(
            ["problem", "code", "family", "elements", "modes", "step_s", "error_m", "time_s"]
            + [f"time_{k + 1}_s" for k in range(repeats)]
            + ["status", "error_tolerance"]
        )
        for r in runs:
            times = [f"{x:.6g}" for x in r.times_s] + [""] * (repeats - len(r.times_s))
            w.writerow(
                [r.problem, r.family.code, r.family.name, r.elements, r.modes, f"{r.step:g}"]
                + [f"{r.error_m:.6e}", f"{r.time_s:.6g}"]
                + times
                + [r.status, "" if r.error_tolerance is None else f"{r.error_tolerance:g}"]
            )


def pareto(runs: list[Run]) -> list[Run]:
    """Runs that no cheaper run beats in error (time ascending)."""
    front, best = [], math.inf
    for r in sorted(runs, key=lambda r: (r.time_s, r.error_m)):
        if r.error_m < best:
            front.append(r)
            best = r.error_m
    return front


def ok_runs(runs: list[Run]) -> list[Run]:
    return [r for r in runs if r.status == "ok" and math.isfinite(r.error_m)]


def cheapest(runs: list[Run], tol: float) -> Run | None:
    hits = [r for r in ok_runs(runs) if r.error_m <= tol]
    return min(hits, key=lambda r: r.time_s) if hits else None


def size(r: Run) -> str:
    """The run's mesh: "n = 8" (ANCF elements) or "6 modes" (a modal family)."""
    return f"{r.modes} modes" if r.family.modes_key else f"n = {r.elements}"


def stepping(r: Run, unit: str = " s") -> str:
    """The run's time stepping: "h = 0.0001 s" or, error-controlled, "error tol. 1e-05"."""
    if r.error_tolerance is not None:
        return f"error tol. {r.error_tolerance:g}"
    return f"h = {r.step:g}{unit}"


def describe(r: Run | None) -> str:
    if r is None:
        return "none reaches it"
    return f"{r.family.name}, {size(r)}, {stepping(r)}: {r.time_s:.3g} s, {r.error_m:.2e} m"


def ratio_table(runs: list[Run], tolerances: tuple[float, ...] = TOLERANCES) -> str:
    """Markdown: per tolerance the cheapest run of each code and Exudyn's time / hybeam's."""
    lines = [
        "| tolerance [m] | cheapest hybeam run | cheapest Exudyn run | Exudyn time / hybeam time |",
        "|---|---|---|---|",
    ]
    for tol in tolerances:
        hy = cheapest([r for r in runs if r.family.code == "hybeam"], tol)
        ex = cheapest([r for r in runs if r.family.code == "exudyn"], tol)
        ratio = f"{ex.time_s / hy.time_s:.1f}" if hy and ex else "n/a"
        lines.append(f"| {tol:g} | {describe(hy)} | {describe(ex)} | {ratio} |")
    return "\n".join(lines)


def family_table(
    runs: list[Run], families: list[Family], tolerances: tuple[float, ...] = TOLERANCES
) -> str:
    """Markdown: per tolerance the cheapest run of each family (seconds; - if none)."""
    lines = [
        "| tolerance [m] | " + " | ".join(f.name for f in families) + " |",
        "|---|" + "---|" * len(families),
    ]
    for tol in tolerances:
        cells = []
        for fam in families:
            r = cheapest([x for x in runs if x.family == fam], tol)
            cells.append("-" if r is None else f"{r.time_s:.3g} s ({size(r)}, {stepping(r, '')})")
        lines.append(f"| {tol:g} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def summary_table(sections: list[tuple[Problem, list[Run]]], tol: float = 1e-5) -> str:
    """Markdown: per problem, the cheapest run of each hybeam family within `tol` and Exudyn's
    cheapest time over it."""
    lines = [
        "| problem | family | cheapest setting | time | Exudyn / family |",
        "|---|---|---|---|---|",
    ]
    for prob, runs in sections:
        ex = cheapest([r for r in runs if r.family.code == "exudyn"], tol)
        label = prob.name
        hits = []
        for fam in prob.families:
            r = cheapest([x for x in runs if x.family == fam], tol)
            if fam.code == "hybeam" and r is not None:
                hits.append(r)
        for r in sorted(hits, key=lambda r: r.time_s):
            ratio = f"{ex.time_s / r.time_s:.1f}×" if ex else "n/a"
            setting = f"{size(r)}, {stepping(r)}"
            lines.append(f"| {label} | {r.family.name} | {setting} | {r.time_s:.3g} s | {ratio} |")
            label = ""
    return "\n".join(lines)


def read_csv(path: Path) -> dict[str, list[Run]]:
    """The runs of a `write_csv` file by problem (times: the median as the one time; no tip
    series), for regenerating the tables without running."""
    out: dict[str, list[Run]] = {}
    with path.open(newline="") as f:
        for row in csv.DictReader(f):
            fams = {x.name: x for x in PROBLEMS[row["problem"]].families}
            r = Run(
                row["problem"],
                fams[row["family"]],
                int(row["elements"]),
                float(row["step_s"]),
                int(row["modes"]),
                [float(row["time_s"])] if row["time_s"] else [],
                row["status"],
                float(row["error_m"]),
                float(row["error_tolerance"]) if row.get("error_tolerance") else None,
            )
            out.setdefault(r.problem, []).append(r)
    return out


SUMMARY_HEADING = "## Per family at 1e-5 m"


def summary_section(sections: list[tuple[Problem, list[Run]]]) -> list[str]:
    """The page's per-family summary (heading, text, table)."""
    return [
        SUMMARY_HEADING,
        "",
        "The cheapest run of each hybeam family within 1e-5 m in the run above, against Exudyn's "
        "cheapest (from the runs CSV; `peers.py --summary CSV` prints it again):",
        "",
        summary_table(sections),
        "",
        "What these tables mean for choosing a scene's setting, and how earlier runs compare: "
        "`docs/performance-notes.md` (written by hand).",
        "",
    ]


def xy(runs: list[Run]) -> tuple[list[float], list[float]]:
    return [r.time_s for r in runs], [r.error_m for r in runs]


STYLE = {0: ("tab:blue", "o"), 1: ("tab:red", "s"), 2: ("tab:green", "^"), 3: ("tab:purple", "D")}


def figure(path: Path, prob: Problem, runs: list[Run], title: str) -> None:
    import matplotlib

    matplotlib.use("svg")
    import matplotlib.pyplot as plt

    plt.rcParams["svg.hashsalt"] = "hybeam-peers"
    fig, ax = plt.subplots(figsize=(7.0, 5.0))
    for k, fam in enumerate(prob.families):
        color, marker = STYLE[k % len(STYLE)]
        mine = ok_runs([r for r in runs if r.family == fam])
        if not mine:
            continue
        style = {"color": color, "marker": marker}
        ax.scatter(*xy(mine), alpha=0.45, s=28, label=f"{fam.name}: every grid point", **style)
        ax.plot(*xy(pareto(mine)), lw=1.6, label=f"{fam.name}: Pareto front", **style)
    for tol in prob.tolerances:
        ax.axhline(tol, color="0.6", lw=0.8, ls=":")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("run time [s] (median of the repeats)")
    ax.set_ylabel("max |tip - reference| over the 1 ms grid [m]")
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(path, metadata={"Date": None})
    plt.close(fig)


def machine() -> dict:
    model = ""
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True).stdout
        model = next(
            (ln.split(":", 1)[1].strip() for ln in out.splitlines() if "Model name" in ln), ""
        )
    except OSError:
        pass
    return {"nproc": os.cpu_count(), "model": model or platform.processor() or "unknown"}


# ------------------------------------------------------------------------------------ main


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--quick",
        action="store_true",
        help="small grid, short t_end (0.5 s; large: 0.3 s), 1 repeat",
    )
    ap.add_argument(
        "--summary",
        type=Path,
        metavar="CSV",
        help="print the page's per-family summary of a runs CSV (no runs) and exit",
    )
    ap.add_argument("--hybeam", type=Path, default=ROOT / "target/release/hybeam")
    ap.add_argument(
        "--problems",
        default="small",
        help=f"comma-separated problems of one suite, or a suite's name: small = "
        f"{','.join(SUITES['small'])} (the default; docs/performance.md), large = "
        f"{','.join(SUITES['large'])} (docs/peers-large.md)",
    )
    ap.add_argument("--t-end", type=float, help="override the grid's end time [s]")
    ap.add_argument("--repeats", type=int, help="override the number of timing repeats")
    ap.add_argument("--out-dir", type=Path, help="default docs/report (quick: target/peers-quick)")
    ap.add_argument(
        "--doc",
        type=Path,
        help="default docs/performance.md, large suite docs/peers-large.md (quick: in --out-dir)",
    )
    ap.add_argument("--shared", default="", help="note on the machine's other load, for the doc")
    ap.add_argument(
        "--hybeam-tolerance",
        default=repr(HYBEAM_NEWTON_TOL),
        help="hybeam's Newton tolerance in the grid runs (solver.tolerance), or 'scene' for "
        f"the scenes' own (default {HYBEAM_NEWTON_TOL:g}, Exudyn's)",
    )
    args = ap.parse_args(argv)
    if args.summary:
        runs = read_csv(args.summary)
        print("\n".join(summary_section([(PROBLEMS[n], runs[n]) for n in PROBLEMS if n in runs])))
        return 0
    if args.hybeam_tolerance == "scene":
        hybeam_tol = None
    else:
        try:
            hybeam_tol = float(args.hybeam_tolerance)
        except ValueError:
            hybeam_tol = math.nan
        if not (math.isfinite(hybeam_tol) and 1e-15 <= hybeam_tol < 1e-2):
            ap.error(
                f"--hybeam-tolerance {args.hybeam_tolerance}: give a number in [1e-15, 0.01) "
                "(hybeam's solver.tolerance) or 'scene'"
            )
    names = [
        y for x in args.problems.split(",") if x.strip() for y in SUITES.get(x.strip(), [x.strip()])
    ]
    unknown = [x for x in names if x not in PROBLEMS]
    if unknown or not names:
        ap.error(
            f"--problems: unknown {unknown or names}; choose from {', '.join(PROBLEMS)} "
            f"or a suite ({', '.join(SUITES)})"
        )
    suites = {PROBLEMS[x].suite for x in names}
    if len(suites) > 1:
        ap.error(f"--problems: {names} mixes the suites {sorted(suites)}; run each on its own")
    (suite,) = suites
    large = suite == "large"
    grids = {PROBLEMS[x].grid(args.quick) for x in names}
    if len(grids) > 1:
        ap.error(f"--problems: {names} have different grids; run them separately")
    (grid,) = grids
    if args.t_end or args.repeats:
        grid = Grid(
            grid.elements,
            grid.steps,
            args.t_end or grid.t_end,
            grid.ref_elements,
            grid.ref_step,
            args.repeats or grid.repeats,
        )
    out_dir = args.out_dir or (ROOT / ("target/peers-quick" if args.quick else "docs/report"))
    page = "peers-large.md" if large else "performance.md"
    doc = args.doc or (out_dir / page if args.quick else ROOT / "docs" / page)
    out_dir.mkdir(parents=True, exist_ok=True)
    cache_dir = ROOT / "target/peers-cache"

    import exudyn

    if exudyn.__version__ != EXUDYN_VERSION:
        print(f"warning: Exudyn {exudyn.__version__}, not {EXUDYN_VERSION}", file=sys.stderr)
    if not args.hybeam.exists():
        sys.exit(f"{args.hybeam} missing: cargo build --release --bin hybeam (run.sh does)")

    def log(msg: str) -> None:
        print(time.strftime("%H:%M:%S"), msg, flush=True)

    started = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    load_before = os.getloadavg()
    clock = time.perf_counter()
    sections, all_runs = [], []
    for name in names:
        prob = PROBLEMS[name]
        cache = cache_dir / f"ref_{name}{'_quick' if args.quick else ''}.npz"
        refs = reference(args.hybeam, prob, grid, cache, log)
        peer_gap = max_distance(refs["ref"], refs["peer"])
        log(
            f"[{name}] fine runs of the two codes differ by {peer_gap:.3e} m; the reference lies "
            f"{max_distance(refs['ref'], refs['half']):.3e} m from its half-refined run; its tip "
            "moves up to {:.3f} m, its chord turns up to {:.0f} deg".format(*motion(refs["ref"]))
        )
        runs = sweep(args.hybeam, prob, grid, refs["ref"], log, hybeam_tol)
        all_runs += runs
        svg = out_dir / f"peers_{name}.svg"
        figure(
            svg,
            prob,
            runs,
            f"{name}: hybeam vs Exudyn {exudyn.__version__}, t_end = {grid.t_end:g} s, "
            f"reference {prob.reference.name} n = {grid.ref_elements}, h = {grid.ref_step:g} s",
        )
        sections.append((prob, runs, refs, peer_gap, svg))
    csv_path = out_dir / ("peers_large_runs.csv" if large else "peers_runs.csv")
    write_csv(csv_path, all_runs, grid.repeats)
    minutes = (time.perf_counter() - clock) / 60.0
    load_after = os.getloadavg()

    for prob, runs, _, _, _ in sections:
        print(f"\n{prob.name}\n{ratio_table(runs, prob.tolerances)}")
    command = os.environ.get("PEERS_COMMAND") or shlex.join(["python", *sys.argv])
    write_doc(
        doc,
        sections,
        grid,
        command,
        csv_path,
        started,
        minutes,
        load_before,
        load_after,
        args,
        hybeam_tol,
    )
    print(f"\nwrote {csv_path}, {doc} and the SVGs in {out_dir} ({minutes:.1f} min)")
    return 0


def rel(p: Path, start: Path) -> str:
    return os.path.relpath(p.resolve(), start.resolve())


def mesh(fam: Family, n: int) -> str:
    """n, and its split over the family's ANCF segments if it has several ("64 (21 + 43)")."""
    counts = [k for _, k in fam.segment_elements(n)]
    return f"{n}" if len(counts) < 2 else f"{n} ({' + '.join(map(str, counts))})"


def write_doc(
    doc, sections, grid, command, csv_path, started, minutes, before, after, args, hybeam_tol
):
    import exudyn

    m = machine()
    shared = args.shared or (
        "The machine was shared with other work during the run: treat the times as indicative."
    )
    here = doc.parent
    large = any(prob.suite == "large" for prob, *_ in sections)
    parts = [
        "# Performance, large deformation: hybeam against Exudyn"
        if large
        else "# Performance: hybeam against Exudyn",
        "",
        f"Generated by `benches/peers/peers.py` (issue {42 if large else 23}); the numbers below "
        "are those of the run that wrote this page. Method, settings and caveats: "
        f"`benches/peers/README.md`{', section Large deformation' if large else ''}.",
        "",
        f"- Command: `{command}`",
        f"- Started {started}, took {minutes:.1f} min.",
        f"- Machine: {m['nproc']} cores (`nproc`), `{m['model']}` (`lscpu | grep 'Model name'`); "
        f"load average {before[0]:.2f} at the start, {after[0]:.2f} at the end. {shared}",
        f"- Codes: hybeam (`{rel(args.hybeam, ROOT)}`, release build), Exudyn "
        f"{exudyn.__version__} (PyPI wheel, in its own venv).",
        f"- Grid: elements {list(grid.elements)} (how they map onto each family's mesh: per "
        f"problem below), steps {', '.join(f'{h:g}' for h in grid.steps)} s, "
        f"t_end = {grid.t_end:g} s, "
        f"median of {grid.repeats} repeat(s), the codes alternating.",
        "- Newton: "
        + (
            f"both codes stop on the increments at {hybeam_tol:g} (hybeam's `solver.tolerance`, "
            f"Exudyn's relative and absolute tolerance {EXUDYN_NEWTON_TOL:g}); the references "
            "at the scenes' own tolerance."
            if hybeam_tol is not None
            else f"hybeam at its scenes' own tolerance, Exudyn at {EXUDYN_NEWTON_TOL:g}."
        ),
        "- Error: max over the 1 ms output grid of |tip - reference| (Euclidean).",
        "- Time: hybeam: the `wall X s` its CLI prints (model build, initial accelerations, "
        "stepping and formatting the CSV rows in memory; no process start, no file write); "
        "Exudyn: around `exu.SolveDynamic` (model building and `mbs.Assemble` excluded).",
        f"- All runs: `{rel(csv_path, here)}`.",
        "",
    ]
    for prob, runs, refs, gap, svg in sections:
        ref_t, peer_t = float(refs["ref_time"]), float(refs["peer_time"])
        parts += [f"## {prob.name}", ""]
        if prob.description:
            parts += [prob.description, ""]
        if large:
            disp, turn = motion(refs["ref"])
            parts += [
                f"Motion (the reference): the tip moves up to {disp:.3f} m from its start "
                f"({disp / sum(x.length for x in prob.rod):.2f} L), the root-to-tip chord "
                f"turns up to {turn:.0f}° from its start.",
                "",
            ]
        parts += [
            f"Elements: {prob.note}.",
            "",
            f"Reference: {prob.reference.name}, n = {mesh(prob.reference, grid.ref_elements)}, "
            f"h = {grid.ref_step:g} s "
            f"({ref_t:.2f} s). The same mesh and step in {prob.peer_check.name} ({peer_t:.2f} s) "
            f"lies **{gap:.2e} m** from it (max over the 1 ms grid). The reference's own error, "
            f"estimated as its distance to the same code at half the elements and twice the step "
            f"(n = {mesh(prob.reference, grid.ref_elements // 2)}, h = {2 * grid.ref_step:g} s): "
            f"{max_distance(refs['ref'], refs['half']):.2e} m.",
            "",
            "Cheapest run of each code reaching each tolerance:",
            "",
            ratio_table(runs, prob.tolerances),
            "",
            "Cheapest run of each family:",
            "",
            family_table(runs, prob.families, prob.tolerances),
            "",
            f"![{prob.name}]({rel(svg, here)})",
            "",
        ]
        missing = {r.family.name: r.status for r in runs if r.status.startswith(NOT_AVAILABLE)}
        if missing:
            parts += [
                "Not run: "
                + "; ".join(f"{name} ({status})" for name, status in missing.items())
                + " (pending families, `benches/peers/README.md`).",
                "",
            ]
    parts += summary_section([(prob, runs) for prob, runs, *_ in sections])
    doc.write_text("\n".join(parts))


if __name__ == "__main__":
    sys.exit(main())
