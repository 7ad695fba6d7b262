"""``python -m img2logo``: the ``img2logo`` command line (:func:`img2logo.cli.main`)."""

import sys

from .cli import main

sys.exit(main())
