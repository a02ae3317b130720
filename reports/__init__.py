"""Runner, comparisons, plots, HTML report, gates and the ``contact-vv`` CLI."""
