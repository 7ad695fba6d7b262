"""``python -m img2logo.experiments NOTEBOOK OUTPUT [--smoke] [-p NAME VALUE]...``: run one notebook."""

import sys

from .runner import main

sys.exit(main())
