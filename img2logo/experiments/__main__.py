"""``python -m img2logo.experiments NOTEBOOK OUTPUT [--smoke] [-p NAME VALUE]...``: run one notebook."""

import sys

from .runner import main

if __name__ == "__main__":  # not on a mere import (the docs build imports every module)
    sys.exit(main())
