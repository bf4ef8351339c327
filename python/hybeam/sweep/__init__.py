"""`hybeam.sweep`: parameter studies of a beam FMU on Dask (`hybeam-sweep`, docs/sweeps.md): the
study file (`study`), the runner (`sweep`) and its chunks on Dask (`run`, `store`), structure
variants built per scene (`build`), the ranking (`sensitivity`), the figure (`plot`) and the
command line (`cli`)."""
