"""``python -m vsgl.bench``: the same as ``python -m vsgl bench``."""

import sys

from .cli import main

sys.exit(main())
