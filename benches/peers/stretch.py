"""Large stretch: hybeam's ANCF cable against Exudyn's ObjectANCFCable2D at 10-20 % axial strain.

The rod of `stretch_rod.toml` (d = 5 cm, L = 0.5 m, E = 150 kPa, rho = 1100 kg/m^3, clamped,
released straight and horizontal under gravity; its root stretches up to 19 % as it swings down),
run in both codes at the same mesh and step (index-3 generalized-alpha, rho_inf = 0.9, Newton
on the increments at 1e-10), with `solver.max_axial_strain = 0.25` in hybeam. Both use the same
strain measures (epsilon = |r'| - 1, curvature (r' x r'')/|r'|^2; docs/references.md). Prints,
per mesh and step, the largest tip distance between the codes over the run and, as the scale it
is measured against, the distance between hybeam's run and hybeam's run at twice the elements
(the discretization error). Issue 39; start it through run.sh's venv:

    cargo build --release --bin hybeam
    target/peers-venv/bin/python benches/peers/stretch.py --hybeam target/release/hybeam
"""

from __future__ import annotations

import argparse
import math
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from peers import EXUDYN_NEWTON_TOL as NEWTON_TOL
from peers import OUTPUT_STEP, exudyn_settings

HERE = Path(__file__).resolve().parent
SCENE = HERE / "stretch_rod.toml"
LENGTH, DIAMETER, DENSITY, GRAVITY = 0.5, 0.05, 1100.0, 9.81
YOUNG = 1.5e5  # Pa


def hybeam(binary: Path, n: int, h: float, t_end: float) -> tuple[np.ndarray, float]:
    """Tip positions on the output grid and the largest axial strain over the run (from the
    ParaView series' ranges)."""
    with tempfile.TemporaryDirectory() as tmp:
        out, vtk = Path(tmp) / "tip.csv", Path(tmp) / "vtk"
        cmd = [str(binary), "run", str(SCENE), "--out", str(out), "--quiet", "--vtk", str(vtk)]
        for s in (
            f"segments.0.elements={n}",
            f"segments.0.youngs_modulus={YOUNG!r}",
            f"solver.max_step={h!r}",
            f"simulation.t_end={t_end!r}",
            f"simulation.output_step={OUTPUT_STEP!r}",
            f"solver.tolerance={NEWTON_TOL!r}",
        ):
            cmd += ["--set", s]
        subprocess.run(cmd, check=True, capture_output=True, text=True)
        data = np.loadtxt(out, delimiter=",", skiprows=1, usecols=(1, 2), ndmin=2)
        strain = max(
            float(m)
            for p in vtk.glob("*.vtu")
            for m in re.findall(
                r'Name="axial_strain"[^>]*RangeMax="([^"]+)"', p.read_text(errors="replace")
            )
        )
    return data, strain


def exudyn(n: int, h: float, t_end: float) -> np.ndarray:
    """Tip positions on the output grid from Exudyn's ANCF cable (the peers' settings)."""
    import exudyn as exu
    from exudyn.beams import GenerateBeamElementsAlongLine
    from exudyn.itemInterface import ObjectANCFCable2D, SensorNode

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    area = math.pi * DIAMETER**2 / 4.0
    inertia = math.pi * DIAMETER**4 / 64.0
    template = ObjectANCFCable2D(
        massPerLength=DENSITY * area, bendingStiffness=YOUNG * inertia, axialStiffness=YOUNG * area
    )
    beam = GenerateBeamElementsAlongLine(
        mbs,
        [0.0, 0.0, 0.0],
        [LENGTH, 0.0, 0.0],
        n,
        template,
        [0.0, -GRAVITY, 0.0],
        # hybeam's clamp holds the root slope's direction, not its length (the root section
        # stretches): fix x, y and r'_y only. Clamping r'_x too (the peers' [True] * 4) holds the
        # root's strain at zero and parts the codes by 2.5e-5 m already at E = 1.5e7 Pa.
        [True, True, False, True],
    )
    sensor = mbs.AddSensor(
        SensorNode(
            nodeNumber=beam["nodes"][-1],
            outputVariableType=exu.OutputVariableType.Position,
            storeInternal=True,
            writeToFile=False,
        )
    )
    mbs.Assemble()
    settings = exudyn_settings(t_end, h)
    if exu.SolveDynamic(mbs, settings) is False:
        raise RuntimeError(f"Exudyn SolveDynamic failed (n={n}, h={h})")
    data = np.asarray(mbs.GetSensorStoredData(sensor))
    return data[:, 1:3]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hybeam", type=Path, default=HERE.parents[1] / "target/release/hybeam")
    ap.add_argument("--elements", default="8,16")
    ap.add_argument("--steps", default="2e-4,1e-4")
    ap.add_argument("--t-end", type=float, default=1.0)
    args = ap.parse_args(argv)
    print("| elements | step [s] | largest strain | hybeam − Exudyn [m] | hybeam n − 2n [m] |")
    print("|---|---|---|---|---|")
    for n in (int(x) for x in args.elements.split(",")):
        for h in (float(x) for x in args.steps.split(",")):
            tip, strain = hybeam(args.hybeam, n, h, args.t_end)
            fine, _ = hybeam(args.hybeam, 2 * n, h, args.t_end)
            peer = exudyn(n, h, args.t_end)
            k = min(len(tip), len(peer))
            gap = float(np.max(np.linalg.norm(tip[:k] - peer[:k], axis=1)))
            mesh = float(np.max(np.linalg.norm(tip - fine, axis=1)))
            print(f"| {n} | {h:g} | {strain:.3f} | {gap:.2e} | {mesh:.2e} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
