"""The FMU's views over a long run: 60 000 fmi2DoStep calls of 1 ms with
visualization.directory = DIR and visualization.max_bytes = CAP; prints the process's resident
memory, the files in DIR and their bytes after 1 000, 10 000, 30 000 and 60 000 steps (the
bytes stay at most CAP, the memory flat once the cap is reached).

    .venv/bin/python benches/fmu_views_memory.py FMU DIR [CAP]   (default CAP 2e7 bytes)
"""

import os
import shutil
import sys

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


def rss_mib() -> int:
    with open("/proc/self/status") as f:
        return int(f.read().split("VmRSS:")[1].split()[0]) // 1024


def main() -> None:
    fmu, out = sys.argv[1], sys.argv[2]
    cap = float(sys.argv[3]) if len(sys.argv) > 3 else 2e7
    shutil.rmtree(out, ignore_errors=True)
    md = read_model_description(fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    s = FMU2Slave(
        guid=md.guid,
        unzipDirectory=extract(fmu),
        modelIdentifier=md.coSimulation.modelIdentifier,
        instanceName="views",
    )
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    s.setString([vr["visualization.directory"]], [out])
    s.setReal([vr["visualization.max_bytes"]], [cap])
    s.exitInitializationMode()
    h = 1e-3
    for k in range(60000):
        s.doStep(k * h, h)
        if k + 1 in (1000, 10000, 30000, 60000):
            files = os.listdir(out)
            size = sum(os.path.getsize(os.path.join(out, f)) for f in files)
            print(f"steps {k + 1}: RSS {rss_mib()} MiB, {len(files)} files, {size} bytes")
    s.terminate()
    s.freeInstance()


if __name__ == "__main__":
    main()
