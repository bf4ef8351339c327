"""`hybeam.cosim`: the co-simulation master (`hybeam-cosim`): system files (TOML, SSP,
OSP; `system`, `ssp`), FMU subsystems (`subsystem`), the coupling algorithms (`master`), the
runner (`run`), the studies (`stability`) and the command lines (`cli`)."""
