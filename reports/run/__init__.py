"""Planning, running and writing cases: units, executors, runner, sweeps, thresholds."""
