"""Python tools of hybeam (a flexible-beam FMI 2.0 co-simulation FMU): `hybeam.cosim`, the
co-simulation master behind the `hybeam-cosim` command."""
