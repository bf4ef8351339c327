"""FMUs of a scene study (`[study] scene`): the scene with a variant's `scene:` values, built once
per distinct structure with `cargo fmu-build` (linux64) from the hybeam source tree this package
lives in, and cached by the scene text's SHA-256 under the output directory."""

import copy
import hashlib
import pathlib
import subprocess

import tomli_w
import tomllib

from .study import SCENE, StudyError

#: the source tree (python/hybeam/sweep/build.py → the repository)
ROOT = pathlib.Path(__file__).resolve().parents[3]


def scene_text(scene: pathlib.Path, values: dict) -> str:
    """The scene file with `values` ({"scene:a.b.c": x}) set: a dotted path, a list entry by
    index or, for a list of tables, by its `name`."""
    doc = tomllib.loads(scene.read_text())
    out = copy.deepcopy(doc)
    for key, x in values.items():
        path = key[len(SCENE) :].split(".")
        node = out
        for i, part in enumerate(path):
            last = i == len(path) - 1
            if isinstance(node, list):
                hit = None
                if part.isdigit() and int(part) < len(node):
                    hit = int(part)
                else:
                    names = [t.get("name") if isinstance(t, dict) else None for t in node]
                    hit = names.index(part) if part in names else None
                if hit is None:
                    raise StudyError(
                        f"[parameters] {key!r}: {part!r} is no entry of the list there; "
                        "give an index or a segment's name"
                    )
                if last:
                    node[hit] = x
                else:
                    node = node[hit]
            elif isinstance(node, dict):
                if last:
                    node[part] = x
                elif part in node:
                    node = node[part]
                else:
                    raise StudyError(f"[parameters] {key!r}: the scene has no {part!r} there")
    return tomli_w.dumps(out)


def build(scene: pathlib.Path, values: dict, cache: pathlib.Path) -> tuple[pathlib.Path, str]:
    """The FMU of `scene` with `values`, built into `cache/<hash>/` unless there already, and
    the build's error message ("" when it built)."""
    text = scene_text(scene, values)
    key = hashlib.sha256(text.encode()).hexdigest()[:16]
    d = cache / key
    fmu = d / f"{scene.stem}.fmu"
    if fmu.exists():
        return fmu, ""
    if not (ROOT / "fmu-build").is_dir():
        raise StudyError(f"[study] scene: building FMUs needs the hybeam source tree ({ROOT})")
    d.mkdir(parents=True, exist_ok=True)
    src = d / f"{scene.stem}.toml"
    src.write_text(text)
    cmd = ["cargo", "fmu-build", str(src), "--out", str(d), "--platforms", "linux64"]
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True)
    if p.returncode != 0 or not fmu.exists():
        lines = [ln for ln in (p.stderr or p.stdout).splitlines() if ln.strip()]
        return fmu, "fmu-build: " + (lines[-1] if lines else f"exit {p.returncode}")
    return fmu, ""
