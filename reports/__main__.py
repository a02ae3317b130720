"""``python -m reports`` is ``contact-vv``."""

import sys

from .cli import main

sys.exit(main())
