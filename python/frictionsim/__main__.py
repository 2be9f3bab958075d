"""``python -m frictionsim``: the command line (see :mod:`frictionsim.cli`)."""

import sys

from .cli import main

if __name__ == "__main__":  # not when a spawned worker of `--jobs N` imports the parent's main module
    sys.exit(main())
