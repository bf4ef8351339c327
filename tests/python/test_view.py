"""The ParaView series of `hybeam run --vtk` opened by a real VTK reader (PyVista on VTK 9.7):
the number of time steps and their times, the points and arrays of each piece as written (the
tip sample against the run's CSV, the section frame orthonormal, the strains finite and
bending present), and an offscreen rendering of the tube filter that is not blank."""

import csv
import subprocess
from pathlib import Path

import numpy as np
import pytest

pv = pytest.importorskip("pyvista")
ROOT = Path(__file__).resolve().parents[2]
HYBEAM = ROOT / "target" / "release" / "hybeam"
POINT_ARRAYS = {
    "velocity": 3,
    "tangent": 3,
    "section_y": 3,
    "section_z": 3,
    "axial_strain": 1,
    "curvature": 1,
    "curvature_y": 1,
    "curvature_z": 1,
    "twist": 1,
    "arc": 1,
    "radius": 1,
    "stress": 1,
}


@pytest.fixture(scope="module")
def strip(tmp_path_factory):
    """strip_3d (modal + ANCF, bends in two planes and twists) for 50 ms at 5 ms outputs."""
    if not HYBEAM.exists():
        pytest.fail(f"{HYBEAM} missing: cargo build --release --bin hybeam")
    out = tmp_path_factory.mktemp("strip")
    subprocess.run(
        [
            str(HYBEAM),
            "run",
            str(ROOT / "scenes" / "strip_3d.toml"),
            "--out",
            str(out / "run.csv"),
            "--t-end",
            "0.05",
            "--output-step",
            "5e-3",
            "--vtk",
            str(out / "vtk"),
            "--samples",
            "4",
            "--quiet",
        ],
        check=True,
    )
    with open(out / "run.csv") as fh:
        rows = list(csv.DictReader(fh))
    return out, rows


def test_series_opens_with_its_times_points_and_arrays(strip):
    out, rows = strip
    reader = pv.get_reader(str(out / "vtk" / "beam.pvd"))
    assert reader.number_time_points == len(rows) == 11
    np.testing.assert_allclose(
        reader.time_values, [float(r["time"]) for r in rows], rtol=0, atol=1e-15
    )
    # modal segment: 1 body x 4 + 1 samples; ANCF: 8 elements x 4 + 1; + the root vertex
    n_points = (4 + 1) + (8 * 4 + 1) + 1
    for k, row in enumerate(rows):
        reader.set_active_time_point(k)
        grid = reader.read()[0]
        assert grid.n_points == n_points
        # two polylines (segments), one joint vertex, one root vertex
        assert list(grid.cell_data["kind"]) == [0, 0, 1, 2]
        assert list(grid.cell_data["segment"]) == [0, 1, 1, -1]
        for name, comps in POINT_ARRAYS.items():
            a = np.asarray(grid.point_data[name])
            assert a.shape[0] == n_points and (a.ndim == 1 or a.shape[1] == comps), name
            assert np.all(np.isfinite(a)), name
        beam = grid.extract_cells([0, 1])
        # the last polyline point is the tip of the CSV (same f64)
        tip_index = int(grid.get_cell(1).point_ids[-1])
        tip = grid.points[tip_index]
        want = [float(row[f"tip.position.{c}"]) for c in "xyz"]
        np.testing.assert_allclose(tip, want, rtol=0, atol=1e-15)
        t, y, z = (np.asarray(grid.point_data[n]) for n in ("tangent", "section_y", "section_z"))
        np.testing.assert_allclose(np.einsum("ij,ij->i", t, y), 0, atol=1e-12)
        np.testing.assert_allclose(np.cross(t, y), z, atol=1e-12)
        assert beam.n_points == n_points - 1
    # the strip bends in both planes and twists by the end
    grid = reader.read()[0]
    assert np.abs(grid.point_data["curvature_y"]).max() > 0
    assert np.abs(grid.point_data["curvature_z"]).max() > 0
    assert np.abs(grid.point_data["twist"]).max() > 0
    assert np.asarray(grid.point_data["stress"]).max() > 0
    radius = np.asarray(grid.point_data["radius"])[:-1]
    np.testing.assert_allclose(radius, 0.002)  # the 4 mm strip's half width


def test_tube_renders_offscreen(strip, tmp_path):
    out, _ = strip
    reader = pv.get_reader(str(out / "vtk" / "beam.pvd"))
    reader.set_active_time_point(reader.number_time_points - 1)
    grid = reader.read()[0]
    lines = grid.extract_cells([0, 1]).extract_surface(algorithm=None)
    tube = lines.tube(radius=0.004, n_sides=12)
    plotter = pv.Plotter(off_screen=True, window_size=(480, 320))
    plotter.add_mesh(tube, scalars="curvature", show_scalar_bar=False)
    plotter.view_isometric()
    img = plotter.screenshot(str(tmp_path / "tube.png"))
    plotter.close()
    assert (tmp_path / "tube.png").stat().st_size > 1000
    colours = np.unique(img.reshape(-1, img.shape[-1]), axis=0)
    assert len(colours) > 20, f"rendering nearly blank: {len(colours)} colours"
