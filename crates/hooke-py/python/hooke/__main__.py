"""``python -m hooke``: the ``hooke`` command line."""

import sys

from . import _console

sys.exit(_console())
