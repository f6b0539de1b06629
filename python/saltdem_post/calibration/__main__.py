"""``python3 -m saltdem_post.calibration``: the ``saltdem-calibrate`` command line."""

import sys

from .cli import main

sys.exit(main())
