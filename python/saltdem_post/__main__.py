"""``python3 -m saltdem_post``: the ``saltdem-post`` command line (installed,
or with ``python/`` on the module path: ``PYTHONPATH=python``)."""

import sys

from .cli import main

sys.exit(main())
