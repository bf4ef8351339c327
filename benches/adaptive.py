"""Work and precision of the ESDIRK4's error control (`solver.error_tolerance`, issue 42).

Runs `hybeam run` on the soft rod and the Case 1 all-ANCF rod at 16 and 32 elements over 2 s
(communication and output step 1 ms): the error-controlled ESDIRK4 at a grid of tolerances,
with the scene's Newton tolerance (1e-11) and with the tied one (1e-3 x error_tolerance),
beside the fixed-step ESDIRK4 at the steps of docs/accuracy.md up to the communication step.
Prints a markdown table: wall time (one run on a shared machine: compare within a table),
accepted and rejected steps, Newton iterations, factorizations, the max tip error against the
physical reference (docs/accuracy.md: all-ANCF with 8x (soft rod) or 4x (Case 1) the elements,
h = 1e-5 s, Newton tolerance 1e-12) and against the same mesh with the ESDIRK4 at h = 1e-5 s
(the time integration's error alone). docs/report/error_control.md holds its last table.

    cargo build --release --bin hybeam
    python3 benches/adaptive.py > target/adaptive.md   # about 10 minutes here

References are cached in target/adaptive-cache/ (delete it to recompute them).
"""

import csv
import math
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HYBEAM = ROOT / "target" / "release" / "hybeam"
CACHE = ROOT / "target" / "adaptive-cache"
T_END = 2.0
SCENES = {"soft_rod": 8, "case1_ancf": 4}
ELEMENTS = [16, 32]
TOLERANCES = [1e-5, 1e-6, 1e-7, 1e-8, 1e-9]
FIXED_STEPS = [1e-3, 5e-4, 2e-4, 1e-4, 5e-5]
SUMMARY = re.compile(
    r"(\d+) steps \((\d+) rejected\), (\d+) Newton iterations, (\d+) factorizations, "
    r"wall ([0-9.]+) s"
)


def run(scene: str, sets: list[str], out: Path) -> dict:
    """One `hybeam run` of `scenes/<scene>.toml` with the overrides `sets`, its tip history
    written to `out`; returns the work it reports."""
    args = [str(HYBEAM), "run", f"scenes/{scene}.toml", "--quiet", "--out", str(out)]
    args += [f"--set={s}" for s in [f"simulation.t_end={T_END}", *sets]]
    done = subprocess.run(args, cwd=ROOT, capture_output=True, text=True, check=True)
    m = SUMMARY.search(done.stdout)
    if m is None:
        raise RuntimeError(f"no summary in: {done.stdout} {done.stderr}")
    steps, rejected, iterations, factorizations, wall = m.groups()
    return {
        "steps": int(steps),
        "rejected": int(rejected),
        "iterations": int(iterations),
        "factorizations": int(factorizations),
        "wall": float(wall),
    }


def tips(path: Path) -> list[tuple[float, float]]:
    """The tip positions (x, y) of a written run, one row per output time."""
    with path.open() as f:
        rows = csv.reader(f)
        header = next(rows)
        ix, iy = header.index("tip.position.x"), header.index("tip.position.y")
        return [(float(r[ix]), float(r[iy])) for r in rows]


def max_error(a: list, b: list) -> float:
    """The largest distance between two tip histories of the same output times."""
    if len(a) != len(b):
        raise RuntimeError(f"{len(a)} against {len(b)} samples")
    return max(math.hypot(p[0] - q[0], p[1] - q[1]) for p, q in zip(a, b, strict=True))


def reference(scene: str, elements: int, method: str) -> list:
    """The tip history of `scene` with `elements` ANCF elements at h = 1e-5 s, Newton
    tolerance 1e-12, with `method` (the physical reference of docs/accuracy.md is
    generalized-alpha's), cached."""
    CACHE.mkdir(parents=True, exist_ok=True)
    path = CACHE / f"{scene}-e{elements}-h1e-5-{method}.csv"
    if not path.exists():
        print(f"computing {path.name}", file=sys.stderr)
        sets = [
            f"segments.0.elements={elements}",
            f"solver.method={method}",
            "solver.max_step=1e-5",
            "solver.tolerance=1e-12",
        ]
        run(scene, sets, path)
    return tips(path)


def main() -> None:
    print(
        "| scene | elements | setting | wall [s] | steps | rejected | Newton it. | factor. "
        "| max tip err vs physical ref [m] | vs same mesh, ESDIRK4 h = 1e-5 s [m] |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    out = CACHE / "run.csv"
    for scene, refine in SCENES.items():
        physical = reference(scene, 16 * refine, "generalized_alpha")
        for elements in ELEMENTS:
            same = reference(scene, elements, "esdirk4")
            base = [f"segments.0.elements={elements}", "solver.method=esdirk4"]
            settings = [(f"`h={h:g}`", [f"solver.max_step={h:g}"]) for h in FIXED_STEPS]
            for tol in TOLERANCES:
                control = ["solver.max_step=1e-2", f"solver.error_tolerance={tol:g}"]
                settings.append((f"`error_tolerance={tol:g}`", control))
                tied = [*control, f"solver.tolerance={max(1e-3 * tol, 1e-15):g}"]
                settings.append((f"`error_tolerance={tol:g}` tied", tied))
            for label, sets in settings:
                work = run(scene, base + sets, out)
                tip = tips(out)
                print(
                    f"| {scene} | {elements} | {label} | {work['wall']:.3f} | {work['steps']} "
                    f"| {work['rejected']} | {work['iterations']} | {work['factorizations']} "
                    f"| {max_error(tip, physical):.2e} | {max_error(tip, same):.2e} |",
                    flush=True,
                )


if __name__ == "__main__":
    main()
