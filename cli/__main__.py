"""``python -m cli``: the ``flexmm`` command."""

import sys

from .app import main

sys.exit(main())
