"""Sampling onto common points, metrics, cycles, maxima and the one verdict."""
