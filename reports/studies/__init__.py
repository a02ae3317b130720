"""Grid and jump studies as tables and flags, numerical uncertainty, events."""
