"""``python -m frictionsim``: the command line (see :mod:`frictionsim.cli`)."""

import sys

from .cli import main

sys.exit(main())
