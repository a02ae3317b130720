"""``python -m reports.cli`` is ``contact-vv``."""

import sys

from reports.cli import main

sys.exit(main())
