"""The results directory: its file names, staging and lock, manifest, writers and readers."""
