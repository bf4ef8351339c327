"""Times 1000 fmi2DoStep calls of 1 ms (tip.force.y = 0.05 N) on packaged beam FMUs through
fmpy's FMU2Slave; prints the best and median of RUNS runs and the final tip.position.y (its
repr: equal bits are equal text). With DIR, visualization.directory = DIR.

    .venv/bin/python benches/fmu_steps.py FMU [RUNS] [DIR]
"""

import shutil
import sys
import time

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


def main():
    path = sys.argv[1]
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    views = sys.argv[3] if len(sys.argv) > 3 else None
    md = read_model_description(path)
    vrs = {v.name: v.valueReference for v in md.modelVariables}
    unzipped = extract(path)
    times, y = [], None
    for _ in range(runs):
        s = FMU2Slave(
            guid=md.guid,
            unzipDirectory=unzipped,
            modelIdentifier=md.coSimulation.modelIdentifier,
            instanceName="bench",
        )
        s.instantiate()
        if views:
            s.setString([vrs["visualization.directory"]], [views])
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        s.exitInitializationMode()
        s.setReal([vrs["tip.force.y"]], [0.05])
        t0 = time.perf_counter()
        for k in range(1000):
            s.doStep(k * 1e-3, 1e-3)
        times.append(time.perf_counter() - t0)
        y = s.getReal([vrs["tip.position.y"]])[0]
        s.terminate()
        s.freeInstance()
    shutil.rmtree(unzipped, ignore_errors=True)
    times.sort()
    print(
        f"{path}: 1000 steps: best {times[0] * 1e3:.1f} ms, median "
        f"{times[len(times) // 2] * 1e3:.1f} ms over {runs} runs; tip.position.y = {y!r}"
    )


if __name__ == "__main__":
    main()
