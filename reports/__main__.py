"""``python -m reports`` is ``contact-vv``."""

import sys

from reports.cli import main

sys.exit(main())
