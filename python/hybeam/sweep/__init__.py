"""hybeam-sweep: parameter studies of a beam FMU on Dask (docs/sweeps.md)."""
