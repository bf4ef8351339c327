"""The real-time mode's accuracy against the normal mode (docs/realtime.md).

For each case: a converged reference (the normal mode at a quarter of the smallest step,
Newton tolerance 1e-13), then the normal and the real-time mode at the same internal step;
prints the largest tip distance from the reference over the run [m], the Newton iterations and
factorizations, as the Markdown table of docs/realtime.md. Released straight (`initial.state =
"straight"`) so that the beams move. Uses the release runner (`cargo build --release --bin
hybeam`) and the Python standard library only.

    python3 benches/realtime/accuracy.py [T_END]     (default 0.5 s)
"""

from __future__ import annotations

import csv
import re
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
RUNNER = ROOT / "target" / "release" / "hybeam"

# (scene, internal steps [s], real-time settings beyond mode = "realtime")
CASES: list[tuple[str, list[float], list[str]]] = [
    ("case1", [1e-4, 1e-3], []),
    ("case2", [1e-4, 1e-3], []),
    ("case3", [1e-4, 1e-3], []),
    ("case1_3d", [1e-4, 1e-3], []),
    ("boom", [2e-4, 1e-3], ["solver.realtime_iterations=2"]),
    ("boom_3d", [2e-4, 1e-3], ["solver.realtime_iterations=2"]),
]


def run(scene: str, t_end: float, sets: list[str], out: Path) -> str:
    args = [str(RUNNER), "run", str(ROOT / "scenes" / f"{scene}.toml"), "--out", str(out)]
    for s in ['initial.state="straight"', f"simulation.t_end={t_end}", *sets]:
        args += ["--set", s]
    done = subprocess.run(args, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        return "failed: " + (done.stderr.strip().splitlines() or ["?"])[-1][:120]
    return done.stdout + done.stderr


def tips(path: Path) -> list[list[float]]:
    with path.open() as f:
        rows = list(csv.reader(f))
    head = rows[0]
    cols = [
        head.index(c) for c in ("tip.position.x", "tip.position.y", "tip.position.z") if c in head
    ]
    return [[float(r[c]) for c in cols] for r in rows[1:]]


def distance(a: list[list[float]], b: list[list[float]]) -> float:
    n = min(len(a), len(b))
    return max(
        sum((x - y) ** 2 for x, y in zip(p, q, strict=True)) ** 0.5
        for p, q in zip(a[:n], b[:n], strict=True)
    )


def work(log: str) -> str:
    m = re.search(r"(\d+) Newton iterations, (\d+) factorizations", log)
    return f"{m.group(1)} / {m.group(2)}" if m else "–"


def main() -> None:
    t_end = float(sys.argv[1]) if len(sys.argv) > 1 else 0.5
    print(
        f"Tip distance from the converged reference over {t_end} s [m];"
        " Newton iterations / factorizations."
    )
    print()
    print(
        "| scene | step [s] | normal | its / facts | real-time | its / facts | real-time / normal |"
    )
    print("|---|--:|--:|--:|--:|--:|--:|")
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        for scene, steps, rt in CASES:
            ref = d / f"{scene}_ref.csv"
            h_ref = min(steps) / 4
            log = run(scene, t_end, [f"solver.max_step={h_ref}", "solver.tolerance=1e-13"], ref)
            if log.startswith("failed"):
                print(f"| {scene} | reference {log} |")
                continue
            reference = tips(ref)
            for h in steps:
                row = [scene, f"{h:g}"]
                errors = []
                for sets in (
                    [f"solver.max_step={h}"],
                    [f"solver.max_step={h}", 'solver.mode="realtime"', *rt],
                ):
                    out = d / "x.csv"
                    log = run(scene, t_end, sets, out)
                    if log.startswith("failed"):
                        row += [log, "–"]
                        errors.append(None)
                        continue
                    e = distance(tips(out), reference)
                    errors.append(e)
                    row += [f"{e:.2e}", work(log)]
                ratio = f"{errors[1] / errors[0]:.3f}" if None not in errors and errors[0] else "–"
                print("| " + " | ".join(row + [ratio]) + " |")


if __name__ == "__main__":
    main()
