"""``python -m img2logo``: the ``img2logo`` command line (:func:`img2logo.app.cli.main`)."""

import sys

from .app.cli import main

if __name__ == "__main__":  # not on a mere import (a tool that imports every module)
    sys.exit(main())
