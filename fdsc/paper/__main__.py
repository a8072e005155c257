"""``python -m fdsc.paper reproduce --out DIR``."""

import sys

from .cli import main

sys.exit(main())
