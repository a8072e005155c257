"""``python -m fdsc.paper reproduce --out DIR``."""

import sys

from fdsc.paper.cli import main

sys.exit(main())
