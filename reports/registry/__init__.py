"""Solver records, error budgets, tolerances and the errors the CLI reports."""
