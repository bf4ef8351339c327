"""Fatigue of a run's stress history (issue 40): rainflow cycles (the `rainflow` package,
ASTM E1049-85 §5.4.4), Miner's linear damage on a Basquin S–N curve, the equivalent stress
range; for one result CSV or for every variant of a `hybeam-sweep` study (docs/fatigue.md)."""
