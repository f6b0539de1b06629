"""``python -m saltdem_post`` (with ``python/`` on ``sys.path``)."""

import sys

from .cli import main

sys.exit(main())
