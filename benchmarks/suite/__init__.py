"""The benchmarks as code, run by airspeed velocity (``asv``; ``benchmarks/README.md``,
"Benchmarks as code"): wall time, peak memory and work counts of fixed problems."""
