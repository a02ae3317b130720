"""What reads a results directory for people: HTML report, plots, gate, baselines."""
